"""A taught (sparse) polyline's fit tried again where the first one fell short: where it came
back as its own lines, kept corners without a word, or kept more than a third of its moves.

The band fit along a taught polyline is a heuristic: a chain within a smaller tolerance is
within this one too, and the first fit can miss one that exists. Each retry keeps the tolerance
and is taken only where it is better by a measure the user sees (fewer segments, no corner),
never at the cost of an arc tighter than the polygon turns.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.corners import corners_and_notes
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc
from coatsim.geometry.recover import recover_exact
from coatsim.geometry.sparse import near_radius

# (polysegment, verified deviation, input's tightest radius, limits kept, notes): the fitter's result
Fit = tuple[Polysegment, float, "float | None", bool, tuple[str, ...]]
# the fitter at (tolerance, corner_deg)
Fitter = Callable[[float, float], Fit]

TAUGHT_SHARE = 1 / 3  # a taught curve's chain should keep at most this share of its moves; if not, ...
TAUGHT_AIM = 0.9  # ... it is fitted again within this share of σ (the fewer segments kept)
LINES_AIMS = (0.95, 0.9, 0.8, 0.7, 0.6, 0.5)  # a taught polyline back as its lines is fitted again within these shares of σ
NO_CORNERS_DEG = 179.0  # corner_deg of the retry without the vertices that turn more than corner_deg
OWN_SLACK = 1.02  # a rounded corner's arcs are no tighter than the polygon turns there, to this factor
GENTLE_DEG = 90.0  # corners kept that turn less than this, ...
KNOT_SIGMAS = 4.0  # ... with no other corner within this many σ, are named in a note


def retried(points: np.ndarray, closed: bool, tol: float, corner_deg: float, fit: Fitter, found: Fit) -> Fit:
    """``found`` (the fit of taught ``points`` within ``tol``), or a better one: (1) one that
    follows points that came back as their own lines, from a smaller tolerance; (2) one without
    the corners kept silently at vertices turning more than ``corner_deg``, where its arcs are
    no tighter than the polygon turns at them and it needs no more segments (else a note names
    the gentle ones, _gentle_corners); (3) for a loop
    keeping more than a third of its moves, one with fewer segments from TAUGHT_AIM σ."""
    moves = len(points) - 1
    if found[0].n_segments >= moves and found[0].corners:
        found = _from_smaller(tol, corner_deg, fit, found, moves)
    if found[0].corners and not found[4]:
        found = _rounded(points, closed, tol, fit, found)
        gentle = _gentle_corners(found[0], tol)
        if gentle:
            found = found[:4] + ((_corner_note(found[0], gentle, corner_deg),),)
    if closed and found[0].n_segments > TAUGHT_SHARE * moves and _smooth(found):
        found = _tighter_aim(points, tol, corner_deg, fit, found)
    return found


def _smooth(fit: Fit) -> bool:
    return not fit[0].corners and not fit[4]


def _from_smaller(tol: float, corner_deg: float, fit: Fitter, found: Fit, moves: int) -> Fit:
    """The first chain within LINES_AIMS σ without corners and with at most TAUGHT_SHARE of the
    moves, else the best with fewer segments than moves (without corners first, then the fewest
    segments, then the largest aim), its corners and notes as they are at that aim. The fit is not
    monotone in σ: an epitrochoid taught with 30 points came back as its 30 lines at 0.7 of its
    chordal deviation, as 27 segments with 21 corners from 0.6 of σ (then the first aim with
    fewer segments than moves), and as 9 arcs from 0.95."""
    tried = []
    for share in LINES_AIMS:
        other = _tried(fit, share * tol, corner_deg)
        if other is None or other[0].n_segments >= moves:
            continue
        if not other[0].corners and other[0].n_segments <= TAUGHT_SHARE * moves:
            return other
        tried.append((other, share))
    if not tried:
        return found
    return min(tried, key=lambda item: (bool(item[0][0].corners), item[0][0].n_segments, -item[1]))[0]


def _rounded(points: np.ndarray, closed: bool, tol: float, fit: Fitter, found: Fit) -> Fit:
    """The fit without corners where it needs no more segments and its arcs are no tighter than
    the circle through three vertices at the tightest corner it drops (a lobe of a taught rose,
    not a rectangle's corner filleted within σ)."""
    other = _tried(fit, tol, NO_CORNERS_DEG)
    if other is None or not _smooth(other) or other[0].n_segments > found[0].n_segments:
        return found
    segs = found[0].segments
    at = np.array([segs[k].end for k in found[0].corners])
    vertex = np.argmin(np.linalg.norm(points[None, :, :] - at[:, None, :], axis=2), axis=1)
    own = float(near_radius(points, closed)[vertex].min())
    tightest = min((s.radius for s in other[0].segments if isinstance(s, Arc)), default=np.inf)
    return other if tightest * OWN_SLACK >= own else found


def _gentle_corners(poly: Polysegment, tol: float) -> list[int]:
    """The corners turning less than GENTLE_DEG with no other corner within KNOT_SIGMAS σ: where
    a smooth curve taught with few points may turn (a polygon's square corner, or a cusp taught
    with two close points, is a corner beyond doubt)."""
    segs = poly.segments
    at = np.array([segs[k].end for k in poly.corners])
    out = []
    for i, k in enumerate(poly.corners):
        turn = math.remainder(segs[(k + 1) % len(segs)].start_heading - segs[k].end_heading, 2 * math.pi)
        near = np.linalg.norm(at - at[i], axis=1) < KNOT_SIGMAS * tol
        if abs(turn) < math.radians(GENTLE_DEG) and near.sum() == 1:
            out.append(k)
    return out


def _corner_note(poly: Polysegment, corners: list[int], corner_deg: float) -> str:
    first = poly.segments[corners[0]].end
    return (f"{len(corners)} taught vertices turn more than corner_deg {corner_deg:g} degrees and more than "
            f"their neighbours: kept as corners (first at ({first[0]:.6g}, {first[1]:.6g})); a chain through them "
            "without a corner needs more segments or arcs tighter than the polygon turns there; a larger corner_deg "
            "rounds them")


def _tighter_aim(points: np.ndarray, tol: float, corner_deg: float, fit: Fitter, found: Fit) -> Fit:
    """A loop's chain from TAUGHT_AIM σ where it is smooth with fewer segments: where a loop's
    chain starts and closes on a few vertices a tighter aim often lands on fewer pieces (open
    taught paths, whose ends are pinned, gained nothing from it in scripts/bench_sparse.py)."""
    aim = TAUGHT_AIM * tol
    # a loop with corners at the aim has one at its seam: that chain would not replace this one
    if recover_exact(points, True, aim) is None and len(corners_and_notes(points, True, corner_deg, aim)[0]):
        return found
    other = _tried(fit, aim, corner_deg)
    return other if other is not None and _smooth(other) and other[0].n_segments < found[0].n_segments else found


def _tried(fit: Fitter, tol: float, corner_deg: float) -> Fit | None:
    """The fit, or None where it refuses (a retry never turns a fit into a refusal)."""
    try:
        return fit(tol, corner_deg)
    except InputError:
        return None

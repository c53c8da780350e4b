"""Sparse polylines as the paths they are: taught points a robot joins with straight moves.

Where a polyline's edges are long against σ, the edges next to a vertex that turns dip inside
a smooth curve through the vertices by about the sagitta d (refine.chord_insets). A smooth
chain within σ of the vertex and of its edges passes *between* them: d/2 inside the vertex,
d/2 outside the edges, with σ − d/2 to spare either way — the vertex's *channel*. The fit of
a sparse run follows a *guide* along the channels' middles (a cubic Hermite curve through the
shifted vertices, tangent there to the circle through each three consecutive ones) inside a
band narrowed to the channels; the refinement and the exact check measure against the
polyline itself.

A chain with fewer segments than moves cannot fillet every vertex (a line and an arc per
move): it passes a vertex on an arc spanning the vertex and its edges, no tighter than the
polyline turns there, so it strays at least about d/2 from the vertex or its edges
(rounding_error). A vertex between two long edges is *roundable* when that is within
ROUND_SHARE σ; where σ is below it, the vertex is a corner at this tolerance
(coatsim.geometry.corners) and a note says from which tolerance on it is rounded. An open sparse
run that no chain with fewer segments than moves follows is fitted in halves
(coatsim.geometry.halves); a loop, and what no half follows, is kept as its own lines
(taught_lines).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.envelope import SPARSE_EDGE_SIGMAS
from coatsim.geometry.limits import FitLimits
from coatsim.geometry.nearest import PolylineIndex
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.primitives import Line
from coatsim.geometry.rdp import rdp_indices, simplify_closed
from coatsim.geometry.refine import chord_insets
from coatsim.geometry.run_fit import RunFit

SPARSE_INSET = 0.25  # a run is sparse where an edge dips this share of σ inside the curve through its vertices
ROUND_SHARE = 1.0  # a vertex is roundable when its rounding error (half its chord inset) is at most this share of σ
MIN_WIDTH = 0.1  # the band keeps at least this share of σ where a channel is narrower
KNOT_SIGMAS = 1.0  # the guide has a knot every σ along an edge ...
KNOTS_PER_EDGE = (4, 64)  # ... but at least and at most this many
MAX_KNOTS = 50_000  # the guide has at most about this many points
GUIDE_SHARE = 1.0  # the guide's arcs are as gentle as keeps their apex within this share of σ


@dataclass(frozen=True, eq=False)
class Guide:
    """A dense smooth curve (m, 2) along the channels of a sparse run (closed loop: last =
    first), the share of σ the band keeps at each of its points (m,), the unit normal
    across the channel at its start (2,), along which a loop's start may slide, and the
    polyline itself with points along its edges (k, 2), where the refinement measures it
    (a loop's from where the guide starts on its first edge)."""

    points: np.ndarray
    width: np.ndarray
    slide: np.ndarray
    edges: np.ndarray


def _turns(points: np.ndarray, closed: bool) -> np.ndarray:
    """Signed turn (rad) at every vertex (0 at the ends of an open polyline; the seam of a
    closed one, last point = first, at index 0 and n - 1)."""
    d = np.diff(points, axis=0)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.zeros(len(points))
    turn[1:-1] = np.remainder(np.diff(heading) + np.pi, 2 * np.pi) - np.pi
    if closed and len(d) > 1:
        turn[0] = turn[-1] = math.remainder(float(heading[0] - heading[-1]), 2 * math.pi)
    return turn


def _neighbour_edges(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Length of the edge before and after every vertex (0 beyond the ends of an open one)."""
    ell = np.linalg.norm(np.diff(points, axis=0), axis=1)
    before, after = np.concatenate(([0.0], ell)), np.concatenate((ell, [0.0]))
    if closed and len(ell) > 1:
        before[0], after[-1] = ell[-1], ell[0]
    return before, after


def sparse_vertices(points: np.ndarray, closed: bool, tolerance: float) -> np.ndarray:
    """Whether each vertex sits between two edges at least SPARSE_EDGE_SIGMAS σ long (n,)."""
    before, after = _neighbour_edges(points, closed)
    return np.minimum(before, after) >= SPARSE_EDGE_SIGMAS * tolerance


def is_sparse(points: np.ndarray, closed: bool, tolerance: float) -> bool:
    """Whether a run has a sparse vertex whose edges dip SPARSE_INSET σ or more inside the
    curve through its vertices (a chain must pass between them there)."""
    pts = np.asarray(points, dtype=float)
    if len(pts) < 3:
        return False
    left, right = chord_insets(pts, closed)
    return bool(np.any(sparse_vertices(pts, closed, tolerance) & (left + right >= SPARSE_INSET * tolerance)))


def rounding_error(points: np.ndarray, closed: bool) -> np.ndarray:
    """Per vertex (n,), the least deviation (mm) of a chain with fewer segments than the
    polyline has moves where it passes the vertex. Such a chain cannot fillet each vertex
    (two segments a move): it passes a vertex on an arc no tighter than the polyline turns
    there (the circle through three consecutive vertices, the vertex's or a neighbour's),
    half way between the vertex and its edges. Where that arc, tangent to both edges, fits
    in the vertex's share of them (_room), it strays half its apex from both (a line meets
    a taught fillet so: the long edge's own circle through three vertices is far too
    gentle to matter there); else it spans the edges and strays half the vertex's chord
    inset (the sagitta of its longer edge on the circle through it and its neighbours)."""
    pts = np.asarray(points, dtype=float)
    left, right = chord_insets(pts, closed)
    spanning = (left + right) / 2
    half = np.abs(_turns(pts, closed)) / 2
    radius = near_radius(pts, closed)
    with np.errstate(invalid="ignore", over="ignore"):
        fits = (half > 0) & (radius * np.tan(half) <= _room(pts, closed))
        filleted = np.where(fits, radius * (1.0 / np.cos(half) - 1.0) / 2, np.inf)
    return np.minimum(spanning, filleted)


def near_radius(pts: np.ndarray, closed: bool) -> np.ndarray:
    """Per vertex (n,), the tightest circle (mm) through three consecutive vertices centred
    on it or on a neighbour (inf where they are collinear, and beyond an open run's ends)."""
    body = pts[:-1] if closed else pts
    radius = np.full(len(body), np.inf)
    a, b, c = (np.roll(body, 1, axis=0), body, np.roll(body, -1, axis=0)) if closed else (body[:-2], body[1:-1], body[2:])
    u, v = b - a, c - a
    cross = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    sides = np.linalg.norm(u, axis=1) * np.linalg.norm(c - b, axis=1) * np.linalg.norm(v, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        own = np.where(cross > 0, sides / (2 * cross), np.inf)
    if closed:
        radius = np.minimum(np.minimum(own, np.roll(own, 1)), np.roll(own, -1))
        return np.append(radius, radius[:1])
    radius[1:-1] = own
    near = radius.copy()
    near[1:] = np.minimum(near[1:], radius[:-1])
    near[:-1] = np.minimum(near[:-1], radius[1:])
    return near


def own_radius(points: np.ndarray, closed: bool) -> float:
    """The tightest circle (mm) through three consecutive vertices (inf if none turns)."""
    return float(np.min(near_radius(np.asarray(points, dtype=float), closed)))


def unroundable(points: np.ndarray, closed: bool, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """Sparse vertices σ cannot round with fewer segments than moves: their indices
    (interior vertices; for a closed polyline 0 .. n - 2) and the deviation each needs (mm,
    rounding_error). A vertex's need depends on it and its neighbours alone, so one that
    becomes a corner changes nothing for the others."""
    pts = np.asarray(points, dtype=float)
    long = sparse_vertices(pts, closed, tolerance)
    long[-1] = False  # the seam of a loop is vertex 0; an open polyline's ends are never corners
    long[0] &= closed
    error = rounding_error(pts, closed)
    index = np.flatnonzero(long & (error > ROUND_SHARE * tolerance))
    return index, error[index]


def rounding_tolerance(error: np.ndarray) -> float:
    """The tolerance (mm) from which vertices of these rounding errors are rounded, rounded
    up to four significant digits (as the note prints it)."""
    need = float(np.max(error)) / ROUND_SHARE
    unit = 10.0 ** (math.floor(math.log10(need)) - 3)
    return math.ceil(need / unit) * unit


def corner_note(points: np.ndarray, index: np.ndarray, error: np.ndarray, tolerance: float) -> str:
    """The note for vertices kept as corners because σ is below what the polyline allows."""
    first = points[int(index[0])]
    return (f"{len(index)} vertices kept as corners (first at ({first[0]:.6g}, {first[1]:.6g})): tolerance_mm "
            f"{tolerance:g} is below what the polyline allows there (no chain of arcs as gentle as its own turning, "
            f"with fewer segments than moves, passes within it of the vertices and their edges); a tolerance of "
            f"{rounding_tolerance(error):.4g} mm or more rounds them")


def guide(points: np.ndarray, closed: bool, tolerance: float, limits: FitLimits) -> Guide | None:
    """The guide of a sparse run (``closed``: a loop, last point = first) under the caps of
    ``limits``, None if the run is not sparse (is_sparse).

    Every vertex is rounded by an arc tangent to both edges, as gentle as the edges' shares
    (the vertex at each end of an edge gets a part of it in proportion to its turn) and a
    channel of GUIDE_SHARE σ allow, but no tighter than the caps; the straight parts run
    along the edges. That chain lies apex e inside each vertex and on its edges; the guide
    is it moved out by e/2 at each arc's middle, by a shift that varies linearly along it in
    between, so it runs through the middle of each channel."""
    pts = np.asarray(points, dtype=float)
    if not is_sparse(pts, closed, tolerance):
        return None
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
    turn = _turns(pts, closed)
    half = np.abs(turn) / 2
    room = _room(pts, closed)
    with np.errstate(divide="ignore", invalid="ignore"):
        widest = room / np.tan(half)
        gentle = np.minimum(widest, GUIDE_SHARE * tolerance / (1.0 / np.cos(half) - 1.0))
        radius = np.where(half > 0, np.minimum(widest, np.maximum(gentle, 1.0 / limits.at_knots(s))), 0.0)
    segments, apex_at = _fillet_chain(pts, closed, turn, radius)
    step = max(KNOT_SIGMAS * tolerance, float(sum(seg.length for seg in segments)) / MAX_KNOTS)
    dense, along, normal = _sampled(segments, step)
    apex = radius * (1.0 / np.cos(half) - 1.0)
    vertex = np.flatnonzero(half > 0)
    if closed:
        vertex = vertex[vertex < len(pts) - 1]
    shift_at, shift = apex_at[vertex], -np.sign(turn[vertex]) * apex[vertex] / 2
    total = float(along[-1])
    if closed:
        shift_at = np.concatenate((shift_at - total, shift_at, shift_at + total))
        shift = np.tile(shift, 3)
    else:
        shift_at, shift = np.concatenate(([0.0], shift_at, [total])), np.concatenate(([0.0], shift, [0.0]))
    moved = dense + np.interp(along, shift_at, shift)[:, None] * normal
    if closed:
        moved[-1] = moved[0]
    else:
        moved[-1] = pts[-1]
    width = np.clip(1.0 - _distance(moved, pts) / tolerance, MIN_WIDTH, 1.0)
    # A loop's guide starts on its first edge, where the arc of vertex 0 leaves it: so do
    # the measured edges, or the refinement would pair the chain's arc length with the
    # polyline's shifted by that much (by up to half an edge).
    edges = np.vstack((dense[:1], pts[1:], dense[:1])) if closed else pts
    return Guide(moved, width, normal[0], along_edges(edges, tolerance))


def _room(pts: np.ndarray, closed: bool) -> np.ndarray:
    """Per vertex, how far along each of its edges an arc rounding it may reach: its share
    of the shorter one, shared with the vertex at the edge's other end by their turns."""
    turn = np.abs(_turns(pts, closed))
    before, after = _neighbour_edges(pts, closed)
    prev_turn, next_turn = np.roll(turn, 1), np.roll(turn, -1)
    if closed:  # the seam's neighbours across it (index 0 and n - 1 are the same vertex)
        prev_turn[0], next_turn[-1] = turn[-2], turn[1]
    else:
        prev_turn[0], next_turn[-1] = 0.0, 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.minimum(before * turn / (turn + prev_turn), after * turn / (turn + next_turn))
    return np.where(turn > 0, share, 0.0)


def _fillet_chain(pts: np.ndarray, closed: bool, turn: np.ndarray, radius: np.ndarray) -> tuple[tuple, np.ndarray]:
    """Lines along the edges and an arc of ``radius`` tangent to both edges at every vertex
    that turns; a loop starts on its first edge where the arc at vertex 0 leaves it. Returns
    the segments and the arc length of each vertex's arc middle along them (n,)."""
    d = np.diff(pts, axis=0)
    ell = np.linalg.norm(d, axis=1)
    heading = np.arctan2(d[:, 1], d[:, 0])
    trim = radius * np.tan(np.abs(turn) / 2)
    n = len(ell)
    kappa, length, apex_at = [], [], np.zeros(len(pts))
    at = 0.0
    for k in range(n):
        j = k + 1 if k + 1 < n or not closed else 0  # the vertex this edge ends at
        line = ell[k] - trim[k] - trim[k + 1]
        if line > 1e-9 * ell[k]:
            kappa.append(0.0)
            length.append(line)
            at += line
        if (closed or k + 1 < n) and turn[j] != 0:
            arc = radius[j] * abs(turn[j])
            kappa.append(math.copysign(1.0 / radius[j], turn[j]))
            length.append(arc)
            apex_at[j] = at + arc / 2
            at += arc
    first = pts[0] + trim[0] * d[0] / ell[0] if closed else pts[0]
    return chain((float(first[0]), float(first[1])), float(heading[0]), kappa, length), apex_at


def _sampled(segments: tuple, step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points every ``step`` mm or closer along a chain (every junction included), their
    arc length and the unit normal (left) there."""
    t0 = segments[0].tangents(np.zeros(1))
    pts, along, normal = [np.asarray([segments[0].start], dtype=float)], [np.zeros(1)], [np.column_stack((-t0[:, 1], t0[:, 0]))]
    offset = 0.0
    for seg in segments:
        u = np.linspace(0.0, seg.length, max(1, int(math.ceil(seg.length / step))) + 1)[1:]
        pts.append(seg.points(u))
        along.append(offset + u)
        t = seg.tangents(u)
        normal.append(np.column_stack((-t[:, 1], t[:, 0])))
        offset += seg.length
    return np.vstack(pts), np.concatenate(along), np.vstack(normal)


def _distance(at: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Distance (m,) from each point to the polyline (nearest edges found with a proof)."""
    index = PolylineIndex(pts)
    bound = index.bound(at)[0]
    return index.exact(at, bound)[0]


def _knots(chord: np.ndarray, tolerance: float) -> np.ndarray:
    """Points per edge of the guide and of along_edges: one every KNOT_SIGMAS σ, within KNOTS_PER_EDGE."""
    return np.clip(np.ceil(chord / (KNOT_SIGMAS * tolerance)).astype(int), *KNOTS_PER_EDGE)


def along_edges(points: np.ndarray, tolerance: float) -> np.ndarray:
    """The polyline with points spread evenly along each edge (the vertices kept)."""
    ell = np.linalg.norm(np.diff(points, axis=0), axis=1)
    out = [points[:1]]
    for a, b, m in zip(points[:-1], points[1:], _knots(ell, tolerance)):
        u = np.arange(1, m + 1) / m
        part = a + u[:, None] * (b - a)
        part[-1] = b
        out.append(part)
    return np.vstack(out)


def simplified(pts: np.ndarray, closed_loop: bool, tolerance: float) -> np.ndarray:
    """Indices of the vertices RDP keeps within ``tolerance`` (at least a triangle of a loop)."""
    keep = simplify_closed(pts, tolerance) if closed_loop else rdp_indices(pts, tolerance)
    return keep if not closed_loop or len(keep) >= 4 else np.arange(len(pts))


def taught_lines(pts: np.ndarray, closed_loop: bool, tolerance: float) -> RunFit:
    """A sparse run as its own lines (those of its vertices RDP keeps within half the
    tolerance), a corner at every vertex, with a note: looser caps or fillets would turn
    tighter than the taught points do."""
    v = pts[simplified(pts, closed_loop, tolerance / 2)]
    lines = tuple(Line((float(a[0]), float(a[1])), (float(b[0]), float(b[1]))) for a, b in zip(v[:-1], v[1:]))
    corners = tuple(range(len(lines) - (0 if closed_loop else 1)))
    note = (f"the {len(pts)} points from ({pts[0][0]:.6g}, {pts[0][1]:.6g}) to ({pts[-1][0]:.6g}, {pts[-1][1]:.6g}) are "
            f"kept as {len(lines)} lines: no chain of arcs as gentle as their own turning, with fewer segments "
            f"than they have moves, stays within tolerance_mm {tolerance:g} of them; a larger tolerance rounds them")
    return RunFit(lines, hausdorff(pts, Polysegment(lines)).hausdorff, True, corners, (note,))

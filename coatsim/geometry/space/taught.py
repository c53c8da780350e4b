"""Sparse space polylines as the paths they are: taught points a robot joins with straight moves.

As in the plane (coatsim.geometry.sparse): where the edges are long against σ, a chain within σ
of the vertices and of the edges passes *between* them, inside each vertex that turns by about
half the sagitta e of its rounding and outside its edges by as much. The fit follows a *guide*
along those channels' middles: every vertex is rounded by an arc tangent to both its edges, in
their plane, as gentle as its share of the edges and an apex of GUIDE_SHARE σ allow (a true
corner — turning more than ``corner_deg`` and STANDS_OUT times either neighbour, or doubling
back — is kept); that chain, sampled, is moved back out towards each vertex by e/2 at its arc's
middle, by a shift that varies linearly along it in between. The guide is fitted as a dense
space curve within σ less its own distance from the polyline (that distance is the guide's at
its worst, at a vertex: wider rooms are tried while the chain holds), and the chain is certified
against the polyline itself.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.corners import STANDS_OUT
from coatsim.geometry.envelope import SPARSE_EDGE_SIGMAS
from coatsim.geometry.sparse import GUIDE_SHARE, KNOT_SIGMAS, MAX_KNOTS, SPARSE_INSET
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import SpaceCurve
from coatsim.geometry.space.deviation import hausdorff3
from coatsim.geometry.space.nearest import polyline_index

ARC_SAMPLES = 8  # a rounding arc is sampled at least this many times
CUSP_DEG = 170.0  # a vertex turning more is a corner however its neighbours turn (the path doubles back)
RESCUE_SHARE = 0.25  # the guide is fitted where the polyline's own fit needs more than this share of its moves
NOISE_FLIPS = (30, 0.4)  # from this many turns on, a polyline turning back on this share of them is measured noise
ROOMS = (1.0, 1.4, 1.8)  # the guide is fitted within these multiples of σ less its distance from the polyline

Fit = Callable[[SpaceCurve, float], tuple[SpaceChain, int]]  # (chain, corners it added where lines stand in)


def _edges(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per vertex of the polyline (a loop's without its repeated last point): the unit edge
    direction before and after it and the lengths of those edges (0 beyond an open one's ends)."""
    body = points[:-1] if closed else points
    d = np.diff(points, axis=0)
    ell = np.linalg.norm(d, axis=1)
    unit = d / ell[:, None]
    if closed:
        return np.roll(unit, 1, axis=0), unit, np.stack((np.roll(ell, 1), ell))
    n = len(body)
    before, after = np.zeros((n, 3)), np.zeros((n, 3))
    before[1:], after[:-1] = unit, unit
    return before, after, np.stack((np.concatenate(([0.0], ell)), np.concatenate((ell, [0.0]))))


def _turns(before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """|turn| (rad) at every vertex between its edge directions (0 where one is missing)."""
    cos = np.clip(np.einsum("ij,ij->i", before, after), -1.0, 1.0)
    sin = np.linalg.norm(np.cross(before, after), axis=1)
    have = (np.linalg.norm(before, axis=1) > 0) & (np.linalg.norm(after, axis=1) > 0)
    return np.where(have, np.arctan2(sin, cos), 0.0)


def is_sparse3(points: np.ndarray, closed: bool, tolerance: float) -> bool:
    """Whether a space polyline's edges are SPARSE_EDGE_SIGMAS σ long or longer (their median:
    a few long steps of noisy dense points are none) and it has a vertex between two such edges
    that dip SPARSE_INSET σ or more inside the curve through its vertices."""
    pts = np.asarray(points, dtype=float)
    if len(pts) < 3 or np.median(np.linalg.norm(np.diff(pts, axis=0), axis=1)) < SPARSE_EDGE_SIGMAS * tolerance:
        return False
    before, after, ell = _edges(pts, closed)
    turn = _turns(before, after)
    span = ell.sum(axis=0)
    inset = np.divide(ell.max(axis=0) ** 2 * turn, 4 * span, out=np.zeros_like(span), where=span > 0)
    return bool(np.any((ell.min(axis=0) >= SPARSE_EDGE_SIGMAS * tolerance) & (inset >= SPARSE_INSET * tolerance)))


def noisy(points: np.ndarray) -> bool:
    """Whether a polyline's vertices are measured points with their noise rather than taught
    ones: over NOISE_FLIPS[0] turns or more, the next vertex turns back against the last
    (binormals opposed) at NOISE_FLIPS[1] of them or more. A taught polygon of a smooth curve
    turns one way between its inflections (at most 0.17 of its turns back on the benchmark's
    families at 15 vertices and more); the passes over a scan with 0.2 mm of noise turn back at
    0.6 of theirs, and their guide cost ten times the polyline's own fit for a segment in twenty."""
    d = np.diff(np.asarray(points, dtype=float), axis=0)
    binormal = np.cross(d[:-1], d[1:])
    size = np.linalg.norm(binormal, axis=1)
    unit = binormal[size > 0] / size[size > 0, None]
    if len(unit) < NOISE_FLIPS[0]:
        return False
    return float(np.mean(np.einsum("ij,ij->i", unit[1:], unit[:-1]) < 0)) >= NOISE_FLIPS[1]


def guide3(points: np.ndarray, closed: bool, tolerance: float, corner_deg: float) -> np.ndarray:
    """The guide of a sparse space polyline (see the module text), dense points (m, 3); a loop's
    last point is its first."""
    pts = np.asarray(points, dtype=float)
    before, after, ell = _edges(pts, closed)
    turn = _turns(before, after)
    near = np.maximum(np.roll(turn, 1), np.roll(turn, -1))  # (an open one's ends turn 0)
    corner = ((turn > math.radians(corner_deg)) & (turn > STANDS_OUT * near)) | (turn > math.radians(CUSP_DEG))
    turn = np.where(corner, 0.0, turn)
    prev_turn, next_turn = np.roll(turn, 1), np.roll(turn, -1)
    if not closed:
        prev_turn[0], next_turn[-1] = 0.0, 0.0
    half = turn / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        room = np.minimum(ell[0] * turn / (turn + prev_turn), ell[1] * turn / (turn + next_turn))
        radius = np.where(half > 0, np.minimum(room / np.tan(half), GUIDE_SHARE * tolerance / (1 / np.cos(half) - 1)), 0.0)
    reach = radius * np.tan(half)  # along each edge from the vertex
    apex = radius * (1 / np.cos(half) - 1)
    body = pts[:-1] if closed else pts
    inward = after - before
    norm = np.linalg.norm(inward, axis=1)
    inward = np.divide(inward, norm[:, None], out=np.zeros_like(inward), where=norm[:, None] > 0)
    step = max(KNOT_SIGMAS * tolerance, float(ell[1].sum()) / MAX_KNOTS)
    samples, shifts = [], []  # per vertex: its arc's samples, then the edge after it
    for i in range(len(body)):
        p = body[i]
        if radius[i] > 0:
            centre = p + inward[i] * radius[i] / math.cos(half[i])
            start, end = p - reach[i] * before[i] - centre, p + reach[i] * after[i] - centre
            count = 2 * max(ARC_SAMPLES // 2, int(math.ceil(radius[i] * turn[i] / (2 * step))))  # even: a sample at the apex
            angle = np.linspace(0.0, 1.0, count + 1)[:, None] * turn[i]
            arc = centre + (np.sin(turn[i] - angle) * start + np.sin(angle) * end) / math.sin(turn[i])
            samples.append(arc)
            shifts.append((len(arc) // 2, -inward[i] * apex[i] / 2))
        else:
            samples.append(p[None])
            shifts.append((0, np.zeros(3)))
        if i < len(body) - 1 or closed:
            a = samples[-1][-1]
            b = body[(i + 1) % len(body)] - reach[(i + 1) % len(body)] * before[(i + 1) % len(body)]
            count = max(1, int(math.ceil(float(np.linalg.norm(b - a)) / step)))
            samples.append(a + np.linspace(0.0, 1.0, count + 1)[1:-1, None] * (b - a))
            shifts.append(None)
    dense = np.vstack(samples)
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))))
    first = np.cumsum([0] + [len(x) for x in samples[:-1]])
    at = [(float(s[first[k] + shift[0]]), shift[1]) for k, shift in enumerate(shifts) if shift is not None]
    where = np.array([a for a, _ in at])
    vectors = np.array([v for _, v in at])
    if closed:
        total = float(s[-1] + np.linalg.norm(dense[0] - dense[-1]))
        where = np.concatenate((where - total, where, where + total))
        vectors = np.vstack((vectors, vectors, vectors))
    moved = dense + np.column_stack([np.interp(s, where, vectors[:, k]) for k in range(3)])
    return np.vstack((moved, moved[:1])) if closed else moved


def taught_fit(curve: SpaceCurve, tolerance: float, corner_deg: float, fit: Fit,
               beat: int) -> tuple[SpaceChain, float, int] | None:
    """The chain of a sparse space polyline fitted along its guide by ``fit`` (a dense space
    curve and a tolerance -> a chain and the corners it added), its certified deviation from
    the polyline and those corners; None where the polyline's own fit needs ``beat`` segments,
    no more than RESCUE_SHARE of its moves (a smooth pass sampled every few σ: its guide costs
    fits and gains nothing), the polyline is not sparse or is measured noise (``noisy``), the
    guide leaves no room, or no chain within σ has fewer segments than ``beat``."""
    pts = curve.points
    if beat <= RESCUE_SHARE * (len(pts) - 1) or not is_sparse3(pts, curve.closed, tolerance) or noisy(pts):
        return None
    guide = guide3(pts, curve.closed, tolerance, corner_deg)
    to_polyline = polyline_index(pts)[0].distance(guide)[0].max()
    from_polyline = polyline_index(guide)[0].distance(_along(pts, tolerance / 4))[0].max()
    room = tolerance - max(float(to_polyline), float(from_polyline)) - tolerance / 8  # (the edges measured every σ/4)
    best = None
    for wider in ROOMS:  # the room is the guide's distance at its worst (a vertex): wider, while the chain holds
        if not 0 < wider * room < tolerance:
            break
        try:
            chain, added = fit(SpaceCurve(guide, curve.closed, curve.name), wider * room)
        except InputError:  # no chain along the guide: the polyline's own fit stands
            break
        dev = hausdorff3(pts, chain, tolerance).hausdorff
        if dev > tolerance:
            break
        if chain.n_segments < (beat if best is None else best[0].n_segments):
            best = (chain, dev, added)
    return best


def _along(points: np.ndarray, step: float) -> np.ndarray:
    """The polyline with points at most ``step`` apart along every edge."""
    out = [points[:1]]
    for a, b in zip(points[:-1], points[1:]):
        count = max(1, int(math.ceil(float(np.linalg.norm(b - a)) / step)))
        out.append(a + np.linspace(0.0, 1.0, count + 1)[1:, None] * (b - a))
    return np.vstack(out)

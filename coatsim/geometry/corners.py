"""True corners of an input polyline: a large turn within a short length."""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.envelope import SPARSE_EDGE_SIGMAS
from coatsim.geometry.sparse import corner_note, sparse_vertices, unroundable

SPARSE = 10.0  # a polyline whose median edge is this many σ long has only its vertices to go by
CONCENTRATED = 2.0  # a corner turns at most this much more over 3w than over w
STANDS_OUT = 2.0  # a polygon's corner turns more than this many times either neighbouring vertex


def _point_at(points: np.ndarray, s: np.ndarray, at: np.ndarray) -> np.ndarray:
    return np.column_stack((np.interp(at, s, points[:, 0]), np.interp(at, s, points[:, 1])))


def detect_corners(points: np.ndarray, closed: bool, corner_deg: float, tolerance: float) -> np.ndarray:
    """Indices of the vertices where the curve has a true corner at tolerance σ (see
    corners_and_notes)."""
    return corners_and_notes(points, closed, corner_deg, tolerance)[0]


def corners_and_notes(points: np.ndarray, closed: bool, corner_deg: float,
                      tolerance: float) -> tuple[np.ndarray, tuple[str, ...]]:
    """Indices of the vertices where the curve has a true corner at tolerance σ, and a note
    on the vertices σ is too small to round.

    Between short edges: where the curve turns by more than ``corner_deg`` within a window
    w = max(3 median edge lengths, σ) on each side, and still does over 3w. The turn is
    measured between the chords p(s - w) -> p(s) and p(s) -> p(s + w), so fine sampling of a
    smooth bend does not count while a sharp vertex does; requiring the turn over 3w too
    rejects digitising noise, and requiring it to be at most twice the turn over w rejects
    smooth bends that a large tolerance makes turn much within w. Neighbouring detections
    within 2w collapse to the vertex with the largest turn. A polyline whose median edge is
    SPARSE σ or longer has its vertices turning more than ``corner_deg`` as corners instead.

    Between long edges (coatsim.geometry.sparse, a taught path): where σ is below what the
    polyline allows (no arc as gentle as its own turning rounds the vertex within σ), or
    where it turns more than ``corner_deg`` and more than STANDS_OUT times either
    neighbour (a polygon's corner, not a step of a taught curve); so does a knot of
    vertices within σ of each other (_sharp_knots: a cusp taught with two close points).
    End points of an open curve are never corners.
    """
    pts = np.asarray(points, dtype=float)
    dense = _dense_corners(pts, closed, corner_deg, tolerance)
    long = sparse_vertices(pts, closed, tolerance)
    if not long.any():
        return dense, ()
    turn = _vertex_turns(pts, closed)
    prev_turn, next_turn = np.roll(turn, 1), np.roll(turn, -1)
    if closed:
        prev_turn[0] = turn[-2]  # the seam's neighbour across it
    sharp = long & (turn > math.radians(corner_deg)) & (turn > STANDS_OUT * np.maximum(prev_turn, next_turn))
    sharp[-1] = False
    if not closed:
        sharp[0] = False
    kept = [int(c) for c in dense if not long[c]]
    tight, needs = unroundable(pts, closed, tolerance)
    knots = _sharp_knots(pts, closed, corner_deg, tolerance)
    corners = np.array(sorted(set(kept) | set(np.flatnonzero(sharp).tolist()) | set(tight.tolist()) | set(knots)),
                       dtype=int)
    return corners, ((corner_note(pts, tight, needs, tolerance),) if len(tight) else ())


def _sharp_knots(pts: np.ndarray, closed: bool, corner_deg: float, tolerance: float) -> list[int]:
    """Vertices of the knots that turn like a corner. A knot is two or more vertices joined
    by edges shorter than SPARSE_EDGE_SIGMAS σ, between longer ones, all within that of
    their mean (no farther apart than a sparse edge is long): a chain within σ passes them
    as one vertex, it turns as much as they do together. A knot that turns more than
    ``corner_deg`` and more than STANDS_OUT times the vertices on either side of it (a cusp
    taught with two close points, a star's tip as σ grows past half its edges) gives its
    vertices turning more than ``corner_deg`` (or its sharpest) as corners. A loop is
    looked at from a vertex between two longer edges (none: no knot)."""
    if closed:
        ell = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        long = ell >= SPARSE_EDGE_SIGMAS * tolerance
        start = np.flatnonzero(long & np.roll(long, 1))
        if not len(start):
            return []
        order = (np.arange(len(pts)) + int(start[0])) % (len(pts) - 1)
        return sorted(int(order[k]) for k in _sharp_knots(pts[order], False, corner_deg, tolerance))
    d = np.diff(pts, axis=0)
    ell = np.linalg.norm(d, axis=1)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.zeros(len(pts))
    turn[1:-1] = np.remainder(np.diff(heading) + math.pi, 2 * math.pi) - math.pi
    short = ell < SPARSE_EDGE_SIGMAS * tolerance
    found: list[int] = []
    first = 1
    while first < len(ell):
        if not short[first] or short[first - 1]:
            first += 1
            continue
        last = first  # vertices first .. last + 1, joined by the short edges first .. last
        while last + 1 < len(ell) and short[last + 1]:
            last += 1
        members = np.arange(first, last + 2)
        first = last + 1
        spread = np.linalg.norm(pts[members] - pts[members].mean(axis=0), axis=1).max()
        if last + 1 >= len(ell) or spread > SPARSE_EDGE_SIGMAS * tolerance:
            continue  # (up to an open run's end, or a dense stretch)
        together = abs(float(turn[members].sum()))
        beside = max(abs(float(turn[members[0] - 1])), abs(float(turn[members[-1] + 1])))
        if together > math.radians(corner_deg) and together > STANDS_OUT * beside:
            sharp = members[np.abs(turn[members]) > math.radians(corner_deg)]
            found += sharp.tolist() if len(sharp) else [int(members[np.argmax(np.abs(turn[members]))])]
    return found


def _dense_corners(pts: np.ndarray, closed: bool, corner_deg: float, tolerance: float) -> np.ndarray:
    """Corners by the rule for short edges (see detect_corners)."""
    edges = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    if float(np.median(edges)) >= SPARSE * tolerance:
        return _vertex_corners(pts, closed, corner_deg)
    s = np.concatenate(([0.0], np.cumsum(edges)))
    total = s[-1]
    w = max(3.0 * float(np.median(edges)), tolerance)
    n = len(pts) - 1 if closed else len(pts)
    idx = np.arange(n)
    if closed:
        ext_s = np.concatenate((s[:-1] - total, s, s[1:] + total))
        ext_p = np.vstack((pts[:-1], pts, pts[1:]))
    else:
        ext_s, ext_p = s, pts
        idx = idx[(s[:n] >= 3 * w) & (s[:n] <= total - 3 * w)]
    if len(idx) == 0 or 3 * w >= total / 4:
        return np.empty(0, dtype=int)
    here = pts[idx]

    def turn_within(width: float) -> np.ndarray:
        before = _point_at(ext_p, ext_s, s[idx] - width) - here
        after = _point_at(ext_p, ext_s, s[idx] + width) - here
        a_in = np.arctan2(-before[:, 1], -before[:, 0])
        a_out = np.arctan2(after[:, 1], after[:, 0])
        return np.abs(np.remainder(a_out - a_in + math.pi, 2 * math.pi) - math.pi)

    # A corner turns sharply at w and still at 3w: noise on single vertices does not persist
    # over the wider chords, a smooth bend does not turn enough within w.
    near, wide = turn_within(w), turn_within(3 * w)
    turn = np.minimum(near, wide)
    # ... and it is concentrated: a smooth bend keeps turning over the wider chords (three
    # times as much on a circle), a corner does not.
    hits = np.flatnonzero((turn > math.radians(corner_deg)) & (wide <= CONCENTRATED * near))
    vertex_turn = _vertex_turns(pts, closed)
    corners: list[int] = []
    for h in hits[np.argsort(-turn[hits], kind="stable")]:
        v = sharpest_near(s, vertex_turn, int(idx[h]), w, closed)
        if w > tolerance and not stands_out(vertex_turn, v, corner_deg, closed):
            continue  # ... and where the spacing sets w, a vertex there is sharp (see stands_out)
        if all(_arc_gap(s, v, c, total, closed) > 2 * w for c in corners):
            corners.append(v)
    return np.array(sorted(set(corners)), dtype=int)


def stands_out(vertex_turn: np.ndarray, v: int, corner_deg: float, closed: bool) -> bool:
    """Whether vertex v turns more than ``corner_deg`` or more than STANDS_OUT times either
    neighbour: a corner, or a corner rounded over a few vertices, is sharp at one; a bend the
    sampling resolves turns alike at neighbouring vertices, each a little. (Where the window w is
    σ, a bend turning that much within it is a corner at this tolerance however it is sampled:
    rounded within σ; where the spacing sets w, the chord test reads a tight bend beside a line —
    a raster's turn-around of radius 3.6 mm on points 0.5 mm apart at σ 0.5 — as a corner too.)"""
    last = len(vertex_turn) - 1
    before = vertex_turn[v - 1] if v > 0 else (vertex_turn[last - 1] if closed else 0.0)
    after = vertex_turn[v + 1] if v < last else (vertex_turn[1] if closed else 0.0)
    return bool(vertex_turn[v] > math.radians(corner_deg) or vertex_turn[v] > STANDS_OUT * max(before, after))


def _vertex_turns(pts: np.ndarray, closed: bool) -> np.ndarray:
    """|turn| (rad) at every vertex between its two edges (0 at the ends of an open curve)."""
    d = np.diff(pts, axis=0)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.zeros(len(pts))
    turn[1:-1] = np.abs(np.remainder(np.diff(heading) + math.pi, 2 * math.pi) - math.pi)
    if closed:
        turn[0] = turn[-1] = abs(math.remainder(heading[0] - heading[-1], 2 * math.pi))
    return turn


def sharpest_near(s: np.ndarray, vertex_turn: np.ndarray, v: int, w: float, closed: bool) -> int:
    """The vertex within w of vertex v that turns most (where a cusp or a sharp corner
    really is: the chord test ties along the stretch around it)."""
    total = s[-1]
    if closed:  # vertices 0 .. n-2, distances around the loop
        gap = np.abs(s[:-1] - s[v])
        near = np.flatnonzero(np.minimum(gap, total - gap) <= w)
    else:
        near = np.flatnonzero(np.abs(s - s[v]) <= w)
        near = near[(near > 0) & (near < len(s) - 1)]
    return int(near[np.argmax(vertex_turn[near])]) if len(near) else v


def _vertex_corners(pts: np.ndarray, closed: bool, corner_deg: float) -> np.ndarray:
    """Corners of a sparse polyline (edges much longer than the tolerance): there is nothing
    between its vertices to tell a bend from a corner, so each vertex turning by more than
    ``corner_deg`` is one."""
    d = np.diff(pts, axis=0)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.abs(np.remainder(heading - np.roll(heading, 1) + math.pi, 2 * math.pi) - math.pi)
    hits = np.flatnonzero(turn > math.radians(corner_deg))  # hit i: vertex i, between edges i-1 and i
    return hits if closed else hits[hits > 0]


def _arc_gap(s: np.ndarray, i: int, j: int, total: float, closed: bool) -> float:
    gap = abs(s[i] - s[j])
    return min(gap, total - gap) if closed else gap

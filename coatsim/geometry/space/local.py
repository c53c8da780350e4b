"""Local shape of a space curve: robust curvature, tangents and true corners.

The curvature is the planar envelope's windowed-means estimate (coatsim.geometry.envelope)
taken in space: the mean positions over three stretches of length w, centred at s − w, s and
s + w, and the angle between the two chords joining them, over w (exact on a circle for any w
below half its circumference). The tangent at a vertex is the derivative of a least-squares
quadratic through the points within ± w. A corner is, as in the plane
(coatsim.geometry.corners), a turn above ``corner_deg`` between the chords p(s − w) -> p(s)
and p(s) -> p(s + w) that persists over 3w and is concentrated (at most twice the turn at w),
with a sharp vertex near it where the spacing sets w (coatsim.geometry.corners.stands_out).
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.corners import CONCENTRATED, SPARSE, sharpest_near, stands_out
from coatsim.geometry.envelope import MAX_GRID, WINDOW_EDGES, WINDOW_SIGMAS, CurvatureProfile


def arc_length(points: np.ndarray) -> np.ndarray:
    return np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))))


def window_mm(points: np.ndarray, tolerance: float) -> float:
    edge = float(np.median(np.linalg.norm(np.diff(points, axis=0), axis=1)))
    return max(WINDOW_SIGMAS * tolerance, WINDOW_EDGES * edge)


def _unrolled(points: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray, float]:
    """(points, arc length, offset of the original start): a closed loop is laid out three
    times so that windows wrap around its seam."""
    if not closed:
        return points, arc_length(points), 0.0
    body = points[:-1]
    pts = np.vstack((body, body, body, body[:1]))
    s = arc_length(pts)
    return pts, s, s[len(body)]


def _interp(points: np.ndarray, s: np.ndarray, at: np.ndarray) -> np.ndarray:
    return np.column_stack([np.interp(at, s, points[:, k]) for k in range(points.shape[1])])


def curvature_profile3(points: np.ndarray, closed: bool, tolerance: float) -> CurvatureProfile:
    """|κ| (1/mm) of a space curve on a uniform grid of arc length (see the module text)."""
    pts, s, offset = _unrolled(np.asarray(points, dtype=float), closed)
    length = float(arc_length(points)[-1])
    window = min(window_mm(points, tolerance), length / 2 if closed else length / 3)
    step = max(window / 4, length / MAX_GRID)
    grid = np.linspace(0.0, length, int(math.floor(length / step)) + 1)
    step = float(grid[1] - grid[0]) if len(grid) > 1 else length
    d = np.diff(pts, axis=0)
    ell = np.linalg.norm(d, axis=1)
    area = np.vstack((np.zeros((1, 3)), np.cumsum(ell[:, None] * (pts[:-1] + pts[1:]) / 2, axis=0)))
    centre = grid + offset
    if not closed:
        centre = np.clip(centre, 1.5 * window, max(1.5 * window, length - 1.5 * window))

    def integral(at: np.ndarray) -> np.ndarray:
        at = np.clip(at, 0.0, s[-1])
        i = np.clip(np.searchsorted(s, at, side="right") - 1, 0, len(s) - 2)
        u = np.where(ell[i] > 0, (at - s[i]) / np.where(ell[i] > 0, ell[i], 1.0), 0.0)
        p = pts[i] + u[:, None] * (pts[i + 1] - pts[i])
        return area[i] + (at - s[i])[:, None] * (pts[i] + p) / 2

    def mean(at: np.ndarray) -> np.ndarray:
        lo, hi = np.clip(at - window / 2, 0.0, s[-1]), np.clip(at + window / 2, 0.0, s[-1])
        width = np.where(hi > lo, hi - lo, 1.0)
        return (integral(hi) - integral(lo)) / width[:, None]

    before, here, after = mean(centre - window), mean(centre), mean(centre + window)
    a, b = here - before, after - here
    turn = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
    return CurvatureProfile(turn / window, step, length, window, closed)


def tangent_at(points: np.ndarray, s: np.ndarray, i: int, window: float) -> np.ndarray:
    """Unit tangent at vertex ``i`` of a run: the derivative of a least-squares quadratic
    through the vertices within ± ``window`` (at least two on each side where there are)."""
    lo = min(int(np.searchsorted(s, s[i] - window)), max(0, i - 2))
    hi = max(int(np.searchsorted(s, s[i] + window, side="right")), min(len(s), i + 3))
    x = s[lo:hi] - s[i]
    scale = max(float(np.abs(x).max()), 1e-300)
    basis = np.column_stack((np.ones_like(x), x / scale, (x / scale) ** 2)) if len(x) > 2 else np.column_stack((np.ones_like(x), x / scale))
    coef = np.linalg.lstsq(basis, points[lo:hi], rcond=None)[0]
    t = coef[1]
    n = float(np.linalg.norm(t))
    if not n > 0:
        t = points[min(i + 1, len(points) - 1)] - points[max(i - 1, 0)]
        n = float(np.linalg.norm(t))
    return t / n


def detect_corners3(points: np.ndarray, closed: bool, corner_deg: float, tolerance: float) -> np.ndarray:
    """Indices of the vertices where the curve turns by more than ``corner_deg`` within
    w = max(3 median edges, σ) and still does over 3w, concentrated there (see the module
    text); detections within 2w collapse to the largest turn; an open curve's ends never are."""
    pts = np.asarray(points, dtype=float)
    edges = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    if float(np.median(edges)) >= SPARSE * tolerance:
        return _vertex_corners(pts, closed, corner_deg)
    w = max(3.0 * float(np.median(edges)), tolerance)
    ext, ext_s, offset = _unrolled(pts, closed)
    s = arc_length(pts)
    total = s[-1]
    n = len(pts) - 1 if closed else len(pts)
    idx = np.arange(n)
    if not closed:
        idx = idx[(s[:n] >= 3 * w) & (s[:n] <= total - 3 * w)]
    if len(idx) == 0 or 3 * w >= total / 4:
        return np.empty(0, dtype=int)
    here = pts[idx]
    at = s[idx] + offset

    def turn(width: float) -> np.ndarray:
        a = here - _interp(ext, ext_s, at - width)
        b = _interp(ext, ext_s, at + width) - here
        return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))

    near, wide = turn(w), turn(3 * w)
    limit = math.radians(corner_deg)
    hit = (near > limit) & (wide > limit) & (wide <= CONCENTRATED * near)
    vertex_turn = _vertex_turns3(pts, closed)
    found: list[int] = []
    for k in np.argsort(-near[hit], kind="stable"):
        i = int(idx[hit][k])
        if w > tolerance and not stands_out(vertex_turn, sharpest_near(s, vertex_turn, i, w, closed), corner_deg, closed):
            continue  # a tight bend the sampling resolves, beside a line: no corner (as in the plane)
        if all(min(abs(s[i] - s[j]), total - abs(s[i] - s[j]) if closed else math.inf) > 2 * w for j in found):
            found.append(i)
    return np.array(sorted(found), dtype=int)


def _vertex_corners(points: np.ndarray, closed: bool, corner_deg: float) -> np.ndarray:
    """The vertices of a sparse polyline where it turns by more than ``corner_deg``."""
    turn = _vertex_turns3(points, closed)
    return np.flatnonzero(turn[:-1] > math.radians(corner_deg) if closed else turn > math.radians(corner_deg))


def _vertex_turns3(points: np.ndarray, closed: bool) -> np.ndarray:
    """|turn| (rad) at every vertex between its two edges (0 at an open curve's ends; a closed
    one's seam at its first and last point)."""
    body = points[:-1] if closed else points
    before = body - np.roll(body, 1, axis=0)
    after = np.roll(body, -1, axis=0) - body
    turn = np.arctan2(np.linalg.norm(np.cross(before, after), axis=1), np.einsum("ij,ij->i", before, after))
    if closed:
        return np.append(turn, turn[0])
    turn[[0, -1]] = 0.0
    return turn

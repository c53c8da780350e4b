"""The robust local curvature of an input run, and its envelope: how tight the fit may turn.

The curvature at arc length s is estimated from three windowed means of the curve, each the
average position over a stretch of length w, centred at s - w, s and s + w: the turn between
the two chords joining them, over w. On a circle this is exact for any w below half the
circumference; on other curves it is the curvature smoothed over about 3w, and averaging over
the windows keeps digitising noise from spiking it. The window is a few σ, at least two input
edges, and wider where a noise estimate of the input asks for it.

The envelope is the largest |κ| within a neighbourhood: an arc of the fit may not be much
tighter than the input anywhere near the stretch it covers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

WINDOW_SIGMAS = 3.0  # the window is at least this many σ ...
WINDOW_EDGES = 1.0  # ... and at least one median input edge
NOISE_SHARE = 0.2  # noise may move the estimate by this share of the curve's typical |κ| (4 std)
MAX_GRID = 200_000  # estimate points per run, at most
SPARSE_EDGE_SIGMAS = 2.0  # a kink is a vertex between edges this many σ long, at least


@dataclass(frozen=True, eq=False)
class CurvatureProfile:
    """Signed curvature (1/mm) of one run on a uniform grid of arc length.

    ``kappa[i]`` is the estimate at ``s = i * step`` (mm); ``window_mm`` the window w;
    ``closed`` whether the run is a closed loop (the grid then wraps around).
    """

    kappa: np.ndarray
    step: float
    length: float
    window_mm: float
    closed: bool

    def envelope(self, neighbourhood_mm: float) -> np.ndarray:
        """|κ| maximised over ± ``neighbourhood_mm`` around every grid point."""
        from scipy.ndimage import maximum_filter1d

        size = 2 * int(math.ceil(neighbourhood_mm / self.step)) + 1
        return maximum_filter1d(np.abs(self.kappa), size, mode="wrap" if self.closed else "nearest")

    def spread(self, s: np.ndarray, values: np.ndarray, neighbourhood_mm: float) -> np.ndarray:
        """Grid of the largest of ``values`` (given at arc lengths ``s``) within
        ± ``neighbourhood_mm`` of every grid point (0 where there is none)."""
        from scipy.ndimage import maximum_filter1d

        grid = np.zeros(len(self.kappa))
        np.maximum.at(grid, np.clip(np.rint(s / self.step).astype(int), 0, len(grid) - 1), values)
        size = 2 * int(math.ceil(neighbourhood_mm / self.step)) + 1
        return maximum_filter1d(grid, size, mode="wrap" if self.closed else "nearest")

    def at(self, values: np.ndarray, s: np.ndarray) -> np.ndarray:
        """Grid ``values`` at arc lengths ``s`` (the nearest grid point)."""
        i = np.rint(np.asarray(s, dtype=float) / self.step).astype(int)
        return values[np.clip(i, 0, len(values) - 1)]

    def span_max(self, values: np.ndarray, s0: np.ndarray, s1: np.ndarray) -> np.ndarray:
        """Largest of ``values`` over each grid stretch [s0, s1] (arrays of equal shape)."""
        lo = np.clip(np.floor(np.asarray(s0) / self.step).astype(int), 0, len(values) - 1)
        hi = np.clip(np.ceil(np.asarray(s1) / self.step).astype(int), 0, len(values) - 1)
        return np.array([values[a : max(a, b) + 1].max() for a, b in zip(lo.ravel(), hi.ravel())]).reshape(np.shape(s0))

    @property
    def tightest_radius_mm(self) -> float:
        """1 / the largest |κ| (inf for a straight run: one turning less than 1e-6 rad over
        its whole length)."""
        top = float(np.abs(self.kappa).max()) if len(self.kappa) else 0.0
        return 1.0 / top if top * self.length > 1e-6 else math.inf


def _running_integral(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Arc length at each vertex (n,) and the integral of position over arc length (n, 2)."""
    d = np.diff(points, axis=0)
    ell = np.linalg.norm(d, axis=1)
    s = np.concatenate(([0.0], np.cumsum(ell)))
    area = np.vstack((np.zeros((1, 2)), np.cumsum(ell[:, None] * (points[:-1] + points[1:]) / 2, axis=0)))
    return s, area


def _integral_at(points: np.ndarray, s: np.ndarray, area: np.ndarray, at: np.ndarray) -> np.ndarray:
    """∫ p ds from 0 to each of ``at`` (clipped to the run), shape (m, 2)."""
    at = np.clip(at, 0.0, s[-1])
    i = np.clip(np.searchsorted(s, at, side="right") - 1, 0, len(s) - 2)
    ell = s[i + 1] - s[i]
    u = np.where(ell > 0, (at - s[i]) / np.where(ell > 0, ell, 1.0), 0.0)
    p = points[i] + u[:, None] * (points[i + 1] - points[i])
    return area[i] + (at - s[i])[:, None] * (points[i] + p) / 2


def _estimate(points: np.ndarray, closed: bool, window: float, grid: np.ndarray) -> np.ndarray:
    """Signed curvature at the grid positions from windowed means (see the module text)."""
    pts = points
    if closed:  # unroll one lap before and after, so windows wrap around the seam
        body = pts[:-1]
        pts = np.vstack((body, body, body, body[:1]))
    s, area = _running_integral(pts)
    total = s[-1] / 3 if closed else s[-1]
    offset = total if closed else 0.0
    centre = grid + offset
    if not closed:
        centre = np.clip(centre, 1.5 * window, max(1.5 * window, total - 1.5 * window))
    half = window / 2

    def mean(at: np.ndarray) -> np.ndarray:
        lo, hi = np.clip(at - half, 0.0, s[-1]), np.clip(at + half, 0.0, s[-1])
        width = np.where(hi > lo, hi - lo, 1.0)
        return (_integral_at(pts, s, area, hi) - _integral_at(pts, s, area, lo)) / width[:, None]

    before, here, after = mean(centre - window), mean(centre), mean(centre + window)
    a, b = here - before, after - here
    turn = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))
    return turn / window


def kink_demand(points: np.ndarray, closed: bool, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """Arc lengths (mm) of the input's kinks and the curvature (1/mm) each may ask of a
    chain within ``tolerance``: a vertex between two edges of at least 2 σ (sparse there:
    dense noisy input has no say) h > σ off the chord c of its neighbours makes the
    chain bulge by at least h − σ over about that chord (8 (h − σ) / c²) while it also
    keeps to both edges; twice that, but never more than the circle through the three
    vertices (8 h / c²). Smooth dense input has no such vertex (its offsets are far below
    σ), nor has noise below σ; sparse or kinked input has, and the windowed estimate
    smooths it away."""
    pts = np.asarray(points, dtype=float)
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
    if closed:  # every vertex of the loop, its neighbours across the seam
        before, here, after, at = np.roll(pts[:-1], 1, axis=0), pts[:-1], np.roll(pts[:-1], -1, axis=0), s[:-1]
    else:
        before, here, after, at = pts[:-2], pts[1:-1], pts[2:], s[1:-1]
    edges = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    shorter = np.minimum(edges, np.roll(edges, 1)) if closed else np.minimum(edges[1:], edges[:-1])
    chord = after - before
    c = np.linalg.norm(chord, axis=1)
    w = here - before
    with np.errstate(divide="ignore", invalid="ignore"):
        h = np.abs(w[:, 0] * chord[:, 1] - w[:, 1] * chord[:, 0]) / c
        kink = (c > 0) & (h > tolerance) & (shorter >= SPARSE_EDGE_SIGMAS * tolerance)
    h, c = h[kink], c[kink]
    return at[kink], np.minimum(16 * (h - tolerance), 8 * h) / c**2


def end_turning(points: np.ndarray, closed: bool, tolerance: float, window: float) -> tuple[np.ndarray, np.ndarray]:
    """Arc lengths (mm) of the vertices within 1.5 windows of an open run's ends and the
    curvature (1/mm) of the circle through each and its neighbours, where both its edges
    are at least 2 σ (sparse there; dense noisy input has no say). The windowed estimate
    cannot see there (its windows stop at the run's end), and a taught polygon that turns
    ever tighter into its end (a cusp taught with a few points) would get caps gentler than
    its own turning, which no chain within σ of its last edges keeps."""
    pts = np.asarray(points, dtype=float)
    if closed or len(pts) < 3:
        return np.empty(0), np.empty(0)
    ell = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate(([0.0], np.cumsum(ell)))
    a, b, c = pts[:-2], pts[1:-1], pts[2:]
    u, v = b - a, c - a
    cross = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    sides = ell[:-1] * ell[1:] * np.linalg.norm(v, axis=1)
    at = s[1:-1]
    near_end = (at < 1.5 * window) | (at > s[-1] - 1.5 * window)
    keep = near_end & (np.minimum(ell[:-1], ell[1:]) >= SPARSE_EDGE_SIGMAS * tolerance) & (sides > 0)
    return at[keep], 2 * cross[keep] / sides[keep]


def _offset_spread(points: np.ndarray) -> float:
    """Median |second difference| of the vertices' signed offsets from their neighbours' chord."""
    a, m, b = points[:-2], points[1:-1], points[2:]
    chord = b - a
    norm = np.linalg.norm(chord, axis=1)
    ok = norm > 0
    offset = np.zeros(len(m))
    offset[ok] = ((m - a)[ok, 0] * chord[ok, 1] - (m - a)[ok, 1] * chord[ok, 0]) / norm[ok]
    return float(np.median(np.abs(offset[2:] - 2 * offset[1:-1] + offset[:-2])))


def noise_mm(points: np.ndarray) -> float:
    """Robust estimate of the input's digitising noise (mm).

    The offsets of the vertices from their neighbours' chords, differenced twice, keep the
    noise and little of a smooth curve (for independent noise of std η their median absolute
    value is 0.674 · 3η). What remains of the curve grows 16-fold when every other vertex is
    used; noise does not, which separates the two.
    """
    if len(points) < 13:
        return 0.0
    one, two = _offset_spread(points), _offset_spread(points[::2])
    return math.sqrt(max(0.0, (256 * one**2 - two**2) / 255)) / (0.674 * 3.0)


def curvature_profile(points: np.ndarray, closed: bool, tolerance: float) -> CurvatureProfile:
    """The robust curvature of a run (a closed loop when ``closed``), at tolerance σ."""
    pts = np.asarray(points, dtype=float)
    ell = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    length = float(ell.sum())
    edge = float(np.median(ell))
    window = max(WINDOW_SIGMAS * tolerance, WINDOW_EDGES * edge)
    cap = length / 2 if closed else length / 3
    window = min(window, cap)
    step = max(window / 4, length / MAX_GRID)
    grid = np.linspace(0.0, length, int(math.floor(length / step)) + 1)
    step = float(grid[1] - grid[0]) if len(grid) > 1 else length
    kappa = _estimate(pts, closed, window, grid)
    eta = noise_mm(pts)
    # Noise of std η moves the estimate by about √6·η·√edge / w^2.5 (means over w / edge
    # vertices): widen the window until four of those are a small share of the typical |κ|.
    # Where the curve turns much tighter than is typical (a tight turn of a noisy curve), a
    # narrower window already meets that share of the |κ| there, and keeps the turn's
    # curvature instead of smoothing it away: each point keeps the narrowest window that does.
    narrow = np.full(len(grid), np.nan)
    while eta > 1e-9 * length and window < cap:
        error = 4 * math.sqrt(6) * eta * math.sqrt(edge) / window**2.5
        typical = float(np.percentile(np.abs(kappa), 90))
        if error <= NOISE_SHARE * max(typical, 1e-12):
            break
        settled = np.isnan(narrow) & (error <= NOISE_SHARE * np.abs(kappa))
        narrow[settled] = kappa[settled]
        window = min(cap, window * 1.5)
        kappa = _estimate(pts, closed, window, grid)
    kappa = np.where(np.isnan(narrow), kappa, narrow)
    return CurvatureProfile(kappa, step, length, window, closed)

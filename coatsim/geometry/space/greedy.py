"""The greedy 3-D arc fitter: the benchmark's baseline, and where the G1 fit takes its first knots.

From the current input point, the longest run of input points whose arc through its first,
middle and last point (a line when those are collinear) keeps every point of the run within
σ (doubling, then bisection); the next run starts where that one ends. The arcs meet at
input points with kinks at every junction: a chain a controller cannot follow without
stopping, but the fewest pieces a fitter without tangency finds this way.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from coatsim.geometry.space.primitives import DegenerateArc, Line3, arc_through


def arc_fits(points: np.ndarray, i: int, j: int, tolerance: float) -> bool:
    """Whether the arc through points i, (i + j) // 2 and j (a line when they are collinear)
    keeps every point from i to j within ``tolerance``."""
    if j - i < 2:
        return True
    try:
        seg = arc_through(points[i], points[(i + j) // 2], points[j])
    except DegenerateArc:
        seg = Line3(points[i], points[j])
    return float(seg.nearest(points[i : j + 1])[0].max()) <= tolerance


def farthest(i: int, n: int, fits: Callable[[int, int], bool]) -> int:
    """The farthest j (i < j <= n - 1) with ``fits(i, j)``, by doubling the step from i and
    then bisection (``fits`` taken as holding up to some j and not beyond)."""
    step, good, bad = 1, i + 1, None
    while True:
        j = min(n - 1, i + step)
        if not fits(i, j):
            bad = j
            break
        good = j
        if j == n - 1:
            break
        step *= 2
    if bad is not None:
        lo, hi = good, bad
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if fits(i, mid) else (lo, mid)
        good = lo
    return good


def greedy_knots(points: np.ndarray, tolerance: float) -> np.ndarray:
    """Indices of the input points where the greedy arcs meet, first and last included."""
    n, i, knots = len(points), 0, [0]
    while i < n - 1:
        i = farthest(i, n, lambda a, b: arc_fits(points, a, b, tolerance))
        knots.append(i)
    return np.array(knots)

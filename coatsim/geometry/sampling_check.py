"""Whether a point curve is sampled finely enough to be fitted, checked before the fit.

A curve drawn or sampled from a shape turns little from one chord to the next except at a few
corners. Random points, a sine sampled coarser than its wavelength or a spiral with more turns
than points double back (turn by more than 90°) at a large share of their points: there is no
shape between the points for the fitter to find, and its work on them grows without bound. The
count of such points is held to the budget ``curve_reversals`` (a saw blade of a thousand
teeth is within it).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from coatsim.core.budgets import check_budget, limit

REVERSAL_DEG = 90.0  # a turn of more than this between consecutive chords doubles back


def reversals(points: np.ndarray) -> int:
    """Interior points (n, d) of a polyline where the chord direction turns by more than
    ``REVERSAL_DEG`` (repeated points skipped)."""
    chords = np.diff(np.asarray(points, dtype=float), axis=0)
    chords = chords[np.any(chords != 0.0, axis=1)]
    if len(chords) < 2:
        return 0
    dots = np.einsum("ij,ij->i", chords[:-1], chords[1:])
    lengths = np.linalg.norm(chords, axis=1)
    return int(np.count_nonzero(dots < np.cos(np.radians(REVERSAL_DEG)) * lengths[:-1] * lengths[1:]))


def check_sampling(points: np.ndarray, name: str, hint: Callable[[], str] = lambda: "") -> None:
    """BudgetExceeded when the curve doubles back at more points than the budget
    ``curve_reversals``: its sampling is coarser than its own features (``hint``: more to say
    then, such as the noise found)."""
    count = reversals(points)
    share = count / max(len(points) - 2, 1)
    check_budget(f"{name}: points where the curve doubles back (turns by more than {REVERSAL_DEG:g}°: {share:.0%} of "
                 "its points; its sampling is coarser than its own features, such as random points, measurement "
                 "noise larger than the point spacing, a wave sampled more coarsely than its wavelength or more turns "
                 "than points)", count, "curve_reversals",
                 "smooth or thin out a noisy measured curve, sample the curve with several points per bend, or give "
                 f"fewer, larger features{hint() if not count <= limit('curve_reversals') else ''}")

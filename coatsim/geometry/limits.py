"""How tight and how short the fitted arcs of one run may be.

An arc may be at most ``TIGHTER`` times as tight as the input's robust curvature envelope
over the stretch it covers and a neighbourhood around it (coatsim.geometry.envelope), or
than the kinks of sparse input there force (kink_demand), or, near an open run's ends, than
the sparse polygon's own three-vertex circles (end_turning). Given a
programmed speed v and a tool acceleration limit a, where the input allows v (its envelope at
most a / v²) no arc may need more than a either (|κ| <= a / v²), and where the input needs a
tighter turn, no arc may be tighter than the input there. Every fitted segment but the only
one of a run is at least ``min_length_mm`` long (default: 5 σ, or 1/500 of the run if longer).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from coatsim.core.budgets import MAX_ABS_COORDINATE_MM
from coatsim.core.errors import InputError
from coatsim.geometry.envelope import CurvatureProfile, curvature_profile, end_turning, kink_demand

TIGHTER = 1.22  # an arc may be this much tighter than the input near it (1.25 with the fit's 2 % slack)
MIN_LENGTH_SIGMAS = 5.0  # the default shortest segment, in σ ...
MIN_LENGTH_SHARE = 1 / 500  # ... or this share of the run, if that is longer
NEIGHBOURHOOD_WINDOWS = 2.0  # the neighbourhood of a stretch: this many curvature windows


def check_min_segment(min_segment_mm: float | None) -> None:
    """InputError when a shortest segment is asked that is longer than any curve coatsim reads."""
    if min_segment_mm is not None and min_segment_mm > MAX_ABS_COORDINATE_MM:
        raise InputError(f"min_segment_mm: {min_segment_mm:g} mm is longer than any curve coatsim reads "
                         f"({MAX_ABS_COORDINATE_MM:g} mm); give a shorter one", parameters=("min_segment_mm",))


@dataclass(frozen=True, eq=False)
class FitLimits:
    """The limits of one run.

    ``near``: the input's |κ| maximised over a neighbourhood of every grid point of
    ``profile`` (1/mm); ``speed_kappa``: a / v² (1/mm) or None; ``floor``: the smallest cap
    any arc gets (1/mm); ``min_length_mm``: the shortest segment; ``loosen``: a factor on
    the curvature limits from the input (never on the speed's).
    """

    profile: CurvatureProfile
    near: np.ndarray
    speed_kappa: float | None
    floor: float
    min_length_mm: float
    loosen: float = 1.0

    @cached_property
    def cap(self) -> np.ndarray:
        """Largest |κ| of an arc covering each grid point (1/mm)."""
        cap = self.loosen * TIGHTER * self.near
        if self.speed_kappa is not None:
            cap = np.minimum(cap, np.maximum(self.speed_kappa, self.loosen * self.near))
        return cap

    def at_knots(self, s: np.ndarray) -> np.ndarray:
        """Cap of an arc covering each arc length ``s`` of the run (mm)."""
        return np.maximum(self.profile.at(self.cap, s), self.floor)

    def over(self, s0: np.ndarray, s1: np.ndarray) -> np.ndarray:
        """Cap of an arc covering each stretch [s0, s1] of the run (mm)."""
        return np.maximum(self.profile.span_max(self.cap, s0, s1), self.floor)

    def relaxed(self, factor: float) -> FitLimits:
        """The same limits with the input's curvature limits ``factor`` times as loose."""
        return replace(self, loosen=self.loosen * factor, floor=self.floor * factor)


def fit_limits(points: np.ndarray, closed_loop: bool, tolerance: float, min_length_mm: float | None,
               speed_kappa: float | None) -> FitLimits:
    """The limits of one run; ``speed_kappa`` = a / v² (1/mm) when the speed is given."""
    profile = curvature_profile(points, closed_loop, tolerance)
    min_length = max(MIN_LENGTH_SIGMAS * tolerance, MIN_LENGTH_SHARE * profile.length) if min_length_mm is None else min_length_mm
    neighbourhood = max(NEIGHBOURHOOD_WINDOWS * profile.window_mm, min_length)
    near = np.maximum(profile.envelope(neighbourhood), profile.spread(*kink_demand(points, closed_loop, tolerance), neighbourhood))
    # (a taught polygon's own turning where the estimate cannot see: arcs as tight as it, not TIGHTER)
    at, turning = end_turning(points, closed_loop, tolerance, profile.window_mm)
    near = np.maximum(near, profile.spread(at, turning / TIGHTER, neighbourhood))
    # An arc that bulges σ/8 from its chord over the whole run is as good as a line: the
    # floor keeps straight stretches (envelope ~ 0) from forbidding every curvature.
    floor = tolerance / max(profile.length, tolerance) ** 2
    if speed_kappa is not None:
        floor = min(floor, speed_kappa)
    return FitLimits(profile, near, speed_kappa, floor, min(min_length, profile.length))


def arc_excess(kappa: np.ndarray, length: np.ndarray, limits: FitLimits, total: float) -> float:
    """Largest |κ| / cap over a chain's segments, each mapped onto the run by its share of
    the chain's length (``total`` = run length, mm)."""
    ends = np.concatenate(([0.0], np.cumsum(length)))
    ends = ends / ends[-1] * total
    caps = limits.over(ends[:-1], ends[1:])
    return float(np.max(np.abs(kappa) / caps)) if len(kappa) else 0.0

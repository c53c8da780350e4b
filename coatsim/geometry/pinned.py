"""The planar fit of an open run whose end tangents are pinned: the paper's method (the default
fitter's run fit, coatsim.geometry.fit.fit_run) with the chain leaving its first point and/or
arriving at its last along given headings, so that it joins a fixed neighbour tangent-continuously
(a stretch in one principal plane meeting one in another along the axis both share)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.geometry.corners import corners_and_notes
from coatsim.geometry.degenerate import split_long_arcs
from coatsim.geometry.dynamics import curvature_limit
from coatsim.geometry.fit import fit_run
from coatsim.geometry.limits import fit_limits
from coatsim.geometry.primitives import Segment

HEADING_TOL_RAD = 1e-9  # a pinned end whose heading is further off was not kept (the fillet fallback)


@dataclass(frozen=True, eq=False)
class PinnedFit:
    """The chain of the run, its verified deviation (mm), the input's tightest radius (mm, None
    when straight) and whether the run's curvature caps and minimum length were kept."""

    segments: tuple[Segment, ...]
    deviation_mm: float
    input_min_radius_mm: float | None
    limits_kept: bool


def _off(heading: float, wanted: float) -> float:
    return abs(math.remainder(heading - wanted, 2.0 * math.pi))


def fit_pinned(points: np.ndarray, tolerance: float, start_heading: float | None, end_heading: float | None,
               corner_deg: float, min_segment_mm: float | None, speed_mm_s: float | None,
               tool_accel_mm_s2: float | None) -> PinnedFit | None:
    """The G1 chain within ``tolerance`` of the open run ``points`` (n, 2) leaving along
    ``start_heading`` and arriving along ``end_heading`` (rad; None: free), or None when the run
    has a true corner or no chain keeping the pins was found within ``tolerance``."""
    pts = np.asarray(points, dtype=float)
    if start_heading is None and end_heading is None:
        raise ValueError("fit_pinned needs at least one pinned heading")
    corners, _ = corners_and_notes(pts, False, corner_deg, tolerance)
    if len(corners):
        return None
    backwards = start_heading is None  # only the end pinned: fit the reversed run with its start pinned
    run = pts[::-1] if backwards else pts
    first = end_heading + math.pi if backwards else start_heading
    last = None if backwards else end_heading
    limits = fit_limits(run, False, tolerance, min_segment_mm, curvature_limit(speed_mm_s, tool_accel_mm_s2))
    found = fit_run(run, tolerance, False, limits, fillet=min_segment_mm is None, start_heading=first, end_heading=last)
    segments = found.segments
    if found.corners or found.deviation_mm > tolerance or _off(segments[0].start_heading, first) > HEADING_TOL_RAD \
            or (last is not None and _off(segments[-1].end_heading, last) > HEADING_TOL_RAD):
        return None
    if backwards:
        segments = tuple(s.reversed() for s in reversed(segments))
    radius = limits.profile.tightest_radius_mm
    return PinnedFit(split_long_arcs(segments), found.deviation_mm, radius if math.isfinite(radius) else None,
                     found.limits_kept)

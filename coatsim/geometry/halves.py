"""An open sparse run that no one chain follows, fitted in two halves joined tangent-continuously.

The band fit looks for one chain along a whole taught run; on a long jittered run it can fail
where each half fits easily (a log spiral taught with 20 points: no chain of the 19 moves,
3 arcs for the first 10 and 2 for the rest). So the run is cut in the middle of an edge of its
middle third, the one whose end vertices a chain passes closest, and the halves are fitted
with the same tangent there (_Run.joints: along the edge, else the first half's free end), so
the chain stays G1; the run's pinned end tangents stay pinned. Each half that fails is cut again
the same way; a joint where a half's own lines had to be kept is a corner. The halves are kept
only where they need fewer segments than the run's own lines (sparse.taught_lines).

A taught loop no chain follows keeps its lines (coatsim.geometry.segment): cut in halves at its
first point, taught ellipses closed with a corner there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Iterator

import numpy as np

from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.limits import FitLimits, fit_limits
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.run_fit import RunFit
from coatsim.geometry.sparse import rounding_error, taught_lines

MIN_SPLIT_MOVES = 6  # a run is cut in halves only when each half keeps at least 3 moves
JOINT_RAD = 1e-9  # tangents this close at a joint are continuous

# fit.fit_run: (points, tolerance, closed_loop, limits, *, fillet, start_heading, end_heading)
RunFitter = Callable[..., RunFit]


@dataclass(frozen=True, eq=False)
class _Run:
    """A run to cut at the middle of its edge ``edge`` (from vertex edge to edge + 1), what
    fits its halves, and its pinned end tangents."""

    pts: np.ndarray
    edge: int
    tolerance: float
    limits: FitLimits
    fit: RunFitter
    fillet: bool
    start_heading: float | None
    end_heading: float | None

    @property
    def middle(self) -> np.ndarray:
        """The cut: the middle of the edge (mm)."""
        return (self.pts[self.edge] + self.pts[self.edge + 1]) / 2

    def head(self, start: float | None, end: float | None) -> RunFit:
        """The first half's fit, to the cut, its end tangents pinned where given."""
        return self._part(np.vstack((self.pts[:self.edge + 1], self.middle)), start, end)

    def tail(self, start: float | None, end: float | None) -> RunFit:
        """The second half's fit, from the cut, its end tangents pinned where given."""
        return self._part(np.vstack((self.middle, self.pts[self.edge + 1:])), start, end)

    def joints(self) -> Iterator[tuple[RunFit, RunFit]]:
        """The halves' fits, joined: both along the edge at its middle (where a smooth curve
        through the vertices runs parallel to it); else the first half free at its end and the
        second pinned to it."""
        d = self.pts[self.edge + 1] - self.pts[self.edge]
        along = math.atan2(d[1], d[0])
        yield self.head(self.start_heading, along), self.tail(along, self.end_heading)
        first = self.head(self.start_heading, None)
        yield first, self.tail(first.segments[-1].end_heading, self.end_heading)

    def _part(self, pts: np.ndarray, start: float | None, end: float | None) -> RunFit:
        """One half, an open run under its own curvature caps (the whole run's minimum length
        and speed), its end tangents pinned where given (only the end: the reversed half's start)."""
        if start is None and end is not None:
            return self._part(pts[::-1], end + math.pi, None).reversed()
        own = fit_limits(pts, False, self.tolerance, self.limits.min_length_mm, self.limits.speed_kappa)
        return self.fit(pts, self.tolerance, False, own, fillet=self.fillet, start_heading=start, end_heading=end)


def in_halves(points: np.ndarray, tolerance: float, limits: FitLimits, fit: RunFitter,
              fillet: bool = True, start_heading: float | None = None, end_heading: float | None = None) -> RunFit:
    """The open run in two halves fitted with ``fit`` (fit.fit_run), joined as smoothly as they
    fit (fewest corners, then fewest segments), or its own lines where those need no more
    segments or the run is too short to cut."""
    pts = np.asarray(points, dtype=float)
    lines = taught_lines(pts, False, tolerance)
    if len(pts) - 1 < MIN_SPLIT_MOVES:
        return lines
    run = _Run(pts, _calm_edge(pts), tolerance, limits, fit, fillet, start_heading, end_heading)
    best: RunFit | None = None
    for first, second in run.joints():
        candidate = _joined(first, second)
        if best is None or (len(candidate.corners), len(candidate.segments)) < (len(best.corners), len(best.segments)):
            best = candidate
        if not best.corners:
            break
    if len(best.segments) >= len(lines.segments):
        return lines
    return RunFit(best.segments, hausdorff(pts, Polysegment(best.segments)).hausdorff,
                  best.limits_kept, best.corners, best.notes)


def _calm_edge(pts: np.ndarray) -> int:
    """The edge of the run's middle third whose middle a chain passes closest: the one whose
    end vertices turn least (their rounding errors summed); the halves meet there exactly."""
    moves = len(pts) - 1
    error = rounding_error(pts, False)
    middle = np.arange(moves // 3, moves - moves // 3)
    return int(middle[np.argmin(error[middle] + error[middle + 1])])


def _joined(first: RunFit, second: RunFit) -> RunFit:
    """The two halves' chain (deviation not measured), a corner where the joint is not G1."""
    segments = first.segments + second.segments
    corners = list(first.corners) + [len(first.segments) + k for k in second.corners]
    if not _same(second.segments[0].start_heading, first.segments[-1].end_heading):
        corners.append(len(first.segments) - 1)
    return RunFit(segments, math.nan, first.limits_kept and second.limits_kept, tuple(sorted(set(corners))),
                  first.notes + second.notes)


def _same(a: float, b: float) -> bool:
    return abs(math.remainder(a - b, 2 * math.pi)) <= JOINT_RAD

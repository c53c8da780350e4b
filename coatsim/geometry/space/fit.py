"""The 3-D fitter of a run between corners: a greedy chain of spatial biarcs through the input.

Knots are input vertices with the curve's own tangent there (coatsim.geometry.space.local);
from the current knot the fitter takes the farthest next knot (doubling, then bisection)
whose biarc (over a few junction ratios, the best kept) stays within the working tolerance
of the input points it spans, keeps every arc within the curvature cap of the stretch it
covers (coatsim.geometry.limits: the input's own curvature near it, the speed's) and no
shorter than the minimum segment length. Every knot carries the curve's point and tangent,
so the chain is G1 at every knot and every biarc junction, and errors do not accumulate.
Where no such biarc leaves a knot (sparse or noisy input turning faster than its own curvature
envelope allows an arc to, a stretch that doubles back), the longest line within the
tolerance does: a line never breaks a limit, and its ends are corners where the tangents
differ (the next biarc leaves along the line if it can), never an arc tighter than allowed.
Afterwards collinear lines and co-circular arcs are merged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from coatsim.geometry.limits import FitLimits
from coatsim.geometry.space.biarc import biarc
from coatsim.geometry.space.local import arc_length, tangent_at
from coatsim.geometry.space.nearest import edge_distance
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3

RATIOS = (1.0, 0.5, 2.0)  # junction ratios β/α tried per biarc
BIARC_PROBES = 9  # points along each arc checked against the input stretch while fitting
MERGE_TOL = 1e-9  # lines this collinear, arcs this co-circular (relative) merge


@dataclass(frozen=True)
class RunChain:
    """A run's segments, whether every arc kept its cap and minimum length, and the chain's
    certified deviation from the run (mm) when it is known."""

    segments: tuple[Segment3, ...]
    limits_kept: bool
    deviation_mm: float | None = None


class _Run:
    """One run of input points with its arc lengths, tangents (cached) and limits."""

    def __init__(self, points: np.ndarray, tol: float, limits: FitLimits, window: float,
                 start_tangent: np.ndarray | None, end_tangent: np.ndarray | None):
        self.p, self.tol, self.limits, self.window = points, tol, limits, window
        self.s = arc_length(points)
        self.tangents: dict[int, np.ndarray] = {}
        if start_tangent is not None:
            self.tangents[0] = start_tangent
        if end_tangent is not None:
            self.tangents[len(points) - 1] = end_tangent

    def tangent(self, i: int) -> np.ndarray:
        if i not in self.tangents:
            self.tangents[i] = tangent_at(self.p, self.s, i, self.window)
        return self.tangents[i]

    def best_biarc(self, i: int, j: int, start: np.ndarray | None = None) -> tuple[float, tuple[Segment3, ...]] | None:
        """The biarc from knot i (leaving along ``start``, the curve's tangent by default) to
        knot j with the smallest deviation within tolerance, the caps and the minimum length,
        with that deviation."""
        best = None
        t0 = self.tangent(i) if start is None else start
        for ratio in RATIOS:
            pair = biarc(self.p[i], t0, self.p[j], self.tangent(j), ratio)
            if pair is None or not self._within_limits(pair, i, j):
                continue
            dev = self.deviation(pair, i, j)
            if dev <= self.tol and (best is None or dev < best[0]):
                best = (dev, pair)
        return best

    def _within_limits(self, pair: tuple[Segment3, ...], i: int, j: int) -> bool:
        lengths = np.array([seg.length for seg in pair])
        if lengths.sum() <= 0:
            return False
        ends = self.s[i] + np.concatenate(([0.0], np.cumsum(lengths))) / lengths.sum() * (self.s[j] - self.s[i])
        caps = self.limits.over(ends[:-1], ends[1:])
        kappa = np.array([seg.curvature for seg in pair])
        short = (lengths < self.limits.min_length_mm) & (lengths < lengths.sum())
        return bool(np.all(kappa <= caps * (1 + 1e-9)) and not (short & (kappa > 0)).any())

    def deviation(self, pair: tuple[Segment3, ...], i: int, j: int) -> float:
        """Largest distance of the input points i..j to the biarc and of probe points of the
        biarc to the input edges i..j (the exact check of the whole chain comes later)."""
        pts = self.p[i : j + 1]
        to_chain = np.min(np.stack([seg.nearest(pts)[0] for seg in pair]), axis=0).max()
        if to_chain > self.tol:
            return float(to_chain)
        probes = np.vstack([seg.points(np.linspace(0.0, seg.length, BIARC_PROBES)[1:-1]) for seg in pair])
        edges = np.arange(i, j)
        d = np.min(edge_distance(np.repeat(probes, len(edges), axis=0), self.p, np.tile(edges, len(probes)))
                   .reshape(len(probes), len(edges)), axis=1)
        return float(max(to_chain, d.max()))


def _farthest(run: _Run, i: int, fits: Callable[[int], tuple[Segment3, ...] | None],
              first: int) -> tuple[int, tuple[Segment3, ...]] | None:
    """The farthest knot j >= ``first`` that ``fits`` reaches from knot i: doubling the span,
    then bisection."""
    n = len(run.p)
    first = min(max(first, i + 1), n - 1)
    good: tuple[int, tuple[Segment3, ...]] | None = None
    step, bad = 1, None
    while True:
        j = min(n - 1, first + step - 1)
        found = fits(j)
        if found is None:
            bad = j
            break
        good = (j, found)
        if j == n - 1:
            return good
        step *= 2
    lo = good[0] if good else i
    while bad - lo > 1:
        mid = (lo + bad) // 2
        found = fits(mid)
        if found is None:
            bad = mid
        else:
            lo, good = mid, (mid, found)
    return good


def _biarc_to(run: _Run, i: int, start: np.ndarray | None) -> tuple[int, tuple[Segment3, ...]] | None:
    """The farthest knot one honest biarc reaches from knot i, from the first at least two
    minimum lengths away (shorter biarcs cannot keep it)."""
    first = int(np.searchsorted(run.s, run.s[i] + 2 * run.limits.min_length_mm))

    def fits(j: int) -> tuple[Segment3, ...] | None:
        found = run.best_biarc(i, j, start)
        return None if found is None else found[1]
    return _farthest(run, i, fits, first)


def _line_to(run: _Run, i: int) -> tuple[int, tuple[Segment3, ...]]:
    """The farthest knot a line from knot i reaches within tolerance (the next one at least:
    the chord to a neighbour is the input's own edge)."""
    def fits(j: int) -> tuple[Segment3, ...] | None:
        line = (Line3(run.p[i], run.p[j]),)
        return line if j == i + 1 or run.deviation(line, i, j) <= run.tol else None
    return _farthest(run, i, fits, i + 1)  # type: ignore[return-value]


def fit_run3(points: np.ndarray, tol: float, limits: FitLimits, window: float,
             start_tangent: np.ndarray | None = None, end_tangent: np.ndarray | None = None) -> RunChain:
    """A chain of lines and arcs through a run of input points (n, 3) within about ``tol``
    (the caller certifies it exactly) whose every arc keeps the limits; where no such biarc
    leaves a knot, the longest line within ``tol`` does, with a corner at each of its ends
    unless the tangents agree (a line is always honest). ``start_tangent``/``end_tangent``
    pin the tangents at the run's ends (a closed loop's seam)."""
    run = _Run(points, tol, limits, window, start_tangent, end_tangent)
    segments: list[Segment3] = []
    i, arriving = 0, None  # arriving: the direction of a line that ended at knot i
    while i < len(points) - 1:
        found = _biarc_to(run, i, arriving) if arriving is not None else None
        found = found or _biarc_to(run, i, None)
        arriving = None
        if found is None:
            found = _line_to(run, i)
            arriving = found[1][0].direction
        j, pair = found
        segments.extend(seg for seg in pair if seg.length > 0)
        i = j
    return RunChain(merge_segments(tuple(segments)), True)


def merge_segments(segments: tuple[Segment3, ...]) -> tuple[Segment3, ...]:
    """Consecutive collinear lines, and consecutive arcs of one circle turning the same way,
    as one segment each."""
    out: list[Segment3] = []
    for seg in segments:
        prev = out[-1] if out else None
        if isinstance(seg, Line3) and isinstance(prev, Line3):
            if np.linalg.norm(np.cross(prev.direction, seg.direction)) <= MERGE_TOL and prev.direction @ seg.direction > 0:
                out[-1] = Line3(prev.start, seg.end)
                continue
        if isinstance(seg, Arc3) and isinstance(prev, Arc3):
            scale = MERGE_TOL * max(1.0, prev.radius)
            same = (np.linalg.norm(prev.center - seg.center) <= scale and abs(prev.radius - seg.radius) <= scale
                    and np.linalg.norm(prev.normal - seg.normal) <= MERGE_TOL)
            if same and prev.sweep + seg.sweep <= math.pi:
                out[-1] = Arc3(prev.start, seg.end, prev.center, prev.normal, prev.radius, prev.sweep + seg.sweep)
                continue
        out.append(seg)
    return tuple(out)

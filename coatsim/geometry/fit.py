"""The default fitter: guaranteed-tolerance G1 arc/line chains with few, honest segments.

Per run of the curve between true corners (or the whole closed loop):
1. a greedy C1 piecewise-quadratic fit of the integrated heading inside a band (band_fit),
   under the run's curvature caps and minimum segment length (limits),
2. a minimax refinement of the chain in its (heading, curvature, length) parameters that
   also pins the run's end point (and closes a loop with its start heading), under the same
   limits (refine),
3. the exact two-sided Hausdorff check (deviation) and the check of the limits; if either
   fails, the band fit is repeated with its states re-measured on the real arcs, then with a
   narrower band,
4. if the refined deviation is just above σ, the worst segment is split in two instead,
5. if no chain keeps the limits, chains within a fraction of σ are tried, then (dense runs)
   looser caps, and as the last resort fillets at every vertex; a sparse run (taught points,
   coatsim.geometry.sparse) is band-fitted along its guide and, where even that finds no
   chain, an open one in halves joined G1 (coatsim.geometry.halves), each half again the same
   way; a loop, and what no half follows, comes back as its own lines with a note, never as
   arcs tighter than it turns.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.progress import check_time
from coatsim.geometry.band_fit import BandProblem, BandStuck, fit_band
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fillet import fillet_chain
from coatsim.geometry.halves import in_halves
from coatsim.geometry.limits import MIN_LENGTH_SIGMAS, FitLimits, arc_excess, fit_limits
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.primitives import Line, Segment, snap_end
from coatsim.geometry.recover import recover_exact
from coatsim.geometry.refine import (ChainParams, close_exactly, lateral_residuals, refine_chain, split_segment,
                                     worst_segment)
from coatsim.geometry.run_fit import RunFit
from coatsim.geometry.simpler import fewer, straightened
from coatsim.geometry.sparse import guide as sparse_guide, is_sparse, own_radius, simplified, taught_lines

MAX_ATTEMPTS = 20
PIN_RAD = 1e-9  # a pinned end tangent is kept to this (rad)
SLACK = 0.02  # caps and minimum length hold to this share (the stretch a segment covers is mapped by length)
NARROWER = (0.5, 0.25)  # then fits within these shares of the tolerance, under their own caps
RELAX = (1.5, 3.0)  # then caps loosened by these factors
SPARSE_RELAX = 1.25  # taught points get caps loosened by this factor (with arcs no tighter than they turn)
RELAXED_ATTEMPTS = 8  # attempts granted to each of those tries
QUICK_ATTEMPTS = 4  # attempts of a quick try (a closed loop fitted from its first point)
SPLIT_BELOW = 1.0  # a run whose refined deviation is this close to σ gets one more joint,
MAX_SPLITS = 2  # up to this many times before the band narrows instead
TARGET = 0.98  # refine until the sampled deviation is this fraction of σ
NEAR_MISS = 1.2  # a chain within this many σ with fewer segments than the first within σ is worth ...
NEAR_RETRIES = 3  # ... up to this many more band fits narrowed from its band (_constrained)
BAND_KNOTS = 100_000  # the band fit sees at most about this many points of a run


def total_turn(points: np.ndarray) -> float:
    """Total signed turning (rad) of a closed polyline, a multiple of 2π."""
    d = np.diff(points, axis=0)
    h = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    closing = math.remainder(h[0] - h[-1], 2 * math.pi)
    return float(h[-1] - h[0] + closing)


def build_chain(start: np.ndarray, p: ChainParams, end: np.ndarray) -> tuple[Segment, ...]:
    """Segments of the chain with the last end point snapped exactly onto ``end``."""
    return snap_end(chain((float(start[0]), float(start[1])), p.heading, p.kappa, p.length), end)


def _params_from_band(prob: BandProblem, ref: float, slope: float, pieces) -> ChainParams:
    kappa = np.array([p.kappa for p in pieces])
    length = np.array([p.length for p in pieces])
    return ChainParams(ref + slope, kappa, length)


def _near_chord(pts: np.ndarray, tolerance: float) -> bool:
    """Whether every point is within ``tolerance`` of the line through the end points, and
    the points run along it without turning back by more than ``tolerance``."""
    chord = pts[-1] - pts[0]
    norm = float(np.linalg.norm(chord))
    if norm == 0.0:
        return False
    rel = pts - pts[0]
    offset = rel @ np.array([-chord[1], chord[0]]) / norm
    along = rel @ chord / norm
    back = np.maximum.accumulate(along) - along
    return bool(np.abs(offset).max() <= tolerance and back.max() <= tolerance)


def _honest(params: ChainParams, limits: FitLimits, total: float) -> bool:
    """Whether every curvature is under its stretch's cap and every length at least the
    minimum (a run of one segment may be shorter)."""
    if len(params.length) > 1 and params.length.min() < (1 - SLACK) * limits.min_length_mm:
        return False
    return arc_excess(params.kappa, params.length, limits, total) <= 1 + SLACK


def _pinned_turn(pts: np.ndarray, start_heading: float, end_heading: float) -> float:
    """The turning (rad) from ``start_heading`` to ``end_heading`` nearest the polyline's own."""
    d = np.diff(pts, axis=0)
    h = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    return float(h[-1] - h[0]) + math.remainder(float(h[0]) - start_heading, 2 * math.pi) \
        + math.remainder(end_heading - float(h[-1]), 2 * math.pi)


def _pins_kept(segs: tuple[Segment, ...], start_heading: float | None, end_heading: float | None) -> bool:
    """Whether a chain starts and ends on the pinned tangents (to round-off)."""
    ok = start_heading is None or abs(math.remainder(segs[0].start_heading - start_heading, 2 * math.pi)) <= PIN_RAD
    return ok and (end_heading is None or abs(math.remainder(segs[-1].end_heading - end_heading, 2 * math.pi)) <= PIN_RAD)


@dataclass(frozen=True, eq=False)
class _Target:
    """What the chains of one run are refined against and checked on: the run's points
    ``pts``, the samples the refinement measures (``measured``: the points, or a sparse
    run's points along its edges), the start and end points, the total turn (loops and
    pinned ends), the direction a sparse loop's start may slide along, the caps, the run's
    length and tolerance, and the pinned end tangents."""

    pts: np.ndarray
    measured: np.ndarray
    start: np.ndarray
    end: np.ndarray
    turn: float | None
    slide: np.ndarray | None
    limits: FitLimits
    total: float
    tolerance: float
    closed_loop: bool
    start_heading: float | None
    end_heading: float | None

    def settle(self, params: ChainParams, target: float, hopeless: float = math.inf,
               lines: np.ndarray | None = None) -> tuple[ChainParams, float, tuple[Segment, ...], bool, float]:
        """Refine, close and build a chain (the segments of ``lines`` kept straight):
        (parameters, sampled deviation, segments, whether it keeps the caps and pins, exact
        deviation (inf when it does not, or when the sampled one is above ``hopeless``: the
        exact check is the costly part; the refinement stops where it stalls above it)."""
        params, sampled = refine_chain(self.start, params, self.measured, self.end, self.turn, self.limits, target,
                                       fixed_heading=self.start_heading is not None, closed_loop=self.closed_loop,
                                       slide=self.slide, slide_mm=self.tolerance, stall_above=hopeless, lines=lines)
        origin = self.origin(params)
        end = origin if self.slide is not None else self.end
        params = close_exactly(origin, params, end, self.turn, lines)
        segs = build_chain(origin, params, end)
        honest = _honest(params, self.limits, self.total) and _pins_kept(segs, self.start_heading, self.end_heading)
        dev = hausdorff(self.pts, Polysegment(segs)).hausdorff if honest and sampled <= hopeless else math.inf
        return params, sampled, segs, honest, dev

    def sampled(self, params: ChainParams) -> float:
        """The largest lateral distance (mm) of the measured samples from the chain of
        ``params`` as it is (refine's measure, without refining)."""
        return float(np.abs(lateral_residuals(self.origin(params), params, self.measured, self._fractions)).max())

    @cached_property
    def _fractions(self) -> np.ndarray:
        """Each measured sample's share of the measured polyline's length (refine's pairing)."""
        seg = np.linalg.norm(np.diff(self.measured, axis=0), axis=1)
        return np.concatenate(([0.0], np.cumsum(seg))) / seg.sum()

    def origin(self, params: ChainParams) -> np.ndarray:
        """Where the chain of ``params`` starts."""
        return self.start if self.slide is None else self.start + params.shift * self.slide


def _constrained(pts: np.ndarray, tolerance: float, closed_loop: bool, limits: FitLimits,
                 budget: list[int], start_heading: float | None = None,
                 end_heading: float | None = None) -> tuple[tuple[Segment, ...], float] | None:
    """Band fit, refinement and the exact check under ``limits``; None if no chain within
    ``tolerance`` is found within the attempt ``budget`` (a shared one-element counter).
    ``start_heading`` (and then optionally ``end_heading``) pin the chain's end tangents.
    A sparse run is band-fitted along its guide (coatsim.geometry.sparse), a sparse loop
    starts in the channel of its first vertex, and a sparse run's chain gives up every
    junction it can and runs straight where its points do (coatsim.geometry.simpler); a
    sparse run whose chain needs more segments than it has moves gets none (its own lines
    follow it with fewer). Where an honest chain of fewer segments missed by a little
    (NEAR_MISS) before the first one within, a few more bands narrowed from its band are
    tried (NEAR_RETRIES) and the fewest segments within win."""
    total = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    turn = total_turn(pts) if closed_loop else None
    if start_heading is not None and end_heading is not None:
        turn = _pinned_turn(pts, start_heading, end_heading)
    path = sparse_guide(pts, closed_loop, tolerance, limits)
    if path is None:
        tgt = _Target(pts, pts, pts[0], pts[-1], turn, None, limits, total, tolerance, closed_loop,
                      start_heading, end_heading)
        prob, ref = BandProblem.from_points(_band_knots(pts), limits)
    else:
        start = path.points[0]
        tgt = _Target(pts, path.edges, start, start if closed_loop else pts[-1], turn,
                      path.slide if closed_loop else None, limits, total, tolerance, closed_loop,
                      start_heading, end_heading)
        prob, ref = BandProblem.from_points(path.points, limits, path.width, total)
    pinned_slope = None if start_heading is None else math.remainder(start_heading - ref, 2 * math.pi)
    band, target = tolerance, TARGET * tolerance
    params: ChainParams | None = None
    splits, landed, shrink, at_start = 0, False, 0.9, 0
    tried: dict[tuple[bytes, float, float], tuple] = {}  # a chain refined before (band fits often repeat one) is not again
    best: tuple[tuple[Segment, ...], float] | None = None  # the fewest segments within tolerance so far
    near: tuple[int, float, float] | None = None  # an honest near miss with fewer: (segments, band, deviation)
    retries = 0
    while budget[0] > 0:
        budget[0] -= 1
        check_time("fitting the curve")  # the budget seconds bounds a slow fit (coatsim.core.progress)
        if params is None:
            try:
                slope, pieces = fit_band(prob, ref, band, start_slope=pinned_slope, end_turn=turn, landed=landed)
            except BandStuck as stuck:
                at_start = at_start + 1 if stuck.knot == 0 else 0
                if at_start >= 3:
                    return None  # no first piece fits these bands: narrower ones fit none either
                band *= shrink if landed else 0.7
                landed = False
                continue
            params = _params_from_band(prob, ref, slope, pieces)
        key = (params.vector().tobytes(), params.shift, target)
        if key not in tried:
            tried[key] = tgt.settle(params, target)
        params, sampled, segs, honest, dev = tried[key]
        if path is None and honest and tolerance < dev <= NEAR_MISS * tolerance and (near is None or len(segs) < near[0]):
            near = (len(segs), band, dev)
        if dev <= tolerance and honest:
            if path is None:
                if best is None or len(segs) < len(best[0]):
                    best = (segs, dev)
                if near is None or len(best[0]) <= near[0] or retries >= NEAR_RETRIES:
                    return best
                # fewer segments missed by little (the flower r = 30 + 8 cos 5θ at σ 0.5: 21 at 1.04 σ, then
                # 30 within): a band narrowed from that miss's, unlanded, may fit as few
                retries += 1
                band = near[1] * float(np.clip(0.97 * tolerance / near[2], 0.5, 0.95))
                near = (near[0], band, tolerance)
                params, landed, splits = None, False, 0
                continue
            simple = straightened(tgt, fewer(tgt, params, segs, dev, TARGET * tolerance), TARGET * tolerance)
            return simple[1:] if len(simple[1]) < len(pts) else None  # more arcs than taught moves cut none
        if honest and sampled <= target:
            # The samples met the target but the exact check did not (chords of the input
            # cut inside the chain): aim lower with the same segments.
            target *= 0.99 * tolerance / dev
        elif (honest and (sampled < SPLIT_BELOW * tolerance or len(params.length) == 1) and splits < MAX_SPLITS
              and _splittable(params, tgt.origin(params), tgt.measured, limits)):
            # (one refined segment is the best single arc: no narrower band makes it fit)
            params = split_segment(params, worst_segment(tgt.origin(params), params, tgt.measured))
            splits += 1
        else:
            # A new band fit: the same band with states re-measured on the real arcs, then
            # a band narrower by what the deviation asks for.
            shrink = float(np.clip(0.97 * tolerance / dev, 0.5, 0.95)) if honest else 0.9
            single = len(params.length) == 1 and splits == 0  # re-measuring one piece changes nothing
            if landed or single:
                band *= shrink
            splits, params, landed = 0, None, not landed and not single
    return best


def _band_knots(pts: np.ndarray) -> np.ndarray:
    """The points the band fit works on: all of them up to BAND_KNOTS, else every k-th one
    (and the last), so its cost stays linear; the refinement and the exact check see all."""
    step = -(-len(pts) // BAND_KNOTS)
    if step == 1:
        return pts
    return np.vstack((pts[:-1:step], pts[-1:]))


def _splittable(params: ChainParams, start: np.ndarray, pts: np.ndarray, limits: FitLimits) -> bool:
    """Whether the worst segment is long enough to be cut in two."""
    return params.length[worst_segment(start, params, pts)] >= 2 * limits.min_length_mm


def fit_simple(points: np.ndarray, tolerance: float, closed_loop: bool, start_heading: float | None = None,
               end_heading: float | None = None) -> RunFit | None:
    """A run that is one line within ``tolerance`` (open runs), or exactly a chain of lines
    and arcs, as that chain with its verified deviation (if it keeps the pinned end tangents
    given); else None."""
    pts = np.asarray(points, dtype=float)
    end = pts[-1]
    if not closed_loop and _near_chord(pts, tolerance):
        line = (Line((float(pts[0][0]), float(pts[0][1])), (float(end[0]), float(end[1]))),)
        dev = hausdorff(pts, Polysegment(line)).hausdorff
        if dev <= tolerance and _pins_kept(line, start_heading, end_heading):
            return RunFit(line, dev)
    exact = recover_exact(pts, closed_loop, tolerance)
    if exact is not None and _pins_kept(exact, start_heading, end_heading):
        return RunFit(exact, hausdorff(pts, Polysegment(exact)).hausdorff)
    return None


def fit_free(points: np.ndarray, tolerance: float, closed_loop: bool, limits: FitLimits,
             quick: bool = False, fillet: bool = True, start_heading: float | None = None,
             end_heading: float | None = None) -> RunFit | None:
    """G1 chain within ``tolerance`` of a free-form run (start and end points kept exactly)
    under the curvature caps and minimum length of ``limits``, and its verified deviation.

    Where no such chain is found, chains within a fraction of the tolerance are tried, then
    loosened caps, and as the last resort every vertex of the input is rounded
    (fillet_chain). ``quick``: a few attempts under the caps as they are, None if those
    fail. Without ``fillet`` (a minimum length the caller insists on), no chain found is an
    InputError instead of the fillets. ``start_heading`` / ``end_heading`` pin the end
    tangents (see fit_run); the last resort does not keep them.
    """
    pts = np.asarray(points, dtype=float)
    pins = (start_heading, end_heading) if not closed_loop else (None, None)
    lone_kink = _single_kink(pts, closed_loop, tolerance, pins) and not is_sparse(pts, closed_loop, tolerance)
    if fillet and not quick and lone_kink:
        segs = fillet_chain(pts, tolerance, closed_loop)
        dev = hausdorff(pts, Polysegment(segs)).hausdorff
        if dev <= tolerance:
            return RunFit(segs, dev, limits_kept=False)
    if quick:
        found = _constrained(pts, tolerance, closed_loop, limits, [QUICK_ATTEMPTS], *pins)
        return None if found is None else RunFit(*found)
    found = _constrained(pts, tolerance, closed_loop, limits, [MAX_ATTEMPTS], *pins)
    # A chain within a smaller tolerance is within this one too: where the band fit's
    # linearisation misleads (a tolerance large against the curve's features), aim lower.
    for share in NARROWER:
        if found is None:
            narrow = fit_limits(pts, closed_loop, share * tolerance, limits.min_length_mm, limits.speed_kappa)
            found = _constrained(pts, share * tolerance, closed_loop, narrow, [RELAXED_ATTEMPTS], *pins)
    if found is not None:
        return RunFit(*found)
    if fillet and limits.min_length_mm > MIN_LENGTH_SIGMAS * tolerance:
        # The default shortest segment of a long run (its share of the run) can be longer
        # than a tight turn lets an arc be: segments down to the σ-based default, caps kept.
        shorter = replace(limits, min_length_mm=MIN_LENGTH_SIGMAS * tolerance)
        found = _constrained(pts, tolerance, closed_loop, shorter, [MAX_ATTEMPTS], *pins)
        if found is not None:
            return RunFit(*found, limits_kept=False)
    if is_sparse(pts, closed_loop, tolerance):
        # Caps are estimates: a chain under caps a little looser whose arcs are no tighter
        # than the taught points turn anywhere (the circle through three of them) is honest.
        found = _constrained(pts, tolerance, closed_loop, limits.relaxed(SPARSE_RELAX), [RELAXED_ATTEMPTS], *pins)
        gentle = found is not None and max(abs(s.curvature) for s in found[0]) <= (1 + SLACK) / own_radius(pts, closed_loop)
        if gentle:
            return RunFit(*found)
        if closed_loop:
            return taught_lines(pts, True, tolerance)
        return in_halves(pts, tolerance, limits, fit_run, fillet, *pins)
    for factor in RELAX:
        found = _constrained(pts, tolerance, closed_loop, limits.relaxed(factor), [RELAXED_ATTEMPTS], *pins)
        if found is not None:
            return RunFit(*found, limits_kept=False)
    if not fillet:
        raise InputError(f"no chain within {tolerance:g} mm keeps every segment at least "
                         f"min_segment_mm {limits.min_length_mm:g} mm long; give a shorter one",
                         parameters=("min_segment_mm",))
    # Sparse or kinked input the band fit cannot follow: round the vertices instead, first
    # those of the input simplified within half the tolerance (rounded within the other half).
    for keep, share in ((simplified(pts, closed_loop, tolerance / 2), 0.5), (np.arange(len(pts)), 1.0)):
        segs = fillet_chain(pts[keep], share * tolerance, closed_loop)
        dev = hausdorff(pts, Polysegment(segs)).hausdorff
        if dev <= tolerance:
            return RunFit(segs, dev, limits_kept=False)
    raise InputError(f"the fitter could not reach {tolerance:g} mm on a run of {len(pts)} points")


def _single_kink(pts: np.ndarray, closed_loop: bool, tolerance: float, pins: tuple) -> bool:
    """An open, unpinned run of three points whose middle one is off the chord by more than the
    tolerance: a lone kink (sparse or random input) that only a fillet follows. The band fit
    and its fallbacks would spend ~50 attempts (about a second) before ending there too
    (a sparse run's taught points are not filleted: fit_free's caller skips it for them)."""
    if closed_loop or len(pts) != 3 or pins != (None, None):
        return False
    chord = pts[2] - pts[0]
    length = float(np.hypot(*chord))
    off = abs(float(chord[0] * (pts[1][1] - pts[0][1]) - chord[1] * (pts[1][0] - pts[0][0])))
    return length > 0 and off / length > tolerance


def fit_run(points: np.ndarray, tolerance: float, closed_loop: bool, limits: FitLimits,
            fillet: bool = True, start_heading: float | None = None, end_heading: float | None = None) -> RunFit:
    """G1 chain within ``tolerance`` of a run and its verified deviation (mm): fit_simple,
    else fit_free.

    ``start_heading`` (rad, open runs), and with it ``end_heading``, pin the chain's end
    tangents, e.g. to fixed neighbours it must join G1 (to pin only the end, fit the reversed
    run with its start pinned). The last resort (fillets) does not keep them, so a caller
    checks the result's end headings.
    """
    if end_heading is not None and start_heading is None:
        raise ValueError("end_heading needs start_heading; pin the start of the reversed run instead")
    pins = (start_heading, end_heading) if not closed_loop else (None, None)
    return (fit_simple(points, tolerance, closed_loop, *pins)
            or fit_free(points, tolerance, closed_loop, limits, fillet=fillet, start_heading=pins[0], end_heading=pins[1]))

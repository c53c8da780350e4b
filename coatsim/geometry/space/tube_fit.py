"""The 3-D fitter of a run between corners: a G1 arc spline inside the σ-tube, with as few
pieces as it can keep within σ.

1. The knots of the greedy 3-D arc fitter (coatsim.geometry.space.greedy) start it: one piece
   per greedy arc, each turning as the curve does over its stretch, every junction on the
   curve with the curve's tangent.
2. The whole chain is pulled inside the tube (coatsim.geometry.space.tube): junction points
   and tangents, knots and curvatures free, tangent continuity a constraint, under the run's
   curvature caps and minimum length. Where that stays above the target, more pieces are
   tried, each count from fresh starts (the greedy's knot density, even spacing) and from
   the chain that missed with its worst piece split.
3. Then pieces are merged, two neighbours at a time (those whose curvatures differ least
   over their span first), as long as the merged chain still fits.
4. The chain is built segment by segment from its first state (every segment leaves from
   the end point and end tangent of the one before, so G1 holds to round-off), the last one
   (or the last two, when the end tangent is pinned) closing exactly onto the run's end,
   and certified by the exact two-sided Hausdorff check; if that misses σ, the fit aims
   lower and repeats.

A run it cannot fit within a few rounds, or from no more pieces than the caller already has
(``at_most``: the biarc chain's count), is left to the biarc fitter (None).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.geometry.limits import FitLimits
from coatsim.geometry.space.biarc import biarc, tangent_segment
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.deviation import distance_to_chain, hausdorff3
from coatsim.geometry.space.fit import RunChain
from coatsim.geometry.space.greedy import greedy_knots
from coatsim.geometry.space.local import arc_length
from coatsim.geometry.space.nearest import polyline_index
from coatsim.geometry.space.pieces import curvature_vector, end_states, land, segment, state_point
from coatsim.geometry.space.primitives import Arc3, Segment3
from coatsim.geometry.space.reference import Reference, reference
from coatsim.geometry.space.tube import TubeProblem
from coatsim.geometry.space.tube_chain import Ends, TubeChain

TARGET = 0.999  # the fit aims at this share of σ (the exact check decides)
LOWER = 0.98  # a chain the exact check finds above σ is refitted this much lower, ...
CERTIFY_TRIES = 3  # ... this many times at most
REFINE = 8  # places per input edge measured where the exact check finds a chain that bulged between them
EXTRA_PIECES = (0, 1, 2, 3)  # pieces beyond the greedy's count tried while no chain fits, ...
MORE_PIECES = (1.25, 1.5, 2.0, 3.0)  # ... then these multiples of it, ...
PLATEAU_COUNTS, PLATEAU_GAIN = 2, 0.02  # ... until the closest miss of a count is within this share of the one
                                        # PLATEAU_COUNTS counts before and a curvature cap or the minimum length
STUCK_GAIN = 0.005  # holds it where it misses most, or within this share of the one just before (the same)
BALANCE_ROUNDS = 2  # refits of a count from knots spread to even out the pieces' misses
MERGE_TRIES = 1  # neighbour pairs merged to try one piece fewer (then the chain resampled)
MERGE_STEPS = 60  # steps granted to a chain of one piece fewer
MIN_POINTS = 12  # shorter runs are left to the biarc fitter
CAP_SLACK = 0.02  # curvature caps and the minimum length hold to this share, as in the plane
FRAME_WINDOWS = 3.0  # the frames the chain is measured in are smoothed over this many tangent windows: on noisy
                     # input, frames that jitter from vertex to vertex make the knots' derivatives noise (at 6,
                     # the scan patch's passes took 139 moves where 1 and 3 give 126 and 135)
DENSE_SIGMAS, DENSE_MEDIANS = 5.0, 2.0  # the fit measures the input along its edges at least this often (in σ,
                                        # or in median edges if longer): a chain near sparse points can bulge off a long edge


def fit_tube_run(points: np.ndarray, tol: float, limits: FitLimits, window: float,
                 start_tangent: np.ndarray | None = None, end_tangent: np.ndarray | None = None,
                 seam_tangent: np.ndarray | None = None, at_most: int | None = None,
                 at_least: int = 1) -> RunChain | None:
    """A certified G1 chain within ``tol`` of a run of input points (n, 3) under ``limits``
    (see the module text), or None. ``start_tangent``/``end_tangent`` pin the run's end
    tangents; ``seam_tangent``: the run is a closed loop (its last point its first) with
    this tangent at the seam, where the chain meets its own start tangent (free); ``at_most``:
    no count of pieces above it is tried (the caller has a chain of that many); ``at_least``:
    the search starts at no fewer pieces (the caller knows fewer miss)."""
    seam = seam_tangent is not None
    if len(points) < MIN_POINTS:
        return None
    ref = reference(points, arc_length(points), FRAME_WINDOWS * window, seam_tangent if seam else start_tangent,
                    seam_tangent if seam else end_tangent)
    if seam:
        _, _, u0, v0 = ref.frame(np.array(0.0))
        _, _, u1, v1 = ref.frame(np.array(ref.length))
        turn = np.array([[u1 @ u0, u1 @ v0], [v1 @ u0, v1 @ v0]])
        ends = Ends(False, False, turn)
    else:
        ends = Ends(start_tangent is not None, end_tangent is not None)
    median = float(np.median(np.linalg.norm(np.diff(points, axis=0), axis=1)))
    return _certified(ref, densified(points, max(DENSE_SIGMAS * tol, DENSE_MEDIANS * median)), tol, limits, ends,
                      (at_least, at_most))


def _certified(ref: Reference, points: np.ndarray, tol: float, limits: FitLimits, ends: Ends,
               counts: tuple[int, int | None]) -> RunChain | None:
    """The fewest pieces the tube fit finds within the target at the input points, built and
    certified by the exact check. While that misses: the places of the input it missed at
    (between the measured points) are measured too, and where the fitted chain is within
    there (the built one is not: the biarc that closes a loop) it is aimed lower; the same
    chain is refitted first, searched afresh only if that misses."""
    seam = ends.seam is not None
    s = arc_length(points)
    problem = TubeProblem(ref, points, s, tol, limits, ends)
    target = TARGET * tol
    density = _GreedyDensity.of(points, s, tol)
    chain = _fewest(problem, density, target, counts)
    for _ in range(CERTIFY_TRIES):
        if chain is None:
            return None
        segments, caps = _build(ref, chain, points[-1], ends)
        dev = hausdorff3(points, SpaceChain(segments, seam), tol).hausdorff
        if dev <= tol:
            return RunChain(segments, _honest(segments, caps, limits), dev)
        missed = _missed(points, SpaceChain(segments, seam), target)
        if len(missed):  # the chain bulged between measured points: measure there too, refit it
            points, s = _inserted(points, s, missed)
            problem = TubeProblem(ref, points, s, tol, limits, ends)
        if not len(missed) or float(problem.offsets(chain).max()) <= target:
            target *= LOWER * tol / dev  # the build missed where the fit was within (a loop's closing biarc): aim lower
        closer, miss = problem.fit(chain, target)  # the same pieces pulled in, a fresh search if that misses
        chain = closer if miss <= target else _fewest(problem, density, target, counts)
    return None


def _missed(points: np.ndarray, chain: SpaceChain, target: float) -> np.ndarray:
    """Arc lengths along the polyline ``points`` (k,) of the places farther than ``target`` from
    the chain that its vertices miss: REFINE places on every edge, and the feet on the
    polyline of the chain's points farther than that from it (both directions of the check)."""
    s = arc_length(points)
    u = np.arange(1, REFINE) / REFINE
    at = (s[:-1, None] + u[None, :] * np.diff(s)[:, None]).ravel()
    on_edges = _along(points, s, at)
    far = at[distance_to_chain(on_edges, chain, target) > target]
    index, _ = polyline_index(points)
    probes = np.vstack([seg.points(np.linspace(0.0, seg.length, max(2, int(seg.length / target) + 1)))
                        for seg in chain.segments])
    dist, edge = index.distance(probes)
    out = dist > target
    ab = points[edge[out] + 1] - points[edge[out]]
    foot = np.einsum("ij,ij->i", probes[out] - points[edge[out]], ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    feet = s[edge[out]] + np.clip(foot, 0.0, 1.0) * np.diff(s)[edge[out]]
    return np.setdiff1d(np.unique(np.concatenate((far, feet))), s)


def _along(points: np.ndarray, s: np.ndarray, at: np.ndarray) -> np.ndarray:
    return np.column_stack([np.interp(at, s, points[:, k]) for k in range(3)])


def _inserted(points: np.ndarray, s: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The polyline with vertices added at arc lengths ``at`` (the same polyline), and its arc lengths."""
    s_all = np.concatenate((s, at))
    order = np.argsort(s_all, kind="stable")
    return np.vstack((points, _along(points, s, at)))[order], s_all[order]


def densified(points: np.ndarray, step: float) -> np.ndarray:
    """The polyline with points added on every edge longer than ``step`` (evenly, its
    vertices kept): the same polyline, measured often enough that a chain close to every
    point cannot bulge far from a long edge between them (the exact check measures both ways)."""
    edges = np.diff(points, axis=0)
    cuts = np.maximum(np.ceil(np.linalg.norm(edges, axis=1) / step).astype(int), 1)
    if (cuts == 1).all():
        return points
    share = np.concatenate([np.arange(k) / k for k in cuts])
    edge = np.repeat(np.arange(len(edges)), cuts)
    return np.vstack((points[edge] + share[:, None] * edges[edge], points[-1:]))


@dataclass(frozen=True)
class _GreedyDensity:
    """Where the greedy fitter puts its knots, as a count of greedy arcs behind every knot
    (its last, usually short, arc counted as the share of one it is), to spread any number
    of knots as densely as the greedy's are."""

    index: np.ndarray
    knots: np.ndarray

    @classmethod
    def of(cls, points: np.ndarray, s: np.ndarray, tol: float) -> _GreedyDensity:
        knots = s[greedy_knots(points, tol)]
        index = np.arange(len(knots), dtype=float)
        if len(knots) > 3:
            index[-1] = index[-2] + min(1.0, (knots[-1] - knots[-2]) / (knots[-2] - knots[-3]))
        return cls(index, knots)

    @property
    def count(self) -> int:
        """The greedy's arcs, its last counted whole."""
        return max(1, int(math.ceil(self.index[-1] - 1e-9)))

    def spread(self, count: int) -> np.ndarray:
        """``count`` + 1 knots, the first and last at the run's ends."""
        out = np.interp(np.linspace(0.0, self.index[-1], count + 1), self.index, self.knots)
        out[[0, -1]] = self.knots[[0, -1]]
        return out


def _initial(ref: Reference, knots: np.ndarray) -> TubeChain:
    """A piece per stretch between knots, turning as the curve's tangent does over it, every
    state on the curve with its tangent."""
    _, t0, u0, v0 = ref.frame(knots[:-1])
    _, t1, _, _ = ref.frame(knots[1:])
    cos = np.clip(np.einsum("ij,ij->i", t0, t1), -1.0, 1.0)
    side = t1 - cos[:, None] * t0
    norm = np.linalg.norm(side, axis=1)
    side = side / np.where(norm > 0, norm, 1.0)[:, None]
    rate = np.arccos(cos) / np.diff(knots)
    kappa = rate[:, None] * np.column_stack((np.einsum("ij,ij->i", side, u0), np.einsum("ij,ij->i", side, v0)))
    return TubeChain(knots.astype(float), np.zeros((len(knots), 4)), kappa)


def _fewest(problem: TubeProblem, density: _GreedyDensity, target: float,
            counts: tuple[int, int | None]) -> TubeChain | None:
    """A chain within ``target`` (``_first_within``), then one piece fewer at a time while it
    stays within, each count tried from the chain before with two neighbours merged (those
    whose curvatures differ least over their span first), resampled, and from knots spread
    as the greedy's; None if no count within ``counts`` (fewest, most) gets within."""
    chain = _first_within(problem, density, target, counts)
    if chain is None:
        return None
    while chain.n > 1:
        n = chain.n - 1
        starts = [chain.merged(j) for j in _merge_order(chain)[:MERGE_TRIES]]
        for start in starts + [problem.resampled(chain, n), _initial(problem.ref, density.spread(n))]:
            fewer, dev = problem.fit(start, target, MERGE_STEPS)
            if dev <= target:
                chain = fewer
                break
        else:
            return chain
    return chain


def _first_within(problem: TubeProblem, density: _GreedyDensity, target: float,
                  counts: tuple[int, int | None]) -> TubeChain | None:
    """The first chain within ``target`` of as many pieces as the greedy has arcs (or the fewest of
    ``counts`` (fewest, most), if more), then a few more, then growing shares more
    (MORE_PIECES): each count started from knots spread as the greedy's, spread evenly, and (one
    piece more than a chain that missed) from that chain with its worst piece split. Fresh
    starts, because a chain that missed is often caught in a local optimum no split gets it out
    of. Where more pieces stop bringing the chain closer and no limit holds it, the chain is
    caught in a local optimum: the search goes on at the growing shares (on the trefoil at σ 0.5
    mm 12 to 14 pieces miss by 0.69 to 0.50 mm, 15 fit). No count above ``counts``' most is
    tried."""
    fewest, most = counts
    count = max(density.count, fewest)
    tried = sorted({count + k for k in EXTRA_PIECES} | {math.ceil(count * f) for f in MORE_PIECES})
    tried = [n for n in tried if most is None or n <= most]
    missed: TubeChain | None = None
    misses: list[float] = []
    for n in tried:
        plateau = len(misses) > PLATEAU_COUNTS and misses[-1] >= (1 - PLATEAU_GAIN) * misses[-1 - PLATEAU_COUNTS]
        stuck = len(misses) > 1 and misses[-1] >= (1 - STUCK_GAIN) * misses[-2]
        if plateau or stuck:
            if _held(problem, missed):
                return None  # more pieces stopped bringing the chain closer and a limit holds it out
            if n < count * MORE_PIECES[0]:
                continue  # a local optimum, not a limit: on to the larger counts
        starts = [_initial(problem.ref, density.spread(n)),
                  _initial(problem.ref, np.linspace(density.knots[0], density.knots[-1], n + 1))]
        if missed is not None and missed.n == n - 1:
            starts.insert(0, _split_worst(problem, missed))
        best = None
        for start in starts:
            chain, dev = problem.fit(start, target)
            if dev <= target:
                return chain
            best = (dev, chain) if best is None or dev < best[0] else best
        for _ in range(BALANCE_ROUNDS):
            chain, dev = problem.fit(_initial(problem.ref, _balanced(problem, best[1])), target)
            if dev <= target:
                return chain
            if dev >= best[0]:
                break  # no closer: the next round would start from the same chain
            best = (dev, chain)
        missed = best[1]
        misses.append(best[0])
    return None


def _worst_piece(problem: TubeProblem, chain: TubeChain) -> int:
    """The piece of the chain farthest from the input."""
    worst = problem.s[int(np.argmax(problem.offsets(chain)))]
    return int(np.clip(np.searchsorted(chain.knots, worst, side="right") - 1, 0, chain.n - 1))


def _held(problem: TubeProblem, chain: TubeChain) -> bool:
    """Whether a limit holds the chain where it misses most: the piece there or a neighbour
    at its curvature cap or at the minimum length (to CAP_SLACK)."""
    j = _worst_piece(problem, chain)
    near = slice(max(j - 1, 0), min(j + 2, chain.n))
    caps = problem.limits.over(chain.knots[:-1], chain.knots[1:])[near]
    kappa = np.linalg.norm(chain.kappa[near], axis=1)
    short = np.diff(chain.knots)[near] <= (1 + CAP_SLACK) * problem.limits.min_length_mm
    return bool(np.any(kappa >= (1 - CAP_SLACK) * caps) or np.any(short))


def _balanced(problem: TubeProblem, chain: TubeChain) -> np.ndarray:
    """As many knots as the chain has, spread so that every piece would miss by as much
    (equidistribution): a piece of length h missing by e is worth (e / σ)^(1/3) / h pieces
    per mm (an arc's deviation from a curve grows with the cube of its length), the knots
    cut that density into equal shares."""
    offsets = problem.offsets(chain)
    piece = np.clip(np.searchsorted(chain.knots, problem.s, side="right") - 1, 0, chain.n - 1)
    worst = np.zeros(chain.n)
    np.maximum.at(worst, piece, offsets)
    weight = np.cumsum(np.concatenate(([0.0], np.cbrt(np.maximum(worst, 1e-3 * problem.tol) / problem.tol))))
    knots = np.interp(np.linspace(0.0, weight[-1], chain.n + 1), weight, chain.knots)
    knots[[0, -1]] = chain.knots[[0, -1]]
    return knots


def _merge_order(chain: TubeChain) -> np.ndarray:
    """Interior knots, those joining the most alike neighbours first: the deviation a
    curvature jump Δc makes over a span h is about |Δc| h² / 8."""
    h = np.diff(chain.knots)
    jump = np.linalg.norm(np.diff(chain.kappa, axis=0), axis=1)
    return 1 + np.argsort(jump * (h[:-1] + h[1:]) ** 2, kind="stable")


def _split_worst(problem: TubeProblem, chain: TubeChain) -> TubeChain:
    """The chain with its piece farthest from the input cut in two, the new knot in the
    state the piece has at its middle."""
    j = _worst_piece(problem, chain)
    params = chain.params()[j : j + 1].copy()
    params[0, 1] = (chain.knots[j] + chain.knots[j + 1]) / 2
    return chain.split(j, end_states(problem.ref, params)[0])


def _build(ref: Reference, chain: TubeChain, end: np.ndarray, ends: Ends) -> tuple[tuple[Segment3, ...], np.ndarray]:
    """The chain's segments, each leaving from the end of the one before, closed exactly
    onto ``end`` (a loop onto its own start; see the module text), and the knot span of every
    segment (k, 2) mm."""
    start, t = state_point(ref.frame(chain.knots[0]), chain.states[0, :2], chain.states[0, 2:])
    if ends.seam is None:
        start = ref.points[0].copy()  # the state there is pinned on the curve: exactly its first point
    else:
        end = start  # a loop closes onto its own start
    pinned = ends.end_tangent or ends.seam is not None
    last = max(chain.n - (2 if pinned else 1), 0)
    segments: list[Segment3] = []
    spans: list[tuple[float, float]] = []
    for j in range(last):
        c = curvature_vector(ref.frame(chain.knots[j]), chain.kappa[j], t)
        origin, normal, _, _ = ref.frame(chain.knots[j + 1])
        ell = float(land(start, t, c, origin, normal, np.float64(chain.knots[j + 1] - chain.knots[j])))
        seg = segment(start, t, c, ell)
        segments.append(seg)
        spans.append((chain.knots[j], chain.knots[j + 1]))
        start, t = seg.end, seg.end_tangent
    if pinned:
        end_t = segments[0].start_tangent if ends.seam is not None and segments else _end_tangent(ref, chain, ends)
        tail = biarc(start, t, end, end_t, _ratio(chain))
        if tail is None:
            tail = (tangent_segment(start, t, end),)
        lengths = np.array([seg.length for seg in tail])
        cuts = chain.knots[last] + np.concatenate(([0.0], np.cumsum(lengths))) / max(lengths.sum(), 1e-300) \
            * (chain.knots[-1] - chain.knots[last])
        for seg, a, b in zip(tail, cuts[:-1], cuts[1:]):
            if seg.length > 0:
                segments.append(seg)
                spans.append((a, b))
    else:
        segments.append(tangent_segment(start, t, end))
        spans.append((chain.knots[-2], chain.knots[-1]))
    return tuple(segments), np.array(spans)


def _end_tangent(ref: Reference, chain: TubeChain, ends: Ends) -> np.ndarray:
    _, t = state_point(ref.frame(chain.knots[-1]), chain.states[-1, :2], chain.states[-1, 2:])
    return t


def _ratio(chain: TubeChain) -> float:
    """The tangent-leg ratio β/α of the last two pieces, for the biarc that stands in for them."""
    legs = []
    for c, h in zip(chain.kappa[-2:], np.diff(chain.knots)[-2:]):
        turn = float(np.linalg.norm(c)) * h
        legs.append(h / 2 if turn < 1e-9 else math.tan(min(turn, 3.0) / 2) * h / turn)
    return legs[-1] / legs[0] if len(legs) == 2 and legs[0] > 0 else 1.0


def _honest(segments: tuple[Segment3, ...], spans: np.ndarray, limits: FitLimits) -> bool:
    """Whether every arc keeps the curvature cap of the stretch it covers and every segment
    (but a run's only one) the minimum length, to CAP_SLACK."""
    caps = limits.over(spans[:, 0], spans[:, 1])
    kappa = np.array([seg.curvature if isinstance(seg, Arc3) else 0.0 for seg in segments])
    lengths = np.array([seg.length for seg in segments])
    short = len(segments) > 1 and bool((lengths < (1 - CAP_SLACK) * limits.min_length_mm).any())
    return bool(np.all(kappa <= caps * (1 + CAP_SLACK))) and not short

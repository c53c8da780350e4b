"""G1 arc/line fitting in the integrated-θ domain.

For small deviations the lateral offset of a chain from the curve at arc length s is the
running integral of θ̂ − θ, so we approximate Φ(s) = ∫θ ds (piecewise linear for a polyline)
by a C1 piecewise-quadratic Φ̂ inside the band Φ ± σ. Each quadratic piece has constant
second derivative κ, i.e. it is one arc (a line when κ = 0), and C1 continuity of Φ̂ is
tangent continuity of the chain, so G1 holds by construction.

Given the state (Φ̂, θ̂) at a knot, the curvatures that keep the piece inside the band up to
knot b form an interval; its running intersection gives every reachable end at once. The
curvature of a piece is also capped by the input's own curvature near it (FitLimits), and a
piece is at least the minimum segment length long (so is what remains after it). The greedy
picks each piece's end and curvature by one step of look-ahead: the choice that lets the
*next* piece reach farthest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from coatsim.geometry.limits import FitLimits
from coatsim.geometry.lp import solve_lp

N_END_CANDIDATES = 12
N_CURVATURE_CANDIDATES = 5
N_HEADING_CANDIDATES = 7
LP_KNOTS = 400
LANDED_BAND = 0.9  # a re-measured state keeps its offset within this share of the band
CLOSE_RAD = 0.01  # a loop's pieces that turn by its turn to this close it (fit_band)


@dataclass(frozen=True, eq=False)
class BandProblem:
    """Knots ``s`` (n,) and integrated heading ``phi`` (n,) of one open run of a curve, the
    curvature cap of a piece covering each knot (n,) 1/mm, the shortest piece (mm), the
    run's ``points`` (n, 2) with their tangent headings ``tangent`` (n,) rad, and the share
    of the band open at each knot ``width`` (n,) (1 on dense input; narrower where a sparse
    polyline's channel is, coatsim.geometry.sparse)."""

    s: np.ndarray
    phi: np.ndarray
    cap: np.ndarray
    min_length: float
    points: np.ndarray
    tangent: np.ndarray
    width: np.ndarray
    first_steps: dict = field(default_factory=dict, repr=False)  # see _first_step

    @classmethod
    def from_points(cls, points: np.ndarray, limits: FitLimits, width: np.ndarray | None = None,
                    run_length: float | None = None) -> tuple["BandProblem", float]:
        """Build from a polyline; returns the problem and the reference heading θ is taken from.
        ``width``: the band's share per point (default 1); ``run_length``: the length of the
        run ``limits`` belong to, when ``points`` are a guide of slightly different length."""
        d = np.diff(points, axis=0)
        ell = np.linalg.norm(d, axis=1)
        heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
        ref = float(heading[0])
        s = np.concatenate(([0.0], np.cumsum(ell)))
        phi = np.concatenate(([0.0], np.cumsum((heading - ref) * ell)))
        tangent = np.concatenate(([heading[0]], (heading[:-1] + heading[1:]) / 2, [heading[-1]]))
        cap = limits.at_knots(s if run_length is None else s * (run_length / s[-1]))
        share = np.ones(len(s)) if width is None else np.asarray(width, float)
        return cls(s, phi, cap, limits.min_length_mm, np.asarray(points, float), tangent, share), ref

    def ends_allowed(self, a: int, b: np.ndarray) -> np.ndarray:
        """Whether a piece from knot ``a`` may end at each knot of ``b``: long enough, and
        leaving either nothing or at least a minimum length after it."""
        last = len(self.s) - 1
        rest = self.s[last] - self.s[b]
        return ((self.s[b] - self.s[a] >= self.min_length) | (b == last)) & ((b == last) | (rest >= self.min_length))


@dataclass(frozen=True)
class Piece:
    """One quadratic piece of Φ̂ from knot ``a`` to knot ``b`` with curvature ``kappa``; the
    arc it stands for is ``length`` mm long (s[b] - s[a] unless corrected, see _landed)."""

    a: int
    b: int
    kappa: float
    length: float


@dataclass(frozen=True)
class _Pose:
    """Where the chain really is: its end point (x, y) and heading (rad)."""

    x: float
    y: float
    heading: float

    def along(self, kappa: float, length: float) -> "_Pose":
        sweep = kappa * length
        chord = length * (math.sin(sweep / 2) / (sweep / 2) if abs(sweep) > 1e-12 else 1.0)
        mid = self.heading + sweep / 2
        return _Pose(self.x + chord * math.cos(mid), self.y + chord * math.sin(mid), self.heading + sweep)


def _landed(prob: BandProblem, ref: float, pose: _Pose, piece: Piece, band: float) -> tuple[Piece, _Pose, float, float]:
    """The piece with its arc length corrected so the arc ends on the curve's normal at knot
    b, the chain's pose there, and the Φ-domain state (value, slope) it really has.

    Φ̂ − Φ is the lateral offset only to first order: over a long run the chain drifts along
    the curve by the second-order terms. Measuring the offset and heading of the real arc at
    every knot keeps the greedy's states true to the geometry (an offset beyond the band is
    taken as the band's edge: the refinement that follows closes such gaps).
    """
    b = piece.b
    px, py = prob.points[b]
    tx, ty = math.cos(prob.tangent[b]), math.sin(prob.tangent[b])
    length = piece.length
    for _ in range(4):  # Newton on the tangential gap to the normal line at knot b
        end = pose.along(piece.kappa, length)
        gap = (end.x - px) * tx + (end.y - py) * ty
        rate = math.cos(end.heading - prob.tangent[b])
        if rate < 0.5:
            break
        length -= gap / rate
    if not 0.5 * piece.length <= length <= 1.5 * piece.length:
        length = piece.length
    end = pose.along(piece.kappa, length)
    edge = LANDED_BAND * band * float(prob.width[b])
    offset = float(np.clip(-(end.x - px) * ty + (end.y - py) * tx, -edge, edge))
    return Piece(piece.a, b, piece.kappa, length), end, float(prob.phi[b] + offset), end.heading - ref


def _reach(prob: BandProblem, a: int, value: float, slope: float, band: float) -> tuple[int, np.ndarray, np.ndarray]:
    """Knots a piece from state (value, slope) at knot a can end at.

    Returns (b, lo, hi): the band holds up to knot b, and (lo[i], hi[i]) are the curvatures
    of a piece ending at knot a+1+i that stay inside the band and under the cap of the
    stretch (lo > hi where the cap leaves none), arrays of length b - a.
    """
    n = len(prob.s)
    lo_all, hi_all = [], []
    lo_run, hi_run, cap_run = -np.inf, np.inf, float(prob.cap[a])
    start, width = a + 1, 256
    while start < n:
        stop = min(n, start + width)
        u = prob.s[start:stop] - prob.s[a]
        base = value + slope * u
        lo_at, hi_at = _bounds(prob.phi[start:stop], band * prob.width[start:stop], base, u)
        lo = np.maximum.accumulate(np.concatenate(([lo_run], lo_at)))[1:]
        hi = np.minimum.accumulate(np.concatenate(([hi_run], hi_at)))[1:]
        cap = np.maximum.accumulate(np.concatenate(([cap_run], prob.cap[start:stop])))[1:]
        bad = np.flatnonzero(lo > hi)
        stop_at = bad[0] if len(bad) else len(lo)
        lo_all.append(np.maximum(lo[:stop_at], -cap[:stop_at]))
        hi_all.append(np.minimum(hi[:stop_at], cap[:stop_at]))
        if len(bad):
            break
        lo_run, hi_run, cap_run = lo[-1], hi[-1], cap[-1]
        start, width = stop, width * 4
    lo_cat = np.concatenate(lo_all) if lo_all else np.empty(0)
    hi_cat = np.concatenate(hi_all) if hi_all else np.empty(0)
    return a + len(lo_cat), lo_cat, hi_cat


def _farthest(prob: BandProblem, a: int, lo: np.ndarray, hi: np.ndarray) -> int:
    """The farthest knot a piece from knot a can end at under the caps (a if none)."""
    ok = np.flatnonzero(lo <= hi)
    return a + 1 + int(ok[-1]) if len(ok) else a


def _bounds(phi: np.ndarray, half: np.ndarray, base: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The curvatures (lo, hi) a piece leaving a knot on ``base`` (Φ̂ there) may have to stay within
    ``half`` of Φ at a knot ``u`` mm on: (Φ ∓ half − base)·2/u². A knot at u = 0 (coincident points)
    bounds none: ±inf, or 0/0 on the band's edge."""
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 2.0 / (u * u)
        return np.fmax((phi - half - base) * inv, -np.inf), np.fmin((phi + half - base) * inv, np.inf)


def _farthest_of(prob: BandProblem, knots: list[int], values: list[float], slopes: list[float], band: float,
                 width: int = 256) -> list[int]:
    """_farthest after _reach for many states at once (the look-ahead's candidates): the same
    arithmetic element by element on one (states, ``width``) block of the knots that follow
    each (the band open at each knot by its share, prob.width); a state whose band still holds at the
    block's end goes through _reach itself."""
    n = len(prob.s)
    a = np.asarray(knots, dtype=np.int64)
    if not len(a):
        return []
    idx = a[:, None] + 1 + np.arange(width)
    inside = idx < n
    idx = np.minimum(idx, n - 1)
    u = prob.s[idx] - prob.s[a][:, None]
    base = np.asarray(values)[:, None] + np.asarray(slopes)[:, None] * u
    lo_at, hi_at = _bounds(prob.phi[idx], band * prob.width[idx], base, u)
    lo = np.maximum.accumulate(np.where(inside, lo_at, np.inf), axis=1)
    hi = np.minimum.accumulate(np.where(inside, hi_at, -np.inf), axis=1)
    cap = np.maximum.accumulate(np.concatenate((prob.cap[a][:, None], prob.cap[idx]), axis=1), axis=1)[:, 1:]
    bad = lo > hi  # (past the last knot every entry is bad)
    held = np.where(bad.any(axis=1), bad.argmax(axis=1), width)
    ok = (np.maximum(lo, -cap) <= np.minimum(hi, cap)) & (np.arange(width) < held[:, None])
    last_ok = np.where(ok.any(axis=1), width - 1 - ok[:, ::-1].argmax(axis=1), -1)
    out = []
    for k, knot in enumerate(knots):
        if held[k] == width:  # the band holds past the block: the knots beyond decide
            _, lo_k, hi_k = _reach(prob, knot, values[k], slopes[k], band)
            out.append(_farthest(prob, knot, lo_k, hi_k))
        else:
            out.append(knot + 1 + int(last_ok[k]) if last_ok[k] >= 0 else knot)
    return out


def _advance(prob: BandProblem, a: int, b: int, value: float, slope: float, kappa: float) -> tuple[float, float]:
    u = prob.s[b] - prob.s[a]
    return value + slope * u + 0.5 * kappa * u * u, slope + kappa * u


def _curvature_candidates(lo: float, hi: float) -> np.ndarray:
    cands = np.linspace(lo, hi, N_CURVATURE_CANDIDATES)
    if lo <= 0.0 <= hi:
        cands = np.append(cands, 0.0)
    return cands


def _end_candidates(prob: BandProblem, a: int, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Knots to try as the piece end: the farthest allowed one, and others spread over the
    last 40 % before it."""
    ends = a + 1 + np.flatnonzero(lo <= hi)
    ends = ends[prob.ends_allowed(a, ends)]
    if not len(ends):
        return ends
    s_end = prob.s[ends]
    targets = prob.s[a] + (s_end[-1] - prob.s[a]) * np.linspace(0.6, 1.0, N_END_CANDIDATES)
    return np.unique(ends[np.searchsorted(s_end, targets).clip(0, len(ends) - 1)])


def _best_step(prob: BandProblem, a: int, value: float, slope: float, band: float,
               previous: float | None = None) -> tuple[Piece, float, float, float]:
    """Choose the next piece from a state by one step of look-ahead.

    Among the choices whose following piece reaches farthest, the one with the smallest
    curvature jump from the ``previous`` piece's curvature wins (a tool at speed feels a jump
    as a step of its lateral acceleration), then the longer piece.
    Returns (piece, next value, next slope, score), score = arc length the following piece
    reaches (infinity when this piece ends the run).
    """
    last = len(prob.s) - 1
    b_max, lo, hi = _reach(prob, a, value, slope, band)
    if b_max == last and lo[-1] <= hi[-1]:
        # Final piece: end the run with the curvature that lands closest to the curve's end.
        k_lo, k_hi = lo[-1], hi[-1]
        u = prob.s[last] - prob.s[a]
        ideal = 2.0 * (prob.phi[last] - value - slope * u) / (u * u)
        kappa = 0.0 if k_lo <= 0.0 <= k_hi and abs(ideal) * u * u < 0.2 * band else float(np.clip(ideal, k_lo, k_hi))
        v, t = _advance(prob, a, last, value, slope, kappa)
        return Piece(a, last, kappa, float(prob.s[last] - prob.s[a])), v, t, np.inf
    choices = [(int(b), kappa, *_advance(prob, a, b, value, slope, kappa)) for b in _end_candidates(prob, a, lo, hi)
               for kappa in _curvature_candidates(lo[b - a - 1], hi[b - a - 1])]
    reached = _farthest_of(prob, [c[0] for c in choices], [c[2] for c in choices], [c[3] for c in choices], band)
    options = []
    for (b, kappa, v, t), nxt in zip(choices, reached):
        if nxt != last and prob.s[nxt] - prob.s[b] < prob.min_length:
            continue  # the next piece could not be long enough: a dead end
        score = np.inf if nxt == last else float(prob.s[nxt])
        options.append((score, float(prob.s[b]), float(kappa), b, v, t))
    if not options:
        raise _Stuck(a)
    top = max(o[0] for o in options)
    jump = (lambda k: 0.0) if previous is None else (lambda k: abs(k - previous))
    score, _, kappa, b, v, t = max((o for o in options if o[0] == top), key=lambda o: (-jump(o[2]), o[1], o[2] == 0.0))
    return Piece(a, b, kappa, float(prob.s[b] - prob.s[a])), v, t, score


class _Stuck(Exception):
    """No piece can leave this state inside the band."""

    def __init__(self, knot: int) -> None:
        super().__init__(f"stuck at knot {knot}")
        self.knot = knot


def _start_heading_range(prob: BandProblem, band: float) -> tuple[float, float]:
    """Range of start slopes θ̂(0) for which one piece starting on the curve reaches farthest.

    Binary search on the reach with a 2-variable LP (slope, curvature), then the slope range
    at 70 % of that reach, so the look-ahead has room to choose.
    """
    n = len(prob.s)

    def slope_range(b: int) -> tuple[float, float] | None:
        # at most LP_KNOTS constraints: this only picks the start slopes to try
        knots = np.unique(np.linspace(1, b, min(b, LP_KNOTS)).astype(int))
        u = prob.s[knots] - prob.s[0]
        a_ub = np.vstack((np.column_stack((u, 0.5 * u * u)), -np.column_stack((u, 0.5 * u * u))))
        rhs = prob.phi[knots] - prob.phi[0]
        half = band * prob.width[knots]
        b_ub = np.concatenate((rhs + half, half - rhs))
        cap = float(prob.cap[: b + 1].max())
        out = []
        for c in (1.0, -1.0):
            x = solve_lp(np.array([c, 0.0]), a_ub, b_ub, np.array([-np.inf, -cap]), np.array([np.inf, cap]))
            if x is None:
                return None
            out.append(x[0])
        return out[0], out[1]

    lo, hi = 1, n - 1
    if slope_range(hi) is not None:
        best = hi
    else:
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if slope_range(mid) is not None:
                lo = mid
            else:
                hi = mid
        best = lo
    target = int(np.searchsorted(prob.s, 0.7 * prob.s[best]).clip(1, best))
    rng = slope_range(target)
    if rng is None:  # the sampled LP can miss a feasible slope on very sparse runs
        raise _Stuck(0)
    return rng


def _closing_pair(prob: BandProblem, a: int, value: float, slope: float, band: float, end_slope: float) -> list[Piece] | None:
    """Two pieces from the state at knot ``a`` that end on the curve with ``end_slope``
    (a closed loop then meets its start tangentially), inside the band; None if none fits."""
    last = len(prob.s) - 1
    reach, lo, hi = _reach(prob, a, value, slope, band)
    for j in np.unique(np.linspace(a + 1, min(reach, last - 1), 24).astype(int))[::-1]:
        u1, u2 = prob.s[j] - prob.s[a], prob.s[last] - prob.s[j]
        if u1 <= 0 or u2 <= 0 or not prob.ends_allowed(a, np.array([j]))[0]:
            continue
        # slope:  slope + k1 u1 + k2 u2 = end_slope
        # value:  value + slope (u1 + u2) + k1 (u1²/2 + u1 u2) + k2 u2²/2 = phi[last]
        mat = np.array([[u1, u2], [u1 * u1 / 2 + u1 * u2, u2 * u2 / 2]])
        rhs = np.array([end_slope - slope, prob.phi[last] - value - slope * (u1 + u2)])
        k1, k2 = np.linalg.solve(mat, rhs)
        if not lo[j - a - 1] <= k1 <= hi[j - a - 1]:
            continue
        v, t = _advance(prob, a, j, value, slope, k1)
        reach2, lo2, hi2 = _reach(prob, j, v, t, band)
        if reach2 == last and lo2[-1] <= k2 <= hi2[-1]:
            return [Piece(a, int(j), float(k1), float(u1)), Piece(int(j), last, float(k2), float(u2))]
    return None


def _first_step(prob: BandProblem, band: float, start_slope: float | None) -> tuple[float, Piece, float, float]:
    """The start slope and first piece of a fit within ``band`` (see fit_band), remembered
    per band on ``prob``: the fitter retries a band with its states re-measured, and the
    first step does not depend on that."""
    key = (band, start_slope)
    if key not in prob.first_steps:
        try:
            prob.first_steps[key] = _choose_first_step(prob, band, start_slope)
        except _Stuck as stuck:
            prob.first_steps[key] = stuck
    found = prob.first_steps[key]
    if isinstance(found, _Stuck):
        raise found
    return found


def _choose_first_step(prob: BandProblem, band: float, start_slope: float | None) -> tuple[float, Piece, float, float]:
    if start_slope is None:
        lo, hi = _start_heading_range(prob, band)
        options = np.linspace(lo, hi, N_HEADING_CANDIDATES)
    else:
        options = np.array([start_slope])
    best = None
    for slope in options:
        try:
            piece, v, t, score = _best_step(prob, 0, float(prob.phi[0]), float(slope), band)
        except _Stuck:
            continue
        key = (score, prob.s[piece.b])
        if best is None or key > best[0]:
            best = (key, float(slope), piece, v, t)
    if best is None:
        raise _Stuck(0)
    _, slope0, piece, v, t = best
    return slope0, piece, v, t


def fit_band(
    prob: BandProblem, ref: float, band: float, start_slope: float | None = None, end_turn: float | None = None,
    landed: bool = False,
) -> tuple[float, list[Piece]]:
    """Greedy C1 piecewise-quadratic fit of Φ within ±band over the whole run.

    The run starts on the curve (Φ̂(0) = Φ(0)); its start slope is ``start_slope`` if given,
    otherwise chosen by look-ahead. With ``landed``, the state after every piece is
    re-measured on the real arc (``ref``: the heading Φ is taken against), which helps on
    long runs whose chain drifts along the curve. With ``end_turn`` (closed loops) the last
    pieces are chosen to end with the start slope plus that turn where the band allows it;
    where no pair of pieces does from the slope the look-ahead chose (a seam at a petal's tip:
    it chose 0.26 rad off the curve's tangent), the loop is fitted again starting along the
    input's tangent at the seam, and that fit kept if it closes. Returns (start slope, pieces).
    """
    slope0, pieces = _greedy(prob, ref, band, start_slope, end_turn, landed)
    if end_turn is None or start_slope is not None or _closes(pieces, end_turn):
        return slope0, pieces
    d_first, d_last = prob.points[1] - prob.points[0], prob.points[-1] - prob.points[-2]
    seam = math.remainder(math.atan2(d_first[1] + d_last[1], d_first[0] + d_last[0]) - ref, 2 * math.pi)
    try:
        along = _greedy(prob, ref, band, seam, end_turn, landed)
    except _Stuck:
        return slope0, pieces
    return along if _closes(along[1], end_turn) else (slope0, pieces)


def _closes(pieces: list[Piece], end_turn: float) -> bool:
    """Whether a loop's pieces turn by ``end_turn`` (to CLOSE_RAD): it ends with its start slope."""
    return abs(sum(p.kappa * p.length for p in pieces) - end_turn) <= CLOSE_RAD


def _greedy(prob: BandProblem, ref: float, band: float, start_slope: float | None, end_turn: float | None,
            landed: bool) -> tuple[float, list[Piece]]:
    """One greedy pass of fit_band from ``start_slope`` (or the look-ahead's)."""
    slope0, piece, v, t = _first_step(prob, band, start_slope)
    last = len(prob.s) - 1
    pose = _Pose(float(prob.points[0][0]), float(prob.points[0][1]), ref + slope0)
    pieces: list[Piece] = []
    states = [(0, float(prob.phi[0]), slope0)]
    while True:
        if piece.b < last and landed:
            piece, pose, v, t = _landed(prob, ref, pose, piece, band)
        pieces.append(piece)
        if piece.b == last:
            break
        states.append((piece.b, v, t))
        piece, v, t, _ = _best_step(prob, piece.b, v, t, band, piece.kappa)
    if end_turn is not None:
        # Re-end the loop from the start of the last piece, or of the one before it.
        for back in range(1, min(2, len(pieces)) + 1):
            a, value, slope = states[len(pieces) - back]
            pair = _closing_pair(prob, a, value, slope, band, slope0 + end_turn)
            if pair is not None:
                return slope0, pieces[: len(pieces) - back] + pair
    return slope0, pieces


BandStuck = _Stuck

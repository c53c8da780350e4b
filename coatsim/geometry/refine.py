"""Minimax refinement of a G1 chain in its (start heading, curvature, length) parameters.

The chain starts at a fixed point; every parameter vector is a tangent-continuous chain, so
optimising in this space keeps G1 by construction. We minimise the largest lateral distance
of the input samples to the chain (each sample measured against the carrier circle of the
segment at the same normalised arc length), subject to the chain ending at the run's end
point (open runs) or closing onto its start with the start heading (closed curves), every
curvature staying under the cap of the stretch its segment covers and every length above
the minimum (FitLimits).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from coatsim.geometry.limits import FitLimits
from coatsim.geometry.lp import solve_lp

MAX_SAMPLES = 400
EXCHANGE = 60  # worst points added to the samples per exchange round
EXCHANGE_ROUNDS = 6
EARLY = 12
STALL_STEPS = 4  # a refinement asked to stop when it stalls compares its merit this many steps back ...
STALL_SHARE = 0.01  # ... and stops when it fell by less than this share; it also stops ...
HOPELESS_STEP = 6  # ... after this many steps when its merit is still ...
HOPELESS_SHARE = 6.0  # ... this many times the merit it stops above (taught chains with a junction
# given up that ended within σ were at most 5 times it by then on the taught polygons measured)


@dataclass(frozen=True, eq=False)
class ChainParams:
    """start heading (rad), curvatures (n,) 1/mm, lengths (n,) mm, and how far (mm) the
    start has slid from where it was given (refine_chain's ``slide``; 0 otherwise)."""

    heading: float
    kappa: np.ndarray
    length: np.ndarray
    shift: float = 0.0

    def vector(self) -> np.ndarray:
        """(2n + 1,): heading, curvatures, lengths (not the shift)."""
        return np.concatenate(([self.heading], self.kappa, self.length))

    @classmethod
    def from_vector(cls, x: np.ndarray, shift: float = 0.0) -> "ChainParams":
        n = (len(x) - 1) // 2
        return cls(float(x[0]), x[1 : n + 1].copy(), x[n + 1 : 2 * n + 1].copy(), shift)


def _segment_starts(start: np.ndarray, heading0: np.ndarray, kappa: np.ndarray, length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Segment start points (B, n+1, 2) (index n = chain end) and start headings (B, n+1)
    for a batch of B parameter sets (heading0 (B,), kappa and length (B, n)) from ``start``
    (2,) or one start per set (B, 2)."""
    start = np.asarray(start, dtype=float).reshape(-1, 1, 2)
    sweep = kappa * length
    heading = heading0[:, None] + np.concatenate((np.zeros((len(sweep), 1)), np.cumsum(sweep, axis=1)), axis=1)
    small = np.abs(sweep) < 1e-9
    half = np.where(small, 1.0, sweep / 2)
    factor = np.where(small, 1.0 - sweep**2 / 24, np.sin(half) / half)  # chord = length * sinc
    mid = (heading[:, :-1] + heading[:, 1:]) / 2
    step = (length * factor)[..., None] * np.stack((np.cos(mid), np.sin(mid)), axis=-1)
    pts = np.concatenate((np.broadcast_to(start, (len(sweep), 1, 2)), start + np.cumsum(step, axis=1)), axis=1)
    return pts, heading


def batch_residuals(start: np.ndarray, x: np.ndarray, samples: np.ndarray, s_frac: np.ndarray) -> np.ndarray:
    """Signed lateral distance (B, m) of every sample for a batch of parameter vectors (B, 2n+1)
    from ``start`` (2,) or (B, 2).

    Each sample is compared with the carrier circle (or line) of the segment at the same
    normalised arc length on the chain as the sample has on the input.
    """
    n = (x.shape[1] - 1) // 2
    kappa, length = x[:, 1 : n + 1], x[:, n + 1 :]
    pts, heading = _segment_starts(start, x[:, 0], kappa, length)
    cum = np.concatenate((np.zeros((len(x), 1)), np.cumsum(length, axis=1)), axis=1)
    target = s_frac[None, :] * cum[:, -1:]
    idx = (np.sum(cum[:, None, 1:-1] <= target[:, :, None], axis=2))  # segment of each sample
    rows = np.arange(len(x))[:, None]
    w = samples[None] - pts[rows, idx]
    h = heading[rows, idx]
    lat = -w[..., 0] * np.sin(h) + w[..., 1] * np.cos(h)
    k = kappa[rows, idx]
    a = 2.0 * lat - k * np.einsum("bij,bij->bi", w, w)
    return a / (1.0 + np.sqrt(np.clip(1.0 - k * a, 0.0, None)))


def lateral_residuals(start: np.ndarray, p: ChainParams, samples: np.ndarray, s_frac: np.ndarray) -> np.ndarray:
    """Signed distance of each sample to the carrier of its segment (see batch_residuals)."""
    return batch_residuals(np.asarray(start, float), p.vector()[None], samples, s_frac)[0]


def closure_gap(start: np.ndarray, x: np.ndarray, end: np.ndarray, turn: float | None) -> np.ndarray:
    """Gap (B, 2 or 3) between each chain's end and the required end point (2,) or (B, 2),
    and between its total turning and the required ``turn`` (closed curves)."""
    n = (x.shape[1] - 1) // 2
    pts, heading = _segment_starts(start, x[:, 0], x[:, 1 : n + 1], x[:, n + 1 :])
    gap = pts[:, -1] - end
    if turn is None:
        return gap
    return np.concatenate((gap, heading[:, -1:] - heading[:, :1] - turn), axis=1)


def jacobian(f, z: np.ndarray, eps: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """Value and forward-difference Jacobian of a batched function f((B, d)) -> (B, m)."""
    batch = np.vstack((z, z + eps * np.eye(len(z))))
    out = f(batch)
    return out[0], ((out[1:] - out[0]) / eps).T


def _minimax_step(
    r: np.ndarray, jr: np.ndarray, lift_l: np.ndarray, lift_r: np.ndarray,
    c: np.ndarray, jc: np.ndarray, lower: np.ndarray, upper: np.ndarray, weight: float,
) -> tuple[np.ndarray, float] | None:
    """Solve the linearised step: minimise max_i(±(r_i + J_i dz) + lift_i) + weight·|c + J_c dz|∞
    with ``lower`` <= dz <= ``upper``. Returns (dz, model value) or None."""
    d = jr.shape[1]
    # Inside the bounds a residual moves by at most `reach`; rows that cannot become the
    # largest one are left out of the LP (same optimum, much smaller LP).
    size = np.maximum(r + lift_l, -r + lift_r)
    reach = np.abs(jr) @ np.maximum(np.abs(lower), np.abs(upper))
    active = size + reach >= float(np.max(size - reach))
    r, jr, lift_l, lift_r = r[active], jr[active], lift_l[active], lift_r[active]
    m, k = len(r), len(c)
    # variables: dz (d), t (largest residual), e (largest end gap)
    cost = np.concatenate((np.zeros(d), [1.0, weight]))
    ones_m, ones_k = np.ones((m, 1)), np.ones((k, 1))
    zeros_m, zeros_k = np.zeros((m, 1)), np.zeros((k, 1))
    a_ub = np.vstack((
        np.hstack((jr, -ones_m, zeros_m)),
        np.hstack((-jr, -ones_m, zeros_m)),
        np.hstack((jc, zeros_k, -ones_k)),
        np.hstack((-jc, zeros_k, -ones_k)),
    ))
    b_ub = np.concatenate((-r - lift_l, r - lift_r, -c, c))
    x = solve_lp(cost, a_ub, b_ub, np.concatenate((lower, [0.0, 0.0])), np.concatenate((upper, [np.inf, np.inf])))
    if x is None:
        return None
    return x[:d], float(x[d] + weight * x[d + 1])


class ChainProblem:
    """A run to fit a chain of ``n`` segments to, in scaled variables z = x / ``unit``
    (angles; curvature x run length; length / mean length; the start's slide in mm, when it
    may slide), with the samples the deviation is measured at (``pick``, grown by exchange
    rounds)."""

    def __init__(self, start: np.ndarray, points: np.ndarray, end: np.ndarray, turn: float | None,
                 limits: FitLimits, n: int, fixed_heading: bool = False, closed_loop: bool = False,
                 slide: np.ndarray | None = None, slide_mm: float = 0.0, lines: np.ndarray | None = None) -> None:
        seg = np.linalg.norm(np.diff(points, axis=0), axis=1)
        s = np.concatenate(([0.0], np.cumsum(seg)))
        self.total = float(s[-1])
        self.frac = s / self.total
        self.points = points
        self.start = np.asarray(start, dtype=float)
        self.end = np.asarray(end, dtype=float)
        self.turn = turn
        self.limits = limits
        self.n = n
        self.fixed_heading = fixed_heading
        self.lines = np.zeros(n, dtype=bool) if lines is None else lines
        self.inset_left, self.inset_right = chord_insets(points, closed_loop)
        grid = np.linspace(0, self.total, min(MAX_SAMPLES, len(points)))
        self.pick = np.unique(np.searchsorted(s, grid).clip(0, len(points) - 1))
        self.slide = None if slide is None else np.asarray(slide, dtype=float)
        self.slide_mm = slide_mm
        self.unit = np.concatenate(([1.0], np.full(n, 1.0 / self.total), np.full(n, self.total / n),
                                    [1.0] * (self.slide is not None)))
        self.min_len_z = max(limits.min_length_mm if n > 1 else 0.0, 1e-6 * self.total) / self.unit[n + 1 : 2 * n + 1]

    def _split(self, zb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The chain parameters (B, 2n+1) and the start of each chain (B, 2) of scaled vectors."""
        x = zb * self.unit
        chain = x[:, : 2 * self.n + 1]
        if self.slide is None:
            return chain, np.broadcast_to(self.start, (len(x), 2))
        return chain, self.start + x[:, -1:] * self.slide

    def residuals(self, zb: np.ndarray) -> np.ndarray:
        """Lateral residuals (B, samples) for a batch of scaled vectors."""
        chain, start = self._split(zb)
        return batch_residuals(start, chain, self.points[self.pick], self.frac[self.pick])

    def excess(self, r: np.ndarray, where: np.ndarray | slice) -> np.ndarray:
        """Distance bound per sample: the lateral residual, plus the chord inset of the input
        on the side where the chain lies (output-to-input distance between vertices)."""
        return np.maximum(r + self.inset_left[where], -r + self.inset_right[where])

    def deviation(self, zb: np.ndarray) -> np.ndarray:
        """Largest sampled distance bound (B,)."""
        return self.excess(self.residuals(zb), self.pick).max(axis=1)

    def closure(self, zb: np.ndarray) -> np.ndarray:
        """End gap (and turning gap times the run length) (B, 2 or 3)."""
        scale = np.append([1.0, 1.0], [self.total] * (self.turn is not None))
        chain, start = self._split(zb)
        end = self.end if self.slide is None else start  # a sliding start is a loop's: its end slides along
        return closure_gap(start, chain, end, self.turn) * scale

    def bounds(self, z: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
        """Step bounds: the trust region, the curvature caps of the segments' present
        stretches and the minimum length (a parameter already past its bound may stay but
        not go farther)."""
        n = self.n
        x = z * self.unit
        ends = np.concatenate(([0.0], np.cumsum(x[n + 1 : 2 * n + 1])))
        ends = ends / ends[-1] * self.total
        cap_z = self.limits.over(ends[:-1], ends[1:]) / self.unit[1 : n + 1]
        lower, upper = np.full(len(z), -radius), np.full(len(z), radius)
        kappa = z[1 : n + 1]
        lower[1 : n + 1] = np.clip(np.minimum(-cap_z - kappa, 0.0), -radius, radius)
        upper[1 : n + 1] = np.clip(np.maximum(cap_z - kappa, 0.0), -radius, radius)
        lower[n + 1 : 2 * n + 1] = np.clip(np.minimum(self.min_len_z - z[n + 1 : 2 * n + 1], 0.0), -radius, radius)
        lower[1 : n + 1][self.lines] = upper[1 : n + 1][self.lines] = 0.0  # lines stay lines
        if self.fixed_heading:  # a start tangent pinned by the caller
            lower[0] = upper[0] = 0.0
        if self.slide is not None:  # the start stays within slide_mm of where it was given
            lower[-1] = np.clip(-self.slide_mm - z[-1], -radius, 0.0)
            upper[-1] = np.clip(self.slide_mm - z[-1], 0.0, radius)
        return lower, upper

    def add_missing(self, z: np.ndarray) -> bool:
        """Add the points whose distance bound exceeds every sampled one (the samples missed
        a peak); whether there were any."""
        chain, start = self._split(z[None])
        full = self.excess(batch_residuals(start, chain, self.points, self.frac)[0], slice(None))
        sampled = float(full[self.pick].max())
        order = np.argsort(-full)[:EXCHANGE]
        missing = order[full[order] > 1.001 * sampled + 1e-12]
        self.pick = np.union1d(self.pick, missing)
        return len(missing) > 0


def refine_chain(
    start: np.ndarray,
    params: ChainParams,
    points: np.ndarray,
    end: np.ndarray,
    turn: float | None,
    limits: FitLimits,
    target: float,
    max_iter: int = 40,
    fixed_heading: bool = False,
    closed_loop: bool = False,
    slide: np.ndarray | None = None,
    slide_mm: float = 0.0,
    stall_above: float = math.inf,
    lines: np.ndarray | None = None,
) -> tuple[ChainParams, float]:
    """Minimise the largest lateral deviation of ``points`` from the chain.

    Sequential linear programming with a trust region: at each step the residuals and the
    end conditions are linearised and the LP "minimise the largest residual plus a heavy
    penalty on the end gap" is solved with HiGHS. ``end``: the point the chain must end
    at; ``turn``: the total turning it must have (closed curves: 2π·k), or None.
    Curvatures stay under the caps of ``limits`` for the stretches their segments cover now,
    lengths above its minimum; ``fixed_heading`` keeps the start heading as it is;
    ``closed_loop``: ``points`` close on themselves (their seam is a vertex with chord insets);
    ``slide`` (a unit vector, loops only): the start (and with it the end) may move along it
    by up to ``slide_mm``, from ``start`` plus the ``shift`` of ``params``; ``lines`` (n,):
    the segments kept straight (their curvature 0 in ``params``).
    Stops early once the sampled deviation is below ``target``
    with the end gap closed, or when it is still far above it after a few steps, or when
    after those steps it is above ``stall_above`` and fell by less than STALL_SHARE over the
    last STALL_STEPS steps, or after HOPELESS_STEP steps is still HOPELESS_SHARE times above it.
    Returns (parameters, sampled deviation).
    """
    prob = ChainProblem(start, points, end, turn, limits, len(params.kappa), fixed_heading, closed_loop, slide, slide_mm,
                        lines)
    weight = 100.0  # the end gap costs this many times a lateral deviation

    def merit(zb: np.ndarray) -> np.ndarray:
        return prob.deviation(zb) + weight * np.abs(prob.closure(zb)).max(axis=1)

    z = np.append(params.vector(), [params.shift] * (slide is not None)) / prob.unit
    f = float(merit(z[None])[0])
    radius = 0.05
    iteration = 0  # LP steps, shared by all exchange rounds
    history, stalled = [f], False
    for _ in range(EXCHANGE_ROUNDS):
        linear = None  # the residuals, end gap and their Jacobians at z (kept while a step is refused)
        while iteration < max_iter:
            iteration += 1
            if f <= target or (iteration >= EARLY and f > 1.5 * target):
                break
            stalled = ((iteration >= EARLY and f > stall_above and len(history) > STALL_STEPS
                        and f > (1.0 - STALL_SHARE) * history[-STALL_STEPS - 1])
                       or (iteration > HOPELESS_STEP and f > HOPELESS_SHARE * stall_above))
            if stalled:
                break
            if linear is None:
                linear = (*jacobian(prob.residuals, z), *jacobian(prob.closure, z))
            r, jr, c, jc = linear
            lower, upper = prob.bounds(z, radius)
            solved = _minimax_step(r, jr, prob.inset_left[prob.pick], prob.inset_right[prob.pick], c, jc,
                                   lower, upper, weight)
            if solved is None:
                break
            step, model = solved
            predicted = f - model
            if predicted <= 1e-4 * target:
                break
            f_new = float(merit((z + step)[None])[0])
            ratio = (f - f_new) / predicted
            if ratio > 0:
                z, f, linear = z + step, f_new, None
            radius = radius * 2.0 if ratio > 0.75 else radius * 0.25 if ratio < 0.25 else radius
            history.append(f)
            if radius < 1e-9:
                break
        if stalled or not prob.add_missing(z):
            break
        f = float(merit(z[None])[0])
        history = [f]  # (the merit of the samples added is not comparable with the one before)
    x = z * prob.unit
    return ChainParams.from_vector(x[: 2 * prob.n + 1], float(x[-1]) if slide is not None else params.shift), f


def chord_insets(points: np.ndarray, closed_loop: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """How far the input's edges next to each vertex dip inside a smooth curve through the
    vertices (the sagitta ℓ²|κ|/8), on the left and on the right side, shape (n,) each.

    A chain that passes a vertex on the outer side of a bend is farther from the chords
    than from the vertex by about this much. The ends of an open run have none; the seam
    of a ``closed_loop`` (last point = first) is a vertex like the others.
    """
    d = np.diff(points, axis=0)
    ell = np.linalg.norm(d, axis=1)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.zeros(len(points))
    turn[1:-1] = np.remainder(np.diff(heading) + np.pi, 2 * np.pi) - np.pi
    before, after = np.concatenate(([0.0], ell)), np.concatenate((ell, [0.0]))
    if closed_loop and len(ell) > 1:
        turn[0] = turn[-1] = math.remainder(float(heading[0] - heading[-1]), 2 * math.pi)
        before[0], after[-1] = ell[-1], ell[0]
    longest = np.maximum(before, after)
    span = before + after
    inset = np.divide(longest**2 * np.abs(turn), 4 * span, out=np.zeros_like(span), where=span > 0)
    return np.where(turn > 0, inset, 0.0), np.where(turn < 0, inset, 0.0)


def worst_segment(start: np.ndarray, params: ChainParams, points: np.ndarray) -> int:
    """Index of the segment whose carrier is farthest from its share of ``points``."""
    seg = np.linalg.norm(np.diff(points, axis=0), axis=1)
    frac = np.concatenate(([0.0], np.cumsum(seg))) / seg.sum()
    r = np.abs(lateral_residuals(np.asarray(start, float), params, points, frac))
    cum = np.cumsum(params.length) / params.length.sum()
    return int(np.searchsorted(cum, frac[int(np.argmax(r))]).clip(0, len(cum) - 1))


def split_segment(params: ChainParams, j: int) -> ChainParams:
    """Parameters with segment j cut into two equal halves (same geometry, one more joint)."""
    return ChainParams(
        params.heading,
        np.insert(params.kappa, j, params.kappa[j]),
        np.concatenate((params.length[:j], [params.length[j] / 2] * 2, params.length[j + 1 :])),
        params.shift,
    )


def close_exactly(start: np.ndarray, params: ChainParams, end: np.ndarray, turn: float | None,
                  lines: np.ndarray | None = None) -> ChainParams:
    """Newton steps on the last segments' curvatures and lengths until the chain ends exactly
    at ``end`` (and turns exactly ``turn``); least-norm steps keep the change small. The
    segments of ``lines`` (n,) stay straight."""
    x = params.vector()
    n = len(params.kappa)
    last = range(max(1, n - 2), n + 1)
    free = [i for i in last if lines is None or not lines[i - 1]] + [n + i for i in last]
    scale = np.array([params.length.sum() if i <= n else 1.0 for i in free])
    start = np.asarray(start, float)
    for _ in range(8):
        gap = closure_gap(start, x[None], end, turn)[0]
        if np.abs(gap).max() < 1e-12 * max(1.0, params.length.sum()):
            break
        eps = 1e-7
        cols = []
        for i, sc in zip(free, scale):
            dx = x.copy()
            dx[i] += eps / sc
            cols.append((closure_gap(start, dx[None], end, turn)[0] - gap) / eps)
        step = np.linalg.lstsq(np.column_stack(cols), -gap, rcond=None)[0]
        x[free] += step / scale
    out = ChainParams.from_vector(x, params.shift)
    return out if np.all(out.length > 0) else params

"""A G1 chain of arcs pulled inside the σ-tube around a run: its junction points and tangents
free, optimised all at once (multiple shooting).

The unknowns are the knots s_j (arc lengths of the run where pieces meet), the chain's state
(offset y_j and tangent tilt a_j, coatsim.geometry.space.pieces) at every knot and every
piece's curvature vector c_j. Each piece depends on its own unknowns only, so its end state
and its offsets from the input points it spans are differentiated piece by piece (forward
differences, all pieces at once); tangent continuity is the linear condition "end state of
piece j = state j + 1". Each step solves the second-order cone programme

    minimise  t + W·e   over the step dx, within a trust region,
    |y_i + J_i dx|     <= t        for the sampled input points i (the 2-D offset, a cone),
    |g_j + G_j dx|     <= e        for the continuity gaps g_j of every junction,
    |c_j + dc_j|       <= cap_j    (no arc tighter than the run's curvature cap there, a cone),
    s_j+1 − s_j        >= the minimum segment length,

with Clarabel, and keeps the step if the true merit max|y| + W·max|g| falls (the trust region
grows or shrinks by how well the model predicted it; knots move in a smaller box, as the
offsets bend faster with them). When the samples are within the target, every input point
is measured and those beyond the sampled maximum join the samples (an exchange).

A state at a junction is a point of the tube, not of the curve: the chain need not touch the
input anywhere but at the run's pinned ends, which is what lets it use the whole tube. A
closed loop ends where and as it starts, its seam state free too (the end state is the
start state turned into the end frame).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix, diags
from scipy.sparse.linalg import factorized

from coatsim.geometry.limits import FitLimits
from coatsim.geometry.space.cone_program import ConeProgram
from coatsim.geometry.space.pieces import Samples, end_states, evaluate
from coatsim.geometry.space.reference import Reference
from coatsim.geometry.space.tube_chain import Ends, TubeChain

GAP_WEIGHT = 20.0  # a continuity gap costs this many times a deviation (an exact penalty)
MAX_STEPS = 40
STEPS = np.array([1e-6, 1e-6, 1e-7, 1e-7, 1e-8, 1e-8, 1e-10, 1e-10])  # forward differences of the 8 piece parameters
KNOT_SHARE = 0.05  # a knot moves by at most this share of the mean piece in a unit trust region
PER_PIECE = 16  # input points sampled per piece at first (the exchange adds the ones it misses)
EXCHANGE = 50  # points added per exchange round, at most
EXCHANGE_ROUNDS = 4
CLOSED_GAP = 1e-10  # continuity gaps below this share of the mean piece count as closed
CLOSING_STEPS = 6  # Newton steps that close a chain's gaps (quadratic: a few suffice)
FROZEN_RADIUS = 8.0  # the first trust region with the knots held (the problem is then nearly linear)
GROW, SHRINK = 0.5, 0.1  # the trust region doubles above this ratio of gain to expected gain, quarters below that
STALL = 1e-4  # a step the model expects to gain less than this share of σ ends the descent
CHORD_STEPS = 3  # corrections of a step's gaps along the step's own linearisation
PACE = 8  # steps over which the progress of a descent is judged


@dataclass(frozen=True)
class _Layout:
    """Index of every unknown in the step vector, −1 where fixed: knots (n + 1,), states
    (n + 1, 4), curvatures (n, 2); ``count`` unknowns in all."""

    knot: np.ndarray
    state: np.ndarray
    kappa: np.ndarray
    count: int

    def local(self) -> np.ndarray:
        """The unknowns of each piece's 8 parameters, (n, 8)."""
        return np.column_stack((self.knot[:-1], self.knot[1:], self.state[:-1], self.kappa))


@dataclass(frozen=True, eq=False)
class _Linear:
    """A chain's linearisation: sampled offsets (m, 2), their gradients (m, 2, 8) in the
    parameters of their ``piece`` (m,), the gap Jacobian (4n, count) and gaps (4n,)
    (tilts times ``weight``), the trust-region unit of every unknown and of the 8 piece
    parameters (``scale``), and how fast each piece's end state changes with its end knot
    (n, 4)."""

    layout: _Layout
    y: np.ndarray
    grad: np.ndarray
    piece: np.ndarray
    gaps: csr_matrix
    gap: np.ndarray
    unit: np.ndarray
    scale: np.ndarray
    weight: np.ndarray
    end_rate: np.ndarray

    @cached_property
    def gap_solver(self) -> Callable[[np.ndarray], np.ndarray] | None:
        """Solves G D Gᵀ y = r (D the squared trust-region units), factorised once for every
        correction along this linearisation (None if singular)."""
        try:
            return factorized((self.gaps @ diags(self.unit**2) @ self.gaps.T).tocsc())
        except RuntimeError:
            return None


def _moved(chain: TubeChain, lay: _Layout, dx: np.ndarray) -> TubeChain | None:
    """The chain with the step dx applied as it is (None if knots would cross)."""
    moved = [x.copy() for x in (chain.knots, chain.states, chain.kappa)]
    for arr, idx in zip(moved, (lay.knot, lay.state, lay.kappa)):
        arr[idx >= 0] += dx[idx[idx >= 0]]
    return None if np.any(np.diff(moved[0]) <= 0) else TubeChain(*moved)


class TubeProblem:
    """A run (points (m, 3) at arc lengths s (m,)), its frames, tolerance, limits and ends;
    ``fit`` pulls a TubeChain inside the tube."""

    def __init__(self, ref: Reference, points: np.ndarray, s: np.ndarray, tolerance: float,
                 limits: FitLimits, ends: Ends):
        self.ref, self.points, self.s, self.tol, self.limits, self.ends = ref, points, s, tolerance, limits, ends
        self.pick = np.arange(len(points))
        self.samples = Samples.of(ref, points, s)

    def offsets(self, chain: TubeChain, pick: np.ndarray | None = None) -> np.ndarray:
        """|y| (m,) of the chain at the input points ``pick`` (all by default)."""
        pick = np.arange(len(self.points)) if pick is None else pick
        piece = self._membership(chain, pick)
        return np.linalg.norm(evaluate(self.ref, chain.params(), self.samples.take(pick), piece)[1], axis=-1)

    def fit(self, chain: TubeChain, target: float, max_steps: int = MAX_STEPS) -> tuple[TubeChain, float]:
        """The chain refined until its deviation at every input point is at most ``target``
        (or no step helps, or the pace of the last PACE steps would not get there within
        ``max_steps``), and that deviation (mm; on success the gaps are closed to round-off).
        First with its knots where they are (a nearly linear problem: large steps), then
        with the knots moving too."""
        steps = 0
        self._cover(chain)
        for _ in range(EXCHANGE_ROUNDS + 1):
            chain, sampled, steps = self._descend(chain, target, max_steps, steps, False, FROZEN_RADIUS)
            chain, sampled, steps = self._descend(chain, target, max_steps, steps, True, 1.0)
            full = self.offsets(chain)
            order = np.argsort(-full)[:EXCHANGE]
            missed = order[full[order] > sampled * (1 + 1e-3) + 1e-9 * self.tol]
            if not len(missed) or steps >= max_steps:
                break
            self.pick = np.union1d(self.pick, missed)
        return chain, float(full.max())

    def _cover(self, chain: TubeChain) -> None:
        """The samples: PER_PIECE input points spread over every piece, and every piece's
        point farthest from the chain."""
        edges = np.minimum(np.searchsorted(self.s, chain.knots), len(self.s) - 1)
        spread = np.concatenate([np.linspace(a, b, PER_PIECE).astype(int) for a, b in zip(edges[:-1], edges[1:])])
        full = self.offsets(chain)
        piece = self._membership(chain, np.arange(len(self.s)))
        order = np.lexsort((-full, piece))
        first = np.flatnonzero(np.diff(np.concatenate(([-1], piece[order]))))
        self.pick = np.union1d(spread, order[first])

    def _descend(self, chain: TubeChain, target: float, max_steps: int, steps: int, knots: bool,
                 radius: float) -> tuple[TubeChain, float, int]:
        """Trust-region steps on the sampled merit, the knots moving or not; (chain, sampled
        deviation, steps taken in all)."""
        dev, gap = self._merit(chain)
        f = dev + GAP_WEIGHT * gap
        closed = CLOSED_GAP * float(np.mean(np.diff(chain.knots)))
        lin = None
        paced = (steps, dev)
        while steps < max_steps:
            if steps - paced[0] >= PACE:
                if (paced[1] - dev) * (max_steps - steps) / PACE < dev - target:
                    break  # at this pace the target is out of reach
                paced = (steps, dev)
            if dev <= target:
                closed_chain = self._close(chain, closed)
                if closed_chain is not None:
                    chain, (dev, gap) = closed_chain, self._merit(closed_chain)
                    if dev <= target:
                        break
                    f = dev + GAP_WEIGHT * gap
            steps += 1
            lin = lin or self._linearise(chain, knots)
            step = self._step(chain, lin, radius)
            if step is None:
                break
            trial, model = step
            if f - model <= STALL * self.tol and gap <= closed:
                break  # the model sees no better chain nearby: a (local) optimum
            for _ in range(CHORD_STEPS):  # close the step's gaps (second order in its size)
                trial = self._corrected(trial, lin) or trial
            t_dev, t_gap = self._merit(trial)
            t_f = t_dev + GAP_WEIGHT * t_gap
            ratio = (f - t_f) / max(f - model, 1e-300)
            if ratio > 0:
                f, chain, dev, gap = t_f, trial, t_dev, t_gap
                lin = None
            radius = radius * 2.0 if ratio > GROW else radius * 0.25 if ratio < SHRINK else radius
            if radius < 1e-6:
                break
        if gap > closed:
            closed_chain = self._close(chain, closed)
            if closed_chain is not None:
                chain, (dev, gap) = closed_chain, self._merit(closed_chain)
        return chain, dev, steps

    def _membership(self, chain: TubeChain, pick: np.ndarray) -> np.ndarray:
        return np.clip(np.searchsorted(chain.knots, self.s[pick], side="right") - 1, 0, chain.n - 1)

    def _measure(self, params: np.ndarray, chain: TubeChain, samples: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """(offsets (…, m, 2) at the samples (none without ``samples``), continuity gaps
        (…, n, 4)) of piece parameters (…, n, 8); the knot states compared with are the chain's."""
        piece = self._membership(chain, self.pick)
        ends, offs = evaluate(self.ref, params, self.samples.take(self.pick) if samples else None, piece)
        target = np.broadcast_to(chain.states[1:], ends.shape).copy()
        if self.ends.seam is not None:  # the loop ends where and as it starts
            target[..., -1, :2] = self.ends.seam @ chain.states[0, :2]
            target[..., -1, 2:] = self.ends.seam @ chain.states[0, 2:]
        return offs, ends - target

    def _gap(self, chain: TubeChain) -> float:
        """The largest continuity gap (tilts times the mean piece length)."""
        h = float(np.mean(np.diff(chain.knots)))
        return float(np.abs(self._measure(chain.params(), chain, samples=False)[1] * [1, 1, h, h]).max())

    def _merit(self, chain: TubeChain) -> tuple[float, float]:
        """(largest sampled offset, largest continuity gap, tilts times the mean piece length)."""
        offs, gaps = self._measure(chain.params(), chain)
        h = float(np.mean(np.diff(chain.knots)))
        return float(np.linalg.norm(offs, axis=-1).max()), float(np.abs(gaps * [1, 1, h, h]).max())

    def _layout(self, n: int, knots: bool) -> _Layout:
        fixed = np.zeros((n + 1, 4), dtype=bool)
        fixed[[0, n], :2] = True
        fixed[0, :2] = self.ends.seam is None  # a loop's seam point is free in the tube too
        fixed[0, 2:] = self.ends.start_tangent
        fixed[n, 2:] = self.ends.end_tangent or self.ends.seam is not None
        count = (n - 1 if knots else 0) + int((~fixed).sum()) + 2 * n
        index = iter(range(count))
        knot = np.array([-1] + [next(index) if knots else -1 for _ in range(n - 1)] + [-1])
        state = np.array([[-1 if f else next(index) for f in row] for row in fixed])
        kappa = np.array([[next(index), next(index)] for _ in range(n)], dtype=int).reshape(n, 2)
        return _Layout(knot, state, kappa, count)

    def _linearise(self, chain: TubeChain, knots: bool = True) -> _Linear:
        """The offsets and continuity gaps of the chain and their derivatives."""
        n = chain.n
        lay = self._layout(n, knots)
        local = lay.local()
        h = float(np.mean(np.diff(chain.knots)))
        batch = np.repeat(chain.params()[None], 9, axis=0)
        batch[np.arange(1, 9), :, np.arange(8)] += STEPS[:, None]
        offs, gaps = self._measure(batch, chain)
        d_offs = (offs[1:] - offs[0]) / STEPS[:, None, None]  # (8, m, 2)
        d_gaps = (gaps[1:] - gaps[0]) / STEPS[:, None, None]  # (8, n, 4)
        grad = np.transpose(d_offs, (1, 2, 0))  # (m, 2, 8)
        weight = np.array([1.0, 1.0, h, h])  # tilt gaps times the mean piece length
        g_rows = np.repeat(np.arange(4 * n).reshape(n, 4)[:, :, None], 9, axis=2)
        cols = np.concatenate((np.repeat(local[:, None, :], 4, axis=1), lay.state[1:, :, None]), axis=2)
        vals = np.concatenate((np.transpose(d_gaps, (1, 2, 0)) * weight[None, :, None],
                               -np.broadcast_to(weight, (n, 4))[:, :, None]), axis=2)
        r, c, v = g_rows.ravel(), cols.ravel(), vals.ravel()
        if self.ends.seam is not None:  # the last end state is compared with the turned start state
            for first, w in ((0, 1.0), (2, h)):
                r = np.concatenate((r, np.repeat(4 * (n - 1) + first + np.array([0, 1]), 2)))
                c = np.concatenate((c, np.tile(lay.state[0, first : first + 2], 2)))
                v = np.concatenate((v, -self.ends.seam.ravel() * w))
        keep = c >= 0
        gap_matrix = coo_matrix((v[keep], (r[keep], c[keep])), shape=(4 * n, lay.count)).tocsr()
        scale = np.array([KNOT_SHARE * h, KNOT_SHARE * h, self.tol, self.tol, 4 * self.tol / h, 4 * self.tol / h,
                          8 * self.tol / h**2, 8 * self.tol / h**2])
        unit = np.zeros(lay.count)
        for idx, sc in zip(local.T, scale):
            unit[idx[idx >= 0]] = sc
        unit[lay.state[-1][lay.state[-1] >= 0]] = scale[4]
        return _Linear(lay, offs[0], grad, self._membership(chain, self.pick), gap_matrix, (gaps[0] * weight).ravel(),
                       unit, scale, weight, d_gaps[1])

    def _step(self, chain: TubeChain, lin: _Linear, radius: float) -> tuple[TubeChain, float] | None:
        """One trust-region step: the trial chain and the model's merit for it."""
        lay = lin.layout
        t_col, e_col = lay.count, lay.count + 1
        prog = ConeProgram(lay.count + 2)
        # gaps: ±(g + G dx) − e <= 0
        g = lin.gaps.tocoo()
        ng = g.shape[0]
        for sign in (1.0, -1.0):
            prog.add(np.concatenate((g.row, np.arange(ng))), np.concatenate((g.col, np.full(ng, e_col))),
                     np.concatenate((sign * g.data, -np.ones(ng))), -sign * lin.gap)
        self._limit_rows(prog, chain, lay, lin.scale[6] * radius)
        # offsets: |y_i + J_i dx| <= t for the points that can still be the largest
        reach = np.linalg.norm(lin.grad, axis=1) @ (lin.scale * radius)
        size = np.linalg.norm(lin.y, axis=1)
        act = np.flatnonzero(size + reach >= (size - reach).max())
        k = len(act)
        local = lay.local()[lin.piece[act]]  # (k, 8)
        rows = np.concatenate((np.zeros((k, 1), int), np.ones((k, 8), int), np.full((k, 8), 2)), axis=1) + 3 * np.arange(k)[:, None]
        cols = np.concatenate((np.full((k, 1), t_col), local, local), axis=1)
        vals = np.concatenate((-np.ones((k, 1)), -lin.grad[act, 0], -lin.grad[act, 1]), axis=1)
        rhs = np.column_stack((np.zeros(k), lin.y[act]))
        prog.add(rows, cols, vals, rhs, cone=True)
        cost = np.zeros(lay.count + 2)
        cost[t_col], cost[e_col] = 1.0, GAP_WEIGHT
        bound = lin.unit * radius
        x = prog.solve(cost, np.append(-bound, [0.0, 0.0]), np.append(bound, [np.inf, np.inf]))
        if x is None:
            return None
        trial = self._retracted(chain, lin, x[: lay.count])
        return None if trial is None else (trial, float(x[t_col] + GAP_WEIGHT * x[e_col]))

    def resampled(self, chain: TubeChain, n: int) -> TubeChain:
        """The chain's shape with ``n`` pieces: knots spread as the chain's are (the k-th new
        knot where the chain has k·n_old/n pieces behind it), the states the chain's own at
        the new knots, each curvature the mean of the chain's over the new piece."""
        index = np.arange(chain.n + 1, dtype=float)
        knots = np.interp(np.linspace(0.0, chain.n, n + 1), index, chain.knots)
        knots[[0, -1]] = chain.knots[[0, -1]]
        inner = knots[1:-1]
        j = np.clip(np.searchsorted(chain.knots, inner, side="right") - 1, 0, chain.n - 1)
        params = chain.params()[j].copy()
        params[:, 1] = inner
        states = end_states(self.ref, params)
        turned = np.vstack((np.zeros((1, 2)), np.cumsum(chain.kappa * np.diff(chain.knots)[:, None], axis=0)))
        total = np.column_stack([np.interp(knots, chain.knots, turned[:, k]) for k in range(2)])
        kappa = np.diff(total, axis=0) / np.diff(knots)[:, None]
        return TubeChain(knots, np.vstack((chain.states[:1], states, chain.states[-1:])), kappa)

    def _retracted(self, chain: TubeChain, lin: _Linear, dx: np.ndarray) -> TubeChain | None:
        """The chain after the step dx, a moved knot carrying its state along the piece before
        it: the state there is that piece's, exactly, at the new knot, plus the part of the
        step's state change the knot move does not explain (to first order both are the
        step; beyond it, a knot moved by δ keeps the chain's shape instead of turning the
        next piece by the frame's κδ, so knots can move far in one step)."""
        trial = _moved(chain, lin.layout, dx)
        if trial is None:
            return None
        delta = trial.knots[1:-1] - chain.knots[1:-1]
        if not np.any(delta):
            return trial
        params = chain.params()[:-1].copy()
        params[:, 1] = trial.knots[1:-1]
        followed = end_states(self.ref, params)
        states = trial.states.copy()
        linear = chain.states[1:-1] + lin.end_rate[:-1] * delta[:, None]
        states[1:-1] = followed + (trial.states[1:-1] - linear)
        return TubeChain(trial.knots, states, trial.kappa)

    def _close(self, chain: TubeChain, closed: float) -> TubeChain | None:
        """The chain with its continuity gaps closed below ``closed`` by Newton steps of the
        smallest change (None if they do not converge)."""
        for _ in range(CLOSING_STEPS):
            if self._gap(chain) <= closed:
                return chain
            chain = self._corrected(chain, self._linearise(chain, knots=False))
            if chain is None:
                return None
        return chain if self._gap(chain) <= closed else None

    def _corrected(self, trial: TubeChain, lin: _Linear) -> TubeChain | None:
        """The trial with its continuity gaps closed to first order by the smallest change (in
        the trust region's units) along the linearisation: min |d / unit| with G d = −g(trial)
        (a second-order correction: the gaps of a step grow with its square)."""
        _, gaps = self._measure(trial.params(), trial, samples=False)
        solve = lin.gap_solver
        if solve is None:
            return None
        y = solve(-(gaps * lin.weight).ravel())
        if not np.all(np.isfinite(y)):
            return None
        return _moved(trial, lin.layout, lin.unit**2 * (lin.gaps.T @ y))

    def _limit_rows(self, prog: ConeProgram, chain: TubeChain, lay: _Layout, reach: float) -> None:
        """Minimum lengths ds_j − ds_j+1 <= h_j − min_length (never shorter than a piece is
        now) and curvature caps |c_j + dc_j| <= cap_j (``reach``: the curvature step allowed)."""
        h = np.diff(chain.knots)
        prog.add(np.repeat(np.arange(chain.n), 2), np.column_stack((lay.knot[:-1], lay.knot[1:])),
                 np.tile([1.0, -1.0], chain.n), np.maximum(h - self.limits.min_length_mm, 0.0))
        caps = self.limits.over(chain.knots[:-1], chain.knots[1:])
        n = chain.n
        # an arc above its cap comes down by at most the trust region's curvature step
        caps = np.maximum(caps, np.linalg.norm(chain.kappa, axis=1) - 0.9 * reach)
        rows = np.column_stack((np.ones(n, int), 2 * np.ones(n, int))) + 3 * np.arange(n)[:, None]
        prog.add(rows, lay.kappa, -np.ones((n, 2)), np.column_stack((caps, chain.kappa)), cone=True)

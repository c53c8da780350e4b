"""Differential inverse kinematics with mink: track dense Cartesian samples, check every one.

Per sample: FrameTask on the TCP site (position and orientation), a light PostureTask towards
home, ConfigurationLimit and VelocityLimit, daqp. The first guess is the linear extrapolation
of the two previous solutions, then QP steps until the residual is negligible. A sample whose
residual stays above ``POS_TOL_MM`` / ``ROT_TOL_DEG`` stops the run with an ExecutionError that
names the program step, the pose and the residual.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import mink
import mujoco
import numpy as np

from coatsim.core.numeric import ROUND_OFF
from coatsim.core.errors import ExecutionError
from coatsim.robot.cell import JOINTS, M_TO_MM, MM, Cell
from coatsim.robot.chain import cell_chain
from coatsim.robot.ik_batch import DAMPING_M2, continuity_ok, first_order, refine, rotation_vectors
from coatsim.robot.turns import within_turns

POS_TOL_MM = 0.05
ROT_TOL_DEG = 0.05
_CONVERGED_MM = 1e-4   # QP steps until this close (1/500 of the tolerance) ...
_CONVERGED_DEG = 1e-4
_MAX_TRACK_ITERS = 8   # ... or this many QP steps per sample
_MAX_POSE_ITERS = 400  # for isolated targets (joint-move end points)
_PREDICTOR_POINTS = 2  # linear extrapolation of the previous solutions
KNOT_MM = 20.0         # spacing of the samples mink solves where the path is smooth
_MIN_KNOT_SAMPLES = 8  # shorter pieces start from the first-order prediction, without knots ...
_MIN_KNOTS = 3         # ... and so do pieces shorter than two knot spacings (no knot inside)
_MAX_NEWTON_ITERS = 6  # batched Newton steps on the samples between the knots ...
_POLISH_MM = 1e-6      # ... until this close
_POLISH_DEG = 1e-6


class UnreachablePose(ExecutionError):
    """The IK cannot put the gun on a pose: the program ``step``, the gun's position (mm) and
    rotation there, the last configuration reached before it (``q_near``) and, once diagnosed,
    the ``reason`` (coatsim.robot.reachability)."""

    def __init__(self, message: str, *, step: str, position_mm: np.ndarray, rotation: np.ndarray,
                 q_near: np.ndarray, reason: str | None = None) -> None:
        super().__init__(message)
        self.step, self.position_mm, self.rotation, self.q_near, self.reason = step, position_mm, rotation, q_near, reason


@dataclass(frozen=True)
class Residual:
    """Largest IK residual over a run: position (mm) and orientation (deg)."""

    position_mm: float
    rotation_deg: float
    iterations: int


def _pose_errors(data, site: int, p_mm: np.ndarray, r: np.ndarray) -> tuple[float, float]:
    """Position (mm) and rotation (deg) distance of the TCP site from a target pose."""
    d = data.site_xpos[site] * M_TO_MM - p_mm
    dp = math.sqrt(float(d @ d))
    # trace(R_site^T R) = sum of element-wise products
    cos = (float(np.dot(data.site_xmat[site], r.ravel())) - 1.0) / 2.0
    return dp, math.degrees(math.acos(min(1.0, max(-1.0, cos))))


def _describe(p_mm: np.ndarray, r: np.ndarray) -> str:
    z = r[:, 2]
    return (f"pose x={p_mm[0]:.3f} y={p_mm[1]:.3f} z={p_mm[2]:.3f} mm, "
            f"tool axis ({z[0]:.3f}, {z[1]:.3f}, {z[2]:.3f})")


class Tracker:
    """Reusable IK solver bound to one cell (mink Configuration owns its own MjData)."""

    def __init__(self, cell: Cell, posture_cost: float = 1e-4):
        self.cell = cell
        self.configuration = mink.Configuration(cell.model, cell.home)
        self.frame = mink.FrameTask("tcp", "site", position_cost=1.0, orientation_cost=1.0, lm_damping=1e-6)
        self.posture = mink.PostureTask(cell.model, cost=posture_cost)
        self.posture.set_target(cell.home)
        self.tasks = [self.frame, self.posture]
        self.config_limit = mink.ConfigurationLimit(cell.model, min_distance_from_limits=1e-3)
        self.velocity_limit = mink.VelocityLimit(cell.model, dict(zip(JOINTS, cell.v_max)))
        self.chain = cell_chain(cell)
        self._single = mujoco.MjData(cell.model)  # one configuration's kinematics, in C
        self._jac = np.zeros((6, cell.model.nv))

    def _target(self, quat_wxyz: np.ndarray, p_mm: np.ndarray) -> None:
        self.frame.set_target(mink.SE3(np.concatenate((quat_wxyz, p_mm * MM))))

    def _iterate(self, p_mm, r, dt, limits, max_iters) -> tuple[float, float, int]:
        cfg, site = self.configuration, self.cell.tcp_site
        dp, dr = _pose_errors(cfg.data, site, p_mm, r)
        it = 0
        while (dp > _CONVERGED_MM or dr > _CONVERGED_DEG) and it < max_iters:
            v = mink.solve_ik(cfg, self.tasks, dt, "daqp", damping=1e-9, limits=limits)
            cfg.integrate_inplace(v, dt)
            dp, dr = _pose_errors(cfg.data, site, p_mm, r)
            it += 1
        return dp, dr, it

    def solve_pose(self, q_start: np.ndarray, p_mm: np.ndarray, r: np.ndarray, label: str) -> np.ndarray:
        """Joint configuration reaching one pose (the goal of a joint move), starting the search
        at ``q_start``. Where the search inside the joint ranges stalls at a limit, the pose
        reached without them counts with each joint a whole turn off if that brings it inside its
        range (the same arm pose: a joint move turns the joint the other way round)."""
        q_start = np.asarray(q_start, float)
        q, dp, dr = self.solve_bounded(q_start, p_mm, r)
        if dp > POS_TOL_MM or dr > ROT_TOL_DEG:
            free, dp_free, dr_free = self.solve_unbounded(q_start, p_mm, r)
            inside = within_turns(free, q_start, self.cell.q_min, self.cell.q_max)
            if dp_free <= POS_TOL_MM and dr_free <= ROT_TOL_DEG and inside is not None:
                q, dp, dr = self.solve_bounded(inside, p_mm, r)
        if dp > POS_TOL_MM or dr > ROT_TOL_DEG:
            raise UnreachablePose(
                f"{label}: cannot reach {_describe(p_mm, r)}: IK residual {dp:.3f} mm / {dr:.3f} deg "
                f"exceeds {POS_TOL_MM} mm / {ROT_TOL_DEG} deg; move the path within the arm's reach",
                step=label, position_mm=p_mm, rotation=r, q_near=q_start)
        return q

    def solve_bounded(self, q_start: np.ndarray, p_mm: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, float, float]:
        """The configuration the IK reaches for one pose inside the joint ranges from ``q_start``,
        and its residual (mm, deg), without judging it."""
        return self._solve(q_start, p_mm, r, [self.config_limit])

    def solve_unbounded(self, q_start: np.ndarray, p_mm: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, float, float]:
        """As ``solve_bounded`` with the joint ranges ignored (where would the joints have to go?)."""
        return self._solve(q_start, p_mm, r, [])

    def _solve(self, q_start, p_mm, r, limits) -> tuple[np.ndarray, float, float]:
        self.configuration.update(np.asarray(q_start, float))
        self._target(_quat(r[None])[0], p_mm)
        dp, dr, _ = self._iterate(p_mm, r, 0.05, limits, _MAX_POSE_ITERS)
        return self.configuration.q.copy(), dp, dr

    def track(
        self,
        q_start: np.ndarray,
        s_mm: np.ndarray,
        positions_mm: np.ndarray,
        rotations: np.ndarray,
        step_time: np.ndarray,
        label: Callable[[int], str],
    ) -> tuple[np.ndarray, np.ndarray, Residual]:
        """Joint configurations (n, 6) along the samples, and the wrist-centre positions (n, 3) mm.

        Predictor-corrector: the first guess at sample i is the linear extrapolation (in the path
        length ``s_mm``) of the last two solutions; mink QP steps correct it until the residual
        is below 10^-4 mm / 10^-4 deg (one step on smooth stretches).
        ``q_start`` must already put the tool on the first sample; ``step_time`` (n,) s is the
        time the programmed speed allows from the previous sample to each sample: it scales the
        joint velocity limit into a per-step bound (a joint move that would need more is a
        singularity symptom and shows up as a residual).

        Where the arm's kinematics are available vectorised, mink solves only knots about
        ``KNOT_MM`` apart (none on pieces under 8 samples or without a knot between their ends,
        which start from the first-order prediction at ``q_start``: the short moves of an
        exact-stop polyline); the samples between start from a cubic through the knot
        solutions, and batched Newton steps bring every sample to 10^-6 mm / 10^-6 deg. The
        result is kept when every sample converged, stays inside the joint limits and within one
        speed-bounded QP step of the per-sample prediction; otherwise every sample is solved as
        above.
        """
        if self.chain is not None and len(s_mm) >= 2:
            fast = self._track_fast(q_start, s_mm, positions_mm, rotations, step_time)
            if fast is not None:
                return fast
        return self._track_samples(q_start, s_mm, positions_mm, rotations, step_time, label, range(len(s_mm)))

    def _track_samples(self, q_start, s_mm, positions_mm, rotations, step_time, label, indices,
                       strict: bool = True) -> tuple[np.ndarray, np.ndarray, Residual] | None:
        """The per-sample predictor-corrector over ``indices`` (all samples, or the knots);
        ``strict=False`` returns None instead of raising on a residual above the tolerance."""
        cfg, cell = self.configuration, self.cell
        idx = np.asarray(indices)
        quats = _quat(rotations[idx])
        qs = np.empty((len(idx), 6))
        wrist = np.empty((len(idx), 3))
        limits = [self.config_limit, self.velocity_limit]
        worst = [0.0, 0.0, 0]
        q = np.asarray(q_start, float)
        s_at = s_mm[idx]
        # the time the programmed speed allows since the previous solved sample
        elapsed = np.concatenate(([0.0], np.cumsum(step_time[1:])))
        dt = np.concatenate(([step_time[idx[0]]], np.diff(elapsed[idx])))
        for k, i in enumerate(idx):
            if k >= 1:
                m = min(k, _PREDICTOR_POINTS)
                q = _extrapolate(s_at[k - m:k], qs[k - m:k], s_at[k])
            cfg.update(np.clip(q, cell.q_min, cell.q_max))
            self._target(quats[k], positions_mm[i])
            dp, dr, it = self._iterate(positions_mm[i], rotations[i], max(float(dt[k]), 1e-4), limits,
                                       _MAX_TRACK_ITERS)
            if dp > POS_TOL_MM or dr > ROT_TOL_DEG:
                if not strict:
                    return None
                raise UnreachablePose(
                    f"{label(i)}: cannot follow the path at {_describe(positions_mm[i], rotations[i])}: "
                    f"IK residual {dp:.3f} mm / {dr:.3f} deg exceeds {POS_TOL_MM} mm / {ROT_TOL_DEG} deg "
                    "(out of reach, joint limit or singularity); move or re-orient the path",
                    step=label(i), position_mm=positions_mm[i], rotation=rotations[i],
                    q_near=qs[k - 1] if k else np.asarray(q_start, float))
            worst = [max(worst[0], dp), max(worst[1], dr), max(worst[2], it)]
            qs[k] = cfg.q
            wrist[k] = cfg.data.site_xpos[cell.wrist_site] * M_TO_MM
        return qs, wrist, Residual(worst[0], worst[1], int(worst[2]))

    def _track_fast(self, q_start, s_mm, positions_mm, rotations, step_time) -> tuple | None:
        """Knots with mink (or the first-order prediction on a short piece, then the knots if
        that does not converge), every sample polished by batched Newton; None where that is not
        the path the per-sample tracker would follow."""
        knots = _knots(s_mm, KNOT_MM) if len(s_mm) >= _MIN_KNOT_SAMPLES else np.zeros(0, int)
        if len(knots) < _MIN_KNOTS:
            fast = self._polish(self._first_order(np.asarray(q_start, float), positions_mm, rotations), 0,
                                s_mm, positions_mm, rotations, step_time)
            if fast is not None or len(knots) == 0:
                return fast
        solved = self._track_samples(q_start, s_mm, positions_mm, rotations, step_time, None, knots, strict=False)
        if solved is None:
            return None
        q_knots, _, knot_residual = solved
        guess = _interpolate(s_mm[knots], q_knots, s_mm)
        guess[knots] = q_knots
        return self._polish(guess, knot_residual.iterations, s_mm, positions_mm, rotations, step_time)

    def batchable(self, s_mm: np.ndarray) -> bool:
        """Whether ``track`` starts a piece at these samples from the first-order prediction
        (a piece without a knot between its ends), so ``track_run`` can solve it with others."""
        return self.chain is not None and len(s_mm) >= 2 and \
            (len(s_mm) < _MIN_KNOT_SAMPLES or len(_knots(s_mm, KNOT_MM)) < _MIN_KNOTS)

    def track_run(self, q_start: np.ndarray, pieces: Sequence[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]
                  ) -> list[tuple[np.ndarray, np.ndarray, Residual]]:
        """``track`` on consecutive rest-to-rest pieces (s_mm, positions_mm, rotations,
        step_time), each ``batchable``, the first starting at ``q_start``: the results of the
        leading pieces, as many as converge, the others left to ``track``.

        An exact-stop polyline is hundreds of such pieces, each a handful of samples, where the
        vectorised steps cost more in calls than in arithmetic. Each piece depends on the one
        before only through its start, the configuration at the rest point between them; those
        are solved one after the other with MuJoCo (a first-order prediction and Newton steps
        on one sample), then every sample of every piece starts from the first-order
        prediction at its piece's start and is polished by one batched Newton refinement, and
        each piece is checked as ``track`` checks it."""
        cell, chain = self.cell, self.chain
        starts = [np.asarray(q_start, float)]
        for s_mm, positions_mm, rotations, _ in pieces[:-1]:
            q_end = self._newton_one(self._first_order(starts[-1], positions_mm[-1:], rotations[-1:])[0],
                                     positions_mm[-1], rotations[-1])
            if q_end is None:
                break
            starts.append(q_end)
        pieces = pieces[:len(starts)]
        owner = np.concatenate([np.full(len(piece[0]), k) for k, piece in enumerate(pieces)])
        positions = np.concatenate([piece[1] for piece in pieces])
        rotations = np.concatenate([piece[2] for piece in pieces])
        q0 = np.array(starts)
        at = chain.poses(q0)
        jac = at.jacobian()
        e = np.hstack((positions * MM - at.tcp[owner], rotation_vectors(rotations, at.rotation[owner])))
        step = np.linalg.solve((jac @ np.swapaxes(jac, 1, 2) + DAMPING_M2 * np.eye(6))[owner], e[..., None])[..., 0]
        guess = q0[owner] + np.einsum("nji,nj->ni", jac[owner], step)
        q, dp, dr, wrist = refine(chain, guess, positions, rotations, _POLISH_MM, _POLISH_DEG, _MAX_NEWTON_ITERS,
                                  cell.wrist_site)
        out = []
        margin = 1e-3  # as the QP's ConfigurationLimit
        for k, (s_mm, _, _, step_time) in enumerate(pieces):
            rows = owner == k
            qk, dpk, drk = q[rows], dp[rows], dr[rows]
            if dpk.max() > _CONVERGED_MM or drk.max() > _CONVERGED_DEG \
                    or np.any(qk < cell.q_min + margin - ROUND_OFF) or np.any(qk > cell.q_max - margin + ROUND_OFF) \
                    or not continuity_ok(s_mm, qk, step_time, cell.v_max):
                break
            out.append((qk, wrist[rows], Residual(float(dpk.max()), float(drk.max()), 0)))
        return out

    def _newton_one(self, q: np.ndarray, p_mm: np.ndarray, r: np.ndarray) -> np.ndarray | None:
        """Newton steps (MuJoCo's kinematics) on one configuration until its TCP is within
        10^-6 mm / 10^-6 deg of the pose; None when it does not get there."""
        model, data, site = self.cell.model, self._single, self.cell.tcp_site
        q = np.array(q, float)
        for it in range(_MAX_NEWTON_ITERS + 1):
            data.qpos[:] = q
            mujoco.mj_kinematics(model, data)
            e = np.concatenate((p_mm * MM - data.site_xpos[site],
                                rotation_vectors(r[None], data.site_xmat[site].reshape(1, 3, 3))[0]))
            if float(np.sqrt(e[:3] @ e[:3])) * M_TO_MM <= _POLISH_MM \
                    and math.degrees(float(np.sqrt(e[3:] @ e[3:]))) <= _POLISH_DEG:
                return q
            if it == _MAX_NEWTON_ITERS:
                return None
            mujoco.mj_comPos(model, data)
            mujoco.mj_jacSite(model, data, self._jac[:3], self._jac[3:], site)
            q += self._jac.T @ np.linalg.solve(self._jac @ self._jac.T + DAMPING_M2 * np.eye(6), e)
        return None

    def _first_order(self, q0: np.ndarray, positions_mm: np.ndarray, rotations: np.ndarray) -> np.ndarray:
        """The first-order prediction from q0 for every sample, with MuJoCo's kinematics and
        Jacobian at q0 (one configuration: cheaper in C than the vectorised chain)."""
        model, data, site = self.cell.model, self._single, self.cell.tcp_site
        data.qpos[:] = q0
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        mujoco.mj_jacSite(model, data, self._jac[:3], self._jac[3:], site)
        return first_order(q0, data.site_xpos[site], data.site_xmat[site].reshape(3, 3), self._jac, positions_mm,
                           rotations)

    def _polish(self, guess, qp_iterations, s_mm, positions_mm, rotations, step_time) -> tuple | None:
        """Every sample, the knots too, polished well below the QP's convergence (a joint path
        without residual noise between neighbouring samples); None unless every sample
        converged inside the joint limits on a path the per-sample tracker would follow."""
        cell = self.cell
        q, dp, dr, wrist = refine(self.chain, guess, positions_mm, rotations, _POLISH_MM, _POLISH_DEG,
                                  _MAX_NEWTON_ITERS, cell.wrist_site)
        margin = 1e-3  # as the QP's ConfigurationLimit
        if dp.max() > _CONVERGED_MM or dr.max() > _CONVERGED_DEG \
                or np.any(q < cell.q_min + margin - ROUND_OFF) or np.any(q > cell.q_max - margin + ROUND_OFF) \
                or not continuity_ok(s_mm, q, step_time, cell.v_max):
            return None
        return q, wrist, Residual(float(dp.max()), float(dr.max()), qp_iterations)


def _knots(s_mm: np.ndarray, spacing_mm: float) -> np.ndarray:
    """Sample indices about ``spacing_mm`` apart along the path, the first and the last included."""
    picks = [0]
    for i in range(1, len(s_mm) - 1):
        if s_mm[i] - s_mm[picks[-1]] >= spacing_mm:
            picks.append(i)
    picks.append(len(s_mm) - 1)
    return np.array(picks)


def _interpolate(s_knots: np.ndarray, q_knots: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Joint configurations at ``s`` from the knot solutions: a cubic spline (linear for fewer
    than four knots, where scipy would solve a dense system)."""
    if len(s_knots) < 4:
        return np.column_stack([np.interp(s, s_knots, q_knots[:, j]) for j in range(q_knots.shape[1])])
    from scipy.interpolate import CubicSpline

    return CubicSpline(s_knots, q_knots, axis=0)(s)


def _extrapolate(s: np.ndarray, q: np.ndarray, x: float) -> np.ndarray:
    """Lagrange extrapolation of q (k, 6) given at s (k,) to the path length x."""
    out = np.zeros(q.shape[1])
    for j in range(len(s)):
        w = 1.0
        for m in range(len(s)):
            if m != j:
                w *= (x - s[m]) / (s[j] - s[m])
        out += w * q[j]
    return out


def _quat(rotations: np.ndarray) -> np.ndarray:
    """wxyz quaternions (n, 4) of rotation matrices (n, 3, 3) (mink and MuJoCo order)."""
    out = np.empty((len(rotations), 4))
    for k, r in enumerate(np.asarray(rotations, float).reshape(-1, 9)):
        mujoco.mju_mat2Quat(out[k], r)
    return out

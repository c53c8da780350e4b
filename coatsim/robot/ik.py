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
from scipy.spatial.transform import Rotation

from coatsim.errors import ExecutionError
from coatsim.robot.cell import JOINTS, MM, M_TO_MM, Cell

POS_TOL_MM = 0.05
ROT_TOL_DEG = 0.05
_CONVERGED_MM = 1e-4   # QP steps until this close (1/500 of the tolerance) ...
_CONVERGED_DEG = 1e-4
_MAX_TRACK_ITERS = 8   # ... or this many QP steps per sample
_MAX_POSE_ITERS = 400  # for isolated targets (joint-move end points)
_PREDICTOR_POINTS = 2  # linear extrapolation of the previous solutions


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
        """Joint configuration reaching one pose, starting the search at ``q_start``."""
        self.configuration.update(np.asarray(q_start, float))
        self._target(_quat(r[None])[0], p_mm)
        dp, dr, _ = self._iterate(p_mm, r, 0.05, [self.config_limit], _MAX_POSE_ITERS)
        if dp > POS_TOL_MM or dr > ROT_TOL_DEG:
            raise ExecutionError(
                f"{label}: cannot reach {_describe(p_mm, r)}: IK residual {dp:.3f} mm / {dr:.3f} deg "
                f"exceeds {POS_TOL_MM} mm / {ROT_TOL_DEG} deg; move the path within the arm's reach"
            )
        return self.configuration.q.copy()

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
        """
        cfg, cell = self.configuration, self.cell
        n = len(positions_mm)
        quats = _quat(rotations)
        qs = np.empty((n, 6))
        wrist = np.empty((n, 3))
        limits = [self.config_limit, self.velocity_limit]
        worst = [0.0, 0.0, 0]
        q = np.asarray(q_start, float)
        for i in range(n):
            if i >= 1:
                k = min(i, _PREDICTOR_POINTS)
                q = _extrapolate(s_mm[i - k:i], qs[i - k:i], s_mm[i])
            cfg.update(np.clip(q, cell.q_min, cell.q_max))
            self._target(quats[i], positions_mm[i])
            dp, dr, it = self._iterate(positions_mm[i], rotations[i], max(float(step_time[i]), 1e-4),
                                       limits, _MAX_TRACK_ITERS)
            if dp > POS_TOL_MM or dr > ROT_TOL_DEG:
                raise ExecutionError(
                    f"{label(i)}: cannot follow the path at {_describe(positions_mm[i], rotations[i])}: "
                    f"IK residual {dp:.3f} mm / {dr:.3f} deg exceeds {POS_TOL_MM} mm / {ROT_TOL_DEG} deg "
                    "(out of reach, joint limit or singularity); move or re-orient the path"
                )
            if dp > worst[0]:
                worst[0] = dp
            if dr > worst[1]:
                worst[1] = dr
            if it > worst[2]:
                worst[2] = it
            qs[i] = cfg.q
            wrist[i] = cfg.data.site_xpos[cell.wrist_site] * M_TO_MM
        return qs, wrist, Residual(worst[0], worst[1], int(worst[2]))


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
    xyzw = Rotation.from_matrix(np.asarray(rotations, float)).as_quat()
    return np.column_stack((xyzw[:, 3], xyzw[:, :3]))


def joint_path_events(cell: Cell, q: np.ndarray, wrist_mm: np.ndarray, labels: Sequence[str],
                      limit_margin_deg: float = 2.0, wrist_deg: float = 10.0) -> list[str]:
    """Joint-limit approaches and near-singular configurations, one message per program step.

    Checks the three singularities of a wrist-partitioned arm: wrist (JT5 near 0), elbow
    (arm stretched to 99 % of its shoulder-to-wrist reach) and shoulder (wrist centre within
    100 mm of the JT1 axis).
    """
    data = mujoco.MjData(cell.model)
    data.qpos[:] = 0.0
    mujoco.mj_kinematics(cell.model, data)
    anchors = data.xanchor[:3] * M_TO_MM
    upper = np.linalg.norm(anchors[2] - anchors[1])
    fore = np.linalg.norm(data.site_xpos[cell.wrist_site] * M_TO_MM - anchors[2])
    reach = np.linalg.norm(wrist_mm - anchors[1], axis=1) / (upper + fore)
    axis_dist = np.linalg.norm(wrist_mm[:, :2] - anchors[0, :2], axis=1)
    margin = math.radians(limit_margin_deg)
    checks: list[tuple[np.ndarray, Callable[[int], str]]] = []
    for j in range(6):
        near_lo = q[:, j] < cell.q_min[j] + margin
        near_hi = q[:, j] > cell.q_max[j] - margin
        checks.append((near_lo | near_hi, lambda i, j=j: (
            f"JT{j + 1} at {math.degrees(q[i, j]):.1f} deg, within {limit_margin_deg:g} deg of its limit "
            f"[{math.degrees(cell.q_min[j]):.0f}, {math.degrees(cell.q_max[j]):.0f}] deg")))
    checks.append((np.abs(np.sin(q[:, 4])) < math.sin(math.radians(wrist_deg)),
                   lambda i: f"near wrist singularity (JT5 = {math.degrees(q[i, 4]):.1f} deg)"))
    checks.append((reach > 0.99, lambda i: f"near elbow singularity (arm stretched to {100 * reach[i]:.1f} % of reach)"))
    checks.append((axis_dist < 100.0, lambda i: f"near shoulder singularity (wrist centre {axis_dist[i]:.0f} mm from the JT1 axis)"))
    events: list[str] = []
    for mask, describe in checks:
        seen: set[str] = set()
        for i in np.flatnonzero(mask):
            if labels[i] not in seen:
                seen.add(labels[i])
                events.append(f"{labels[i]}: {describe(int(i))}")
    return events

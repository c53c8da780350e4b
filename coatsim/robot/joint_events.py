"""Events along a solved joint path that a robot programmer wants to hear about: joints close
to their limits and configurations near the three singularities of a wrist-partitioned arm."""

from __future__ import annotations

import functools
import math
from typing import Callable, Sequence

import mujoco
import numpy as np

from coatsim.robot.cell import M_TO_MM, Cell


@functools.lru_cache(maxsize=4)
def arm_dimensions(cell: Cell) -> tuple[np.ndarray, float, float]:
    """Joint anchors (3, 3) mm of JT1-JT3 at the zero configuration, the upper-arm and the
    shoulder-to-wrist forearm lengths (mm)."""
    data = mujoco.MjData(cell.model)
    data.qpos[:] = 0.0
    mujoco.mj_kinematics(cell.model, data)
    anchors = data.xanchor[:3] * M_TO_MM
    upper = float(np.linalg.norm(anchors[2] - anchors[1]))
    return anchors, upper, float(np.linalg.norm(data.site_xpos[cell.wrist_site] * M_TO_MM - anchors[2]))


def joint_path_events(cell: Cell, q: np.ndarray, wrist_mm: np.ndarray, labels: Sequence[str],
                      limit_margin_deg: float = 2.0, wrist_deg: float = 10.0) -> list[str]:
    """Joint-limit approaches and near-singular configurations, one message per program step.

    Checks the three singularities of a wrist-partitioned arm: wrist (JT5 near 0), elbow
    (arm stretched to 99 % of its shoulder-to-wrist reach) and shoulder (wrist centre within
    100 mm of the JT1 axis).
    """
    anchors, upper, fore = arm_dimensions(cell)
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

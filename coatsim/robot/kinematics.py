"""The cell's kinematics as the interpreter needs it: forward kinematics of joint values and
the home configurations (HOME n is the model's keyframe ``home`` for n = 1, ``home<n>`` else)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import numpy as np

from coatsim.core.numeric import ROUND_OFF
from coatsim.core.errors import ExecutionError
from coatsim.path.tool_frames import gun_in_tcp
from coatsim.geometry.space.pose import Pose
from coatsim.path.toolpath import ToolFrame


class CellKinematics:
    """Forward kinematics and home poses of a loaded cell."""

    def __init__(self, cell) -> None:
        import mujoco

        self.cell = cell
        self._data = mujoco.MjData(cell.model)

    def forward(self, joints_rad: np.ndarray, tool: Optional[ToolFrame] = None) -> Pose:
        """The controller's TCP for ``joints_rad``: the gun's pose, or with a TOOL the flange
        times that TOOL (the gun's pose times M^-1, M = TOOL^-1 GUN)."""
        q = np.asarray(joints_rad, dtype=float)
        cell = self.cell
        outside = np.flatnonzero((q < cell.q_min - ROUND_OFF) | (q > cell.q_max + ROUND_OFF))
        if len(outside):
            j = int(outside[0])
            raise ExecutionError(f"joint {j + 1} at {np.degrees(q[j]):.3f} deg is outside the cell's range "
                                 f"{np.degrees(cell.q_min[j]):.1f}..{np.degrees(cell.q_max[j]):.1f} deg")
        position, rotation = cell.forward(self._data, q)
        if tool is None:
            return Pose(rotation, position)
        m_rotation, m_offset = gun_in_tcp(tool, cell.gun_rotation, cell.gun_offset_mm)
        tcp_rotation = rotation @ m_rotation.T
        return Pose(tcp_rotation, position - tcp_rotation @ m_offset)

    def home(self, number: int) -> Optional[np.ndarray]:
        import mujoco

        if number == 1:
            return self.cell.home.copy()
        key = mujoco.mj_name2id(self.cell.model, mujoco.mjtObj.mjOBJ_KEY, f"home{number}")
        return None if key < 0 else self.cell.model.key_qpos[key][:6].copy()


class LazyKinematics:
    """CellKinematics of a model file, loaded the first time a program needs it."""

    def __init__(self, model: Optional[str | Path] = None) -> None:
        self.model = model
        self._loaded: Optional[CellKinematics] = None

    def _get(self) -> CellKinematics:
        if self._loaded is None:
            from coatsim.robot.cell import load_cell

            self._loaded = CellKinematics(load_cell(self.model))
        return self._loaded

    def forward(self, joints_rad: np.ndarray, tool: Optional[ToolFrame] = None) -> Pose:
        return self._get().forward(joints_rad, tool)

    def home(self, number: int) -> Optional[np.ndarray]:
        return self._get().home(number)

"""The program's TOOL in the robot stage: the IK targets the gun site where the controller's TOOL
puts the flange (see :mod:`coatsim.path.tool_frames` for the frames), motions after a TOOL
change start where the flange is, and a TOOL that is not the cell's gun is a warning.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from coatsim.path import tool_frames
from coatsim.geometry.space.rotations import matrix_to_oat
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.path.toolpath import JointMove, ToolFrame, ToolPath
from coatsim.robot.cell import Cell


def mount(tool: ToolFrame | None, cell: Cell) -> tuple[np.ndarray, np.ndarray]:
    """M = T^-1 G for the cell's gun G: rotation (3, 3) and offset (3,) mm."""
    return tool_frames.gun_in_tcp(tool, cell.gun_rotation, cell.gun_offset_mm)


def to_gun(positions_mm: np.ndarray, rotations: np.ndarray, m_rotation: np.ndarray,
           m_offset_mm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gun poses for programmed TCP poses (n, 3) and (n, 3, 3): position + R m_offset, R m_rotation."""
    return positions_mm + rotations @ m_offset_mm, rotations @ m_rotation


def _reexpress(pose: Pose, m_from: tuple[np.ndarray, np.ndarray], m_to: tuple[np.ndarray, np.ndarray]) -> Pose:
    """A TCP pose under one TOOL as the TCP pose under another, the flange (and gun) unmoved:
    P M_from M_to^-1."""
    gun_p, gun_r = to_gun(pose.translation_mm, pose.rotation, *m_from)
    r_to, p_to = m_to
    rotation = gun_r @ r_to.T
    return Pose(rotation, gun_p - rotation @ p_to)


def gun_tool(cell: Cell) -> Pose:
    """The TOOL that makes the controller's TCP the cell's gun (for programs written for it)."""
    x, y, z = (round(float(v), 9) + 0.0 for v in cell.gun_offset_mm)
    return pose_from_xyzoat((x, y, z, *(round(v, 9) + 0.0 for v in matrix_to_oat(cell.gun_rotation))))


def with_tool_changes(toolpath: ToolPath, cell: Cell) -> ToolPath:
    """The toolpath with the start of every motion after a TOOL change expressed with the new
    TOOL, so the motion starts where the flange is (the interpreter cannot do this when the
    earlier TOOL was the controller's own)."""
    moves = list(toolpath.moves)
    for k in range(1, len(moves)):
        before, now = moves[k - 1].settings.tool, moves[k].settings.tool
        if before is now or isinstance(moves[k], JointMove):
            continue
        start = _reexpress(_end(moves[k - 1]), mount(before, cell), mount(now, cell))
        moves[k] = replace(moves[k], start=start)
    return replace(toolpath, moves=tuple(moves))


def _end(move) -> Pose:
    return move.target if isinstance(move, JointMove) else move.end


def tool_mismatches(toolpath: ToolPath, cell: Cell) -> list[str]:
    """One warning per TOOL statement whose TCP is not the cell's gun, naming its line."""
    return [f"{toolpath.name}: line {line} (TOOL): {text}"
            for line, text in tool_frames.tool_mismatches(toolpath, cell.gun_rotation, cell.gun_offset_mm)]

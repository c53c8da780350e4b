"""The program's TOOL against a physical gun: where the spray point goes when they differ.

The controller computes every pose with the TOOL the program gives it: to put its TCP T (the
TOOL, in the flange frame) at a programmed pose P it puts the flange at P T^-1. The gun on the
flange is G (its TCP in the flange frame), so the physical spray point runs at P M with
M = T^-1 G. A matching TOOL gives M = identity; a TOOL 50 mm longer than the gun leaves the
spray point 50 mm short of the programmed TCP, back along the tool axis. A program without
TOOL runs with the controller's own, taken to be the gun (M = identity).
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.space.rotations import matrix_to_oat
from coatsim.geometry.space.pose import rotation_angle
from coatsim.path.toolpath import ToolFrame, ToolPath

MATCH_MM = 1e-3   # a TOOL this close to the gun (and MATCH_DEG in angle) counts as the gun's
MATCH_DEG = 1e-3


def gun_in_tcp(tool: ToolFrame | None, gun_rotation: np.ndarray, gun_offset_mm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """M = T^-1 G: the gun in the frame of the controller's TCP, rotation (3, 3) and offset (3,) mm."""
    if tool is None:
        return np.eye(3), np.zeros(3)
    r_t = np.asarray(tool.rotation, float)
    return r_t.T @ np.asarray(gun_rotation, float), r_t.T @ (np.asarray(gun_offset_mm, float) - np.asarray(tool.offset_mm, float))


def trans_text(rotation: np.ndarray, offset_mm: np.ndarray) -> str:
    """A frame as AS writes it, to 3 decimals: TRANS(x,y,z,o,a,t)."""
    values = [round(float(v), 3) + 0.0 for v in offset_mm] + [round(v, 3) + 0.0 for v in matrix_to_oat(rotation)]
    return "TRANS(" + ",".join(f"{v:g}" for v in values) + ")"


def tool_mismatches(toolpath: ToolPath, gun_rotation: np.ndarray, gun_offset_mm: np.ndarray) -> list[tuple[int, str]]:
    """(TOOL line, description) for every TOOL the moves use whose TCP is not the gun's: how
    far the spray point runs from the programmed TCP and how the spray axis turns."""
    seen: set[int] = set()
    out: list[tuple[int, str]] = []
    for move in toolpath.moves:
        tool = move.settings.tool
        if tool is None or tool.line in seen:
            continue
        seen.add(tool.line)
        m_rotation, m_offset = gun_in_tcp(tool, gun_rotation, gun_offset_mm)
        turn = math.degrees(rotation_angle(np.eye(3), m_rotation))
        tilt = math.degrees(math.acos(min(1.0, max(-1.0, float(m_rotation[2, 2])))))
        distance = float(np.linalg.norm(m_offset))
        if distance <= MATCH_MM and turn <= MATCH_DEG:
            continue
        dx, dy, dz = (float(v) + 0.0 for v in m_offset)
        text = (f"TOOL {trans_text(tool.rotation, tool.offset_mm)} is not the gun's TCP "
                f"{trans_text(gun_rotation, gun_offset_mm)}: the spray point runs {distance:.3f} mm from the "
                f"programmed TCP (tool frame x {dx:.3f}, y {dy:.3f}, z {dz:.3f} mm)")
        if tilt > MATCH_DEG:
            text += f", the spray axis tilted by {tilt:.3f} deg from the programmed one"
        elif turn > MATCH_DEG:
            text += f", the tool frame rolled by {turn:.3f} deg about the spray axis"
        out.append((tool.line, text))
    return out

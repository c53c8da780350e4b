"""What a UR controller does at a waypoint, as the twin models it (URScript manual, movej/movel/
movep/movec; a Chinese translation of its section 13.1 was read).

``r`` is the blend radius of the motion's target, metres: with ``r = 0`` the robot stops at the
target; with ``r > 0`` it leaves the path when it comes within r of the target and joins the next
motion as far after it (the twin's ``accuracy_mm`` = 1000 r; a movep blends on a circle, which the
twin rounds with its own blend within the same distance). When a motion's blend region overlaps
the previous or the next one's, the controller skips the motion and warns "overlapping blends";
the twin instead caps each blend at half of each neighbouring move (as for every language) and
says so once.
"""

from __future__ import annotations

from coatsim.path.toolpath import MotionSettings
from coatsim.path.toolpath_builder import ToolPathBuilder

M_TO_MM = 1000.0


def blend_settings(speed_mm_s: float, r_m: float) -> MotionSettings:
    """The settings of a motion at ``speed_mm_s`` with blend radius ``r_m``."""
    return MotionSettings(speed_mm_s, r_m * M_TO_MM, r_m > 0.0, r_m <= 0.0)


def note_overlaps(builder: ToolPathBuilder, where: str) -> None:
    """One warning when two blends overlap inside a move (the controller would skip it)."""
    moves = builder.moves
    for k in range(1, len(moves)):
        before, move = moves[k - 1], moves[k]
        if move.kind == "joint" or before.settings.stop_at_end:
            continue
        radii = before.settings.accuracy_mm + (0.0 if move.settings.stop_at_end else move.settings.accuracy_mm)
        if radii > move.length_mm:
            builder.warn("overlap", f"{where}:{move.line}: the blends at both ends of this move overlap "
                         f"({radii:.4g} mm of blend radii on {move.length_mm:.4g} mm); the controller skips such a "
                         "move (overlapping blends), the twin blends within half of each neighbouring move")
            return

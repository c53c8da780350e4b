"""What a G-code control does at the junction of two feed moves, as the twin models it.

Path control modes (LinuxCNC's G-code reference; the Fanuc-style G61 is an exact stop too):

- ``G61.1`` exact stop: the tool stops at the end of every move.
- ``G61`` exact path: the tool follows the programmed path exactly, stopping where it must turn
  (a corner) and running straight through a junction where the next move continues in the same
  direction (a tangent or co-linear junction, within ``TANGENT_TOL_DEG``).
- ``G64 P p`` blending within ``p``: the tool leaves the path at most ``p`` from a corner (the
  twin's ``accuracy_mm``; the twin caps it at half of each neighbouring move).
- ``G64`` without ``P`` (the control's default): blending as fast as it can, without a tolerance;
  the twin rounds each corner as far as it models, half of the shorter neighbouring move.
- ``G9`` on a block: an exact stop at its end, that block only.

The modes that depend on the next move are settled when the program has run (:func:`settle`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from coatsim.geometry.space.primitives import arc_through
from coatsim.path.toolpath import MotionSettings
from coatsim.path.toolpath_builder import PendingMove, ToolPathBuilder

TANGENT_TOL_DEG = 0.5
EXACT_STOP, EXACT_PATH, BLEND = "G61.1", "G61", "G64"


@dataclass(frozen=True)
class PathControl:
    """The path control mode in force: ``mode`` one of EXACT_STOP, EXACT_PATH, BLEND, and for
    BLEND the tolerance ``p_mm`` (None: G64 without P)."""

    mode: str = BLEND
    p_mm: Optional[float] = None

    def settings(self, speed_mm_s: float, exact_stop_here: bool) -> MotionSettings:
        """The settings of a feed move under this mode (``exact_stop_here``: a G9 on its block)."""
        blending = self.mode == BLEND
        accuracy = self.p_mm if blending and self.p_mm is not None else 0.0
        return MotionSettings(speed_mm_s, accuracy, blending, self.mode == EXACT_STOP or exact_stop_here)

    def describe(self) -> str:
        return {EXACT_STOP: "G61.1", EXACT_PATH: "G61"}.get(self.mode) or \
            ("G64" if self.p_mm is None else f"G64 P{self.p_mm:g}")


def _tangents(move: PendingMove) -> tuple[np.ndarray, np.ndarray]:
    """Unit tangents at the start and the end of a Cartesian move."""
    start = move.start.translation_mm
    if move.kind == "arc":
        arc = arc_through(start, move.via.translation_mm, move.end.translation_mm)
        return arc.start_tangent, arc.end_tangent
    d = move.end.translation_mm - start
    n = float(np.linalg.norm(d))
    t = d / n if n > 0.0 else np.zeros(3)
    return t, t


def _turn_deg(a: PendingMove, b: PendingMove) -> float:
    ta, tb = _tangents(a)[1], _tangents(b)[0]
    return math.degrees(math.acos(float(np.clip(ta @ tb, -1.0, 1.0))))


def settle(builder: ToolPathBuilder, controls: Sequence[Optional[PathControl]]) -> None:
    """Settle the junction of every feed move with the move after it: G61 stops at a corner,
    G64 without P rounds it as far as the twin models (``controls[k]`` is the mode of move k,
    None for a move that is not a feed move)."""
    moves = builder.moves
    for k, control in enumerate(controls):
        if control is None or moves[k].settings.stop_at_end:
            continue
        nxt = moves[k + 1] if k + 1 < len(moves) and moves[k + 1].kind != "joint" else None
        if control.mode == EXACT_PATH:
            if nxt is None or _turn_deg(moves[k], nxt) > TANGENT_TOL_DEG:
                builder.revise(k, stop_at_end=True)
        elif control.mode == BLEND and control.p_mm is None and nxt is not None:
            builder.revise(k, accuracy_mm=min(moves[k].length_mm, nxt.length_mm) / 2.0)

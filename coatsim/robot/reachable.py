"""Programmed settings the arm cannot honour: a SPEED above what its limits allow on a stretch
(or on a part of it), an ACCURACY longer than every move. Both run (the controller clamps them)
but a user should hear about it, so each becomes a warning event of the execution.
"""

from __future__ import annotations

import numpy as np

from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import Cell
from coatsim.robot.motion_metrics import AT_SPEED
from coatsim.robot.sampling import CartesianPiece, Piece


def speed_event(cell: Cell, piece: CartesianPiece, q: np.ndarray, label: str) -> str | None:
    """A warning when the programmed speed is beyond what the joint speed limits (|dq/ds| v <=
    v_max) and the tool acceleration limit on the path's curvature (kappa v^2 <= a_max) allow
    everywhere on ``piece``, or beyond the joint speed limits on a part of it, where the twin then
    runs below the speed that counts as at speed (AT_SPEED of the programmed one; a sprayed part
    is coated thicker there). ``q`` (n, 6) are the IK solutions of its samples."""
    dq_ds = np.abs(np.gradient(q, piece.s, axis=0))  # rad per mm
    with np.errstate(divide="ignore"):
        joint_mm_s = np.min(cell.v_max / dq_ds, axis=1)
        curve_mm_s = np.sqrt(cell.tool_accel_mm_s2 / np.abs(piece.curvature))
    allowed = np.minimum(joint_mm_s, curve_mm_s)
    programmed = float(np.max(piece.speed))
    if programmed > float(np.max(allowed)):
        return (f"{label}: SPEED {programmed:g} mm/s is beyond the arm, whose joint speed and tool acceleration "
                f"limits allow at most {float(np.max(allowed)):.0f} mm/s on this stretch; the twin runs at those limits")
    beyond = joint_mm_s < AT_SPEED * piece.speed  # (a tight bend slowing the tool is the program's own, not the arm's)
    if not beyond.any():
        return None
    step = np.gradient(piece.s)
    return (f"{label}: SPEED {float(np.max(piece.speed[beyond])):g} mm/s is beyond the arm on "
            f"{float(step[beyond].sum()):.0f} mm of this {float(piece.s[-1] - piece.s[0]):.0f} mm stretch, where its "
            f"joint speed limits allow down to {float(np.min(joint_mm_s[beyond])):.0f} mm/s; the twin runs at those "
            "limits there (where it sprays, the coat is thicker)")


def accuracy_event(toolpath: ToolPath, pieces: tuple[Piece, ...]) -> str | None:
    """A warning when the largest programmed ACCURACY is longer than every Cartesian move: it
    then rounds every blended corner as far as the controller allows (half the shorter
    neighbouring move), which is rarely what was meant."""
    lengths = [p.length for piece in pieces if isinstance(piece, CartesianPiece) for p in piece.reference]
    moves = [toolpath.moves[m] for piece in pieces if isinstance(piece, CartesianPiece) for m in piece.reference_moves]
    if not lengths:
        return None
    accuracy = max(m.settings.accuracy_mm for m in moves)
    longest = max(lengths)
    if accuracy <= longest:
        return None
    return (f"{toolpath.name}: ACCURACY {accuracy:g} mm is longer than every move (the longest is {longest:.4g} mm); "
            "blended corners are rounded as far as the controller allows, half their shorter neighbouring move")

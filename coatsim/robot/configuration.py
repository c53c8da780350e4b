"""The arm's configuration (which of the up to eight IK branches a joint solution is on) and the
flips of it inside a sprayed pass.

A wrist-partitioned six-axis arm reaches most poses in several ways; a controller calls them
shoulder (the wrist centre in front of or behind the JT1 axis), elbow (above or below the line
from the shoulder to the wrist centre) and wrist (JT5 positive or negative). Along a continuous
path the branch can only change through the matching singularity, where joints race or the
controller stops: inside a sprayed pass that ruins the coat, so it is refused (exit 3) naming the
program step and which branch flipped.

A controller's joint move to a pose keeps the arm's configuration (AS: until LEFTY, RIGHTY, ABOVE,
BELOW, UWRIST or DWRIST asks for another) and turns each joint the shortest way: ``kept_goal``
gives the twin's joint moves the same goal.
"""

from __future__ import annotations

from typing import Callable

import mujoco
import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.robot.cell import Cell
from coatsim.robot.chain import cell_chain
from coatsim.robot.turns import within_turns

BRANCHES = ("shoulder", "elbow", "wrist")
_ZERO = 1e-9  # a branch value this close to 0 is on the singularity itself (no side)


class ConfigurationFlip(ExecutionError):
    """The arm changes configuration inside a sprayed pass: ``step`` (the program step where it
    happens) and ``branch`` (shoulder, elbow or wrist)."""

    def __init__(self, message: str, *, step: str, branch: str) -> None:
        super().__init__(message)
        self.step, self.branch = step, branch


def _frames(cell: Cell, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint anchors (n, 6, 3), joint axes (n, 6, 3) and wrist centres (n, 3), metres."""
    chain = cell_chain(cell)
    if chain is not None:
        poses = chain.poses(q)
        return poses.anchors, poses.axes, poses.sites[cell.wrist_site]
    data = mujoco.MjData(cell.model)
    anchors, axes, wrist = np.empty((len(q), 6, 3)), np.empty((len(q), 6, 3)), np.empty((len(q), 3))
    for k, qk in enumerate(q):
        data.qpos[:] = qk
        mujoco.mj_kinematics(cell.model, data)
        anchors[k], axes[k], wrist[k] = data.xanchor[:6], data.xaxis[:6], data.site_xpos[cell.wrist_site]
    return anchors, axes, wrist


def branch_values(cell: Cell, q: np.ndarray) -> np.ndarray:
    """Signed values (n, 3) whose signs name the branch of each configuration q (n, 6): shoulder,
    elbow, wrist (0 on the singularity)."""
    q = np.atleast_2d(np.asarray(q, float))
    anchors, axes, wrist = _frames(cell, q)
    forward = np.cross(axes[:, 1], np.array([0.0, 0.0, 1.0]))
    shoulder = np.einsum("ij,ij->i", (wrist - anchors[:, 0])[:, :2], forward[:, :2])
    elbow = np.einsum("ij,ij->i", np.cross(anchors[:, 2] - anchors[:, 1], wrist - anchors[:, 2]), axes[:, 1])
    return np.column_stack((shoulder, elbow, np.sin(q[:, 4])))


def check_no_flip(cell: Cell, q: np.ndarray, sprayed: np.ndarray, label: Callable[[int], str]) -> None:
    """ConfigurationFlip at the first sample of ``q`` (n, 6) where the branch changes between two
    consecutive sprayed samples (``sprayed`` (n,) bool)."""
    if len(q) < 2:
        return
    sign = np.sign(np.where(np.abs(values := branch_values(cell, q)) < _ZERO, 0.0, values))
    both = sprayed[1:] & sprayed[:-1]
    first: tuple[int, str] | None = None
    for b, name in enumerate(BRANCHES):
        side = sign[:, b].copy()
        for i in range(1, len(side)):  # the last side seen: through the singularity and back is no flip
            if side[i] == 0:
                side[i] = side[i - 1]
        flips = np.flatnonzero(both & (side[1:] * side[:-1] < 0))
        if len(flips) and (first is None or flips[0] + 1 < first[0]):
            first = (int(flips[0]) + 1, name)
    if first is not None:
        step, name = label(first[0]), first[1]
        raise ConfigurationFlip(
            f"{step}: the arm flips its {name} configuration inside a sprayed pass (through the {name} "
            "singularity); re-orient the pass (roll or tool axis) or move the part so one configuration reaches it",
            step=step, branch=name)


def wrist_over(q: np.ndarray) -> np.ndarray:
    """The same arm pose with the wrist turned over: JT4 + 180°, −JT5, JT6 + 180° (the axes of JT4
    and JT6 meet JT5's at the wrist centre)."""
    out = np.array(q, float)
    out[3] += np.pi
    out[4] = -out[4]
    out[5] += np.pi
    return out


def kept_goal(cell: Cell, q_from: np.ndarray, q: np.ndarray) -> np.ndarray:
    """The goal a controller's joint move from ``q_from`` takes for the arm pose that ``q``
    reaches: on ``q_from``'s wrist side (JT5's sign; either side from JT5 = 0), each joint the
    whole number of turns off nearest its value in ``q_from`` inside its range. ``q`` itself where
    no such configuration is inside the ranges."""
    q = np.asarray(q, float)
    side = np.sign(q_from[4]) * np.sign(q[4])
    candidate = wrist_over(q) if side < 0 and abs(np.sin(q_from[4])) > _ZERO else q
    inside = within_turns(candidate, q_from, cell.q_min, cell.q_max)
    return q if inside is None else inside

"""Why a pose cannot be reached, and how much of a program can be.

When the inverse kinematics cannot put the gun on a programmed pose the user needs the reason, in
the order a robot programmer checks them: the wrist centre beyond the arm's reach (or inside its
dead zone near the base), a joint that would have to leave its range (the pose is reached by the
unbounded solution), or a wrist singularity (JT5 near 0: the axes of JT4 and JT6 line up, the
controller cannot turn the tool about them in a straight move; near it JT4 and JT6 race, so one of
them driven out of its range there is named as the singularity, the range with it). ``reachable_fraction`` classifies
every programmed pose of a tool path on its own (each solved from the previous one), for figures.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import mujoco
import numpy as np

from coatsim.path.toolpath import CircularMove, ToolPath
from coatsim.robot.cell import M_TO_MM, Cell
from coatsim.robot.ik import POS_TOL_MM, ROT_TOL_DEG, Tracker, UnreachablePose
from coatsim.robot.joint_events import arm_dimensions
from coatsim.robot.turns import turns_near
from coatsim.robot.tooling import mount, to_gun

WRIST_SINGULAR_DEG = 5.0  # |JT5| below this at the last reached sample: the wrist singularity is why
WRIST_RACE_DEG = 10.0     # ... and below this when JT4 or JT6 is driven out of its range (they race there)
REACH_MARGIN = 1.0        # the wrist centre beyond this share of the shoulder-to-wrist reach: out of reach


@functools.lru_cache(maxsize=4)
def _wrist_in_tcp(cell: Cell) -> np.ndarray:
    """The wrist centre in the gun's TCP frame (mm): fixed, both ride on the last links."""
    data = mujoco.MjData(cell.model)
    data.qpos[:] = cell.home
    mujoco.mj_kinematics(cell.model, data)
    r = data.site_xmat[cell.tcp_site].reshape(3, 3)
    return r.T @ (data.site_xpos[cell.wrist_site] - data.site_xpos[cell.tcp_site]) * M_TO_MM


def reach_reason(cell: Cell, p_gun_mm: np.ndarray, r_gun: np.ndarray) -> str | None:
    """Why the gun pose is out of the arm's reach (None: its wrist centre is within reach)."""
    anchors, upper, fore = arm_dimensions(cell)
    wrist = p_gun_mm + r_gun @ _wrist_in_tcp(cell)
    heading = math.atan2(wrist[1] - anchors[0, 1], wrist[0] - anchors[0, 0])
    c, s = math.cos(heading), math.sin(heading)
    offset = anchors[1] - anchors[0]
    shoulder = anchors[0] + np.array([c * offset[0] - s * offset[1], s * offset[0] + c * offset[1], offset[2]])
    distance = float(np.linalg.norm(wrist - shoulder))
    if distance > REACH_MARGIN * (upper + fore):
        return (f"out of reach: the wrist centre would be {distance:.0f} mm from the shoulder, the arm reaches "
                f"{upper + fore:.0f} mm")
    if distance < abs(upper - fore):
        return f"out of reach: the wrist centre would be {distance:.0f} mm from the shoulder, inside the arm's dead zone"
    return None


def diagnose(tracker: Tracker, q_near: np.ndarray, p_gun_mm: np.ndarray, r_gun: np.ndarray) -> str:
    """Why the IK cannot reach a gun pose near the configuration ``q_near`` (the last one reached)."""
    cell = tracker.cell
    reason = reach_reason(cell, p_gun_mm, r_gun)
    if reason is not None:
        return reason
    q, dp, dr = tracker.solve_unbounded(q_near, p_gun_mm, r_gun)
    q = turns_near(q, q_near)  # where the joints would go on the way from q_near (not whole turns beyond)
    if dp <= POS_TOL_MM and dr <= ROT_TOL_DEG:
        outside = np.flatnonzero((q < cell.q_min) | (q > cell.q_max))
        if len(outside):
            j = int(outside[0])
            limit = (f"JT{j + 1} would have to be at {math.degrees(q[j]):.1f} deg, outside its range "
                     f"[{math.degrees(cell.q_min[j]):.0f}, {math.degrees(cell.q_max[j]):.0f}] deg")
            if j in (3, 5) and abs(math.sin(q_near[4])) < math.sin(math.radians(WRIST_RACE_DEG)):
                return (f"near a wrist singularity (JT5 at {math.degrees(q_near[4]):.1f} deg: JT4 and JT6 line up and "
                        f"turn fast to hold the tool's orientation): {limit}")
            return f"joint limit: {limit}"
    for config in (q_near, q):
        if abs(math.sin(config[4])) < math.sin(math.radians(WRIST_SINGULAR_DEG)):
            return f"near a wrist singularity (JT5 at {math.degrees(config[4]):.1f} deg: JT4 and JT6 line up)"
    if dp <= POS_TOL_MM and dr <= ROT_TOL_DEG:
        return "the joints cannot follow the path there at the programmed speed (near a singularity)"
    return "out of reach for this tool orientation (the inverse kinematics finds no solution)"


@dataclass(frozen=True)
class Reachability:
    """Programmed poses checked, and the (step index, reason) of each one the arm cannot reach."""

    checked: int
    unreachable: tuple[tuple[int, str], ...]

    @property
    def fraction(self) -> float:
        return 1.0 - len(self.unreachable) / self.checked if self.checked else 1.0


def reachable_fraction(toolpath: ToolPath, cell: Cell) -> Reachability:
    """Every Cartesian move's end (and arc via) pose solved in program order from the previous
    solution (from home first), each unreachable one with its reason."""
    tracker = Tracker(cell)
    q = cell.home.copy()
    checked, bad = 0, []
    for index, move in enumerate(toolpath.moves):
        if move.kind == "joint":
            continue
        m_r, m_p = mount(move.settings.tool, cell)
        for pose in ((move.via, move.end) if isinstance(move, CircularMove) else (move.end,)):
            p, r = to_gun(pose.translation_mm[None], pose.rotation[None], m_r, m_p)
            checked += 1
            reason = reach_reason(cell, p[0], r[0])
            if reason is None:
                q_new, dp, dr = tracker.solve_bounded(q, p[0], r[0])
                if dp <= POS_TOL_MM and dr <= ROT_TOL_DEG:
                    q = q_new
                    continue
                reason = diagnose(tracker, q, p[0], r[0])
            bad.append((index, reason))
    return Reachability(checked, tuple(bad))


def explained(error: UnreachablePose, tracker: Tracker) -> UnreachablePose:
    """The IK's failure with the reason the pose cannot be reached (see ``diagnose``)."""
    reason = diagnose(tracker, error.q_near, error.position_mm, error.rotation)
    p, z = error.position_mm, error.rotation[:, 2]
    return UnreachablePose(
        f"{error.step}: cannot reach pose x={p[0]:.1f} y={p[1]:.1f} z={p[2]:.1f} mm, spray axis "
        f"({z[0]:.3f}, {z[1]:.3f}, {z[2]:.3f}): {reason}; {_advice(reason)}",
        step=error.step, position_mm=p, rotation=error.rotation, q_near=error.q_near, reason=reason)


def _advice(reason: str) -> str:
    """What the user can change for a pose the arm cannot reach for ``reason``."""
    if reason.startswith("near a wrist singularity"):
        return ("raise or move the part, or turn the passes, so the spray axis does not line up with the forearm "
                "(JT4's axis) there: a gun tilted away from the robot comes closest to it")
    return "move the path within the arm's reach or re-orient it"

"""ToolPaths built in code for the robot-stage tests (poses in the default cell's workspace)."""

from __future__ import annotations

import numpy as np

from coatsim.path.process import ProcessInfo
from coatsim.geometry.space.pose import Pose
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, MotionSettings, ToolPath

DOWN = np.diag([-1.0, 1.0, -1.0])  # O-A-T (0, 180, 0): tool z along base -z


def pose(x: float, y: float, z: float = 300.0) -> Pose:
    return Pose(DOWN, np.array([x, y, z], dtype=float))


def settings(speed: float = 200.0, accuracy: float = 1.0, stop: bool = False) -> MotionSettings:
    return MotionSettings(speed, accuracy, True, stop)


def lines(points, speed=200.0, accuracy=1.0, stop=False, spray=True, first_line=10) -> list[LinearMove]:
    """LMOVEs through ``points`` (x, y) pairs; the last one stops."""
    moves = []
    for k, (a, b) in enumerate(zip(points[:-1], points[1:])):
        last = k == len(points) - 2
        moves.append(LinearMove(pose(*a), pose(*b), settings(speed, accuracy, stop or last), spray, first_line + k))
    return moves


def approach(point, speed=1000.0) -> JointMove:
    return JointMove(None, pose(*point), settings(speed, 10.0, True), False, 5)


def straight_line(length=300.0, speed=200.0, lead=20.0) -> ToolPath:
    x, y0 = 700.0, -length / 2
    pts = [(x, y0 - lead), (x, y0), (x, y0 + length), (x, y0 + length + lead)]
    moves = [approach(pts[0]), *lines(pts, speed)]
    moves[1] = LinearMove(moves[1].start, moves[1].end, moves[1].settings, False, moves[1].line)
    moves[3] = LinearMove(moves[3].start, moves[3].end, moves[3].settings, False, moves[3].line)
    return ToolPath("line", tuple(moves))


def full_circle(radius=100.0, speed=200.0, centre=(700.0, 0.0)) -> ToolPath:
    """Lead-in line tangent to a full circle made of two C1MOVE/C2MOVE pairs, lead-out line."""
    cx, cy = centre
    start = (cx, cy - radius)
    pts = [(cx + radius, cy), (cx, cy + radius), (cx - radius, cy), start]
    lead = (cx - 30.0, cy - radius)
    s = settings(speed)
    moves = [
        approach(lead),
        LinearMove(pose(*lead), pose(*start), s, True, 10),
        CircularMove(pose(*start), pose(*pts[0]), pose(*pts[1]), s, True, 12),
        CircularMove(pose(*pts[1]), pose(*pts[2]), pose(*start), s, True, 14),
        LinearMove(pose(*start), pose(cx + 30.0, cy - radius), settings(speed, stop=True), True, 15),
    ]
    return ToolPath("circle", tuple(moves), ProcessInfo(lead_in_mm=30.0, lead_out_mm=30.0))


def square(side=200.0, speed=200.0, stop=True, accuracy=1.0) -> ToolPath:
    x0, y0 = 700.0 - side / 2, -side / 2
    pts = [(x0, y0), (x0 + side, y0), (x0 + side, y0 + side), (x0, y0 + side), (x0, y0)]
    return ToolPath("square", (approach(pts[0]), *lines(pts, speed, accuracy, stop)))

"""The tool's orientation along a process path fitted anew: as the original program turned it.

``convert`` fits a program's process path with new lines and arcs. Each new pose takes the tool
rotation the original has at that place along its own path: the original controller's slerp
between its poses, at the place matched by arc length (coatsim.geometry.space.along: a path
passing close to itself does not borrow the tool of its other stretch). The new program's
controller slerps again between the new poses (a line start -> end, an arc start -> via -> end);
where its tool turns further than ``angle_tol_rad`` from the original's (the whole rotation:
spray axis and roll), the segment is halved, the same path and tangents with one more pose,
until it does not. A path sprayed with one tool rotation needs no pose added. An arc's via pose
gets the orientation halfway along the turn from its start pose to its end pose: many controllers
turn the tool so over a circular move whatever the via's orientation (RAPID's circle point,
KRL's auxiliary point, URScript's movec), others through the via's; with the via there, both
turn it alike.
"""

from __future__ import annotations

import math
from typing import Optional, Sequence

import numpy as np

from coatsim.geometry.space.along import AlongPass
from coatsim.geometry.space.orient import MIN_SPLIT_MM, SAMPLES_PER_MM
from coatsim.geometry.space.pose import Pose, exp_rotation, slerp
from coatsim.geometry.space.primitives import Line3, Segment3
from coatsim.path.placement import PlacedMove
from coatsim.path.process_path import ProcessPath

_MIN_SAMPLES = 16  # the tool is compared at least this often along a segment


class TaughtRotations:
    """The original's tool rotations (n, 3, 3) at points (n, 3) of a path fitted to ``path``
    within ``tolerance_mm``, the fitted ``segments`` in the path's order."""

    def __init__(self, segments: Sequence[Segment3], path: ProcessPath, tolerance_mm: float):
        from scipy.spatial.transform import Rotation

        rotations = path.rotations
        self.constant = rotations[0] if np.allclose(rotations, rotations[0], atol=1e-12) else None
        if self.constant is None:
            self.along = AlongPass(segments, path.points, rotations[:, :, 2], tolerance_mm)
            self.rotations = rotations
            self.steps = Rotation.from_matrix(np.einsum("nji,njk->nik", rotations[:-1], rotations[1:])).as_rotvec()

    def __call__(self, x: np.ndarray) -> np.ndarray:
        x = np.atleast_2d(np.asarray(x, dtype=float))
        if self.constant is not None:
            return np.broadcast_to(self.constant, (len(x), 3, 3)).copy()
        edge, u = self.along.input_place(x)
        return self.rotations[edge] @ exp_rotation(u[:, None] * self.steps[edge])


def rotation_angles(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angles (n,) rad of the relative rotations aᵀ b of rotations (n, 3, 3), accurate near 0."""
    rel = np.einsum("nji,njk->nik", a, b)
    cos = (np.trace(rel, axis1=1, axis2=2) - 1.0) / 2.0
    sin = np.linalg.norm(rel - np.transpose(rel, (0, 2, 1)), axis=(1, 2)) / (2.0 * math.sqrt(2.0))
    return np.arctan2(sin, cos)


def _stray(move: PlacedMove, wanted: TaughtRotations, roll: bool = True) -> float:
    """The largest angle (rad) between the tool the controller turns along ``move`` and the
    original's there (their spray axes' without ``roll``)."""
    seg = move.geometry
    s = np.linspace(0.0, seg.length, max(_MIN_SAMPLES, int(math.ceil(seg.length * SAMPLES_PER_MM)) + 1))
    if move.via_pose is None:
        got = slerp(move.start.rotation, move.end.rotation, s / max(seg.length, 1e-300))
    else:
        half = seg.length / 2
        first = s <= half
        got = np.concatenate((slerp(move.start.rotation, move.via_pose.rotation, s[first] / half),
                              slerp(move.via_pose.rotation, move.end.rotation, (s[~first] - half) / half)))
    want = wanted(seg.points(s))
    if not roll:
        cos = np.einsum("ni,ni->n", got[:, :, 2], want[:, :, 2])
        return float(np.arctan2(np.linalg.norm(np.cross(got[:, :, 2], want[:, :, 2]), axis=1), cos).max())
    return float(rotation_angles(got, want).max())


def orient_as_taught(segments: Sequence[Segment3], path: ProcessPath, tolerance_mm: float, angle_tol_rad: float,
                     ends: Optional[tuple[Pose, Pose]] = None) -> tuple[PlacedMove, ...]:
    """The fitted ``segments`` (within ``tolerance_mm`` of ``path``) as moves with the
    original's tool at every pose but an arc's via (module text; ``ends``: the first and last
    pose exactly), halved where the controller's tool strays more than ``angle_tol_rad`` from
    the original's."""
    wanted = TaughtRotations(segments, path, tolerance_mm)
    joints = np.array([segments[0].start] + [s.end for s in segments])
    poses = [Pose(r, p) for r, p in zip(wanted(joints), joints)]
    if ends is not None:
        poses[0], poses[-1] = ends
    out: list[PlacedMove] = []
    todo = [(seg, poses[k], poses[k + 1]) for k, seg in enumerate(segments)]
    while todo:
        seg, start, end = todo.pop(0)
        via = None if isinstance(seg, Line3) else Pose(slerp(start.rotation, end.rotation, 0.5)[0], seg.via)
        move = PlacedMove(seg, start, end, via_pose=via)
        if (wanted.constant is None and seg.length / 2 >= MIN_SPLIT_MM
                and _stray(move, wanted) > angle_tol_rad):
            first, second = seg.halves()
            middle = Pose(wanted(first.end)[0], first.end)
            todo[:0] = [(first, start, middle), (second, middle, end)]
            continue
        out.append(move)
    return tuple(out)


def tool_angle(moves: Sequence[PlacedMove], path: ProcessPath, tolerance_mm: float, roll: bool = True) -> float:
    """The largest angle (rad) between the tool a controller turns along ``moves`` (within
    ``tolerance_mm`` of ``path``) and the original's there; between their spray axes without
    ``roll`` (a language that does not turn the gun about its axis)."""
    wanted = TaughtRotations([m.geometry for m in moves], path, tolerance_mm)
    return max(_stray(m, wanted, roll) for m in moves)

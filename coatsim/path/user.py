"""A user's own program as a scenario variant: its process path as a curve in the workpiece
plane, so coatsim's programs of the same path can be compared with it."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line
from coatsim.geometry.space.primitives import arc_through
from coatsim.path.arcs import move_length, sample_move
from coatsim.geometry.space.pose import Pose
from coatsim.path.process_path import spray_runs
from coatsim.path.toolpath import CircularMove, ToolPath

# a sprayed move whose far end is further than this from the path's plane approaches or leaves it (mm)
PLANE_MM = 1.0


@dataclass(frozen=True, eq=False)
class UserProgram:
    """A program a user brought: its text, the sprayed path as lines and arcs in the workpiece
    plane (``curve``), the dense points of that path (n, 2), its height above the plane (mm);
    ``notes`` what a reader of the comparison must know (other sprayed stretches left out)."""

    text: str
    curve: Polysegment
    points: np.ndarray
    height_mm: float
    notes: tuple[str, ...] = ()

    @property
    def path(self) -> "UserProgram":
        return self

    @property
    def curve_length_mm(self) -> float:
        return self.curve.length


def _local(frame: Pose, p: np.ndarray) -> np.ndarray:
    return frame.rotation.T @ (np.asarray(p, dtype=float) - frame.translation_mm)


def _in_plane(moves: list, frame: Pose) -> tuple[list, tuple[str, ...]]:
    """The sprayed moves without a first one that comes down to the path's plane or a last one
    that leaves it (the gun switched on above the part, ``SIGNAL`` before the approach ends):
    flattened, they would add a stretch the program sprays in the air to the compared path."""
    height = float(np.median([_local(frame, m.end.translation_mm)[2] for m in moves]))
    notes = []
    if len(moves) > 1 and abs(_local(frame, moves[0].start.translation_mm)[2] - height) > PLANE_MM:
        notes.append(f"line {moves[0].line}: the first sprayed move comes to the path's plane from "
                     f"{_local(frame, moves[0].start.translation_mm)[2] - height:+.1f} mm; the compared path starts after it")
        moves = moves[1:]
    if len(moves) > 1 and abs(_local(frame, moves[-1].end.translation_mm)[2] - height) > PLANE_MM:
        notes.append(f"line {moves[-1].line}: the last sprayed move leaves the path's plane by "
                     f"{_local(frame, moves[-1].end.translation_mm)[2] - height:+.1f} mm; the compared path ends before it")
        moves = moves[:-1]
    return moves, tuple(notes)


def user_program(toolpath: ToolPath, frame: Pose, text: str, step_mm: float = 0.5) -> UserProgram:
    """The longest sprayed stretch of ``toolpath`` expressed in ``frame`` (its XY plane)."""
    runs = [r for r in spray_runs(toolpath) if r]
    if not runs:
        raise InputError(f"{toolpath.name}: the gun is never on during an LMOVE or C1MOVE/C2MOVE move; the program "
                         "has no process path to compare")
    lengths = [sum(move_length(toolpath.moves[i]) for i in r) for r in runs]
    longest = runs[int(np.argmax(lengths))]
    moves = [toolpath.moves[i] for i in longest]
    notes: tuple[str, ...] = ()
    if len(runs) > 1:
        lines = [m.line for m in moves]  # a loop's moves come back to earlier lines
        notes = (f"{toolpath.name} sprays {len(runs)} stretches ({sum(lengths):.1f} mm in all); its path here is the "
                 f"longest, lines {min(lines)}-{max(lines)} ({max(lengths):.1f} mm), which the other variants "
                 "spray alone",)
    moves, off_plane = _in_plane(moves, frame)
    notes += off_plane
    segments, points, heights = [], [_local(frame, moves[0].start.translation_mm)[:2]], []
    for m in moves:
        a, b = _local(frame, m.start.translation_mm), _local(frame, m.end.translation_mm)
        heights += [a[2], b[2]]
        if isinstance(m, CircularMove):
            c = arc_through(m.start.translation_mm, m.via.translation_mm, m.end.translation_mm)
            centre = _local(frame, c.center)
            turn = float(frame.rotation.T @ c.normal @ np.array([0.0, 0.0, 1.0]))
            sweep = math.copysign(c.sweep, turn)
            segments.append(Arc(tuple(a[:2]), tuple(b[:2]), tuple(centre[:2]), c.radius, sweep))
            n = max(2, int(math.ceil(move_length(m) / step_mm)))
            points.append(np.array([_local(frame, p)[:2] for p in sample_move(m, np.linspace(0, 1, n + 1)[1:])[0]]))
        else:
            if np.linalg.norm(b[:2] - a[:2]) > 0.0:
                segments.append(Line(tuple(a[:2]), tuple(b[:2])))
            points.append(b[None, :2])
    if not segments:
        raise InputError(f"{toolpath.name}: the sprayed moves do not move along the workpiece plane")
    closed = bool(np.linalg.norm(np.asarray(segments[0].start) - np.asarray(segments[-1].end)) < 1e-6)
    pts = np.vstack(points)
    keep = np.concatenate(([True], np.any(np.diff(pts, axis=0) != 0.0, axis=1)))
    return UserProgram(text, Polysegment(tuple(segments), closed=closed), pts[keep], float(np.median(heights)), notes)

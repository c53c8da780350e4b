"""The process path of a program: the Cartesian moves the gun sprays (or a range of lines),
their points, tool orientations and the plane they lie in.

A path may be traced along any plane in space; :func:`planar_frame` finds it (least squares)
and says how far the path leaves it. A path whose first or last move leaves the plane of the
rest (a sprayed approach or depart) keeps those moves as they are.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.numeric import ROUND_OFF, TINY
from coatsim.core.errors import InputError
from coatsim.path.arcs import move_length, move_rotations, sample_move
from coatsim.path.reading import MoveSource
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, Move, ToolPath

_ARC_SAMPLES_PER_MM = 2.0
_NEAREST_VERTICES = 8  # vertices whose pieces path_distance measures each point against


@dataclass(frozen=True, eq=False)
class PlaneFrame:
    """A plane in the robot base frame: ``origin`` (3,), orthonormal ``e1``, ``e2`` in it,
    ``normal`` = e1 x e2; ``deviation_mm`` the largest distance of the path from it."""

    origin: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    normal: np.ndarray
    deviation_mm: float

    def to_plane(self, points: np.ndarray) -> np.ndarray:
        rel = np.asarray(points, dtype=float) - self.origin
        return np.column_stack((rel @ self.e1, rel @ self.e2))

    def to_space(self, xy: np.ndarray) -> np.ndarray:
        xy = np.atleast_2d(np.asarray(xy, dtype=float))
        return self.origin + xy[:, :1] * self.e1 + xy[:, 1:2] * self.e2


@dataclass(frozen=True, eq=False)
class ProcessPath:
    """Consecutive Cartesian moves (indices into the ToolPath) and their geometry: ``points``
    (n, 3) along the path (move ends, arcs sampled) and ``rotations`` (n, 3, 3) there."""

    moves: tuple[int, ...]
    points: np.ndarray
    rotations: np.ndarray

    @property
    def length_mm(self) -> float:
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())


def _move_points(move: Move, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Points after the start of a move (its end last) and the tool rotations there."""
    if isinstance(move, CircularMove):
        n = max(8, int(math.ceil(move_length(move) * _ARC_SAMPLES_PER_MM / max(spacing, 1e-3))))
        u = np.linspace(0.0, 1.0, n + 1)[1:]
        pts = sample_move(move, u)[0]
        pts[-1] = move.end.translation_mm
    else:
        u = np.array([1.0])
        pts = np.asarray(move.end.translation_mm, dtype=float)[None]
    return pts, move_rotations(move, u)


def path_of(toolpath: ToolPath, moves: tuple[int, ...], spacing_mm: float) -> ProcessPath:
    """The geometry of consecutive Cartesian moves."""
    tp = toolpath.moves
    first = tp[moves[0]]
    pts, rots = [np.asarray(first.start.translation_mm, float)[None]], [np.asarray(first.start.rotation)[None]]
    for i in moves:
        p, r = _move_points(tp[i], spacing_mm)
        pts.append(p)
        rots.append(r)
    return ProcessPath(moves, np.vstack(pts), np.concatenate(rots))


def spray_runs(toolpath: ToolPath) -> list[tuple[int, ...]]:
    """Maximal stretches of consecutive sprayed Cartesian moves (a joint move ends one)."""
    runs, current = [], []
    for i, m in enumerate(toolpath.moves):
        if m.spray and isinstance(m, (LinearMove, CircularMove)):
            current.append(i)
            continue
        if current:
            runs.append(tuple(current))
        current = []
    if current:
        runs.append(tuple(current))
    return runs


def moves_in_lines(toolpath: ToolPath, sources: tuple[MoveSource, ...], first: int, last: int,
                   motions: str) -> tuple[int, ...]:
    """The moves whose statements lie within source lines ``first``..``last``; ``motions`` the
    language's words for its linear and circular moves (for the message)."""
    chosen = [i for i, s in enumerate(sources) if first <= s.first_line and s.last_line <= last]
    if not chosen:
        raise InputError(f"--lines {first}-{last}: no motion comes from these lines")
    if chosen != list(range(chosen[0], chosen[-1] + 1)):
        raise InputError(f"--lines {first}-{last}: the motions of these lines are not consecutive in the run")
    joint = [i for i in chosen if isinstance(toolpath.moves[i], JointMove)]
    if joint:
        raise InputError(f"--lines {first}-{last}: line {toolpath.moves[joint[0]].line} is a joint move; a "
                         f"process path is made of {motions} moves")
    return tuple(chosen)


def planar_frame(points: np.ndarray, tool_z: np.ndarray) -> PlaneFrame:
    """The least-squares plane of ``points`` (n, 3); for a straight path the plane holding the
    line and the mean tool axis. ``e1`` follows the base x axis where it can."""
    pts = np.asarray(points, dtype=float)
    centre = pts.mean(axis=0)
    _, sv, vt = np.linalg.svd(pts - centre, full_matrices=False)
    z = np.asarray(tool_z, dtype=float)
    if len(sv) < 2 or sv[1] <= ROUND_OFF * max(sv[0], 1e-12):
        direction = vt[0]
        normal = np.cross(direction, np.cross(z, direction))
        if np.linalg.norm(normal) < TINY:
            normal = np.cross(direction, [1.0, 0.0, 0.0] if abs(direction[0]) < 0.9 else [0.0, 1.0, 0.0])
    else:
        normal = vt[2] if len(vt) > 2 else np.cross(vt[0], vt[1])
    normal = normal / np.linalg.norm(normal)
    if normal @ z > 0:  # the surface normal faces the tool, which points at it
        normal = -normal
    e1 = np.array([1.0, 0.0, 0.0]) - normal[0] * normal
    if np.linalg.norm(e1) < 1e-6:
        e1 = np.array([0.0, 1.0, 0.0]) - normal[1] * normal
    e1 = e1 / np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    deviation = float(np.abs((pts - centre) @ normal).max())
    return PlaneFrame(centre, e1, e2, normal, deviation)


def path_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Largest distance from the points ``a`` (n, 3) to the polyline through ``b`` (m, 3): to
    the pieces at the _NEAREST_VERTICES vertices nearest each point (where the polyline passes
    a point twice, as a circle closing on the line that led to it, the nearest vertex alone
    may lie on the wrong pass)."""
    from scipy.spatial import cKDTree

    b = np.asarray(b, dtype=float)
    a = np.asarray(a, dtype=float)
    _, nearest = cKDTree(b).query(a, k=min(_NEAREST_VERTICES, len(b)))
    nearest = nearest.reshape(len(a), -1)
    best = np.linalg.norm(a - b[nearest[:, 0]], axis=1)
    for column in nearest.T:
        for shift in (-1, 0):
            i = np.clip(column + shift, 0, len(b) - 2)
            p0, p1 = b[i], b[i + 1]
            d = p1 - p0
            t = np.clip(np.einsum("ij,ij->i", a - p0, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
            best = np.minimum(best, np.linalg.norm(a - (p0 + t[:, None] * d), axis=1))
    return float(best.max())


def dense_points(moves, step_mm: float) -> np.ndarray:
    """Points along Cartesian moves at most ``step_mm`` apart (every move end included)."""
    out = [np.asarray(moves[0].start.translation_mm, dtype=float)[None]]
    for m in moves:
        n = max(1, int(math.ceil(move_length(m) / step_mm)))
        out.append(sample_move(m, np.linspace(0.0, 1.0, n + 1)[1:])[0])
    return np.vstack(out)

"""A program's process path fitted with lines and arcs, for ``convert``.

A path planar within a share of the tolerance (a sprayed approach or depart leaving the plane
is kept as it is) is fitted by the default fitter in that plane on the points the moves pass
through; circular moves the original already has are kept as their exact arcs where that takes
no more moves than fitting the whole path: sampling an arc and fitting it again can only lose it.
Any other path is fitted in space, each arc in its own plane. Every new pose has the original's
tool there (coatsim.path.taught_orientation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence, Union

import numpy as np

from coatsim.core import defaults
from coatsim.geometry import make_curve, segment_curve
from coatsim.geometry.primitives import Line
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3, arc_through
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.path.edit import FittedPath
from coatsim.path.placement import PlacedMove, placed_line
from coatsim.path.process_path import PlaneFrame, ProcessPath, path_of, planar_frame
from coatsim.path.reading import Reading
from coatsim.path.taught_orientation import orient_as_taught
from coatsim.path.toolpath import CircularMove, LinearMove

PLANE_SHARE = 0.5  # the part of the tolerance a path may leave its plane by
MIN_CIRCLE_SWEEP_DEG = 1.0  # a fitted arc turning less is written as its chord where the tolerance allows


def line_span(reading: Reading, moves: Sequence[int]) -> tuple[int, int]:
    sources = reading.move_sources
    return min(sources[i].first_line for i in moves), max(sources[i].last_line for i in moves)


def planar(reading: Reading, moves: tuple[int, ...],
           tol: float) -> Optional[tuple[tuple[int, ...], ProcessPath, PlaneFrame, list[str]]]:
    """The moves (a sprayed approach or depart leaving the plane dropped) and their plane;
    None if they leave every plane by more than PLANE_SHARE of the tolerance."""
    tries = [(moves, [])]
    if len(moves) > 2:
        tries += [(moves[1:], ["first"]), (moves[:-1], ["last"])]
    if len(moves) > 3:
        tries.append((moves[1:-1], ["first", "last"]))
    for subset, dropped in tries:
        path = path_of(reading.toolpath, subset, tol)
        tool_z = np.mean(path.rotations[:, :, 2], axis=0)
        plane = planar_frame(path.points, tool_z)
        if plane.deviation_mm <= PLANE_SHARE * tol:
            notes = [f"line {reading.toolpath.moves[moves[0] if d == 'first' else moves[-1]].line}: the {d} sprayed "
                     "move leaves the plane of the path and is kept as it is" for d in dropped]
            return subset, path, plane, notes
    return None


@dataclass(frozen=True, eq=False)
class TaughtArc(PlacedMove):
    """An arc the original program turns in one circular move, written as one move again
    whatever the language's limit for new arcs: its controller runs the original's."""

    def split(self, max_sweep: float) -> tuple[PlacedMove, ...]:
        return (self,)


def moves_written(segments: Sequence[PlacedMove], max_arc_sweep_deg: float) -> int:
    """How many moves a language splitting arcs above ``max_arc_sweep_deg`` writes ``segments`` as."""
    return sum(len(s.split(math.radians(max_arc_sweep_deg))) if s.is_arc else 1 for s in segments)


def _fit_points(path: ProcessPath, plane: PlaneFrame, fit_tol: float, corner_deg: float, angle_tol_rad: float,
                ends: Optional[tuple[Pose, Pose]]) -> tuple[list[PlacedMove], float, int]:
    """The lines and arcs of the default fitter through the points of ``path`` in ``plane`` with
    the original's tool (``ends`` the first and last pose exactly, if given): the moves, their
    deviation, how many are lines written for arcs turning less than MIN_CIRCLE_SWEEP_DEG."""
    seg = segment_curve(make_curve(plane.to_plane(path.points), "process path", "no"), fit_tol, corner_deg=corner_deg)
    poly = seg.polysegment
    space = plane.to_space(np.array([s.start for s in poly.segments] + [poly.end], dtype=float))
    geometry: list[Segment3] = []
    straightened, n_flat = 0.0, 0
    for k, s in enumerate(poly.segments):
        sagitta = 0.0 if isinstance(s, Line) else s.radius * (1.0 - math.cos(s.sweep / 2.0))
        if isinstance(s, Line) or (abs(s.sweep) < math.radians(MIN_CIRCLE_SWEEP_DEG)
                                   and seg.max_deviation_mm + max(straightened, sagitta) <= fit_tol):
            geometry.append(Line3(space[k], space[k + 1]))
            straightened = max(straightened, sagitta)
            n_flat += not isinstance(s, Line)
        else:
            centre = plane.to_space(np.asarray(s.center))[0]
            geometry.append(Arc3(space[k], space[k + 1], centre, plane.normal if s.sweep > 0 else -plane.normal,
                                 float(np.linalg.norm(space[k] - centre)), abs(s.sweep)))
    moves = orient_as_taught(geometry, path, fit_tol, angle_tol_rad, ends)
    return list(moves), seg.max_deviation_mm + straightened, n_flat


def _taught_arcs(reading: Reading, path: ProcessPath, plane: PlaneFrame, fit_tol: float, corner_deg: float,
                 angle_tol_rad: float, taught: bool) -> tuple[list[PlacedMove], float, int]:
    """The path with each circular move of the original kept as its exact arc (a TaughtArc if
    ``taught``) and each stretch of linear moves between them fitted; the deviation, the number
    of nearly straight arcs written as lines."""
    moves = [reading.toolpath.moves[i] for i in path.moves]
    segments: list[PlacedMove] = []
    deviation, n_flat, k = 0.0, 0, 0
    while k < len(moves):
        m = moves[k]
        if isinstance(m, CircularMove):
            segments.append(taught_move(m, taught))
            k += 1
            continue
        j = k
        while j < len(moves) and not isinstance(moves[j], CircularMove):
            j += 1
        if j - k == 1:
            segments.append(placed_line(m.start, m.end))
        else:
            stretch = path_of(reading.toolpath, path.moves[k:j], fit_tol)
            fitted, dev, flat = _fit_points(stretch, plane, fit_tol, corner_deg, angle_tol_rad, (m.start, moves[j - 1].end))
            segments += fitted
            deviation, n_flat = max(deviation, dev), n_flat + flat
        k = j
    return segments, deviation, n_flat


def _fit_space(reading: Reading, moves: tuple[int, ...], tolerance_mm: float, corner_deg: float,
               angle_tol_rad: float, arc_planes: str) -> FittedPath:
    """A process path that is not planar fitted in space (arcs each in its own plane, in a
    principal plane where ``arc_planes`` asks), the original's tool at every pose."""
    path = path_of(reading.toolpath, moves, tolerance_mm)
    first, last = reading.toolpath.moves[moves[0]], reading.toolpath.moves[moves[-1]]
    seg = segment_space_curve(make_space_curve(path.points, "process path", "no"), tolerance_mm, corner_deg,
                              arc_planes="principal" if arc_planes == "principal" else "any")
    segments = orient_as_taught(seg.chain.segments, path, tolerance_mm, angle_tol_rad, (first.start, last.end))
    n_lines = sum(isinstance(m.geometry, Line3) for m in segments)
    return FittedPath(path, None, segments, len(segments) - n_lines, n_lines, seg.max_deviation_mm,
                      line_span(reading, moves), ())


def fit_path(reading: Reading, moves: tuple[int, ...], tolerance_mm: float, corner_deg: float,
             max_arc_sweep_deg: float, taught: bool, angle_tol_deg: float = defaults.ANGLE_TOL_DEG,
             arc_planes: str = "any") -> FittedPath:
    """Fit one process path with the default fitter in its plane, or in space if it has none
    (:func:`_fit_space`, arcs in ``arc_planes``); each new pose has the original's tool, poses
    added where the controller would turn it more than ``angle_tol_deg`` away
    (coatsim.path.taught_orientation).
    Where the original has circular moves in a plane, their exact arcs are kept (stretches of
    linear moves between them fitted) unless fitting the whole path takes fewer moves (arcs
    split above ``max_arc_sweep_deg``): sampling an arc and fitting it again can only lose it.
    ``taught``: the arcs kept are written as one move each, as the original's (TaughtArc)."""
    tol, angle_tol = tolerance_mm, math.radians(angle_tol_deg)
    found = planar(reading, moves, tol)
    if found is None:
        return _fit_space(reading, moves, tol, corner_deg, angle_tol, arc_planes)
    moves, path, plane, notes = found
    fit_tol = math.sqrt(tol * tol - plane.deviation_mm ** 2)
    segments, deviation, n_flat = _fit_points(path, plane, fit_tol, corner_deg, angle_tol, None)
    if any(isinstance(reading.toolpath.moves[i], CircularMove) for i in moves):
        kept = _taught_arcs(reading, path, plane, fit_tol, corner_deg, angle_tol, taught)
        if moves_written(kept[0], max_arc_sweep_deg) <= moves_written(segments, max_arc_sweep_deg):
            segments, deviation, n_flat = kept
    n_lines = sum(isinstance(m.geometry, Line3) for m in segments)
    if n_flat:
        notes.append(f"lines {'-'.join(map(str, line_span(reading, moves)))}: "
                     f"{n_flat} nearly straight arc(s) (turning less than {MIN_CIRCLE_SWEEP_DEG:g} deg) "
                     "written as lines: a controller cannot place a circle through three nearly collinear points")
    return FittedPath(path, plane, tuple(segments), len(segments) - n_lines, n_lines, deviation,
                      line_span(reading, moves), tuple(notes))


def taught_move(move: Union[LinearMove, CircularMove], taught: bool) -> PlacedMove:
    """A move of the original as a line or its exact arc (a TaughtArc if ``taught``)."""
    if isinstance(move, CircularMove):
        arc = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm)
        return (TaughtArc if taught else PlacedMove)(arc, move.start, move.end, via_pose=move.via)
    return placed_line(move.start, move.end)

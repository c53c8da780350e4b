"""Programs of 3-D passes: a surfacepaths file becomes one program spraying every pass.

Per pass the tool centre point runs at ``point + standoff · normal`` with the spray axis along
minus the normal (both placed in the robot base frame by the part's pose). Variants:

- ``polysegment``: the orientation-aware 3-D fit (coatsim.geometry.space.orient): tangent-
  continuous lines and arcs, each in its own plane, within ``tolerance_mm``, with a pose at every
  segment end and arc middle so that the axis the controller interpolates stays within
  ``angle_tol_deg`` of the surface normal; blended.
- ``polyline-stop`` / ``polyline-blend``: straight moves through the pass's TCP points kept by a
  Douglas–Peucker pass on position (``tolerance_mm``) and axis (``angle_tol_deg``) together, as a
  waypoint planner emits them (no pose added for a smooth turning rate); exact stop at every
  vertex, or blended.

The roll about the axis follows coatsim.path.roll. Each pass gets a lead-in and a lead-out
(coatsim.path.leads; the lengths of the file's leads unless given), the gun open
along the whole pass and its leads (an open pass) or exactly once around (a closed one); the
tool approaches and departs along the axis and travels between passes with the gun off, at a
clearance raised where the straight travel would pass closer to the part than the stand-off
(coatsim.path.travel).
With ``speed_on="trace"`` every move gets the speed that moves the spray spot on the surface
(TCP + standoff · axis, as the controller interpolates the poses) at ``speed_mm_s``; the
stretches where a move's own speed exceeds what its arc allows (v² / r above the tool
acceleration) are the program's speed limits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.scatter import THIN_SCATTERS, scatter_mm
from coatsim.geometry.space.along import AlongPass
from coatsim.geometry.space.orient import ANGLE_TOL_DEG, MIN_SPLIT_MM, slerp_axes
from coatsim.geometry.space.pose import Pose, slerp
from coatsim.geometry.space.primitives import Arc3, Line3
from coatsim.geometry.space.rotations import rot_z
from coatsim.geometry.space.taught import noisy
from coatsim.path.build import ProgramOptions
from coatsim.path.expressible import expressible
from coatsim.path.frames import DEFAULT_FRAME
from coatsim.path.language import UNTILTED_TOL_RAD, Language
from coatsim.path.pass_fits import FitSettings, PassFits, PassTcp, fit_passes, place_passes
from coatsim.path.leads import lead_move
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.plan import ProgramPlan
from coatsim.path.process import SPEED_ON, ProcessInfo, SprayedContour
from coatsim.path.roll import AxisPiece, Oriented, check_rule, oriented_pieces, reference_direction
from coatsim.path.speed_limits import SpeedLimit
from coatsim.path.surfacepaths import SurfacePaths
from coatsim.path.travel import travel_clearances
from coatsim.path.unfold import MIN_ADVANCE

_TRACE_SAMPLES = 33      # samples per move when its trace length is measured
_KINK_RAD = 1e-6         # a junction breaking its tangent by more is a corner (speed 0 there)
_NOISE_SHARE = 0.25      # tool points scattering by more than this share of the tolerance are noise the arcs follow


@dataclass(frozen=True)
class SurfaceOptions:
    """How the passes are placed and fitted: the stand-off (None: the file's, else the default),
    the part's pose in the base frame (None: the file's, else the default workpiece frame), the
    fit's tolerances, the roll rule and offset, where the speed holds, the lead lengths (None:
    the file's), and the tool acceleration the speed limits are computed for (None: corners only)."""

    standoff_mm: Optional[float] = None
    pose: Optional[Pose] = None
    tolerance_mm: float = defaults.TOLERANCE_MM
    angle_tol_deg: float = ANGLE_TOL_DEG
    roll: str = "fixed"
    roll_deg: float = 0.0
    speed_on: str = "tcp"
    lead_in_mm: Optional[float] = None
    lead_out_mm: Optional[float] = None
    tool_accel_mm_s2: Optional[float] = None

    def __post_init__(self) -> None:
        check_rule(self.roll)
        if self.speed_on not in SPEED_ON:
            raise InputError(f"speed_on: expected one of {', '.join(SPEED_ON)}, got {self.speed_on!r}",
                             parameters=("speed_on",))
        for name in ("standoff_mm", "tolerance_mm", "tool_accel_mm_s2"):
            value = getattr(self, name)
            if value is not None and not (math.isfinite(value) and value > 0):
                raise InputError(f"{name}: must be a positive number, got {value}", parameters=(name,))
        for name in ("lead_in_mm", "lead_out_mm"):
            value = getattr(self, name)
            if value is not None and not (math.isfinite(value) and value >= 0):
                raise InputError(f"{name}: must be a number >= 0 (mm), got {value}", parameters=(name,))
        if not math.isfinite(self.roll_deg):
            raise InputError(f"roll_deg: must be a finite number of degrees, got {self.roll_deg}",
                             parameters=("roll_deg",))


@dataclass(frozen=True, eq=False)
class SurfaceProgram:
    """A written program of 3-D passes: its text, plan, per pass the number of lines and arcs,
    the largest angle (rad) between the fitted axis and the wanted one, the notes (what the
    language could not say as asked, where the axis leaves the normal or strays further than
    asked) and per pass the planned tool centre points (n, 3) mm in the base frame, which the
    moves are within ``tolerance_mm`` of."""

    text: str
    plan: ProgramPlan
    counts: tuple[tuple[int, int], ...]
    max_axis_error_rad: float
    notes: tuple[str, ...] = ()
    tcp_mm: tuple[np.ndarray, ...] = ()


def oriented_polyline(points: np.ndarray, axes: np.ndarray, tolerance_mm: float, angle_tol_rad: float) -> np.ndarray:
    """Indices of the vertices Douglas–Peucker keeps when a point must lie within
    ``tolerance_mm`` of its line and its axis within ``angle_tol_rad`` of the axis slerped along
    that line (at the point's fraction of it); the worse of the two ratios picks the split."""
    n = len(points)
    keep = np.zeros(n, dtype=bool)
    keep[[0, n - 1]] = True
    stack = [(0, n - 1)]
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        a, b = points[i], points[j]
        ab = b - a
        den = float(ab @ ab)
        inner = points[i + 1:j]
        u = np.clip((inner - a) @ ab / den, 0.0, 1.0) if den > 0 else np.zeros(len(inner))
        dist = np.linalg.norm(inner - a - u[:, None] * ab, axis=1)
        want = slerp_axes(axes[i], axes[j], u)
        got = axes[i + 1:j]
        angle = np.arctan2(np.linalg.norm(np.cross(got, want), axis=1), np.einsum("ij,ij->i", got, want))
        worst = np.maximum(dist / tolerance_mm, angle / angle_tol_rad)
        k = int(np.argmax(worst))
        if worst[k] > 1.0:
            m = i + 1 + k
            keep[m] = True
            stack += [(i, m), (m, j)]
    return np.flatnonzero(keep)


def _polyline(tcp: np.ndarray, axes: np.ndarray, options: SurfaceOptions) -> list[AxisPiece]:
    keep = oriented_polyline(tcp, axes, options.tolerance_mm, math.radians(options.angle_tol_deg))
    out = []
    for i, j in zip(keep[:-1], keep[1:]):
        if not np.array_equal(tcp[i], tcp[j]):
            mid = slerp_axes(axes[i], axes[j], np.array([0.5]))[0]
            out.append(AxisPiece(Line3(tcp[i], tcp[j]), (axes[i], mid, axes[j])))
    return out


def _trace_ratio(o: Oriented, standoff_mm: float) -> float:
    """TCP length over the length of the spot's trace (TCP + standoff · axis) along one move."""
    u = np.linspace(0.0, 1.0, _TRACE_SAMPLES)
    seg = o.geometry
    p = seg.points(u * seg.length)
    if o.via is None:
        z = slerp(o.start, o.end, u)[:, :, 2]
    else:
        half = u <= 0.5
        z = np.vstack((slerp(o.start, o.via, 2 * u[half])[:, :, 2], slerp(o.via, o.end, 2 * u[~half] - 1)[:, :, 2]))
    trace = float(np.linalg.norm(np.diff(p + standoff_mm * z, axis=0), axis=1).sum())
    return seg.length / trace if trace > 0 else 1.0


def _limits(moves: list[PlacedMove], speed: float, accel: Optional[float], corners: set[int]) -> tuple[SpeedLimit, ...]:
    """Stretches of the curve proper where a move's speed exceeds what its arc allows, and its corners."""
    out, s = [], 0.0
    for k, m in enumerate(moves):
        v = m.speed_mm_s if m.speed_mm_s is not None else speed
        if accel is not None and isinstance(m.geometry, Arc3) and v * v / m.geometry.radius > accel:
            out.append(SpeedLimit(s, s + m.length, math.sqrt(accel * m.geometry.radius)))
        s += m.length
        if k in corners and k < len(moves) - 1:
            out.append(SpeedLimit(s, s, 0.0))
    return tuple(out)


def _corners(pieces: list[AxisPiece]) -> set[int]:
    """Junctions (end of piece k) where the tangent breaks."""
    return {k for k, (a, b) in enumerate(zip(pieces[:-1], pieces[1:]))
            if math.atan2(float(np.linalg.norm(np.cross(a.geometry.end_tangent, b.geometry.start_tangent))),
                          float(a.geometry.end_tangent @ b.geometry.start_tangent)) > _KINK_RAD}


def _placed(oriented: list[Oriented], leads: tuple[float, float], standoff: float, trace_speed: Optional[float]
            ) -> list[PlacedMove]:
    """The pass's moves (lead-in, the pieces, lead-out) with their poses and, on the trace, speeds."""
    moves = []
    for o in oriented:
        seg = o.geometry
        v = None if trace_speed is None else trace_speed * _trace_ratio(o, standoff)
        via = None if o.via is None else Pose(o.via, seg.via)
        moves.append(PlacedMove(seg, Pose(o.start, seg.start), Pose(o.end, seg.end), "curve", False, via, v))
    if leads[0] > 0:
        moves.insert(0, lead_move(oriented[0], leads[0], "lead_in", moves[0].speed_mm_s))
    if leads[1] > 0:
        moves.append(lead_move(oriented[-1], leads[1], "lead_out", moves[-1].speed_mm_s))
    return moves


def build_surface_program(paths: SurfacePaths, options: ProgramOptions, surface: SurfaceOptions,
                          language: Language, fitted: Optional[PassFits] = None) -> SurfaceProgram:
    """The ``options.variant`` program of every pass of ``paths`` in ``language`` (module text).
    ``fitted``: the passes already fitted (:func:`fit_passes`) for another variant; used when
    made with the settings of this program, else the passes are fitted here."""
    settings = surface_fit_settings(paths, surface, options.speed_mm_s)
    pose, standoff = settings.pose, settings.standoff_mm
    leads = [p.lead_lengths_mm() for p in paths.passes]
    lead_in = surface.lead_in_mm if surface.lead_in_mm is not None else max(a for a, _ in leads)
    lead_out = surface.lead_out_mm if surface.lead_out_mm is not None else max(b for _, b in leads)
    if len(paths.passes) > 1 and not options.approach_mm > 0:
        raise InputError(f"approach_mm {options.approach_mm:g}: passes are joined by travel at this clearance; "
                         "it must be > 0 mm", parameters=("approach_mm",))
    if not language.capabilities.tool_orientation:
        _check_untilted(place_passes(paths, settings), language, paths.source)
    if fitted is None or not fitted.settings.same_as(settings):
        fitted = fit_passes(paths, settings)
    tcps = fitted.tcps
    start_x = reference_direction(np.vstack([t.axes for t in tcps]))
    trace_speed = options.speed_mm_s if surface.speed_on == "trace" else None
    angle_tol = math.radians(surface.angle_tol_deg)
    placed, contours, counts, errors, arcs_as_lines = [], [], [], [], 0
    for tcp_path, surface_pass, fit in zip(tcps, paths.passes, fitted.fits):
        tcp, axes = tcp_path.tcp_mm, tcp_path.axes
        pieces = list(fit.pieces)
        wanted = AlongPass([p.geometry for p in pieces], tcp, axes, surface.tolerance_mm)
        oriented = oriented_pieces(pieces, surface.roll, surface.roll_deg, start_x, wanted, angle_tol)
        fit_moves = _placed(oriented, (0.0, 0.0), standoff, trace_speed)
        curve_length = float(sum(m.length for m in fit_moves))
        limits = _limits(fit_moves, options.speed_mm_s, surface.tool_accel_mm_s2,
                         _corners([AxisPiece(o.geometry, (np.zeros(3),) * 3) for o in oriented]))
        if options.variant != "polysegment":
            lines = _polyline(tcp, axes, surface)
            oriented = oriented_pieces(lines, surface.roll, surface.roll_deg, start_x,
                                       AlongPass([p.geometry for p in lines], tcp, axes, surface.tolerance_mm),
                                       angle_tol, max_rate_jump=math.inf)
        if surface.roll == "follow":  # the next pass starts nearest to where this one ends
            start_x = (oriented[-1].end @ rot_z(-math.radians(surface.roll_deg)))[:, 0]
        moves, lined = expressible(_placed(oriented, (lead_in, lead_out), standoff, trace_speed),
                                   language.capabilities.arc_planes, surface.tolerance_mm)
        arcs_as_lines += lined
        length = float(sum(m.length for m in moves if m.part == "curve"))
        limits = tuple(lim.scaled(length / curve_length) for lim in limits)
        errors.append(fit.max_axis_error_rad)
        n_arcs = sum(m.is_arc for m in moves if m.part == "curve")
        counts.append((sum(m.part == "curve" for m in moves) - n_arcs, n_arcs))
        placed.append(PlacedPath(tuple(moves), -axes[0], standoff, lead_in, lead_out, length))
        contours.append(SprayedContour(closed=surface_pass.closed, leads_sprayed=not surface_pass.closed,
                                       speed_limits=limits))
    surface_points = np.vstack([pose.apply(p.points) for p in paths.passes])
    placed = travel_clearances(placed, options.approach_mm, surface_points, standoff, paths.source)
    _check_range(placed, language, paths.source)
    plan, notes = _surface_plan(paths, options, surface, language, placed, tuple(contours), counts,
                                arcs_as_lines, _noise_notes(tcps, surface) + _tilt_notes(tcps, surface)
                                + _axis_notes(errors, surface),
                                (lead_in, lead_out), standoff, pose)
    return SurfaceProgram(language.write(plan), plan, tuple(counts), max(errors), notes, tuple(t.tcp_mm for t in tcps))


def surface_fit_settings(paths: SurfacePaths, surface: SurfaceOptions, speed_mm_s: float) -> FitSettings:
    """The settings the passes of a program placed with ``surface`` at ``speed_mm_s`` are fitted
    with: the stand-off and pose given, else the file's, else the defaults."""
    return FitSettings(surface.standoff_mm or paths.standoff_mm or defaults.STANDOFF_MM,
                       surface.pose or paths.pose or DEFAULT_FRAME, surface.tolerance_mm, surface.angle_tol_deg,
                       speed_mm_s, surface.speed_on, surface.tool_accel_mm_s2)


def _check_untilted(tcps: tuple[PassTcp, ...], language: Language, source: str) -> None:
    """Refuse, before the fit, passes whose spray axis leaves the base's -Z for a language
    without tool orientation."""
    down = np.array([0.0, 0.0, -1.0])
    for k, placed in enumerate(tcps):
        tilt = np.arccos(np.clip(placed.axes @ down, -1.0, 1.0))
        i = int(np.argmax(tilt))
        if tilt[i] > UNTILTED_TOL_RAD:
            raise InputError(f"{source}: passes[{k}] point {i} tilts the gun {math.degrees(tilt[i]):.3g} deg from -Z: "
                             f"{language.title} has no tool orientation, the gun points along -Z; write these "
                             "passes in a language with tool orientation")


def _noise_notes(tcps: tuple[PassTcp, ...], surface: SurfaceOptions) -> tuple[str, ...]:
    """What the user is told where the tool points of a pass scatter about a smooth path by more
    than _NOISE_SHARE of the tolerance (a scanned part's roughness, in its points and, through the
    stand-off, in its normals): the arcs follow that noise within the tolerance, many short ones. Judged only on
    passes whose points turn back and forth like noise (``taught.noisy``), where the scatter
    measures noise rather than a sparse pass's own bends."""
    scatter = [(k, scatter_mm(t.tcp_mm, False)) for k, t in enumerate(tcps) if noisy(t.tcp_mm)]
    over = [(k, s) for k, s in scatter if s > _NOISE_SHARE * surface.tolerance_mm]
    if not over:
        return ()
    k, worst = max(over, key=lambda item: item[1])
    return (f"the tool points scatter up to {worst:.2g} mm (rms) about a smooth path (passes[{k}]; {len(over)} of "
            f"{len(tcps)} passes): the mesh's roughness, a scan's noise, in its points and, through the stand-off, in "
            f"its normals; the arcs follow it within tolerance_mm {fmt_short(surface.tolerance_mm)} with many short moves; a tolerance "
            f"of {fmt_short(THIN_SCATTERS * worst, 2)} mm or more, or a smoother mesh, fits the surface itself",)


def _tilt_notes(tcps: list[PassTcp], surface: SurfaceOptions) -> tuple[str, ...]:
    """What the user is told where the axis leaves the normal further than ``angle_tol_deg`` to
    keep the tool centre point advancing (coatsim.path.unfold)."""
    over = [(k, math.degrees(t.max_tilt_rad)) for k, t in enumerate(tcps)
            if math.degrees(t.max_tilt_rad) > surface.angle_tol_deg * (1 + 1e-6)]
    if not over:
        return ()
    k, worst = max(over, key=lambda item: item[1])
    return (f"the tool axis leaves the normal by up to {worst:.1f} deg (passes[{k}]; {len(over)} of {len(tcps)} passes "
            f"above the {fmt_short(surface.angle_tol_deg)} deg asked) where the surface is concave tighter than the "
            "stand-off: on the normal the tool centre point would stall or run backwards there, so the axis turns "
            f"only as fast as keeps it advancing (at least {fmt_short(100 * MIN_ADVANCE)} % of the spot's way)",)


def _axis_notes(errors: list[float], surface: SurfaceOptions) -> tuple[str, ...]:
    """What the user is told where the fitted axis strays further than ``angle_tol_deg`` from the
    axes it follows (radians per pass in): the fit splits a move until the axis follows, down
    to moves of 2 MIN_SPLIT_MM; the axes (coatsim.path.unfold) turn no faster than keeps the tool
    advancing, so this is a guard, not an expected outcome."""
    over = [(k, math.degrees(e)) for k, e in enumerate(errors) if math.degrees(e) > surface.angle_tol_deg * (1 + 1e-6)]
    if not over:
        return ()
    k, worst = max(over, key=lambda item: item[1])
    return (f"the tool axis strays up to {worst:.1f} deg from the axis planned (passes[{k}]; {len(over)} of "
            f"{len(errors)} passes above the {fmt_short(surface.angle_tol_deg)} deg asked): the axes planned turn "
            f"that far within {fmt_short(2 * MIN_SPLIT_MM)} mm, finer than the fit splits its moves",)


def _surface_plan(paths: SurfacePaths, options: ProgramOptions, surface: SurfaceOptions, language: Language,
                  placed: list[PlacedPath], contours: tuple[SprayedContour, ...], counts: list[tuple[int, int]],
                  arcs_as_lines: int, axis_notes: tuple[str, ...], leads_mm: tuple[float, float], standoff: float,
                  pose: Pose) -> tuple[ProgramPlan, tuple[str, ...]]:
    """The program plan of the placed passes, with its process record and comments, and the notes
    for the user (arcs written as lines, ``axis_notes``)."""
    lead_in, lead_out = leads_mm
    n_lines, n_arcs = sum(c[0] for c in counts), sum(c[1] for c in counts)
    process = ProcessInfo(
        variant=options.variant, source=paths.source, tolerance_mm=surface.tolerance_mm,
        curve_length_mm=sum(p.curve_length_mm for p in placed), lead_in_mm=lead_in, lead_out_mm=lead_out,
        standoff_mm=standoff, speed_mm_s=options.speed_mm_s, accuracy_mm=options.accuracy_mm,
        gun_signal=options.gun_signal, frame=pose, n_segments=n_lines + n_arcs, n_lines=n_lines, n_arcs=n_arcs,
        contours=contours, contour_order=tuple(range(1, len(placed) + 1)) if len(placed) > 1 else None,
        speed_on=surface.speed_on,
    )
    stem = paths.source.replace("\\", "/").split("/")[-1].rsplit(".", 1)[0]
    name = language.check_name(options.name, "name") if options.name is not None else language.program_name(stem)
    comment = (f"coatsim {options.variant} program of {len(placed)} surface passes: {n_lines} lines + {n_arcs} arcs "
               f"in 3-D, tolerance {fmt_short(surface.tolerance_mm)} mm, tool axis within "
               f"{fmt_short(surface.angle_tol_deg)} deg of the normal, roll {surface.roll}, speed on the {surface.speed_on}")
    notes = (() if not arcs_as_lines else
             (f"{arcs_as_lines} arcs written as lines within {fmt_short(surface.tolerance_mm)} mm: "
              f"{language.title} has circular moves only in {language.capabilities.arc_planes} planes"
              + ("; a 3-D curve segmented with arc_planes 'principal' has every arc in them"
                 if language.capabilities.arc_planes == "principal" else ""),)) + axis_notes
    plan = ProgramPlan(name=name, paths=tuple(placed), speed_mm_s=options.speed_mm_s, accuracy_mm=options.accuracy_mm,
                       exact_stop=options.variant == "polyline-stop", approach_mm=options.approach_mm,
                       gun_signal=options.gun_signal, tool=options.tool, process=process, comments=(comment, *notes))
    return plan, notes


def _check_range(paths: list[PlacedPath], language: Language, source: str) -> None:
    corners = np.array([p.translation_mm for path in paths for m in path.segments for p in (m.start, m.end)])
    reach = language.capabilities.max_coordinate_mm
    if not (np.isfinite(corners).all() and np.abs(corners).max() <= reach):
        raise InputError(f"{source}: the placed passes leave the range a program can hold (|x| <= {reach:g} mm)")

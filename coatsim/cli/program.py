"""``coatsim program``: a curve, a drawing or a polysegment in, a robot program out."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Optional

import typer

from coatsim.cli.flags import fail, speaking_flags
from coatsim.core import defaults

if TYPE_CHECKING:
    from coatsim.path.build import BuiltProgram, ProgramOptions
    from coatsim.path.surface_program import SurfaceProgram
    from coatsim.path.language import Language
    from coatsim.path.part_program import PartProgram

def _numbers(text: str, flag: str) -> tuple[float, float, float]:
    """Three comma-separated numbers X,Y,Z."""
    parts = text.split(",")
    try:
        values = tuple(float(t) for t in parts)
    except ValueError:
        values = ()
    if len(values) != 3:
        fail(f"{flag}: expected X,Y,Z, found {text!r}")
    return values  # type: ignore[return-value]


FLAGS = {"tolerance_mm": "--tol", "speed_mm_s": "--speed", "accuracy_mm": "--accuracy", "approach_mm": "--approach",
         "gun_signal": "--gun", "variant": "--variant", "name": "--name", "order": "--order", "frame": "--frame",
         "standoff_mm": "--standoff", "lead_in_mm": "--lead-in", "lead_out_mm": "--lead-out", "roll_deg": "--roll-deg",
         "join_tolerance_mm": "--join-tol", "layers": "--layer", "tool_accel_mm_s2": "--tool-accel",
         "angle_tol_deg": "--angle-tol", "speed_on": "--speed-on", "roll": "--follow-tangent", "pose": "--frame", "language": "--language",
         "spray_axis": "--spray-axis"}


def program(
    input: str = typer.Argument(..., help="Curve file (CSV/TXT/NPY), builtin:NAME, a drawing (DXF/SVG), a polysegment or part JSON (coatsim segment -o), or surface passes (coatsim.surfacepaths/1, coatsim plan -o)."),
    tol: Optional[float] = typer.Option(None, "--tol", help="Tolerance sigma, mm (required for a curve; default for a JSON: its tolerance_mm)."),
    speed: float = typer.Option(defaults.SPEED_MM_S, "--speed", help="Programmed tool speed, mm/s."),
    standoff: Optional[float] = typer.Option(None, "--standoff", help=f"Stand-off of the TCP above the surface, mm [default: the surface paths' own, else {defaults.STANDOFF_MM:g}]."),
    frame: Optional[str] = typer.Option(None, "--frame", help="Workpiece frame (surface paths: the part's pose) x,y,z,o,a,t in the robot base frame (mm, deg O-A-T) [default: the surface paths' mesh pose, else " + ",".join(f"{v:g}" for v in defaults.WORKPIECE_FRAME) + "]."),
    variant: str = typer.Option("polysegment", "--variant", help="polysegment | polyline-stop | polyline-blend."),
    accuracy: float = typer.Option(defaults.ACCURACY_MM, "--accuracy", help="ACCURACY (blend zone radius), mm."),
    lead_in: Optional[float] = typer.Option(None, "--lead-in", help=f"Tangent lead-in before the curve, mm (sprayed on an open curve; a closed one is sprayed exactly once around) [default: the surface paths' leads, else {defaults.LEAD_IN_MM:g}]."),
    lead_out: Optional[float] = typer.Option(None, "--lead-out", help=f"Tangent lead-out after the curve, mm (sprayed on an open curve) [default: the surface paths' leads, else {defaults.LEAD_OUT_MM:g}]."),
    approach: float = typer.Option(defaults.APPROACH_MM, "--approach", help="Approach and depart distance along the tool axis, mm."),
    roll: float = typer.Option(0.0, "--roll-deg", help="Tool roll about the spray axis, deg."),
    follow_tangent: bool = typer.Option(False, "--follow-tangent", help="Turn the tool with the path tangent (roll relative to it); surface paths: otherwise the tool is carried along without turning about its axis."),
    angle_tol: float = typer.Option(defaults.ANGLE_TOL_DEG, "--angle-tol", help="Surface paths: the spray axis the controller interpolates stays this close to the surface normal, deg."),
    spray_axis: Optional[str] = typer.Option(None, "--spray-axis", help="3-D curves (x,y,z columns, or a 3-D polysegment): the gun's fixed direction X,Y,Z in the frame, from the gun toward the curve (0,0,-1: from above); the curve is written as one pass of surface passes' program."),
    speed_on: str = typer.Option("tcp", "--speed-on", help="Surface paths: where the programmed speed holds: tcp (every move) | trace (the spot on the surface: each move gets the speed that moves it at the programmed speed)."),
    center: Optional[bool] = typer.Option(None, "--center/--no-center", help="Move the curve's bounding-box centre to the frame origin [default: on for builtin curves]."),
    gun: int = typer.Option(defaults.GUN_SIGNAL, "--gun", help="Gun output signal number."),
    name: Optional[str] = typer.Option(None, "--name", help="Program name (AS: <= 15 characters) [default: from the input]."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Program file to write [default: the text goes to stdout]."),
    tool_accel: Optional[float] = typer.Option(None, "--tool-accel", help="Tool acceleration limit the curve is segmented for at --speed, m/s² [default: the cell model's]."),
    layer: Optional[list[str]] = typer.Option(None, "--layer", help="Drawings: read only this layer (repeatable) [default: every visible layer]."),
    join_tol: Optional[float] = typer.Option(None, "--join-tol", help="Drawings: join piece ends this close, mm [default: tol/100]."),
    order: str = typer.Option("as-drawn", "--order", help="Parts: spray the contours as-drawn | nearest (next start closest to the last end)."),
    language: Optional[str] = typer.Option(None, "--language", help="Robot language to write: kawasaki-as, abb-rapid, kuka-krl, ... (or a part of the name: rapid) [default: kawasaki-as]; the output's suffix is the language's."),
) -> None:
    """Write the robot program (polysegment or polyline variant) of a curve, or of every
    contour of a drawing one after the other (gun off between them), in a robot language."""
    from coatsim.cli.common import tool_accel_mm_s2
    from coatsim.languages.registry import DEFAULT_LANGUAGE, language as language_named
    from coatsim.path.build import ProgramOptions

    accel_mm_s2 = tool_accel_mm_s2(tool_accel)
    with speaking_flags(FLAGS):
        writer = language_named(language or DEFAULT_LANGUAGE)
        if name is None and output is not None and writer.capabilities.named_by_file:
            name = writer.program_name(output.stem)  # the controller loads a program by its file's name
        options = ProgramOptions(variant=variant, speed_mm_s=speed, accuracy_mm=accuracy, approach_mm=approach,
                                 gun_signal=gun, name=name)
        from coatsim.path.surfacepaths import is_surfacepaths

        if spray_axis is not None and is_surfacepaths(input):
            fail("--spray-axis is for 3-D curves; surface passes carry their own normals")
        if is_surfacepaths(input) or spray_axis is not None:
            axis = None if spray_axis is None else _numbers(spray_axis, "--spray-axis")
            surface = run_surface_program(input, options, tol=tol, frame=frame, standoff_mm=standoff, spray_axis=axis,
                                          lead_in_mm=lead_in, lead_out_mm=lead_out, roll_deg=roll,
                                          follow_tangent=follow_tangent, angle_tol_deg=angle_tol, speed_on=speed_on,
                                          tool_accel_mm_s2=accel_mm_s2, output=output, language=writer)
            if output is None:
                typer.echo(surface.text, nl=False)
            typer.echo(surface_summary(surface) + (f"\nwrote {output}" if output else ""), err=output is None)
            return
        if angle_tol != defaults.ANGLE_TOL_DEG or speed_on != "tcp":
            fail("--angle-tol and --speed-on apply to surface paths (coatsim.surfacepaths/1)")
        frame = frame if frame is not None else ",".join(f"{v:g}" for v in defaults.WORKPIECE_FRAME)
        standoff = defaults.STANDOFF_MM if standoff is None else standoff
        lead_in = defaults.LEAD_IN_MM if lead_in is None else lead_in
        lead_out = defaults.LEAD_OUT_MM if lead_out is None else lead_out
        built = run_program(input, tol, options, frame=frame, standoff_mm=standoff, lead_in_mm=lead_in,
                            lead_out_mm=lead_out, roll_deg=roll, follow_tangent=follow_tangent, center=center,
                            output=output, layers=layer, join_tol=join_tol, order=order, tool_accel_mm_s2=accel_mm_s2,
                            language=writer)
    if output is None:
        typer.echo(built.text, nl=False)
    typer.echo(program_summary(built) + (f"\nwrote {output}" if output else ""), err=output is None)


def run_program(spec: str, tol: Optional[float], options: ProgramOptions, *, frame: str, standoff_mm: float,
                lead_in_mm: float, lead_out_mm: float, roll_deg: float = 0.0, follow_tangent: bool = False,
                center: Optional[bool] = None, output: Optional[Path] = None, layers: Optional[list[str]] = None,
                join_tol: Optional[float] = None, order: str = "as-drawn",
                tool_accel_mm_s2: Optional[float] = None, language: Optional[Language] = None) -> PartProgram:
    """Load ``spec`` (a curve, a drawing or a polysegment/part JSON), place it, write the
    program (to ``output`` if given); a part's contours are sprayed in ``order``.

    ``center`` None centres built-in curves on the frame origin and leaves file curves where
    their coordinates put them. With ``tool_accel_mm_s2`` the curve is segmented for the
    programmed speed (see :func:`load_program_input`).
    """
    import warnings
    from dataclasses import replace

    from coatsim.core.budgets import check_budget
    from coatsim.core.errors import CoatsimWarning
    from coatsim.core.outputs_guard import check_distinct
    from coatsim.languages.registry import DEFAULT_LANGUAGE, language as language_named
    from coatsim.geometry.space.xyzoat import parse_xyzoat
    from coatsim.path.inputs import load_part_input
    from coatsim.path.part_program import build_part_program, part_centering_offset
    from coatsim.path.placement import Placement
    from coatsim.path.program_files import program_paths, write_program

    language = language or language_named(DEFAULT_LANGUAGE)
    placement = Placement(frame=parse_xyzoat(frame, "frame"), standoff_mm=standoff_mm, roll_deg=roll_deg,
                          follow_tangent=follow_tangent, lead_in_mm=lead_in_mm, lead_out_mm=lead_out_mm)
    outputs = program_paths(language, output) if output is not None else ()
    check_distinct([("the input", None if spec.startswith("builtin:") else spec)], [("-o", p) for p in outputs])
    speed = options.speed_mm_s if tool_accel_mm_s2 is not None else None
    inp = load_part_input(spec, tol, layers, join_tol, speed_mm_s=speed, tool_accel_mm_s2=tool_accel_mm_s2)
    moves = sum(len(c.segments) + 4 for c in inp.contours)  # and an approach, lead-in, lead-out, departure
    check_budget(f"{spec}: program lines, at least one move for each of its {moves - 4 * len(inp.contours):,} "
                 "segments", moves, "program_lines", "segment the part with a coarser tolerance")
    if inp.builtin if center is None else center:
        placement = replace(placement, offset_xy=part_centering_offset(inp.contours))
    built = build_part_program(inp.contours, placement, options, language=language, tolerance_mm=inp.tolerance_mm,
                               source=inp.source, points=inp.points, order=order)
    _reads_back(built.text, language)
    longest = max(max(s.length for path in built.plan.paths for s in path.segments), options.approach_mm)
    if options.accuracy_mm > longest:
        warnings.warn(f"--accuracy {options.accuracy_mm:g} mm is longer than every move (the longest is {longest:.4g} "
                      "mm); blended corners are rounded as far as the controller allows, half their shorter "
                      "neighbouring move", CoatsimWarning, stacklevel=2)
    if output is not None:
        write_program(language, built.text, output)
    return built


def run_surface_program(spec: str, options: ProgramOptions, *, tol: Optional[float], frame: Optional[str],
                        standoff_mm: Optional[float], lead_in_mm: Optional[float], lead_out_mm: Optional[float],
                        roll_deg: float, follow_tangent: bool, angle_tol_deg: float, speed_on: str,
                        tool_accel_mm_s2: Optional[float], output: Optional[Path] = None,
                        language: Optional[Language] = None,
                        spray_axis: Optional[tuple[float, float, float]] = None) -> SurfaceProgram:
    """The program of every pass of a surfacepaths file (coatsim.path.surface_program), or of a
    3-D curve sprayed along ``spray_axis`` (coatsim.path.fixed_axis: its leads the planar
    defaults), read back in its own language and written to ``output`` if given."""
    from coatsim.core.outputs_guard import check_distinct
    from coatsim.geometry.space.xyzoat import parse_xyzoat
    from coatsim.languages.registry import DEFAULT_LANGUAGE, language as language_named
    from coatsim.path.program_files import program_paths, write_program
    from coatsim.path.fixed_axis import fixed_axis_paths
    from coatsim.path.surface_program import SurfaceOptions, build_surface_program
    from coatsim.path.surfacepaths import read_surfacepaths

    language = language or language_named(DEFAULT_LANGUAGE)
    check_distinct([("the input", spec)], [("-o", p) for p in (program_paths(language, output) if output else ())])
    if spray_axis is not None:
        paths, tol = fixed_axis_paths(spec, spray_axis, tol)
        lead_in_mm = defaults.LEAD_IN_MM if lead_in_mm is None else lead_in_mm
        lead_out_mm = defaults.LEAD_OUT_MM if lead_out_mm is None else lead_out_mm
    else:
        paths = read_surfacepaths(spec)
    surface = SurfaceOptions(standoff_mm=standoff_mm, pose=None if frame is None else parse_xyzoat(frame, "pose"),
                             tolerance_mm=defaults.TOLERANCE_MM if tol is None else tol, angle_tol_deg=angle_tol_deg,
                             roll="follow" if follow_tangent else "fixed", roll_deg=roll_deg, speed_on=speed_on,
                             lead_in_mm=lead_in_mm, lead_out_mm=lead_out_mm, tool_accel_mm_s2=tool_accel_mm_s2)
    built = build_surface_program(paths, options, surface, language)
    _reads_back(built.text, language)
    if output is not None:
        write_program(language, built.text, output)
    return built


def surface_summary(built: SurfaceProgram) -> str:
    """Lines describing a written program of surface passes."""
    plan, process = built.plan, built.plan.process
    lines = [f"program {plan.name}: {process.variant}, {process.n_lines} lines + {process.n_arcs} arcs in 3-D over "
             f"{len(plan.paths)} passes, {built.text.count(chr(10))} lines of text",
             f"passes {process.curve_length_mm:.3f} mm + lead-in {process.lead_in_mm:g} + lead-out {process.lead_out_mm:g} mm "
             f"each at stand-off {process.standoff_mm:g} mm, {plan.speed_mm_s:g} mm/s on the {process.speed_on}; tool "
             f"axis within {math.degrees(built.max_axis_error_rad):.3f} deg of the axis planned (fit; the normal, but "
             "where a note says it leaves it)"]
    lines += [f"  pass {k + 1}: {n_lines} lines + {n_arcs} arcs, {p.curve_length_mm:.3f} mm"
              for k, ((n_lines, n_arcs), p) in enumerate(zip(built.counts, plan.paths))]
    return "\n".join(lines + [f"note: {n}" for n in built.notes])


def _reads_back(text: str, language: Language) -> None:
    """What goes to disk must read back in its own language (InputError otherwise)."""
    import tempfile

    from coatsim.path.language import ReadOptions
    from coatsim.path.program_files import program_suffixes, write_program

    with tempfile.TemporaryDirectory() as folder:
        paths = write_program(language, text, Path(folder) / f"program{program_suffixes(language)[0]}")
        language.read(list(paths), ReadOptions())


def program_summary(built: BuiltProgram | PartProgram) -> str:
    """Two lines (and one per contour of a part) describing a written program."""
    plan = built.plan
    curves = getattr(built, "curves", None) or (built.curve,)
    n_lines, n_arcs = sum(c.n_lines for c in curves), sum(c.n_arcs for c in curves)
    length = sum(p.curve_length_mm for p in plan.paths)
    lines = [
        f"program {plan.name}: {plan.process.variant}, {n_lines} lines + {n_arcs} arcs, "
        f"{built.text.count(chr(10))} lines of text",
        f"path: curve {length:.3f} mm + lead-in {plan.paths[0].lead_in_mm:g} + lead-out "
        f"{plan.paths[0].lead_out_mm:g} mm at stand-off {plan.paths[0].standoff_mm:g} mm, {plan.speed_mm_s:g} mm/s",
    ]
    if len(curves) > 1:
        lines[1] += f"; {len(curves)} contours, lead-in and lead-out on each, gun off between them"
        lines += [f"  contour {k + 1} (drawn {i + 1}): {c.n_segments} segments, {p.curve_length_mm:.3f} mm"
                  for k, (i, c, p) in enumerate(zip(built.order, curves, plan.paths))]
    return "\n".join(lines)

"""``coatsim execute``: run robot programs on the simulated arm, write the trajectory and the motion figures."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Mapping, Optional, Sequence

import typer

from coatsim.cli.common import LANGUAGE_HELP, SET_HELP
from coatsim.cli.flags import speaking_flags
from coatsim.core import defaults
from coatsim.core.fileio import write_text

if TYPE_CHECKING:
    from coatsim.geometry.space.pose import Pose
    from coatsim.robot.cell import Cell
    from coatsim.robot.execute import Execution

FLAGS = {"gun_signal": "--gun", "step_mm": "--step-mm", "program": "--program", "inputs": "--inputs",
         "part_pose": "--part-pose", "units": "--part-units", "language": "--language"}


def execute(
    program: list[Path] = typer.Argument(..., help="Program file(s) loaded together: programs, then data such as poses."),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF [default: the shipped coating_cell.xml]."),
    output: Path = typer.Option(Path("."), "-o", "--output", help="Folder for trajectory.csv, motion.json, speed.png."),
    gun: int = typer.Option(defaults.GUN_SIGNAL, "--gun", help="Gun output signal number."),
    step: float = typer.Option(defaults.STEP_MM, "--step-mm", help="Cartesian sampling step for IK, mm."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file that no loaded program calls, PC programs *.pc skipped; a note names it]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    settings: Optional[list[str]] = typer.Option(None, "--set", help=SET_HELP),
    timings: bool = typer.Option(False, "--timings", help="Print wall times per phase on stderr."),
    part: Optional[Path] = typer.Option(None, "--part", help="A part mesh (STL/PLY/OBJ/OFF/GLB) put in the cell in place of its plate: a contact of the arm or gun with it is exit 3."),
    part_units: str = typer.Option(defaults.PLAN_UNITS, "--part-units", help="The part mesh's unit: mm | cm | m | in | auto (from the file, else from the extent, with a note), as plan --units."),
    part_pose: Optional[str] = typer.Option(None, "--part-pose", help="The part's pose x,y,z,o,a,t in the robot base frame (mm, deg O-A-T) [default: the frame a coatsim program records, where its passes were planned; else " + ",".join(f"{v:g}" for v in defaults.WORKPIECE_FRAME) + "]."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
    language: Optional[str] = typer.Option(None, "--language", help=LANGUAGE_HELP),
) -> None:
    """Run a program on the simulated arm: IK, timing, MuJoCo playback, motion metrics; exit 3
    if it cannot be executed or the simulated arm diverges."""
    from coatsim.cli.common import input_states, variables

    with speaking_flags(FLAGS):
        result, files = execute_program(program, model, output, gun, step, main, input_states(inputs),
                                        variables(settings), force=force, part=part, part_pose=part_pose,
                                        part_units=part_units, language=language)
    m = result.metrics
    typer.echo(f"cycle {m.cycle_time_s:.3f} s (ideal {m.ideal_time_s:.3f} s, program {m.total_time_s:.3f} s); "
               f"speed mean {m.mean_speed_mm_s:.1f} min {m.min_speed_mm_s:.1f} mm/s of {m.programmed_speed_mm_s:g}, "
               f"CV {m.speed_cv:.4f}, {m.fraction_at_speed:.1%} at speed, {m.stops} stops; path error max "
               f"{m.max_path_error_mm:.3f} rms {m.rms_path_error_mm:.3f} mm; joint speed/accel "
               f"{m.max_joint_speed_ratio:.2f}/{m.max_joint_accel_ratio:.2f} of limits")
    if result.trace is not None and result.trace.standoff_mm > 0:
        tr = result.trace
        ratios = "" if tr.min_ratio is None else f", {tr.min_ratio:.3f} to {tr.max_ratio:.3f} of {tr.target_mm_s:g}"
        typer.echo(f"spray spot on the surface ({tr.standoff_mm:g} mm ahead of the tool): speed mean {tr.mean_mm_s:.1f} "
                   f"min {tr.min_mm_s:.1f} mm/s{ratios}")
    for warning in result.warnings:
        typer.echo(f"warning: {warning}", err=True)
    for event in result.events:
        typer.echo(f"warning: {event}", err=True)
    typer.echo(f"wrote {', '.join(str(f) for f in files)}")
    if timings:
        typer.echo("timings: " + ", ".join(f"{k.removesuffix('_s')} {t:.2f} s" for k, t in result.wall.items()), err=True)


def execute_program(program: Sequence[Path], model: Optional[Path], outdir: Path, gun_signal: int,
                    step_mm: float, main: Optional[str], inputs: Mapping[int, bool], variables: Mapping[str, str],
                    force: bool = False, part: Optional[Path] = None, part_pose: Optional[str] = None,
                    part_units: str = defaults.PLAN_UNITS,
                    language: Optional[str] = None) -> tuple[Execution, list[Path]]:
    """Read program files (in ``language``, default by their suffix or opening), run the main
    program (``main``, default the first), write trajectory.csv, motion.json and speed.png into
    ``outdir`` (held for the run; see coatsim.core.outputs_guard); ``variables`` gives variables
    no file gives; ``part`` a mesh in ``part_units`` put in the cell at ``part_pose`` (x,y,z,o,a,t;
    default the frame the program records, else the workpiece frame), its reading's notes said
    on stdout."""
    from coatsim.core.outputs_guard import check_distinct, output_folder
    from coatsim.languages.registry import language_of
    from coatsim.path.language import ReadOptions
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute
    from coatsim.robot.kinematics import CellKinematics
    from coatsim.robot.plots import plot_speed

    sources = list(program)
    out = Path(outdir)
    names = ["trajectory.csv", "motion.json", "speed.png"]
    files = [out / name for name in names]
    check_distinct([*(("the program", p) for p in sources), ("--model", model), ("--part", part)],
                   [("output", f) for f in files])
    cell = load_cell(model)
    if part is None and (part_pose is not None or part_units != defaults.PLAN_UNITS):
        from coatsim.cli.flags import fail

        fail(f"{'--part-pose places' if part_pose is not None else '--part-units reads'} the part given with --part; "
             "give --part MESH")
    options = ReadOptions(gun_signal=gun_signal, program=main, inputs=inputs, kinematics=CellKinematics(cell),
                          variables=variables)
    toolpath = language_of(sources, language).read([Path(p) for p in sources], options)
    if part is not None:
        cell = _with_part(cell, part, part_pose, part_units, toolpath.process.frame)
    with output_folder(out, names, "coatsim execute", force):
        result = execute(toolpath, cell, step_mm)
        result.log.write_csv(files[0])
        doc = {
            "format": "coatsim.motion/1",
            "program": str(sources[0]) if len(sources) == 1 else [str(p) for p in sources],
            "model": str(model) if model is not None else "default",
            "step_mm": step_mm,
            "motion": result.metrics.as_dict(),
            "trace": None if result.trace is None else result.trace.as_dict(),
            "events": list(result.events),
            "warnings": list(result.warnings),
        }
        write_text(files[1], json.dumps(doc, indent=2) + "\n")
        variant = toolpath.process.variant
        label = f"{toolpath.name} ({variant})" if variant else f"{toolpath.name} ({Path(sources[0]).name})"
        plot_speed(result.log, result.metrics, result.curves, files[2],
                   title=f"{label}: tool speed over the sprayed stretch")
    return result, files


def _with_part(cell: Cell, part: Path, part_pose: Optional[str], part_units: str, frame: Optional[Pose]) -> Cell:
    """The cell with the part read in ``part_units`` placed at ``part_pose``, else where the
    program says its passes were planned (its record's frame), else the default workpiece frame;
    notes on stdout, an overlap with the cell's bodies as a warning."""
    from coatsim.geometry.space.xyzoat import format_xyzoat, parse_xyzoat
    from coatsim.path.frames import DEFAULT_FRAME
    from coatsim.robot.collisions import load_part, part_overlaps, with_part

    if part_pose is not None:
        pose = parse_xyzoat(part_pose, "part_pose")
    else:
        pose = DEFAULT_FRAME if frame is None else frame
        where = "the default workpiece frame" if frame is None else "the frame the program's passes were planned in"
        typer.echo(f"note: the part placed at {format_xyzoat(pose)} ({where}; --part-pose places it elsewhere)")
    placed = load_part(part, pose, part_units)
    for note in placed.notes:
        typer.echo(f"note: {note}")
    cell = with_part(cell, placed)
    for warning in part_overlaps(cell):
        typer.echo(f"warning: {warning}", err=True)
    return cell

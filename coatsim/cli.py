"""Command-line layer: parse arguments, call one stage function, print, return the exit code.

Every CoatsimError becomes one line on stderr and its exit code (coatsim.cli_process); nothing else
is done here.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Optional

import typer

from coatsim.cli_plan import plan_command

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # help texts are plain: "[default: ...]" must not be read as markup
    help="coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating.",
)


def _version(value: bool) -> None:
    if value:
        from coatsim import __version__

        typer.echo(f"coatsim {__version__}")
        raise typer.Exit(0)


@app.callback()
def _main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True, help="Print the version and exit."),
) -> None:
    """coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating."""


def fail(message: str, code: int = 2) -> None:
    """Print a one-line error and exit with ``code``."""
    typer.echo(f"coatsim: error: {message}", err=True)
    raise typer.Exit(code)


SEGMENT_FLAGS = {"tolerance_mm": "--tol", "min_segment_mm": "--min-segment", "speed_mm_s": "--speed", "tool_accel_mm_s2": "--tool-accel"}


def _segment_flags(message: str) -> str:
    """A segment_curve error with its parameter names as the command's flags."""
    for name, flag in SEGMENT_FLAGS.items():
        message = message.replace(name, flag)
    return message


@app.command()
def segment(
    input: str = typer.Argument(..., help="Curve file (CSV/TXT/NPY: x,y columns), a drawing (DXF/SVG) or builtin:NAME[:key=value,...]."),
    tol: float = typer.Option(0.1, "--tol", help="Tolerance sigma: max two-sided deviation, mm."),
    method: str = typer.Option("optimal", "--method", help="optimal (guaranteed tolerance, few segments) | paper (literal RDP on θ)."),
    corner_deg: float = typer.Option(20.0, "--corner-deg", help="Turn within a short length that counts as a true corner, deg."),
    closed: str = typer.Option("auto", "--closed", help="auto | yes | no: whether the curve is a closed loop."),
    theta_tol: Optional[float] = typer.Option(None, "--theta-tol", help="paper method: fixed RDP tolerance on θ instead of searching for tol."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Polysegment JSON to write."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="PNG of the curve (arcs and lines) and of θ with its approximation."),
    timings: bool = typer.Option(False, "--timings", help="Print the fitter's wall time on stderr."),
    min_segment: Optional[float] = typer.Option(None, "--min-segment", help="Shortest fitted segment, mm [default: 5 x --tol or 1/500 of the curve between corners, the longer]."),
    speed: Optional[float] = typer.Option(None, "--speed", help="Programmed speed, mm/s: no arc tighter than speed²/tool-accel where the curve allows; the rest is listed as speed-limited."),
    tool_accel: Optional[float] = typer.Option(None, "--tool-accel", help="Tool acceleration limit with --speed, m/s² [default: the cell model's]."),
    layer: Optional[list[str]] = typer.Option(None, "--layer", help="Drawings: read only this layer (repeatable) [default: every visible layer]."),
    join_tol: Optional[float] = typer.Option(None, "--join-tol", help="Drawings: join piece ends this close, mm [default: tol/100]."),
) -> None:
    """Approximate a curve by tangent-continuous arcs and lines within a tolerance; a drawing
    gives one polysegment per contour (a part JSON when there are several)."""
    import math

    from coatsim.errors import InputError
    from coatsim.geometry import load_curve, segment_curve, write_polysegment_json
    from coatsim.geometry.cad.drawing import is_drawing
    from coatsim.outputs_guard import check_distinct

    if closed not in ("auto", "yes", "no"):
        fail(f"--closed: expected auto, yes or no, got {closed!r}")
    check_distinct([("the input curve", None if input.startswith("builtin:") else input)],
                   [("-o", output), ("--plot", plot)])
    if tool_accel is not None and speed is None:
        fail("--tool-accel: needs --speed")
    accel_mm_s2 = None
    if speed is not None:
        if tool_accel is None:
            from coatsim.robot.cell import load_cell

            accel_mm_s2 = load_cell().tool_accel_mm_s2
        elif math.isfinite(tool_accel) and tool_accel > 0:
            accel_mm_s2 = tool_accel * 1000.0
        else:
            fail(f"--tool-accel: must be a positive number of m/s², got {tool_accel}")
    if is_drawing(input):
        from coatsim.geometry.cad.command import segment_drawing_command

        if min_segment is not None:
            fail("--min-segment applies to point curves; a drawing keeps its lines and arcs as drawn")
        text, seconds = segment_drawing_command(input, tol, layer, join_tol, method, closed, theta_tol, output, plot,
                                                corner_deg, speed, accel_mm_s2)
        typer.echo(text)
        if timings:
            typer.echo(f"timings: reading, chaining and fitting {seconds:.3f} s", err=True)
        return
    if layer or join_tol is not None:
        fail("--layer and --join-tol apply to drawings (DXF, SVG)")
    try:
        seg = segment_curve(load_curve(input, closed), tol, method=method, corner_deg=corner_deg,
                            theta_tolerance=theta_tol, min_segment_mm=min_segment, speed_mm_s=speed,
                            tool_accel_mm_s2=accel_mm_s2)
    except InputError as exc:
        fail(_segment_flags(str(exc)))
    if output is not None:
        write_polysegment_json(output, seg)
    if plot is not None:
        from coatsim.geometry.plots import write_segmentation_plot

        write_segmentation_plot(seg, plot)
    typer.echo(seg.summary())
    for path in (output, plot):
        if path is not None:
            typer.echo(f"wrote {path}")
    if timings:
        typer.echo(f"timings: fitter {seg.seconds:.3f} s", err=True)


@app.command()
def run(
    scenario: Path = typer.Argument(..., help="scenario YAML file (see `coatsim schema`)"),
    outdir: Optional[Path] = typer.Option(None, "-o", "--outdir", help="output folder [default: runs/NAME]"),
    fast: bool = typer.Option(False, "--fast", help="the scenario's coarser mesh and path sampling (for CI)"),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF replacing the scenario's robot.model [default: the scenario's]."),
    timings: bool = typer.Option(False, "--timings", help="Print wall times per stage on stderr."),
    video: bool = typer.Option(False, "--video", help="Also write polysegment.mp4: the polysegment run rendered offscreen (needs imageio-ffmpeg)."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
) -> None:
    """Run a scenario: programs, simulated arm, coating, metrics.json and report.html for every
    variant; exit 1 if a gate fails, 3 if the simulated arm diverges."""
    import time

    from coatsim.errors import GateFailure
    from coatsim.pipeline import run_scenario
    from coatsim.report.summary import summary_text

    started = time.perf_counter()
    result = run_scenario(scenario, outdir, fast=fast, model=model, force=force, video=video)
    typer.echo(summary_text(result.document))
    for warning in result.document["warnings"]:
        typer.echo(f"warning: {warning['variant']}: {warning['message']}", err=True)
    typer.echo(f"wrote {len(result.files)} files to {result.outdir} (report: {result.outdir / 'report.html'})")
    if timings:
        parts = [f"segmentation {result.segmentation_s:.2f} s"]
        parts += [f"{v.name} " + ", ".join(f"{k.removesuffix('_s')} {t:.2f} s" for k, t in v.execution.wall.items())
                  for v in result.variants]
        parts.append(f"report {result.report_s:.2f} s")
        typer.echo(f"timings: {'; '.join(parts)}; total {time.perf_counter() - started:.1f} s", err=True)
    failed = [g["label"] for g in result.document["gates"] if not g["passed"]]
    if failed:
        raise GateFailure(f"{len(failed)} gate(s) failed: {'; '.join(failed)}")


@app.command()
def sweep(
    sweep_file: Path = typer.Argument(..., help="sweep YAML file: base scenario, grid and/or points"),
    outdir: Optional[Path] = typer.Option(None, "-o", "--outdir", help="output folder [default: runs/SWEEP_FILE_NAME]"),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Dask scheduler address, tcp://host:port [default: a local cluster]"),
    workers: Optional[int] = typer.Option(None, "--workers", help="worker processes of the local cluster [default: one per core]"),
    keep_outputs: bool = typer.Option(False, "--keep-outputs", help="keep every run's full outputs in OUTDIR/points/ID/"),
    metric: Optional[list[str]] = typer.Option(None, "--metric", metavar="NAME", help="metric sweep.html plots against each axis (repeatable) [default: the sweep file's]"),
) -> None:
    """Run many scenario points on Dask: results.parquet, results.csv, sweep.html; exit 1 if a
    point or a gate failed. Rerunning into the same folder runs only what is missing."""
    from coatsim.sweep.run import reused_count, run_sweep, sweep_problems

    # an interrupt ends here like any command's (exit 130); the finished points stay for a rerun
    result = run_sweep(sweep_file, outdir, scheduler=scheduler, workers=workers, keep_outputs=keep_outputs,
                       metrics=metric)
    rows = result.table.rows
    ok = sum(r[result.table.columns.index("status")] == "ok" for r in rows)
    typer.echo(f"{len(result.points)} points ({len(result.ran)} run, {reused_count(result.points, result.ran)} reused), "
               f"{len(rows)} rows: {ok} ok, {len(rows) - ok} failed; {len(result.gate_failures)} point(s) failed a gate")
    for p in result.points:
        outcome = result.outcomes[p.id]
        for variant, error in outcome.variants.items():
            if error is not None:
                typer.echo(f"failed: {p.id} [{variant}] ({p.label}): {error}")
        for label in result.gate_failures.get(p.id, ()):
            typer.echo(f"gate failed: {p.id} ({p.label}): {label}")
    typer.echo(f"wrote {', '.join(str(f) for f in result.files)} in {result.seconds:.1f} s")
    problem = sweep_problems(result)
    if problem is not None:
        raise problem


@app.command()
def schema() -> None:
    """Print the JSON Schema of scenario files (point your editor's YAML plugin at it)."""
    from coatsim.scenario import json_schema

    typer.echo(json_schema(), nl=False)


@app.command()
def coat(
    trajectory: Path = typer.Argument(..., help="Trajectory CSV (coatsim execute / run)."),
    surface: str = typer.Option(..., "--surface", help="plate:WxH@x,y,z | cylinder:RxL@x,y,z[,axis] | MESH.stl/ply/obj/glb optionally @x,y,z (mm, base frame)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Mesh vertex spacing, mm (default: sigma/3; R/20 for beta footprints)."),
    footprint: str = typer.Option("gaussian:sigma=5", "--footprint", help="gaussian:sigma= | elliptic:sx=,sy= | beta:radius=,beta= | double-beta:a=,b=,beta1=,beta2= | table:FILE.csv (mm)."),
    rate: float = typer.Option(40.0, "--rate", help="Deposited volume rate Q, mm3/s."),
    standoff: float = typer.Option(100.0, "--standoff", help="Reference stand-off h0 at which the footprint is given, mm."),
    target_um: Optional[float] = typer.Option(None, "--target-um", help="Target thickness for coverage, um (default: the ROI mean)."),
    roi: str = typer.Option("band", "--roi", help="band (sprayed strip) | part (whole part), both minus an edge band."),
    edge_band: Optional[float] = typer.Option(None, "--edge-band", help="Edge band left out of the ROI, mm (default: 3 sigma)."),
    de_exponent: float = typer.Option(1.0, "--de-exponent", help="Deposition efficiency cos^(n-1) of the incidence angle; 1 = off."),
    occlusion: bool = typer.Option(False, "--occlusion", help="Ray-cast visibility for concave parts (slow)."),
    section: Optional[str] = typer.Option(None, "--section", help="Cross-section line x0,y0,x1,y1 in heat-map coordinates, mm."),
    out: Path = typer.Option(Path("out/coat"), "-o", "--out", help="Output folder."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
) -> None:
    """Spray a logged trajectory onto a surface: thickness.ply, coating.json, heatmap.png, section.png."""
    from coatsim.errors import EmptyRegionOfInterest, InputError
    from coatsim.spray.coat import run_coat

    try:
        result, files = run_coat(trajectory, surface, spacing, footprint, rate, standoff, target_um, roi,
                                 edge_band, de_exponent, occlusion, section, out, force)
    except EmptyRegionOfInterest as exc:
        raise InputError(f"{exc}; try --roi part or a smaller --edge-band") from None
    m = result.metrics
    typer.echo(f"{result.surface.n_vertices} vertices, spray {m['spray_time_s']:.3f} s; ROI ({roi}) "
               f"mean {m['thickness_mean_um']:.3f} um, CV {m['thickness_cv']:.4f}, "
               f"min {m['thickness_min_um']:.3f}, max {m['thickness_max_um']:.3f} um; "
               f"deposited {m['deposited_volume_mm3']:.3f} of {m['sprayed_volume_mm3']:.3f} mm3")
    typer.echo(f"wrote {', '.join(str(f) for f in files)}")


@app.command()
def program(
    input: str = typer.Argument(..., help="Curve file (CSV/TXT/NPY), builtin:NAME, a drawing (DXF/SVG), or a polysegment or part JSON (coatsim segment -o)."),
    tol: Optional[float] = typer.Option(None, "--tol", help="Tolerance sigma, mm (required for a curve; default for a JSON: its tolerance_mm)."),
    speed: float = typer.Option(500.0, "--speed", help="Programmed tool speed, mm/s."),
    standoff: float = typer.Option(100.0, "--standoff", help="Stand-off of the TCP above the surface, mm."),
    frame: str = typer.Option("700,0,200,0,0,0", "--frame", help="Workpiece frame x,y,z,o,a,t in the robot base frame (mm, deg O-A-T)."),
    variant: str = typer.Option("polysegment", "--variant", help="polysegment | polyline-stop | polyline-blend."),
    accuracy: float = typer.Option(1.0, "--accuracy", help="ACCURACY (blend zone radius), mm."),
    lead_in: float = typer.Option(30.0, "--lead-in", help="Tangent lead-in before the curve, mm (sprayed on an open curve; a closed one is sprayed exactly once around)."),
    lead_out: float = typer.Option(30.0, "--lead-out", help="Tangent lead-out after the curve, mm (sprayed on an open curve)."),
    approach: float = typer.Option(50.0, "--approach", help="Approach and depart distance along the tool axis, mm."),
    roll: float = typer.Option(0.0, "--roll-deg", help="Tool roll about the spray axis, deg."),
    follow_tangent: bool = typer.Option(False, "--follow-tangent", help="Turn the tool with the path tangent (roll relative to it)."),
    center: Optional[bool] = typer.Option(None, "--center/--no-center", help="Move the curve's bounding-box centre to the frame origin [default: on for builtin curves]."),
    gun: int = typer.Option(1, "--gun", help="Gun output signal number."),
    name: Optional[str] = typer.Option(None, "--name", help="AS program name (<= 15 characters) [default: from the input]."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Program file to write [default: the text goes to stdout]."),
    tool_accel: Optional[float] = typer.Option(None, "--tool-accel", help="Tool acceleration limit the curve is segmented for at --speed, m/s² [default: the cell model's]."),
    layer: Optional[list[str]] = typer.Option(None, "--layer", help="Drawings: read only this layer (repeatable) [default: every visible layer]."),
    join_tol: Optional[float] = typer.Option(None, "--join-tol", help="Drawings: join piece ends this close, mm [default: tol/100]."),
    order: str = typer.Option("as-drawn", "--order", help="Parts: spray the contours as-drawn | nearest (next start closest to the last end)."),
) -> None:
    """Write the Kawasaki AS program (polysegment or polyline variant) of a curve, or of every
    contour of a drawing one after the other (gun off between them)."""
    import math

    from coatsim.program.build import ProgramOptions
    from coatsim.program.run import program_summary, run_program

    options = ProgramOptions(variant=variant, speed_mm_s=speed, accuracy_mm=accuracy, approach_mm=approach,
                             gun_signal=gun, name=name)
    if tool_accel is None:
        from coatsim.robot.cell import load_cell

        accel_mm_s2 = load_cell().tool_accel_mm_s2
    elif math.isfinite(tool_accel) and tool_accel > 0:
        accel_mm_s2 = tool_accel * 1000.0
    else:
        fail(f"--tool-accel: must be a positive number of m/s², got {tool_accel}")
    built = run_program(input, tol, options, frame=frame, standoff_mm=standoff, lead_in_mm=lead_in,
                        lead_out_mm=lead_out, roll_deg=roll, follow_tangent=follow_tangent, center=center,
                        output=output, layers=layer, join_tol=join_tol, order=order, tool_accel_mm_s2=accel_mm_s2)
    if output is None:
        typer.echo(built.text, nl=False)
    typer.echo(program_summary(built) + (f"\nwrote {output}" if output else ""), err=output is None)


@app.command()
def execute(
    program: list[Path] = typer.Argument(..., help="Kawasaki AS file(s) loaded together: programs, then data such as poses."),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF [default: the shipped coating_cell.xml]."),
    output: Path = typer.Option(Path("."), "-o", "--output", help="Folder for trajectory.csv, motion.json, speed.png."),
    gun: int = typer.Option(1, "--gun", help="Gun output signal number."),
    step: float = typer.Option(1.0, "--step-mm", help="Cartesian sampling step for IK, mm."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file, PC programs *.pc skipped]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    timings: bool = typer.Option(False, "--timings", help="Print wall times per phase on stderr."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
) -> None:
    """Run a program on the simulated arm: IK, timing, MuJoCo playback, motion metrics; exit 3
    if it cannot be executed or the simulated arm diverges."""
    from coatsim.program.as_lang.io_model import parse_inputs
    from coatsim.robot.execute import execute_program

    result, files = execute_program(program, model, output, gun, step, main,
                                    parse_inputs(inputs) if inputs is not None else None, force=force)
    m = result.metrics
    typer.echo(f"cycle {m.cycle_time_s:.3f} s (ideal {m.ideal_time_s:.3f} s, program {m.total_time_s:.3f} s); "
               f"speed mean {m.mean_speed_mm_s:.1f} min {m.min_speed_mm_s:.1f} mm/s of {m.programmed_speed_mm_s:g}, "
               f"CV {m.speed_cv:.4f}, {m.fraction_at_speed:.1%} at speed, {m.stops} stops; path error max "
               f"{m.max_path_error_mm:.3f} rms {m.rms_path_error_mm:.3f} mm; joint speed/accel "
               f"{m.max_joint_speed_ratio:.2f}/{m.max_joint_accel_ratio:.2f} of limits")
    for warning in result.warnings:
        typer.echo(f"warning: {warning}", err=True)
    for event in result.events:
        typer.echo(f"warning: {event}", err=True)
    typer.echo(f"wrote {', '.join(str(f) for f in files)}")
    if timings:
        typer.echo("timings: " + ", ".join(f"{k.removesuffix('_s')} {t:.2f} s" for k, t in result.wall.items()), err=True)


@app.command()
def convert(
    paths: list[Path] = typer.Argument(..., help="Kawasaki AS file(s) loaded together: programs, then data such as poses."),
    tol: float = typer.Option(..., "--tol", help="Tolerance sigma: largest deviation from the original path, mm."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Program file to write [default: the text goes to stdout]."),
    gun: int = typer.Option(1, "--gun", help="Gun output signal number: its sprayed moves are the process path."),
    standalone: bool = typer.Option(False, "--standalone", help="A clean program of the path alone instead of the edited original."),
    lines: Optional[str] = typer.Option(None, "--lines", help="FIRST-LAST: the moves of these source lines instead of the sprayed ones."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file, PC programs *.pc skipped]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF for joint poses and HOME [default: the shipped coating_cell.xml]."),
    corner_deg: float = typer.Option(20.0, "--corner-deg", help="Turn within a short length that counts as a true corner, deg."),
    name: Optional[str] = typer.Option(None, "--name", help="Name of the standalone program [default: the original's]."),
) -> None:
    """Rewrite the process path of an existing AS program with arcs within a tolerance."""
    from coatsim.fileio import write_bytes
    from coatsim.outputs_guard import check_distinct
    from coatsim.program.as_lang.io_model import parse_inputs
    from coatsim.program.convert import (
        ConvertOptions,
        conversion_summary,
        convert_program,
    )
    from coatsim.robot.kinematics import LazyKinematics

    check_distinct([*(("the program", p) for p in paths), ("--model", model)], [("-o", output)])
    line_range = None
    if lines is not None:
        first, sep, last = lines.partition("-")
        if not (sep and first.strip().isdigit() and last.strip().isdigit() and int(first) <= int(last)):
            fail(f"--lines {lines!r}: expected FIRST-LAST source line numbers, as in 12-1911")
        line_range = (int(first), int(last))
    options = ConvertOptions(tolerance_mm=tol, gun_signal=gun, program=main, lines=line_range, standalone=standalone,
                             corner_deg=corner_deg, name=name)
    result = convert_program(paths, options, inputs=parse_inputs(inputs) if inputs is not None else None,
                             kinematics=LazyKinematics(model))
    if output is not None:
        write_bytes(output, result.data)  # the original's bytes: encoding and line ends kept
    else:
        sys.stdout.flush()
        sys.stdout.buffer.write(result.data)
        sys.stdout.buffer.flush()
    typer.echo(conversion_summary(result) + (f"\nwrote {output}" if output else ""), err=output is None)


@app.command("check-program")
def check_program(
    paths: list[Path] = typer.Argument(..., help="Kawasaki AS file(s) loaded together: programs, then data such as poses."),
    gun: int = typer.Option(1, "--gun", help="Gun output signal number."),
    main: Optional[str] = typer.Option(None, "--program", help="Main program [default: the first of the first file, PC programs *.pc skipped]."),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="Input signals the cell sets, e.g. 1001,-1002 (minus: off)."),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF for joint poses, HOME and the gun the TOOL is checked against [default: the shipped coating_cell.xml]."),
) -> None:
    """Parse and interpret AS programs; report steps, poses, signals, sprayed path and problems;
    exit 2 if the gun never opens."""
    from coatsim.errors import InputError
    from coatsim.program.as_lang.io_model import parse_inputs
    from coatsim.program.check import check_program as check
    from coatsim.program.run import check_summary
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics
    from coatsim.robot.sampling import plan_pieces

    cell = load_cell(model)
    result = check(paths, gun_signal=gun, program=main, inputs=parse_inputs(inputs) if inputs is not None else None,
                   kinematics=CellKinematics(cell), gun_tcp=(cell.gun_rotation, cell.gun_offset_mm))
    plan_pieces(result.toolpath)  # what the robot stage would reject before any simulation
    typer.echo(check_summary(result))
    if result.errors:
        raise InputError(result.errors[0])


app.command("plan")(plan_command)  # passes on 3-D parts (coatsim/cli_plan.py)


def main() -> None:
    """Console entry point (exit codes in coatsim.cli_process.run_app)."""
    from coatsim.cli_process import run_app

    sys.exit(run_app(app))


if __name__ == "__main__":
    main()

"""Run one scenario: every stage for every program variant, then metrics, gates and report.

curve -> polysegment -> for each variant: program text in its language (written) -> ToolPath
read back from that file -> simulated arm -> trajectory (written) -> coating (written) -> metrics ->
``metrics.json`` and ``report.html``. The execution stage consumes the program text parsed back,
never the in-memory polysegment: the twin runs what the robot would run.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Mapping, Optional

import numpy as np

from coatsim.core.errors import CoatsimError, EmptyRegionOfInterest, InputError
from coatsim.core.fileio import write_text
from coatsim.core.progress import Step, labelled, progress as progress_bar
from coatsim.geometry import make_curve, segment_curve, write_polysegment_json
from coatsim.geometry.cad import PartSegmentation
from coatsim.geometry.curves import ends_meet
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.part_json import write_part_json
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.segment import Segmentation
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions, polyline_of
from coatsim.path.language import ReadOptions
from coatsim.path.part_program import (
    PartProgram,
    build_part_program,
    part_centering_offset,
)
from coatsim.path.placement import Placement
from coatsim.path.program_files import write_program
from coatsim.path.toolpath import ToolPath
from coatsim.path.user import UserProgram, user_program
from coatsim.report.gates import evaluate_gates
from coatsim.report.results import RunResult, VariantRun
from coatsim.report.metrics import (
    assemble,
    coating_group,
    combine_segmentation,
    contours_section,
    segmentation_group,
    to_json,
)
from coatsim.robot.cell import Cell
from coatsim.robot.execute import execute
from coatsim.robot.kinematics import CellKinematics
from coatsim.robot.tooling import gun_tool
from coatsim.run.scenario import (
    ScenarioFile,
    as_dict,
    check_gate_metrics,
    load_scenario,
)
from coatsim.run.scenario_inputs import (
    build_surface,
    curve_frame,
    input_files,
    load_arm,
    read_user_program,
    segment_input,
    user_program_suffix,
    spray_model,
)
from coatsim.run.variant_spec import ProgramVariantSpec
from coatsim.spray.coat import coat
from coatsim.spray.coating_metrics import away_from_border, edge_band_width
from coatsim.spray.deposition import SprayModel
from coatsim.spray.surfaces import Surface
from coatsim.run.part_run import part_output_names, run_part
from coatsim.run.variants import (
    on_common_roi,
    program_files,
    reference_variant,
    variant_names,
    write_thickness_files,
)

FULL_SAMPLE_STEP_MM = 1.0  # path sampling of the arm simulation outside fast mode


@dataclass(frozen=True, eq=False)
class Job:
    """What every variant of a run shares: inputs, placement, part, gun, arm, numerics."""

    loaded: ScenarioFile
    contours: tuple[Segmentation, ...]
    placement: Placement
    surface: Surface
    model: SprayModel
    cell: Cell
    outdir: Path
    sample_step_mm: float
    spacing_mm: float
    away_mm: np.ndarray  # surface vertices clear of the edge band (every variant's ROI)
    # per contour, the polyline variants' curve and its deviation, computed once for both
    polylines: tuple[Optional[Polysegment], ...] = ()
    polyline_deviations_mm: tuple[Optional[float], ...] = ()


def run_variant(name: str, variant: str, language_name: str, job: Job, step: Step) -> VariantRun:
    """Program, execute and coat one built-in variant written in its language; writes its
    program file(s) and ``name.trajectory.csv``."""
    spec, out = job.loaded.spec, job.outdir
    polys = [c.polysegment for c in job.contours]
    writer = language(language_name)
    program_name = writer.program_name(name if writer.capabilities.named_by_file else spec.name)
    options = ProgramOptions(variant=variant, speed_mm_s=spec.speed_of(name), accuracy_mm=spec.motion.accuracy_mm,
                             gun_signal=spec.gun.signal, tool=gun_tool(job.cell), name=program_name)
    program = build_part_program(polys, job.placement, options, language=writer,
                                 tolerance_mm=spec.segmentation.tolerance_mm, source=f"scenario:{spec.name}",
                                 points=[c.curve.points for c in job.contours], order=spec.motion.contour_order,
                                 polylines=job.polylines or None)
    files = program_files(name, writer)
    paths = write_program(writer, program.text, out / files[0])
    toolpath = writer.read(list(paths), ReadOptions(gun_signal=spec.gun.signal, kinematics=CellKinematics(job.cell)))
    return replace(simulate_variant(name, program, toolpath, job, step), program_file=files[0])


def run_program_variant(entry: ProgramVariantSpec, job: Job, step: Step) -> VariantRun:
    """Execute and coat a user's program; writes ``name`` + its suffix (a copy),
    ``name.trajectory.csv`` and ``name.thickness.ply``."""
    toolpath, text = read_user_program(job.loaded, entry, job.cell)
    copy = f"{entry.name}{user_program_suffix(job.loaded, entry)}"
    write_text(job.outdir / copy, text)
    try:
        program = user_program(toolpath, curve_frame(job.loaded.spec), text)
        toolpath = replace(toolpath, warnings=(*toolpath.warnings, *program.notes))  # they reach metrics.json
        return replace(simulate_variant(entry.name, program, toolpath, job, step), program_file=copy)
    except CoatsimError as exc:
        raise exc.prefixed(entry.name) from None


def _user_contour(job: Job, program: UserProgram) -> np.ndarray:
    """The points of the contour a user's program sprays (of a part's, the one nearest to its
    path), placed as coatsim's programs place them (the user's path is in the frame's plane)."""
    placed = [c.curve.points + np.asarray(job.placement.offset_xy, dtype=float) for c in job.contours]
    if len(placed) == 1:
        return placed[0]
    return min(placed, key=lambda pts: hausdorff(pts, program.curve).hausdorff)


def _segmentation_groups(job: Job, program: PartProgram | UserProgram) -> list[dict]:
    """Each contour's segmentation group (drawing order) for coatsim's programs; for a user's
    program, that of the contour it sprays."""
    spec = job.loaded.spec.segmentation
    if isinstance(program, UserProgram):
        points = _user_contour(job, program)
        return [segmentation_group(points, program.curve, spec.tolerance_mm, spec.corner_deg, None)]
    groups: list = [None] * len(job.contours)
    for k, curve in zip(program.order, program.curves):
        c = job.contours[k]
        if curve is c.polysegment:
            known = c.max_deviation_mm
        elif job.polylines and curve is job.polylines[k]:
            known = job.polyline_deviations_mm[k]
        else:
            known = None
        groups[k] = segmentation_group(c.curve.points, curve, spec.tolerance_mm, spec.corner_deg, known)
    return groups


def simulate_variant(name: str, program: PartProgram | UserProgram, toolpath: ToolPath, job: Job,
                     step: Step) -> VariantRun:
    """Execute and coat one variant's program; its metrics against the scenario's curve (each
    contour of a part, and the part as a whole)."""
    spec, out = job.loaded.spec, job.outdir
    step(f"{name}: simulating the arm")
    execution = execute(toolpath, job.cell, step_mm=job.sample_step_mm)
    execution.log.write_csv(out / f"{name}.trajectory.csv")
    step(f"{name}: spraying")
    try:
        result = coat(execution.log, job.surface, job.model, target_um=spec.gun.target_thickness_um,
                      edge_band_mm=spec.coating.edge_band_mm, band_halfwidth_mm=spec.coating.band_halfwidth_mm,
                      spacing=job.spacing_mm, away=job.away_mm)
    except EmptyRegionOfInterest as exc:
        raise EmptyRegionOfInterest(f"{job.loaded.where('workpiece')}: {exc}; check the workpiece pose against the "
                                    "sprayed path and coating.edge_band_mm") from None
    segmentation = _segmentation_groups(job, program)
    groups = {
        "segmentation": combine_segmentation(segmentation),
        "motion": execution.metrics.as_dict(),
        "coating": coating_group(result.metrics),
    }
    per_contour: tuple = ()
    if len(job.contours) > 1 and isinstance(program, PartProgram):
        motion = [None] * len(job.contours)
        for place, k in enumerate(program.order):
            motion[k] = execution.contour_metrics[place].as_dict()
        per_contour = tuple({"segmentation": s, "motion": m} for s, m in zip(segmentation, motion))
    return VariantRun(name, program, execution, result, groups, per_contour, toolpath)


def variant_files(loaded: ScenarioFile, entry) -> tuple[str, ...]:
    """The program file(s) a variant writes: a built-in variant's in its language, a copy of a
    user's program with its language's suffix."""
    builtin = loaded.spec.builtin(entry)
    if builtin is not None:
        return program_files(entry if isinstance(entry, str) else entry.name, language(builtin[1]))
    return (f"{entry.name}{user_program_suffix(loaded, entry)}",)


def output_names(loaded: ScenarioFile, video: bool = False) -> list[str]:
    """The files a run of the scenario ``loaded`` may write into its output folder, in writing
    order (a drawing of several contours writes part.json instead of polysegment.json)."""
    spec = loaded.spec
    if spec.part is not None:
        return part_output_names(loaded)
    names = variant_names(spec)
    programs = [f for entry, v in zip(spec.variants, names) for f in (*variant_files(loaded, entry),
                                                                       f"{v}.trajectory.csv")]
    coats = [f"{v}.{kind}" for v in names for kind in ("thickness.ply", "thickness.glb")]
    movie = [f"{reference_variant(spec)}.mp4"] if video else []
    return ["polysegment.json", "part.json", *programs, "metrics.json", *coats, *movie, "report.html"]


def run_scenario(path: str | Path, outdir: Optional[str | Path] = None, fast: bool = False,
                 progress: Optional[bool] = None, model: Optional[str | Path] = None, force: bool = False, *,
                 keep_going: bool = False, report: bool = True, video: bool = False) -> RunResult:
    """Run every stage of the scenario at ``path`` for every variant and write all outputs.

    ``outdir`` defaults to ``runs/<name>`` and is held for the run (coatsim.core.outputs_guard): no
    output may be an input, and files there that coatsim did not write are replaced only with
    ``force``. ``fast`` uses the scenario's coarser ``fast`` settings; ``progress`` defaults to
    showing a bar when stderr is a terminal; ``model`` replaces the scenario's robot model. With
    ``keep_going`` a variant that cannot run is recorded in ``failures`` (and in the metrics
    document's ``failed``, which then does not pass; gates on it are left out) while the others
    run. ``report=False`` skips report.html (so does a run where no variant ran); ``video`` also
    writes an MP4 of the reference (polysegment) run.

    Returns:
        The RunResult: every variant's program, execution and coat, the metrics document and
        the files written; ``passed`` tells whether every gate held.

    Raises:
        InputError: a scenario, input file or output folder that is not usable (exit 2).
        ExecutionError: a variant that cannot run on the arm, unless ``keep_going`` (exit 3).
    """
    from coatsim.core.outputs_guard import check_distinct, output_folder

    loaded = load_scenario(path)
    check_gate_metrics(loaded)
    out = Path(outdir) if outdir is not None else Path("runs") / loaded.spec.name
    names = output_names(loaded, video)
    check_distinct(input_files(loaded, model), [("output", out / name) for name in names])
    cell = load_arm(loaded, model)
    if loaded.spec.part is not None and video:
        raise InputError(f"{loaded.where('part')}: the cell's video is made for runs of a curve; a run on a 3-D part "
                         "shows the part and the passes in report.html and VARIANT.thickness.glb (video)",
                         parameters=("video",))
    with output_folder(out, names, "coatsim run", force):
        if loaded.spec.part is not None:
            return run_part(loaded, cell, out, fast, progress, keep_going, report)
        return _run_in(loaded, cell, out, fast, progress, keep_going, report, video)


def _run_in(loaded: ScenarioFile, cell: Cell, out: Path, fast: bool, progress: Optional[bool], keep_going: bool,
            report: bool, video: bool) -> RunResult:
    """Every stage of a loaded scenario, writing into the held folder ``out``."""
    spec = loaded.spec
    show = sys.stderr.isatty() if progress is None else progress
    with progress_bar("running the scenario", 3 + 3 * len(spec.variants) + int(video), show) as advance:
        step = labelled(advance)
        step("segmenting the curve")
        contours, part, offset = _segmentation(loaded, cell)
        segmentation_file = out / ("part.json" if len(contours) > 1 else "polysegment.json")
        if part is None:
            write_polysegment_json(segmentation_file, contours[0])
        else:
            write_part_json(segmentation_file, part)
        step("meshing the workpiece")
        job = _job(loaded, cell, out, fast, contours, offset)
        runs, failures = _run_variants(job, step, keep_going)
        step("metrics, gates and report")
        runs = on_common_roi(runs, spec.gun.target_thickness_um)
        document = _document(loaded, runs, contours, failures, fast)
        write_text(out / "metrics.json", to_json(document))
        report_started = time.perf_counter()
        _write_views(loaded, cell, out, runs, contours, part, document, step, report, video)
        report_s = time.perf_counter() - report_started
    unwritten = {f"{v}.{kind}" for v in failures for kind in ("trajectory.csv", "thickness.ply", "thickness.glb", "mp4")}
    unwritten |= set() if report and runs else {"report.html"}
    unwritten |= {"polysegment.json", "part.json"} - {segmentation_file.name}
    written = [name for name in output_names(loaded, video) if name not in unwritten]
    seconds = part.seconds if part is not None else contours[0].seconds
    return RunResult(out, tuple(runs), document, tuple(out / name for name in written), failures, seconds, report_s)


def _segmentation(loaded: ScenarioFile, cell: Cell) -> tuple[tuple[Segmentation, ...], Optional[PartSegmentation],
                                                             tuple[float, float]]:
    """The scenario's contours fitted (of its curve or drawing, else of the sprayed path of its
    first program variant), the drawing's segmentation if any, and the offset that places them."""
    spec = loaded.spec
    if spec.curve is not None:
        contours, part = segment_input(loaded, cell)
        polys = [c.polysegment for c in contours]
        offset = np.add(part_centering_offset(polys) if spec.curve.center else (0.0, 0.0), spec.curve.offset_mm)
        return tuple(contours), part, (float(offset[0]), float(offset[1]))
    entry = spec.programs[0]
    toolpath = read_user_program(loaded, entry, cell)[0]  # (its errors name the variant)
    try:
        user = user_program(toolpath, curve_frame(spec), "")
    except CoatsimError as exc:
        raise exc.prefixed(f"{loaded.where('variants')}: variant {entry.name}") from None
    # a program drives no step it does not list: its path is closed only where it returns to its start
    closed = "yes" if len(user.points) >= 4 and ends_meet(user.points) else "no"
    seg = segment_curve(make_curve(user.points, entry.name, closed), spec.segmentation.tolerance_mm,
                        method=spec.segmentation.method, corner_deg=spec.segmentation.corner_deg,
                        speed_mm_s=spec.motion.speed_mm_s, tool_accel_mm_s2=cell.tool_accel_mm_s2)
    return (seg,), None, (0.0, 0.0)


def _job(loaded: ScenarioFile, cell: Cell, out: Path, fast: bool, contours: tuple[Segmentation, ...],
         offset: tuple[float, float]) -> Job:
    """What every variant shares: the placement, the meshed part, the gun, the polyline of each
    contour for the polyline variants (with its deviation), computed once."""
    spec = loaded.spec
    spacing = spec.fast.coating_spacing_mm if fast else spec.coating.spacing_mm
    sample_step = spec.fast.sample_step_mm if fast else FULL_SAMPLE_STEP_MM
    placement = Placement(frame=curve_frame(spec), standoff_mm=spec.gun.standoff_mm, roll_deg=spec.gun.roll_deg,
                          follow_tangent=spec.gun.follow_tangent, lead_in_mm=spec.motion.lead_in_mm,
                          lead_out_mm=spec.motion.lead_out_mm, offset_xy=offset)
    surface, model = build_surface(loaded, spacing), spray_model(loaded)
    away = away_from_border(surface, edge_band_width(model, spec.coating.edge_band_mm), spacing)
    polylines: tuple = ()
    deviations: tuple = ()
    if any((spec.builtin(v) or ("polysegment",))[0] != "polysegment" for v in spec.variants):
        tol = spec.segmentation.tolerance_mm
        polylines = tuple(polyline_of(c.curve.points, c.polysegment.closed, tol) for c in contours)
        deviations = tuple(hausdorff(c.curve.points, p).hausdorff for c, p in zip(contours, polylines))
    return Job(loaded, contours, placement, surface, model, cell, out, sample_step, spacing, away, polylines,
               deviations)


def _run_variants(job: Job, step: Step, keep_going: bool) -> tuple[list[VariantRun], dict[str, str]]:
    """Each variant programmed, executed and coated; with ``keep_going`` the one-line error of a
    variant that cannot run is kept and the others run."""
    runs, failures = [], {}
    for entry in job.loaded.spec.variants:
        name = entry if isinstance(entry, str) else entry.name
        builtin = job.loaded.spec.builtin(entry)
        step(f"{name}: writing and reading the program")
        try:
            if builtin is not None:
                runs.append(run_variant(name, *builtin, job, step))
            else:
                runs.append(run_program_variant(entry, job, step))  # its errors name the variant
        except CoatsimError as exc:
            if not keep_going:
                raise (exc if builtin is None else exc.prefixed(name)) from None
            failures[name] = str(exc).removeprefix(f"{name}: ")
    return runs, failures


def _document(loaded: ScenarioFile, runs: list[VariantRun], contours: tuple[Segmentation, ...],
              failures: Mapping[str, str], fast: bool) -> dict:
    """The metrics document: every variant's metrics, the gates, the warnings, the contours."""
    spec = loaded.spec
    variants = {r.name: r.groups for r in runs}
    gates = evaluate_gates([g for g in spec.gates if {g.variant, *g.compared} <= set(variants)], variants)
    warnings = [{"variant": r.name, "message": event} for r in runs
                for event in (*r.execution.warnings, *r.execution.events)]
    document = assemble(as_dict(spec), variants, gates, mode="fast" if fast else "full", warnings=warnings)
    if len(contours) > 1:
        order = next((r.program.order for r in runs if isinstance(r.program, PartProgram)), tuple(range(len(contours))))
        document["contours"] = contours_section(contours, order, {r.name: r.contour_groups for r in runs
                                                                   if r.contour_groups})
    if failures:
        document.update(failed=dict(failures), passed=False)
    return document


def _write_views(loaded: ScenarioFile, cell: Cell, out: Path, runs: list[VariantRun],
                 contours: tuple[Segmentation, ...], part: Optional[PartSegmentation], document: dict, step: Step,
                 report: bool, video: bool) -> None:
    """The thickness files of every variant, the video of the reference run and report.html."""
    from coatsim.report.document import write_report

    spec = loaded.spec
    write_thickness_files(runs, out, spec.gun.standoff_mm)
    movie = None
    reference = next((r for r in runs if r.name == reference_variant(spec)), None)
    if video and reference is not None:
        from coatsim.report.data import ReportData
        from coatsim.report.video import write_video

        step("rendering the video")
        data = ReportData(loaded, tuple(contours), tuple(runs), document)
        movie = write_video(out / f"{reference.name}.mp4", data, cell)
    if report and runs:
        write_report(out / "report.html", loaded, contours, runs, document, part.notes if part is not None else (),
                     video=None if movie is None else movie.name)

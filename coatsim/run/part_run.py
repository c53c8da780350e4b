"""Run a scenario on a 3-D part: plan -> programs -> twin -> coat -> metrics, gates, report.

The part's mesh is read in its unit and placed by its pose; passes are planned on its region
(coatsim.geometry.surface, written as ``paths.json``); every built-in variant is written as a
program of those passes in the scenario's language (coatsim.path.surface_program), read back and
run on the simulated arm in a cell that holds the part (orientation, reachability, collisions);
the trajectory is sprayed onto the part's mesh with its shadows (coatsim.spray), and the variants
are measured on the region of interest they share. Stages pass typed values; the execution runs
the program text read back, as for a curve.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import CoatsimError, EmptyRegionOfInterest, InputError
from coatsim.core.fileio import write_text
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.geometry.surface import Box, Everything, Facing, PlanOptions, load_part, plan, write_surfacepaths
from coatsim.geometry.surface import SurfacePaths as Plan
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.gun_side import outward_faces
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions
from coatsim.path.language import ReadOptions
from coatsim.path.program_files import write_program
from coatsim.path.pass_fits import PassFits, fit_passes
from coatsim.path.surface_program import SurfaceOptions, build_surface_program, surface_fit_settings
from coatsim.path.surfacepaths import SurfacePass, SurfacePaths
from coatsim.report.gates import evaluate_gates
from coatsim.report.metrics import assemble, coating_group, to_json
from coatsim.report.results import RunResult, VariantRun
from coatsim.report.surface_metrics import passes_section, surface_segmentation_group
from coatsim.robot.cell import Cell
from coatsim.robot.collisions import PartMesh, with_part
from coatsim.robot.execute import execute
from coatsim.robot.kinematics import CellKinematics
from coatsim.robot.tooling import gun_tool
from coatsim.core.progress import Step, labelled, progress as progress_bar
from coatsim.run.part_spec import RegionSpec
from coatsim.run.scenario import ScenarioFile, as_dict
from coatsim.run.scenario_inputs import spray_model
from coatsim.run.variants import on_common_roi, program_files, write_thickness_files
from coatsim.spray.coat import coat
from coatsim.spray.coating_metrics import away_from_border, edge_band_width
from coatsim.spray.deposition import SprayModel
from coatsim.spray.surfaces import Surface, mesh_surface

PATHS_FILE = "paths.json"
#: the planner's parameters as the scenario names them
PLAN_KEYS = {"spacing_mm": "paths.spacing_mm", "ripple_pct": "paths.ripple_pct", "standoff_mm": "paths.standoff_mm",
             "step_direction": "paths.direction", "margin_mm": "paths.margin_mm", "edge_band_mm": "paths.edge_band_mm",
             "region": "part.region", "units": "part.units", "pose": "part.pose", "pattern": "paths.pattern",
             "order": "paths.order", "footprint_sigma_mm": "gun.footprint"}


@dataclass(frozen=True, eq=False)
class PartJob:
    """What every variant of a run on a part shares: the plan, its passes as a program's input
    (placed by the part's pose), the coating mesh, the gun, the cell with the part in it."""

    loaded: ScenarioFile
    plan: Plan
    passes: SurfacePaths
    surface: Surface
    model: SprayModel
    cell: Cell
    outdir: Path
    sample_step_mm: float
    spacing_mm: float
    away_mm: np.ndarray  # coating-mesh vertices clear of the part's border by the edge band


def region_of(spec: RegionSpec) -> Facing | Box | Everything:
    """The planner's region of the scenario's ``part.region``."""
    if spec.all:
        return Everything()
    if spec.box is not None:
        return Box(tuple(spec.box[:3]), tuple(spec.box[3:]))
    return Facing(None if spec.facing is None else tuple(spec.facing), spec.max_angle_deg)


def standoff_of(loaded: ScenarioFile) -> float:
    """The passes' stand-off: ``paths.standoff_mm``, else the gun's."""
    return loaded.spec.planned.standoff_mm or loaded.spec.gun.standoff_mm


def plan_part(loaded: ScenarioFile, model: SprayModel) -> tuple[Part, Plan]:
    """The part read in its unit and the passes planned on its region (errors name the key)."""
    spec, paths = loaded.spec.part, loaded.spec.planned
    try:
        part = load_part(loaded.resolve(spec.mesh), spec.units)
    except InputError as exc:
        raise InputError(f"{loaded.where('part', 'mesh')}: part.mesh: {exc}") from None
    options = PlanOptions(
        footprint_sigma_mm=model.footprint.sigma_mm, standoff_mm=standoff_of(loaded), pattern=paths.pattern,
        spacing_mm=paths.spacing_mm, ripple_pct=paths.ripple_pct,
        step_direction=None if paths.direction is None else tuple(paths.direction), region=region_of(spec.region),
        margin_mm=paths.margin_mm, edge_band_mm=paths.edge_band_mm, order=paths.order, pose=tuple(spec.pose))
    try:
        return part, plan(part, options)
    except CoatsimError as exc:
        raise exc.reworded(PLAN_KEYS).prefixed(loaded.where("paths")) from None


def program_input(planned: Plan, pose: Pose, source: str) -> SurfacePaths:
    """The plan as the programs read passes (the same values ``paths.json`` carries)."""
    passes = tuple(SurfacePass(p.points, p.normals, p.closed, p.lead_in, p.lead_out) for p in planned.passes)
    return SurfacePaths(source, passes, planned.standoff_mm, pose, planned.mesh.file)


def part_job(loaded: ScenarioFile, cell: Cell, out: Path, fast: bool, part: Part, planned: Plan,
             model: SprayModel) -> PartJob:
    """The coating mesh placed in the cell, the cell with the part, the numerics of the mode."""
    spec = loaded.spec
    pose = pose_from_xyzoat(tuple(float(v) for v in spec.part.pose))
    matrix = np.eye(4)
    matrix[:3, :3], matrix[:3, 3] = pose.rotation, pose.translation_mm
    spacing = spec.fast.coating_spacing_mm if fast else spec.coating.spacing_mm
    faces = outward_faces(part, region_of(spec.part.region))
    try:
        surface = mesh_surface(part.vertices_mm, faces, spacing, matrix, spec.part.mesh)
    except InputError as exc:
        raise InputError(f"{loaded.where('coating', 'spacing_mm')}: {exc}") from None
    away = away_from_border(surface, edge_band_width(model, spec.coating.edge_band_mm), spacing)
    placed = with_part(cell, PartMesh(pose.apply(part.vertices_mm), faces))
    sample = spec.fast.sample_step_mm if fast else defaults.STEP_MM
    return PartJob(loaded, planned, program_input(planned, pose, PATHS_FILE), surface, model, placed, out, sample,
                   spacing, away)


def placing(job: PartJob) -> SurfaceOptions:
    """How the scenario places and fits the passes of every variant."""
    spec = job.loaded.spec
    return SurfaceOptions(standoff_mm=job.passes.standoff_mm, pose=job.passes.pose,
                          tolerance_mm=spec.segmentation.tolerance_mm, angle_tol_deg=spec.planned.angle_tol_deg,
                          roll="follow" if spec.gun.follow_tangent else "fixed", roll_deg=spec.gun.roll_deg,
                          speed_on=spec.planned.speed_on, tool_accel_mm_s2=job.cell.tool_accel_mm_s2)


def run_part_variant(name: str, variant: str, language_name: str, job: PartJob, step: Step,
                     fitted: Optional[PassFits] = None) -> VariantRun:
    """Program, execute and coat one built-in variant; writes its program file(s) and
    ``name.trajectory.csv``. ``fitted``: the passes fitted for another variant at the same speed
    (coatsim.path.pass_fits), else they are fitted here."""
    spec, out = job.loaded.spec, job.outdir
    writer = language(language_name)
    options = ProgramOptions(variant=variant, speed_mm_s=spec.speed_of(name), accuracy_mm=spec.motion.accuracy_mm,
                             gun_signal=spec.gun.signal, tool=gun_tool(job.cell),
                             name=writer.program_name(name if writer.capabilities.named_by_file else spec.name))
    program = build_surface_program(job.passes, options, placing(job), writer, fitted)
    files = program_files(name, writer)
    written = write_program(writer, program.text, out / files[0])
    toolpath = writer.read(list(written), ReadOptions(gun_signal=spec.gun.signal, kinematics=CellKinematics(job.cell)))
    step(f"{name}: simulating the arm")
    execution = execute(toolpath, job.cell, step_mm=job.sample_step_mm)
    execution.log.write_csv(out / f"{name}.trajectory.csv")
    step(f"{name}: spraying")
    try:
        result = coat(execution.log, job.surface, job.model, roi="field", target_um=spec.gun.target_thickness_um,
                      edge_band_mm=spec.coating.edge_band_mm, band_halfwidth_mm=spec.coating.band_halfwidth_mm,
                      spacing=job.spacing_mm, away=job.away_mm)
    except EmptyRegionOfInterest as exc:
        raise EmptyRegionOfInterest(f"{job.loaded.where('part')}: {exc}; check part.pose and coating.edge_band_mm") \
            from None
    groups = {
        "segmentation": surface_segmentation_group(program.plan.paths, program.tcp_mm, spec.segmentation.tolerance_mm,
                                                   spec.segmentation.corner_deg),
        "motion": execution.metrics.as_dict(),
        "coating": coating_group(result.metrics),
    }
    return VariantRun(name, program, execution, result, groups, (), toolpath, program_file=files[0])


def part_output_names(loaded: ScenarioFile) -> list[str]:
    """The files a run on a part may write, in writing order."""
    spec = loaded.spec
    programs = []
    for entry in spec.variants:
        variant, lang = spec.builtin(entry)
        name = entry if isinstance(entry, str) else entry.name
        programs += [*program_files(name, language(lang)), f"{name}.trajectory.csv"]
    coats = [f"{v}.{kind}" for v in spec.variant_names for kind in ("thickness.ply", "thickness.glb")]
    return [PATHS_FILE, *programs, "metrics.json", *coats, "report.html"]


def plan_summary(planned: Plan) -> dict:
    """``metrics.json`` "plan": the planned passes' figures."""
    s = planned.stats
    return {"pattern": planned.pattern, "passes": s.passes, "region_area_mm2": s.region_area_mm2,
            "spacing_mm": planned.spacing_mm, "ripple_pct": planned.ripple_pct, "standoff_mm": planned.standoff_mm,
            "coverage": s.coverage, "spacing_min_mm": s.spacing_min_mm, "spacing_max_mm": s.spacing_max_mm,
            "mesh": {"file": planned.mesh.file, "vertices": planned.mesh.vertices, "faces": planned.mesh.faces},
            "notes": list(planned.notes)}


def _variants(job: PartJob, step: Step, keep_going: bool) -> tuple[list[VariantRun], dict[str, str]]:
    """Every variant run; the passes fitted once per programmed speed, as all variants need them."""
    runs, failures, fits = [], {}, {}
    for entry in job.loaded.spec.variants:
        name = entry if isinstance(entry, str) else entry.name
        speed = job.loaded.spec.speed_of(name)
        step(f"{name}: writing and reading the program")
        try:
            if speed not in fits:
                fits[speed] = fit_passes(job.passes, surface_fit_settings(job.passes, placing(job), speed))
            runs.append(run_part_variant(name, *job.loaded.spec.builtin(entry), job, step, fits[speed]))
        except CoatsimError as exc:
            if not keep_going:
                raise exc.prefixed(name) from None
            failures[name] = str(exc)
    return runs, failures


def _document(loaded: ScenarioFile, job: PartJob, runs: list[VariantRun], failures: dict[str, str], fast: bool) -> dict:
    spec = loaded.spec
    variants = {r.name: r.groups for r in runs}
    gates = evaluate_gates([g for g in spec.gates if {g.variant, *g.compared} <= set(variants)], variants)
    warnings = [{"variant": r.name, "message": event} for r in runs
                for event in (*r.program.notes, *r.execution.warnings, *r.execution.events)]
    document = assemble(as_dict(spec), variants, gates, mode="fast" if fast else "full", warnings=warnings)
    document["plan"] = plan_summary(job.plan)
    document["passes"] = passes_section([p.length_mm for p in job.plan.passes], {r.name: r.execution for r in runs})
    if failures:
        document.update(failed=dict(failures), passed=False)
    return document


def run_part(loaded: ScenarioFile, cell: Cell, out: Path, fast: bool, progress: Optional[bool], keep_going: bool,
             report: bool) -> RunResult:
    """Every stage of a scenario on a part, writing into the held folder ``out``."""
    from coatsim.report.part_document import write_part_report

    spec = loaded.spec
    show = sys.stderr.isatty() if progress is None else progress
    with progress_bar("running the scenario", 3 + 3 * len(spec.variants), show) as advance:
        step = labelled(advance)
        step("planning passes on the part")
        started = time.perf_counter()
        model = spray_model(loaded)
        part, planned = plan_part(loaded, model)
        plan_s = time.perf_counter() - started
        write_surfacepaths(out / PATHS_FILE, planned)
        step("meshing the part")
        job = part_job(loaded, cell, out, fast, part, planned, model)
        runs, failures = _variants(job, step, keep_going)
        step("metrics, gates and report")
        runs = on_common_roi(runs, spec.gun.target_thickness_um) if runs else runs
        document = _document(loaded, job, runs, failures, fast)
        write_text(out / "metrics.json", to_json(document))
        report_started = time.perf_counter()
        write_thickness_files(runs, out, job.passes.standoff_mm)
        if report and runs:
            write_part_report(out / "report.html", loaded, runs, document, planned.notes)
        report_s = time.perf_counter() - report_started
    unwritten = {f"{v}.{kind}" for v in failures for kind in ("trajectory.csv", "thickness.ply", "thickness.glb")}
    unwritten |= set() if report and runs else {"report.html"}
    written = [name for name in part_output_names(loaded) if name not in unwritten]
    return RunResult(out, tuple(runs), document, tuple(out / name for name in written), failures, plan_s, report_s)

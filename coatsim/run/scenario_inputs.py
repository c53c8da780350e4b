"""What a scenario reads: its curve or drawing (segmented), the part, the gun, the arm, the
users' programs, and the list of every input file (so that no output can overwrite one)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import numpy as np

from coatsim.core.errors import CoatsimError, InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.geometry import (
    Curve,
    builtin_curve,
    make_curve,
    read_curve_file,
    segment_curve,
)
from coatsim.geometry.cad import PartSegmentation, is_drawing, segment_drawing
from coatsim.geometry.segment import Segmentation
from coatsim.languages.registry import language_of
from coatsim.geometry.space.rotations import oat_to_matrix
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.path.language import ReadOptions
from coatsim.path.toolpath import ToolPath
from coatsim.robot.cell import Cell, load_cell
from coatsim.robot.kinematics import CellKinematics
from coatsim.run.scenario import Scenario, ScenarioFile
from coatsim.run.variant_spec import ProgramVariantSpec
from coatsim.spray.deposition import SprayModel
from coatsim.spray.efficiency import parse_efficiency_spec
from coatsim.spray.footprints import parse_footprint_spec
from coatsim.spray.surfaces import Surface, cylinder, mesh_file, plate


def segment_input(loaded: ScenarioFile, cell: Cell) -> tuple[tuple[Segmentation, ...], Optional[PartSegmentation]]:
    """The scenario's contours segmented: one for a curve; a drawing's every contour (and the
    part they make). The fitter knows the programmed speed and the arm's tool acceleration
    limit: no arc tighter than v² / a where the curve allows the speed, the rest listed as
    speed-limited."""
    spec, seg = loaded.spec.curve, loaded.spec.segmentation
    speed = {"speed_mm_s": loaded.spec.motion.speed_mm_s, "tool_accel_mm_s2": cell.tool_accel_mm_s2}
    if spec.file is None or not is_drawing(spec.file):
        return (segment_curve(load_input_curve(loaded), seg.tolerance_mm, method=seg.method,
                              corner_deg=seg.corner_deg, **speed),), None
    if seg.method != "optimal":
        raise InputError(f"{loaded.where('segmentation', 'method')}: segmentation.method: a drawing keeps its lines "
                         "and arcs exactly; 'paper' applies to point curves")
    layers = [spec.layer] if isinstance(spec.layer, str) else spec.layer
    angle = math.radians(spec.rotate_deg)
    rotation = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    try:
        part = segment_drawing(loaded.resolve(spec.file), seg.tolerance_mm, layers=layers,
                               join_tolerance_mm=spec.join_tolerance_mm, rotation=rotation, scale=spec.scale,
                               corner_deg=seg.corner_deg, **speed)
    except InputError as exc:
        raise InputError(f"{loaded.where('curve')}: curve: {exc}") from None
    return part.contours, part



def load_input_curve(loaded: ScenarioFile) -> Curve:
    """The scenario's curve, scaled and rotated as the scenario says (mm, workpiece plane)."""
    spec = loaded.spec.curve
    closed = "auto" if spec.closed == "auto" else ("yes" if spec.closed else "no")
    try:
        if spec.builtin is not None:
            curve = builtin_curve(spec.builtin, closed, **spec.params)
        else:
            curve = read_curve_file(loaded.resolve(spec.file), closed)
    except InputError as exc:
        raise InputError(f"{loaded.where('curve')}: curve: {exc}") from None
    angle = math.radians(spec.rotate_deg)
    rotation = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    try:  # checked again: a scale can push a valid curve out of range
        with np.errstate(all="ignore"):
            placed = curve.transformed(rotation, np.zeros(2), spec.scale)
            return make_curve(placed.points, curve.name, "yes" if curve.closed else "no")
    except InputError as exc:
        raise InputError(f"{loaded.where('curve', 'scale')}: curve (scaled by {spec.scale:g}): {exc}") from None



def _pose_matrix(position: list[float], oat: list[float]) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = oat_to_matrix(*oat)
    pose[:3, 3] = position
    return pose



def curve_frame(spec: Scenario) -> Pose:
    """The frame whose XY plane holds the curve: the workpiece frame, lifted to the top of a
    cylinder."""
    wp = spec.workpiece
    pose = _pose_matrix(wp.pose.position_mm, wp.pose.oat_deg)
    origin = pose[:3, 3] + (wp.radius_mm * pose[:3, 2] if wp.kind == "cylinder" else 0.0)
    return pose_from_xyzoat((*(float(v) for v in origin), *(float(v) for v in wp.pose.oat_deg)))



def build_surface(loaded: ScenarioFile, spacing_mm: float) -> Surface:
    """The coated part, meshed at ``spacing_mm``, placed in the robot base frame."""
    wp = loaded.spec.workpiece
    pose = _pose_matrix(wp.pose.position_mm, wp.pose.oat_deg)
    try:
        if wp.kind == "plate":
            return plate(wp.size_mm[0], wp.size_mm[1], spacing_mm, pose)
        if wp.kind == "cylinder":
            return cylinder(wp.radius_mm, wp.length_mm, spacing_mm, wp.axis, pose)
        return mesh_file(loaded.resolve(wp.file), spacing_mm, pose)
    except InputError as exc:
        raise InputError(f"{loaded.where('workpiece')}: workpiece: {exc}") from None



def spray_model(loaded: ScenarioFile) -> SprayModel:
    """The gun as the coating stage models it (a table footprint is read relative to the scenario)."""
    gun = loaded.spec.gun
    text, efficiency = (f"table:{loaded.resolve(t.split(':', 1)[1].strip())}" if t.strip().lower().startswith("table:")
                        else t for t in (gun.footprint, gun.efficiency))
    try:
        return SprayModel(parse_footprint_spec(text), gun.flow_mm3_s, gun.standoff_mm, parse_efficiency_spec(efficiency))
    except InputError as exc:
        raise InputError(f"{loaded.where('gun')}: gun: {exc}") from None



def load_arm(loaded: ScenarioFile, override: Optional[str | Path] = None) -> Cell:
    """The robot cell: ``override`` (a model file, relative to the working folder) if given,
    else the scenario's ``robot.model`` (the shipped cell for ``default``, otherwise an MJCF
    file relative to the scenario)."""
    if override is not None:
        try:
            return load_cell(override)
        except InputError as exc:
            raise InputError(f"--model: {exc}") from None
    model = loaded.spec.robot.model
    try:
        return load_cell(None if model == "default" else loaded.resolve(model))
    except InputError as exc:
        raise InputError(f"{loaded.where('robot', 'model')}: robot.model: {exc}") from None



def read_user_program(loaded: ScenarioFile, entry: ProgramVariantSpec, cell: Cell) -> tuple[ToolPath, str]:
    """The ToolPath of a program variant and its text (the files one after the other); a
    variant needs a sprayed path: InputError naming the outputs a program that never opens the
    gun switches."""
    files = [loaded.resolve(f) for f in entry.files]
    try:
        options = ReadOptions(gun_signal=loaded.spec.gun.signal, program=entry.main, inputs=entry.input_states or {},
                              kinematics=CellKinematics(cell), variables=entry.variables, needs_spray=True)
        toolpath = language_of(files, entry.language).read(files, options)
    except CoatsimError as exc:
        said = exc.reworded({"gun_signal": "gun.signal"})
        raise said.prefixed(f"{loaded.where('variants')}: variant {entry.name}") from None
    return toolpath, "\n".join(decode_text(read_program_file(f)) for f in files)



def user_program_suffix(loaded: ScenarioFile, entry: ProgramVariantSpec) -> str:
    """The suffix of the copy of a user's program a run writes: its language's first."""
    return language_of([loaded.resolve(f) for f in entry.files], entry.language).suffixes[0]


def input_files(loaded: ScenarioFile, model: Optional[str | Path] = None) -> list[tuple[str, Optional[Path]]]:
    """Every file the scenario reads, labelled by its key (None where the key names no file)."""
    spec = loaded.spec
    table = spec.gun.footprint.strip()
    scenario_model = None if spec.robot.model == "default" else loaded.resolve(spec.robot.model)
    robot = Path(model) if model is not None else scenario_model
    files: list[tuple[str, Optional[Path]]] = [
        ("the scenario", loaded.path),
        ("curve.file", loaded.resolve(spec.curve.file) if spec.curve is not None and spec.curve.file else None),
        ("workpiece.file", loaded.resolve(spec.workpiece.file) if spec.workpiece is not None
         and spec.workpiece.kind == "mesh" else None),
        ("part.mesh", loaded.resolve(spec.part.mesh) if spec.part is not None else None),
        ("gun.footprint", loaded.resolve(table.split(":", 1)[1].strip()) if table.lower().startswith("table:") else None),
        ("gun.efficiency", loaded.resolve(spec.gun.efficiency.split(":", 1)[1].strip())
         if spec.gun.efficiency.strip().lower().startswith("table:") else None),
        ("--model" if model is not None else "robot.model", robot),
    ]
    for entry in spec.variants:
        if isinstance(entry, ProgramVariantSpec):
            files += [(f"the program of variant {entry.name}", loaded.resolve(f)) for f in entry.files]
    return files

"""Scenario files: the strict schema of one coating job and its YAML loading.

A scenario names the curve, the fitter options, the workpiece, the robot, the gun, the motion,
the program variants to compare, the coating mesh and the CI gates. Loading is strict: an
unknown key, a wrong type or a value out of range is an InputError that names the file, the
line and the key path, e.g. ``job.yaml:12: gun.standoff_mm: Input should be greater than 0
(got -5)``.
"""

from __future__ import annotations

import difflib
import inspect
import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal, Mapping, Optional, Union

from pydantic import Field, ValidationError, field_validator, model_validator

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.builtin_curves import BUILTINS
from coatsim.geometry.cad.drawing import is_drawing
from coatsim.path.build import VARIANTS
from coatsim.report.catalogue import METRICS
from coatsim.spray.efficiency import parse_efficiency_spec
from coatsim.spray.footprints import parse_footprint_spec
from coatsim.core.yamlsource import Loc, format_validation_error, load_yaml_with_lines, where_in
from coatsim.run.part_spec import PartSpec, PathsSpec, WorkpieceSpec
from coatsim.run.spec_fields import NonNegative, Positive, Strict, Vec2
from coatsim.run.variant_spec import BuiltinVariantSpec, ProgramSpec, ProgramVariantSpec, VariantEntry, VariantLabel

BuiltinName = Literal[tuple(sorted(BUILTINS))]  # type: ignore[valid-type]
# A scenario name names the run folder (runs/NAME) and its programs: never '.', '..', '-x'.
SCENARIO_NAME = r"^[A-Za-z][A-Za-z0-9_.-]{0,63}$"



class CurveSpec(Strict):
    """Where the curve comes from (exactly one of ``builtin`` or ``file``) and how it is
    placed in the workpiece XY plane: scaled, rotated, then its bounding-box centre moved
    to ``offset_mm`` (when ``center``). A drawing (DXF, SVG) is a part: every contour on its
    ``layer``(s) is sprayed, one after the other."""

    builtin: Optional[BuiltinName] = Field(None, description="built-in curve name")
    file: Optional[str] = Field(None, description="CSV/TXT/NPY curve file or DXF/SVG drawing, relative to the scenario")
    layer: Optional[Union[str, list[str]]] = Field(None, description="drawings: the layer(s) to read "
                                                   "(default: every visible layer)")
    join_tolerance_mm: Optional[Positive] = Field(None, description="drawings: join piece ends this close "
                                                  "(default: tolerance / 100)")
    params: dict[str, Union[int, float, str]] = Field(default_factory=dict, description="built-in curve parameters")
    closed: Union[Literal["auto"], bool] = "auto"
    scale: Positive = 1.0
    rotate_deg: float = 0.0
    center: bool = True
    offset_mm: Vec2 = Field(default_factory=lambda: [0.0, 0.0])

    @model_validator(mode="after")
    def _one_source(self) -> CurveSpec:
        if (self.builtin is None) == (self.file is None):
            raise ValueError("give exactly one of 'builtin' or 'file'")
        if self.file is not None and self.params:
            raise ValueError("'params' applies to built-in curves only")
        drawing = self.file is not None and is_drawing(self.file)
        if not drawing and (self.layer is not None or self.join_tolerance_mm is not None):
            raise ValueError("'layer' and 'join_tolerance_mm' apply to drawings (DXF, SVG files) only")
        if drawing and self.closed != "auto":
            raise ValueError("'closed' applies to point curves; a drawn contour is closed where its ends meet")
        if self.builtin is not None:
            allowed = [p for p in inspect.signature(BUILTINS[self.builtin]).parameters if p != "points"]
            unknown = sorted(set(self.params) - set(allowed))
            if unknown:
                raise ValueError(
                    f"built-in {self.builtin!r} has no parameter {unknown[0]!r} (allowed: {', '.join(allowed)})"
                )
        return self


class SegmentationSpec(Strict):
    """Fitter options: tolerance in mm (guaranteed), fitting method, corner threshold."""

    tolerance_mm: Positive = defaults.TOLERANCE_MM
    method: Literal["optimal", "paper"] = "optimal"
    corner_deg: Annotated[float, Field(gt=0, lt=180)] = defaults.CORNER_DEG




class RobotSpec(Strict):
    """The arm: ``default`` (the project's MJCF arm) or an MJCF file relative to the scenario."""

    model: str = "default"


class GunSpec(Strict):
    """Spray gun: stand-off along the surface normal, footprint, deposited volume rate Q,
    the thickness the job aims for, the output signal that opens the gun, and the tool roll
    about the spray axis (fixed, or turning with the path when ``follow_tangent``)."""

    standoff_mm: Positive = defaults.STANDOFF_MM
    footprint: str = Field(defaults.FOOTPRINT, description="gaussian:sigma=S, elliptic:sx=A,sy=B, beta:radius=R,beta=B, "
                           "double-beta:a=A,b=B,beta1=P,beta2=Q or table:FILE.csv (mm; FILE relative to the scenario)")
    flow_mm3_s: Positive = defaults.FLOW_MM3_S
    target_thickness_um: Positive = 10.0
    signal: Annotated[int, Field(ge=1, le=defaults.MAX_SIGNAL)] = defaults.GUN_SIGNAL
    roll_deg: float = 0.0
    follow_tangent: bool = False
    efficiency: str = Field(defaults.EFFICIENCY, description="deposition efficiency by spray angle: none, angle (1 down to 60 deg, "
                            "the documented curve below), angle:DEG=DE,..., table:FILE.csv or cosine:n=N")

    @field_validator("footprint")
    @classmethod
    def _footprint(cls, spec: str) -> str:
        if not spec.strip().lower().startswith("table:"):
            try:
                parse_footprint_spec(spec)
            except InputError as exc:
                raise ValueError(str(exc)) from None
        return spec

    @field_validator("efficiency")
    @classmethod
    def _efficiency(cls, spec: str) -> str:
        if not spec.strip().lower().startswith("table:"):
            try:
                parse_efficiency_spec(spec)
            except InputError as exc:
                raise ValueError(str(exc)) from None
        return spec


class MotionSpec(Strict):
    """Programmed tool speed, blending accuracy, straight run-in/run-out lengths, and the
    order in which the contours of a part are sprayed."""

    speed_mm_s: Positive = defaults.SPEED_MM_S
    accuracy_mm: NonNegative = defaults.ACCURACY_MM
    lead_in_mm: NonNegative = defaults.LEAD_IN_MM
    lead_out_mm: NonNegative = defaults.LEAD_OUT_MM
    contour_order: Literal["as-drawn", "nearest"] = Field("as-drawn", description="parts: spray the contours as drawn, "
                                                          "or each next one whose start is nearest the last end")


class CoatingSpec(Strict):
    """Coating mesh spacing and the region of interest the thickness metrics cover: the
    sprayed track, ``band_halfwidth_mm`` to each side of it (default 2 sigma of the
    footprint), without ``edge_band_mm`` along the part border (default 3 sigma)."""

    spacing_mm: Positive = 1.5
    band_halfwidth_mm: Optional[Positive] = None
    edge_band_mm: Optional[NonNegative] = None


class FastSpec(Strict):
    """What ``--fast`` changes (for CI): coarser coating mesh and coarser path sampling."""

    coating_spacing_mm: Positive = 3.0
    sample_step_mm: Positive = 1.0


class GateSpec(Strict):
    """A pass/fail check on one metric of one variant: against a ``threshold``, or against
    ``factor`` times the same metric of the ``compare_to`` variant — or of each of a list of
    variants, i.e. of the best of them (``compare_to: [polyline-stop, polyline-blend]``)."""

    metric: Annotated[str, Field(pattern=r"^[a-z_]+\.[a-z0-9_]+$", description="group.name, e.g. coating.thickness_cv")]
    variant: VariantLabel = "polysegment"
    op: Literal["<", "<=", ">", ">=", "=="]
    threshold: Optional[float] = None
    compare_to: Optional[Union[VariantLabel, Annotated[list[VariantLabel], Field(min_length=1)]]] = None
    factor: Positive = 1.0

    @field_validator("compare_to", mode="before")
    @classmethod
    def _some_variant(cls, value: Any) -> Any:
        if isinstance(value, list) and not value:
            raise ValueError("expected a variant or a list of at least one variant, got []")
        return value

    @property
    def compared(self) -> tuple[str, ...]:
        """The compared variants (none for a threshold gate)."""
        if self.compare_to is None:
            return ()
        return (self.compare_to,) if isinstance(self.compare_to, str) else tuple(self.compare_to)

    @model_validator(mode="after")
    def _one_reference(self) -> GateSpec:
        if (self.threshold is None) == (self.compare_to is None):
            raise ValueError("give exactly one of 'threshold' or 'compare_to'")
        if self.variant in self.compared:
            raise ValueError(f"'compare_to' must name other variants than {self.variant!r}")
        if len(set(self.compared)) != len(self.compared):
            raise ValueError("'compare_to' lists a variant twice")
        if self.threshold is not None and self.factor != 1.0:
            raise ValueError("'factor' applies only with 'compare_to'")
        return self


class Scenario(Strict):
    """One coating job, as written in a scenario YAML file."""

    name: Annotated[str, Field(pattern=SCENARIO_NAME, description="a file stem: names the run folder and its programs")]
    description: str = ""
    curve: Optional[CurveSpec] = Field(None, description="the curve; without it, the sprayed path of the first "
                                       "program variant")
    segmentation: SegmentationSpec = Field(default_factory=SegmentationSpec)
    workpiece: Optional[WorkpieceSpec] = Field(None, description="the plate, cylinder or mesh a curve is sprayed on "
                                               "(or give a 'part')")
    part: Optional[PartSpec] = Field(None, description="a 3-D part whose passes are planned on its mesh")
    paths: Optional[PathsSpec] = Field(None, description="with a 'part': the passes planned on it")
    robot: RobotSpec = Field(default_factory=RobotSpec)
    gun: GunSpec = Field(default_factory=GunSpec)
    motion: MotionSpec = Field(default_factory=MotionSpec)
    variants: Annotated[list[VariantEntry], Field(min_length=1)] = Field(default_factory=lambda: list(VARIANTS))
    program: ProgramSpec = Field(default_factory=ProgramSpec)
    coating: CoatingSpec = Field(default_factory=CoatingSpec)
    fast: FastSpec = Field(default_factory=FastSpec)
    gates: list[GateSpec] = Field(default_factory=list)

    @field_validator("name", mode="before")
    @classmethod
    def _file_stem(cls, name: Any) -> Any:
        if isinstance(name, str) and not re.match(SCENARIO_NAME, name):
            raise ValueError(f"{name!r} is not a safe file stem: a letter, then letters, digits, '_', '-' or '.' "
                             "(at most 64 characters), e.g. 'paper_spiral'")
        return name

    @field_validator("variants")
    @classmethod
    def _unique(cls, variants: list) -> list:
        names = [v if isinstance(v, str) else v.name for v in variants]
        twice = [v for i, v in enumerate(names) if v in names[:i]]
        if twice:
            raise ValueError(f"variant {twice[0]!r} is listed twice")
        return variants

    @model_validator(mode="after")
    def _curve_or_program(self) -> Scenario:
        if (self.workpiece is None) == (self.part is None):
            raise ValueError("give exactly one of 'workpiece' (a curve sprayed on a plate, cylinder or mesh) or "
                             "'part' (passes planned on a 3-D part)")
        if self.part is None:
            if self.paths is not None:
                raise ValueError("'paths' plans passes on a 'part'; give 'part: {mesh: FILE}'")
        elif self.curve is not None or self.programs:
            raise ValueError("a 'part' is sprayed along the passes planned on it ('paths'); a curve or a user's "
                             "program over a mesh is 'workpiece: {kind: mesh, file: ...}'")
        else:
            return self
        if self.curve is None and not self.programs:
            raise ValueError("give a 'curve', or a program variant ({name: ..., program: FILE.as}) whose sprayed "
                             "path is the curve")
        return self

    @property
    def planned(self) -> PathsSpec:
        """The planning options of a part (the defaults when ``paths`` is not given)."""
        return self.paths if self.paths is not None else PathsSpec()

    @property
    def variant_names(self) -> list[str]:
        return [v if isinstance(v, str) else v.name for v in self.variants]

    @property
    def programs(self) -> list[ProgramVariantSpec]:
        """The program variants, in order."""
        return [v for v in self.variants if isinstance(v, ProgramVariantSpec)]

    def speed_of(self, name: str) -> float:
        """The programmed speed (mm/s) of the variant ``name``: its own, else ``motion.speed_mm_s``."""
        own = [v.speed_mm_s for v in self.variants if isinstance(v, BuiltinVariantSpec) and v.name == name]
        return own[0] if own and own[0] is not None else self.motion.speed_mm_s

    def builtin(self, entry: Any) -> tuple[str, str] | None:
        """(variant, language) of a built-in variant entry; None for a user's program."""
        if isinstance(entry, str):
            return entry, self.program.language
        if isinstance(entry, BuiltinVariantSpec):
            return entry.variant, entry.language or self.program.language
        return None


@dataclass(frozen=True)
class ScenarioFile:
    """A validated scenario with its source file and the line of every key path."""

    spec: Scenario
    path: Path
    lines: Mapping[Loc, int]

    def where(self, *loc: str | int) -> str:
        """``file:line`` of the deepest key path prefix of ``loc`` that the file spells out."""
        return where_in(self.path, self.lines, loc)

    def resolve(self, relative: str) -> Path:
        """A file named in the scenario, relative to the scenario's folder."""
        p = Path(relative).expanduser()
        return p if p.is_absolute() else self.path.parent / p


def check_references(spec: Scenario, where: ScenarioFile) -> None:
    """Gates may only name variants the scenario runs."""
    for i, gate in enumerate(spec.gates):
        for key, names in (("variant", (gate.variant,)), ("compare_to", gate.compared)):
            for name in names:
                if name not in spec.variant_names:
                    raise InputError(
                        f"{where.where('gates', i, key)}: gates[{i}].{key}: variant {name!r} is not run "
                        f"(add it to 'variants': {', '.join(spec.variant_names)})"
                    )


def check_gate_metrics(loaded: ScenarioFile) -> None:
    """Every gate names a metric of the catalogue (checked before anything runs)."""
    for i, gate in enumerate(loaded.spec.gates):
        if gate.metric not in METRICS:
            close = difflib.get_close_matches(gate.metric, list(METRICS), n=1)
            group = [m for m in METRICS if m.split(".")[0] == gate.metric.split(".")[0]]
            hint = f"did you mean {close[0]!r}?" if close else f"known: {', '.join(group or METRICS)}"
            raise InputError(f"{loaded.where('gates', i, 'metric')}: gates[{i}].metric: unknown metric {gate.metric!r}; {hint}")


def load_scenario(path: str | Path) -> ScenarioFile:
    """Read and validate a scenario YAML file; any defect is an InputError with its line."""
    path = Path(path)
    data, lines = load_yaml_with_lines(path)
    if not isinstance(data, dict):
        raise InputError(f"{path}:1: a scenario is a mapping of keys (name, curve, workpiece, ...)")
    try:
        spec = Scenario.model_validate(data)
    except ValidationError as exc:
        raise InputError(format_validation_error(exc, path, data, lines, Scenario)) from None
    loaded = ScenarioFile(spec, path, lines)
    check_references(spec, loaded)
    return loaded


def json_schema() -> str:
    """The JSON Schema of scenario files (for editor completion), as indented JSON text."""
    schema = Scenario.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "coatsim scenario"
    return json.dumps(schema, indent=2, sort_keys=True) + "\n"


def as_dict(spec: Scenario) -> dict[str, Any]:
    """Plain JSON-ready dict of a scenario (for metrics.json and the report)."""
    return spec.model_dump(mode="json")

"""Scenario keys of the part a job sprays: the plate, cylinder or mesh under a curve (its
pose in the robot base frame), and a 3-D part with the region of it coated and the passes
planned on it."""

from __future__ import annotations

from typing import Annotated, Literal, Optional, Union

from pydantic import Field, model_validator

from coatsim.core import defaults
from coatsim.run.spec_fields import NonNegative, Positive, Strict, Vec3, Vec6


class PoseSpec(Strict):
    """Workpiece frame in the robot base frame, as AS writes a pose: origin x, y, z (mm) and
    O-A-T Euler angles (deg, z-y'-z''). The curve lies in the frame's XY plane and the
    sprayed side faces the frame's +z axis."""

    position_mm: Vec3 = Field(default_factory=lambda: list(defaults.WORKPIECE_FRAME[:3]))
    oat_deg: Vec3 = Field(default_factory=lambda: list(defaults.WORKPIECE_FRAME[3:]))


class PlateSpec(Strict):
    """A flat rectangular plate centred on the workpiece origin, sprayed side +z."""

    kind: Literal["plate"]
    size_mm: Annotated[list[Positive], Field(min_length=2, max_length=2)]
    pose: PoseSpec = Field(default_factory=PoseSpec)


class CylinderSpec(Strict):
    """The outside of a cylinder centred on the workpiece origin, its axis along the frame's
    ``axis``; the curve lies in the plane tangent to the cylinder at its top (frame +z)."""

    kind: Literal["cylinder"]
    radius_mm: Positive
    length_mm: Positive
    axis: Literal["x", "y"] = "x"
    pose: PoseSpec = Field(default_factory=PoseSpec)


class MeshSpec(Strict):
    """A mesh file (STL/PLY/OBJ, mm), relative to the scenario."""

    kind: Literal["mesh"]
    file: str
    pose: PoseSpec = Field(default_factory=PoseSpec)


WorkpieceSpec = Annotated[Union[PlateSpec, CylinderSpec, MeshSpec], Field(discriminator="kind")]


class RegionSpec(Strict):
    """Which faces of the part are coated, in the part's own frame: those whose outward normal
    lies within ``max_angle_deg`` of ``facing`` (default: the part's thinnest axis on the side
    its normals face), those whose centre is inside ``box`` [xmin, ymin, zmin, xmax, ymax, zmax]
    (mm), or ``all``; facing and box keep only the faces the gun sees."""

    facing: Optional[Vec3] = Field(None, description="the gun's side, a direction in the part's frame")
    max_angle_deg: Annotated[float, Field(gt=0, lt=180)] = defaults.PLAN_FACING_DEG
    box: Optional[Vec6] = Field(None, description="xmin, ymin, zmin, xmax, ymax, zmax (mm, part frame)")
    all: bool = False

    @model_validator(mode="after")
    def _one_kind(self) -> RegionSpec:
        if (self.facing is not None) + (self.box is not None) + self.all > 1:
            raise ValueError("give at most one of 'facing', 'box' or 'all: true'")
        if "max_angle_deg" in self.model_fields_set and (self.box is not None or self.all):
            raise ValueError("'max_angle_deg' applies to a facing region")
        if self.box is not None and not all(lo < hi for lo, hi in zip(self.box[:3], self.box[3:])):
            raise ValueError("'box' is xmin, ymin, zmin, xmax, ymax, zmax with each min below its max")
        return self


class PartSpec(Strict):
    """A 3-D part: its mesh file (STL, PLY, OBJ, OFF, GLB; relative to the scenario), the unit
    the file is in, its pose in the robot base frame [x, y, z (mm), O, A, T (deg)] and the
    region of it that is coated."""

    mesh: str
    units: Literal["mm", "cm", "m", "in", "auto"] = defaults.PLAN_UNITS
    pose: Vec6 = Field(default_factory=lambda: list(defaults.WORKPIECE_FRAME))
    region: RegionSpec = Field(default_factory=RegionSpec)


class PathsSpec(Strict):
    """The passes planned on the part (``coatsim plan``): the pattern, the spacing along the
    surface (``spacing_mm``, or the largest that keeps the overlap ``ripple_pct``; default two
    standard deviations of the footprint), the stand-off (default the gun's), the raster's step
    ``direction`` (part frame), the lead past the region's edge, the band kept free along its
    border, the spraying order; then how each pass becomes a program: the spray axis within
    ``angle_tol_deg`` of the normal, and where the programmed speed holds (``trace``: the spray
    spot on the surface, so the coat does not thin where the tool swings round a bend)."""

    pattern: Literal["raster", "geodesic", "boundary"] = defaults.PLAN_PATTERN
    spacing_mm: Optional[Positive] = None
    ripple_pct: Optional[Annotated[float, Field(gt=0, lt=100)]] = None
    standoff_mm: Optional[Positive] = Field(None, description="default: gun.standoff_mm")
    direction: Optional[Vec3] = Field(None, description="raster: the planes' normal, from one pass to the next")
    margin_mm: Optional[NonNegative] = Field(None, description="lead past the region's edge (default 3 sigma)")
    edge_band_mm: NonNegative = defaults.PLAN_EDGE_BAND_MM
    order: Literal["serpentine", "oneway"] = defaults.PLAN_ORDER
    angle_tol_deg: Annotated[float, Field(gt=0, lt=90)] = defaults.ANGLE_TOL_DEG
    speed_on: Literal["tcp", "trace"] = defaults.SCENARIO_SPEED_ON

    @model_validator(mode="after")
    def _one_spacing(self) -> PathsSpec:
        if self.spacing_mm is not None and self.ripple_pct is not None:
            raise ValueError("give at most one of 'spacing_mm' or 'ripple_pct'")
        if self.direction is not None and self.pattern != "raster":
            raise ValueError("'direction' applies to the raster pattern")
        return self

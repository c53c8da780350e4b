"""Which faces are coated: facing a direction, inside a box, or all; seen from the gun's side.

The gun comes from one side, ``toward`` (a unit vector from the part to the gun). By default
it is the part's thinnest principal axis, on the side the part's normals face (an open scan) or
with its largest coordinate positive (a closed part: +Z for a part lying in the XY plane).

- ``Facing(direction, max_angle_deg)``: faces whose outward normal lies within the angle of the
  direction (which is then the gun's side); face normals, not smoothed ones, so that a CAD
  part's sharp edge bounds the region exactly;
- ``Box(low_mm, high_mm)``: faces whose centre lies in the box; the gun's side is then the mean
  normal of those faces where they mostly face one way (a box round a side face: that side);
- ``Everything()``: every face; on a closed part, passes then run round it.

Facing and box regions keep only faces the gun sees: a ray from the face toward the gun's side
that hits the part removes the face, so a closed part is cut on the side the gun sees and never
through both skins.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Union

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.surface.features import sharp_at_scale

BOX_FACING = 0.5  # a box's faces face one way when their mean normal is this long against their area

@dataclass(frozen=True)
class Facing:
    """Faces whose outward normal lies within ``max_angle_deg`` of ``direction`` (part frame;
    None: the default gun side)."""

    direction: tuple[float, float, float] | None = None
    max_angle_deg: float = defaults.PLAN_FACING_DEG


@dataclass(frozen=True)
class Box:
    """Faces whose centre lies in the axis-aligned box ``low_mm`` .. ``high_mm`` (part frame)."""

    low_mm: tuple[float, float, float]
    high_mm: tuple[float, float, float]

    def holds(self, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
        """The faces (m,) bool whose centre lies in the box."""
        centres = vertices[faces].mean(axis=1)
        low, high = np.asarray(self.low_mm, dtype=float), np.asarray(self.high_mm, dtype=float)
        return np.all((centres >= low) & (centres <= high), axis=1)


@dataclass(frozen=True)
class Everything:
    """Every face of the part."""


RegionSpec = Union[Facing, Box, Everything]


def unit_vector(vector: tuple[float, float, float] | np.ndarray, what: str, parameter: str) -> np.ndarray:
    """``vector`` normalised; an InputError naming ``what`` (the option ``parameter``) if it is
    not a finite non-zero 3-vector."""
    v = np.asarray(vector, dtype=float).ravel()
    norm = float(np.linalg.norm(v)) if v.shape == (3,) else math.nan
    if not (math.isfinite(norm) and norm > 1e-12):
        found = ", ".join(f"{x:g}" for x in np.ravel(np.asarray(vector, dtype=float)))
        raise InputError(f"{what} must be three finite numbers, not all zero, found {found}", parameters=(parameter,))
    return v / norm


def principal_axes(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Rows: the principal axes of the surface (its area spread uniformly over each triangle, so
    the result does not depend on how the surface is triangulated), largest spread first (3, 3)."""
    corners = vertices[faces]
    area = 0.5 * np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    total = corners.sum(axis=1)
    mean = (area[:, None] * total).sum(axis=0) / (3 * area.sum())
    # E[x x^T] over a triangle = (sum_i v_i v_i^T + (sum_i v_i)(sum_i v_i)^T) / 12
    second = (np.einsum("f,fij,fik->jk", area, corners, corners) + np.einsum("f,fj,fk->jk", area, total, total))
    cov = second / (12 * area.sum()) - np.outer(mean, mean)
    _, vectors = np.linalg.eigh(cov)
    return vectors[:, ::-1].T


def sign_fixed(axis: np.ndarray) -> np.ndarray:
    """``axis`` with its largest-magnitude coordinate positive (a deterministic sign)."""
    return axis if axis[np.argmax(np.abs(axis))] > 0 else -axis


def default_toward(vertices: np.ndarray, faces: np.ndarray, closed: np.ndarray) -> np.ndarray:
    """The default gun side: the thinnest principal axis, signed by the open faces' mean
    normal when they have one, else with its largest coordinate positive."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(cross, axis=1)
    axis = sign_fixed(principal_axes(vertices, faces)[2])
    open_normal = cross[~closed].sum(axis=0)
    lean = float(open_normal @ axis)
    if abs(lean) > 1e-3 * float(area[~closed].sum()) * 2:
        return axis if lean > 0 else -axis
    return axis


def box_toward(vertices: np.ndarray, faces: np.ndarray, box: Box) -> np.ndarray | None:
    """The gun's side for a box region: the area-weighted mean outward normal of the faces whose
    centre lies in the box, where they mostly face one way (its length at least BOX_FACING of
    their area: a box round one side of a part); None where they face every way (a box round
    the whole part), and the part's default side holds."""
    inside = box.holds(vertices, faces)
    a, b, c = (vertices[faces[inside, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    total = cross.sum(axis=0)
    length = float(np.linalg.norm(total))
    if not inside.any() or length < BOX_FACING * float(np.linalg.norm(cross, axis=1).sum()):
        return None
    return total / length


def select_faces(vertices: np.ndarray, faces: np.ndarray, selection_normals: np.ndarray, spec: RegionSpec,
                 toward: np.ndarray, clearance_mm: float) -> np.ndarray:
    """The coated faces (m,) bool; ``selection_normals`` are unit outward face normals; what
    hides a face must stand more than ``clearance_mm`` above it (noise on a scan does not)."""
    if isinstance(spec, Everything):
        return np.ones(len(faces), dtype=bool)
    if isinstance(spec, Facing):
        mask = selection_normals @ toward >= math.cos(math.radians(spec.max_angle_deg)) - 1e-12
    else:
        mask = spec.holds(vertices, faces)
    return mask & _seen(vertices, faces, selection_normals, mask, toward, clearance_mm)


def _seen(vertices: np.ndarray, faces: np.ndarray, normals: np.ndarray, mask: np.ndarray,
          toward: np.ndarray, clearance_mm: float) -> np.ndarray:
    """Faces (among ``mask``) that face the gun's side and that a ray toward it leaves freely."""
    import trimesh

    seen = np.zeros(len(faces), dtype=bool)
    candidates = np.flatnonzero(mask & (normals @ toward > 0))
    if not len(candidates):
        return seen
    extent = float(np.ptp(vertices, axis=0).max())
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    origins = (vertices[faces[candidates]].mean(axis=1) + 1e-6 * extent * normals[candidates]
               + clearance_mm * toward)
    hit = mesh.ray.intersects_any(origins, np.tile(toward, (len(candidates), 1)))
    seen[candidates[~np.asarray(hit, dtype=bool)]] = True
    return seen


def check_region(spec: RegionSpec) -> None:
    """An InputError for a region that cannot select anything."""
    if isinstance(spec, Facing):
        if spec.direction is not None:
            unit_vector(spec.direction, "region facing direction", "region")
        if not (math.isfinite(spec.max_angle_deg) and 0 < spec.max_angle_deg <= 180):
            raise InputError(f"region facing angle must be in (0, 180] degrees, found {spec.max_angle_deg:g}",
                             parameters=("region",))
    elif isinstance(spec, Box):
        low, high = np.asarray(spec.low_mm, dtype=float), np.asarray(spec.high_mm, dtype=float)
        if low.shape != (3,) or high.shape != (3,) or not np.all(np.isfinite(low) & np.isfinite(high)):
            raise InputError("region box must be six finite numbers xmin,ymin,zmin,xmax,ymax,zmax (mm)",
                             parameters=("region",))
        if not np.all(high > low):
            shown = ", ".join(f"{v:g}" for v in (*low, *high))
            raise InputError(f"region box must have max > min on every axis (xmin,ymin,zmin,xmax,ymax,zmax), "
                             f"found {shown}",
                             parameters=("region",))


def smoothing_ring(vertices: np.ndarray, faces: np.ndarray, mask: np.ndarray, reach_mm: float,
                   scale_mm: float) -> np.ndarray:
    """Faces outside the region within ``reach_mm`` of it, reached without crossing an edge
    sharp at the smoothing length ``scale_mm`` (features.sharp_at_scale): normals are smoothed
    over them too, so that where the surface runs on past the region's border the normals at the
    border are not biased inward."""
    from scipy.spatial import cKDTree

    pairs, sharp = sharp_at_scale(vertices, faces, scale_mm)
    pairs = pairs[~sharp]
    centres = vertices[faces].mean(axis=1)
    near = cKDTree(centres[mask]).query(centres, distance_upper_bound=reach_mm)[0] <= reach_mm
    grown = mask.copy()
    while True:
        touch = np.zeros(len(faces), dtype=bool)
        touch[pairs[grown[pairs[:, 0]], 1]] = True
        touch[pairs[grown[pairs[:, 1]], 0]] = True
        new = touch & near & ~grown
        if not new.any():
            return grown & ~mask
        grown |= new

"""An independent check of a plan against its part, run before a plan is returned.

It uses only the part as read (not the refined and cut meshes the planner worked on) and the
plan's passes: every point must lie on the part's surface, every normal must be a unit vector
within a few degrees of the cone of the part's face normals around it (the faces whose bounding
boxes reach within two smoothing lengths per axis, where the smoothing draws nearly all its weight; a
sharp edge widens the cone, a flat face narrows it to its normal), and on a closed part every
normal must point out of it.
"""

from __future__ import annotations

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.geometry.surface.boxes import TriangleBoxes
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import face_normals
from coatsim.geometry.surface.surfacepaths import SurfacePaths

#: a point farther than this fraction of the part's extent from its surface is off the mesh
ON_MESH_FRACTION = 1e-6
#: the cone holds the faces within this many smoothing lengths
CONE_SMOOTHING_LENGTHS = 2.0
#: the cone's faces stand for cells of this fraction of its radius (verify._representatives)
CONE_CELLS = 6.0
#: points checked at once (bounds the memory of the point-face pairs)
VERIFY_CHUNK = 2048
#: a normal may leave the cone of the face normals around it by this much
NORMAL_TOLERANCE_DEG = 5.0


class PlanCheckFailed(ExecutionError):
    """A plan failed its independent check (exit 3)."""


def _where(paths: SurfacePaths, flat_index: int) -> str:
    sizes = np.cumsum([len(p.points) for p in paths.passes])
    k = int(np.searchsorted(sizes, flat_index, side="right"))
    start = int(sizes[k - 1]) if k else 0
    return f"pass {k + 1} point {flat_index - start + 1}"


def _fail(paths: SurfacePaths, index: int, problem: str) -> None:
    raise PlanCheckFailed(f"plan check: {_where(paths, index)} {problem}; the mesh defeats the planner here: "
                          "repair the mesh (holes, folds) or report it with the mesh")


def verify(part: Part, paths: SurfacePaths) -> None:
    """Raise PlanCheckFailed naming the first point that fails (see the module docstring)."""
    import trimesh

    if not paths.passes:
        return
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    length = np.linalg.norm(normals, axis=1)
    bad = np.flatnonzero(~(np.abs(length - 1) <= 1e-6))
    if len(bad):
        _fail(paths, int(bad[0]), f"has a normal of length {length[bad[0]]:.6g}")
    tolerance = ON_MESH_FRACTION * part.extent_mm
    owner, _, distance = TriangleBoxes(part.vertices_mm, part.faces).touching(points, tolerance)
    nearest = np.full(len(points), np.inf)
    np.minimum.at(nearest, owner, distance)
    off = np.flatnonzero(~(nearest <= tolerance))
    if len(off):
        _fail(paths, int(off[0]), "lies off the part's surface")
    radius = CONE_SMOOTHING_LENGTHS * paths.stats.normal_smoothing_mm
    chosen, face_n, area = _representatives(part, radius / CONE_CELLS)
    cone = TriangleBoxes(part.vertices_mm, part.faces[chosen])
    for chunk in np.array_split(np.arange(len(points)), max(1, len(points) // VERIFY_CHUNK)):
        owner, face = cone.near(points[chunk], radius)
        excess = _normal_excess_deg(normals[chunk], owner, face_n[face], area[face])
        worst = int(np.argmax(excess))
        if excess[worst] > NORMAL_TOLERANCE_DEG:
            _fail(paths, int(chunk[worst]), f"has a normal {excess[worst]:.3g} deg outside the faces around it")
    mesh = trimesh.Trimesh(part.vertices_mm, part.faces, process=False)
    if mesh.is_watertight:
        inward = np.flatnonzero(mesh.contains(points + 1e-4 * part.extent_mm * normals))
        if len(inward):
            _fail(paths, int(inward[0]), "has a normal pointing into the part")


def _representatives(part: Part, cell_mm: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One face for each cell of a grid and each direction (to about 20 deg) of the faces whose
    centres lie in it: (their ids, unit normals, the area of all the faces they stand for). The
    cone test then sees every direction near a point without visiting every face of a fine scan."""
    normals, area = face_normals(part.vertices_mm, part.faces)
    centres = part.vertices_mm[part.faces].mean(axis=1)
    key = np.column_stack([np.floor((centres - centres.min(axis=0)) / cell_mm), np.round(normals * 3)]).astype(np.int64)
    _, first, group = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return first, normals[first], np.bincount(group.ravel(), weights=area, minlength=len(first))


def _normal_excess_deg(normals: np.ndarray, owner: np.ndarray, near: np.ndarray, area: np.ndarray) -> np.ndarray:
    """By how much each normal leaves the cone of the face normals near it (deg): ``near``
    (k, 3) with their ``area`` for the pairs (``owner`` ascending, every point at least once);
    the cone is centred on their area-weighted mean, face normals taken on the normal's side."""
    aligned = near * np.where(np.einsum("ij,ij->i", near, normals[owner]) < 0, -1.0, 1.0)[:, None]
    starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
    mean = np.add.reduceat(aligned * area[:, None], starts, axis=0)
    mean /= np.maximum(np.linalg.norm(mean, axis=1), 1e-300)[:, None]
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(owner)]))
    cos = np.clip(np.einsum("ij,ij->i", aligned, mean[group]), -1, 1)
    spread = np.arccos(np.minimum.reduceat(cos, starts))
    return np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals, mean), -1, 1)) - spread)

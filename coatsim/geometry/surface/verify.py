"""An independent check of a plan against its part, run before a plan is returned.

It uses only the part as read (not the refined and cut meshes the planner worked on) and the
plan's passes: every point must lie on the part's surface, every normal must be a unit vector
within a few degrees of the cone of the part's face normals around it (the faces whose bounding
boxes reach within three smoothing lengths, where the smoothing draws nearly all its weight; a
sharp edge widens the cone, a flat face narrows it to its normal), and on a closed part every
normal must point out of it.
"""

from __future__ import annotations

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import face_normals
from coatsim.geometry.surface.surfacepaths import SurfacePaths

#: a point farther than this fraction of the part's extent from its surface is off the mesh
ON_MESH_FRACTION = 1e-6
#: the cone holds the faces within this many smoothing lengths
CONE_SMOOTHING_LENGTHS = 3.0
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
    tree = _box_tree(part)
    tolerance = ON_MESH_FRACTION * part.extent_mm
    owner, face = _boxes_near(tree, points, tolerance)
    triangles = part.vertices_mm[part.faces[face]]
    distance = np.linalg.norm(trimesh.triangles.closest_point(triangles, points[owner]) - points[owner], axis=1)
    nearest = np.full(len(points), np.inf)
    np.minimum.at(nearest, owner, distance)
    off = np.flatnonzero(~(nearest <= tolerance))
    if len(off):
        _fail(paths, int(off[0]), "lies off the part's surface")
    owner, face = _boxes_near(tree, points, CONE_SMOOTHING_LENGTHS * paths.stats.normal_smoothing_mm)
    excess = _normal_excess_deg(part, normals, owner, face)
    worst = int(np.argmax(excess))
    if excess[worst] > NORMAL_TOLERANCE_DEG:
        _fail(paths, worst, f"has a normal {excess[worst]:.3g} deg outside the faces around it")
    mesh = trimesh.Trimesh(part.vertices_mm, part.faces, process=False)
    if mesh.is_watertight:
        inward = np.flatnonzero(mesh.contains(points + 1e-4 * part.extent_mm * normals))
        if len(inward):
            _fail(paths, int(inward[0]), "has a normal pointing into the part")


def _box_tree(part: Part):
    """An R-tree of the part's triangles' bounding boxes."""
    from rtree import index

    triangles = part.vertices_mm[part.faces]
    properties = index.Property()
    properties.dimension = 3
    return index.Index((np.arange(len(triangles)), triangles.min(axis=1), triangles.max(axis=1)),
                       properties=properties)


def _boxes_near(tree, points: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (point, face) whose bounding box reaches within ``radius`` of the point (per axis)."""
    face, counts = tree.intersection_v(points - radius, points + radius)
    owner = np.repeat(np.arange(len(points)), np.asarray(counts, dtype=np.int64))
    return owner, np.asarray(face, dtype=np.int64)


def _normal_excess_deg(part: Part, normals: np.ndarray, owner: np.ndarray, face: np.ndarray) -> np.ndarray:
    """By how much each normal leaves the cone of the face normals near it (deg; the cone is
    centred on their area-weighted mean, face normals taken on the normal's side)."""
    fn, area = face_normals(part.vertices_mm, part.faces)
    aligned = fn[face] * np.where(np.einsum("ij,ij->i", fn[face], normals[owner]) < 0, -1.0, 1.0)[:, None]
    mean = np.zeros_like(normals)
    np.add.at(mean, owner, aligned * area[face][:, None])
    mean /= np.maximum(np.linalg.norm(mean, axis=1), 1e-300)[:, None]
    spread = np.zeros(len(normals))
    np.maximum.at(spread, owner, np.arccos(np.clip(np.einsum("ij,ij->i", aligned, mean[owner]), -1, 1)))
    return np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals, mean), -1, 1)) - spread)

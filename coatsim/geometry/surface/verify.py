"""An independent check of a plan against its part, run before a plan is returned.

It uses only the part as read (not the refined and cut meshes the planner worked on) and the
plan's passes: every point must lie on the part's surface, every normal must be a unit vector
within a few degrees of the cone of the part's face normals around it (the faces within the
smoothing length; a sharp edge widens the cone, a flat face narrows it to its normal), and on a
closed part every normal must point out of it.
"""

from __future__ import annotations

import numpy as np

from coatsim.errors import ExecutionError
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import face_normals
from coatsim.geometry.surface.surfacepaths import SurfacePaths

#: a point farther than this fraction of the part's extent from its surface is off the mesh
ON_MESH_FRACTION = 1e-6
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
    from scipy.spatial import cKDTree

    if not paths.passes:
        return
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    mesh = trimesh.Trimesh(part.vertices_mm, part.faces, process=False)
    _, distance, nearest_face = trimesh.proximity.closest_point(mesh, points)
    off = np.flatnonzero(distance > ON_MESH_FRACTION * part.extent_mm)
    if len(off):
        _fail(paths, int(off[0]), f"lies {distance[off[0]]:.3g} mm off the part's surface")
    length = np.linalg.norm(normals, axis=1)
    bad = np.flatnonzero(np.abs(length - 1) > 1e-6)
    if len(bad):
        _fail(paths, int(bad[0]), f"has a normal of length {length[bad[0]]:.6g}")
    fn, area = face_normals(part.vertices_mm, part.faces)
    centres = part.vertices_mm[part.faces].mean(axis=1)
    near = cKDTree(centres).query_ball_point(points, paths.stats.normal_smoothing_mm, return_sorted=False)
    counts = np.array([len(n) for n in near]) + 1
    owner = np.repeat(np.arange(len(points)), counts)
    face = np.concatenate([np.r_[f, n] for f, n in zip(nearest_face, near)]).astype(np.int64)
    aligned = fn[face] * np.sign(np.einsum("ij,ij->i", fn[face], normals[owner]) + 1e-300)[:, None]
    mean = np.zeros_like(points)
    np.add.at(mean, owner, aligned * area[face][:, None])
    mean /= np.maximum(np.linalg.norm(mean, axis=1), 1e-300)[:, None]
    spread = np.zeros(len(points))
    np.maximum.at(spread, owner, np.arccos(np.clip(np.einsum("ij,ij->i", aligned, mean[owner]), -1, 1)))
    excess = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals, mean), -1, 1)) - spread)
    worst = int(np.argmax(excess))
    if excess[worst] > NORMAL_TOLERANCE_DEG:
        _fail(paths, worst, f"has a normal {excess[worst]:.3g} deg outside the faces around it")
    if mesh.is_watertight:
        probe = points + 1e-4 * part.extent_mm * normals
        inward = np.flatnonzero(mesh.contains(probe))
        if len(inward):
            _fail(paths, int(inward[0]), "has a normal pointing into the part")

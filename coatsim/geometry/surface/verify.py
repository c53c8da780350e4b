"""An independent check of a plan against its part, run before a plan is returned.

It uses only the part as read (not the refined and cut meshes the planner worked on) and the
plan's passes: every point must lie on the part's surface (its facets, or the smooth surface
their corner normals describe, which the planner lifts its points onto: within the bound on
that lift, normals.Facets.largest_lift_mm), every normal must be a unit vector
within a few degrees of the cone of the part's face normals near it, and on a closed part every
normal must point out of it. The faces near a point are those of its own feature region (the
faces joined to the ones it lies on by edges that are not sharp at the smoothing length, as the
planner judges them: features.sharp_at_scale, so a scan's slivers cut no island out of its
sheet; a point on a sharp edge may take either side) whose bounding boxes reach within two
smoothing lengths per axis, where the smoothing draws nearly all its weight: facets of a curved
surface widen the cone, a flat face narrows it to its normal, and a normal averaged across a
sharp edge fails.
"""

from __future__ import annotations

import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.geometry.surface.boxes import TriangleBoxes
from coatsim.geometry.surface.features import feature_labels
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import Facets, face_normals, orient
from coatsim.geometry.surface.surfacepaths import SurfacePaths

#: a point farther than this fraction of the part's extent from its surface is off the mesh
ON_MESH_FRACTION = 1e-6
#: the cone holds the faces within this many smoothing lengths
CONE_SMOOTHING_LENGTHS = 2.0
#: the cone's faces stand for cells of this fraction of its radius (verify._representatives)
CONE_CELLS = 6.0
#: points checked at once (bounds the memory of the point-face pairs)
VERIFY_CHUNK = 2048
#: on a closed part a normal's probe of this fraction of the extent must not end inside it ...
INWARD_STEP_FRACTION = 1e-4
#: ... deeper than this fraction of the probe (about 6 deg into the part)
INWARD_DEPTH_FRACTION = 0.1
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


def verify(part: Part, paths: SurfacePaths) -> float:
    """Raise PlanCheckFailed naming the first point that fails (see the module docstring);
    return the largest angle (deg) by which a normal leaves the cone of the faces near it."""
    import trimesh

    if not paths.passes:
        return 0.0
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    length = np.linalg.norm(normals, axis=1)
    bad = np.flatnonzero(~(np.abs(length - 1) <= 1e-6))
    if len(bad):
        _fail(paths, int(bad[0]), f"has a normal of length {length[bad[0]]:.6g}")
    tolerance = ON_MESH_FRACTION * part.extent_mm
    facets = Facets.of(part.vertices_mm, orient(part.vertices_mm, part.faces, None).faces,
                       paths.stats.normal_smoothing_mm)
    reach = tolerance + facets.largest_lift_mm()
    owner, _, distance = facets.boxes.touching(points, reach)
    nearest = np.full(len(points), np.inf)
    np.minimum.at(nearest, owner, distance)
    off = np.flatnonzero(~(nearest <= reach))
    if len(off):
        _fail(paths, int(off[0]), "lies off the part's surface")
    radius = CONE_SMOOTHING_LENGTHS * paths.stats.normal_smoothing_mm
    face_n, area = face_normals(part.vertices_mm, part.faces)
    label = feature_labels(part.vertices_mm, part.faces, paths.stats.normal_smoothing_mm)
    chosen = _representatives(part, face_n, label, radius / CONE_CELLS)
    group_area = np.bincount(chosen, weights=area, minlength=len(part.faces))
    weight = np.where(group_area > 0, group_area, area)  # a representative stands for its group's area
    chosen = np.unique(chosen)
    cone = TriangleBoxes(part.vertices_mm, part.faces[chosen])
    worst_deg = 0.0
    for chunk in np.array_split(np.arange(len(points)), max(1, len(points) // VERIFY_CHUNK)):
        owner, face, distance = facets.boxes.touching(points[chunk], reach)
        on = distance <= nearest[chunk][owner] + reach  # the faces nearest the point, to the lift: a point lifted
        # onto the smooth surface at a sharp edge lies as near the other side's facet as its own
        own = (owner[on], face[on])
        owner, rep = cone.near(points[chunk], radius)
        near = (owner, chosen[rep])
        excess = _normal_excess_deg(normals[chunk], own, near, face_n, weight, label)
        worst = int(np.argmax(excess))
        worst_deg = max(worst_deg, float(excess[worst]))
        if excess[worst] > NORMAL_TOLERANCE_DEG:
            _fail(paths, int(chunk[worst]), f"has a normal {excess[worst]:.3g} deg outside the faces around it")
    mesh = trimesh.Trimesh(part.vertices_mm, part.faces, process=False)
    if mesh.is_watertight:
        step = INWARD_STEP_FRACTION * part.extent_mm
        probes = points + step * normals
        inside = np.flatnonzero(mesh.contains(probes))
        if len(inside):  # again from the point's foot on the facets: a point lifted onto a concave
            # stretch of the smooth surface lies inside the facets by up to their sagitta
            probes[inside] = trimesh.proximity.closest_point(mesh, points[inside])[0] + step * normals[inside]
            inside = inside[mesh.contains(probes[inside])]
        # a probe running along a face (at a concave sharp edge) is not inside by rounding alone
        depth = np.linalg.norm(trimesh.proximity.closest_point(mesh, probes[inside])[0] - probes[inside], axis=1) \
            if len(inside) else np.zeros(0)
        inward = inside[depth > INWARD_DEPTH_FRACTION * step]
        if len(inward):
            _fail(paths, int(inward[0]), "has a normal pointing into the part")
    return worst_deg


def _representatives(part: Part, face_n: np.ndarray, label: np.ndarray, cell_mm: float) -> np.ndarray:
    """For each face, the face that stands for it: one per feature region, cell of a grid and
    direction (to about 20 deg) of the faces whose centres lie in it. The cone test then sees
    every direction near a point without visiting every face of a fine scan."""
    centres = part.vertices_mm[part.faces].mean(axis=1)
    key = np.column_stack([label, np.floor((centres - centres.min(axis=0)) / cell_mm),
                           np.round(face_n * 3)]).astype(np.int64)
    _, first, group = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return first[group.ravel()]


def _normal_excess_deg(normals: np.ndarray, own: tuple[np.ndarray, np.ndarray], near: tuple[np.ndarray, np.ndarray],
                       face_n: np.ndarray, area: np.ndarray, label: np.ndarray) -> np.ndarray:
    """By how much each normal leaves the cone of the face normals near it (deg). ``own``: pairs
    (point, face) of the faces each point lies on; ``near``: pairs (point, face) of the faces
    near it, with their ``area``. Per point and feature region of its own faces, the cone holds
    that region's near and own faces, centred on their area-weighted mean, face normals taken
    on the normal's side; a point takes the region that fits best (inf with no face at all)."""
    count = int(label.max()) + 1
    allowed = np.unique(own[0] * count + label[own[1]])
    key_near = near[0] * count + label[near[1]]
    keep = np.isin(key_near, allowed)
    owner = np.concatenate([own[0], near[0][keep]])
    face = np.concatenate([own[1], near[1][keep]])
    key = owner * count + label[face]
    order = np.argsort(key, kind="stable")
    key, owner, near_n, weight = key[order], owner[order], face_n[face[order]], area[face[order]]
    aligned = near_n * np.where(np.einsum("ij,ij->i", near_n, normals[owner]) < 0, -1.0, 1.0)[:, None]
    starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]]) if len(key) else np.zeros(0, dtype=np.int64)
    excess = np.full(len(normals), np.inf)
    if not len(starts):
        return excess
    mean = np.add.reduceat(aligned * weight[:, None], starts, axis=0)
    mean /= np.maximum(np.linalg.norm(mean, axis=1), 1e-300)[:, None]
    group = np.repeat(np.arange(len(starts)), np.diff(np.r_[starts, len(key)]))
    cos = np.clip(np.einsum("ij,ij->i", aligned, mean[group]), -1, 1)
    spread = np.arccos(np.minimum.reduceat(cos, starts))
    off = np.arccos(np.clip(np.einsum("ij,ij->i", normals[owner[starts]], mean), -1, 1))
    np.minimum.at(excess, owner[starts], np.degrees(off - spread))
    return excess

"""Coated surfaces: triangle meshes in mm in the robot base frame, with what the kernel needs.

A ``Surface`` carries vertices, faces, unit vertex normals, barycentric vertex areas (one third
of each adjacent face's area, so Σ A_i T_i is the deposited volume) and 2-D ``view``
coordinates for heat maps: top view (x, y) for plates and mesh files, unrolled
(along-axis, arc length) for cylinders. Built-in parts are generated analytically (exact
normals); mesh files are loaded with trimesh and refined until no edge exceeds the spacing.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.numeric import ROUND_OFF, TINY, steps_over
from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, check_budget
from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.fileio import check_input
from coatsim.core.units import UNITS_MM
from coatsim.geometry.surface.mesh import UNIT_CHOICES, guessed_unit_note, length_unit, units_of

MIN_PART_MM = 1e-3  # smallest plate or cylinder dimension (a micrometre)
MESH_SUFFIXES = (".stl", ".ply", ".obj", ".glb", ".gltf", ".off")


@dataclass(frozen=True, eq=False)
class Surface:
    """A coated part: n vertices (mm, base frame), m triangles, unit normals, vertex areas (mm²)."""

    name: str
    kind: str
    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    areas: np.ndarray
    view: np.ndarray
    view_labels: tuple[str, str]

    @property
    def n_vertices(self) -> int:
        return len(self.vertices)

    @property
    def area_mm2(self) -> float:
        return float(self.areas.sum())


def vertex_areas(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Barycentric vertex areas: one third of the area of every adjacent triangle."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    face_area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    return np.bincount(faces.ravel(), weights=np.repeat(face_area / 3, 3), minlength=len(vertices))


def _check_spacing(spacing: float) -> None:
    if not (math.isfinite(spacing) and spacing > 0):
        raise InputError(f"surface spacing must be a positive number of mm, found {spacing:g}")


def _grid_size(what: str, extent_u: float, extent_v: float, spacing: float, min_u: int = 1) -> tuple[int, int]:
    """Cells along u and v of a structured grid at ``spacing``; its vertex count is checked
    against the budget mesh_vertices before anything is allocated."""
    cells_u, cells_v = max(min_u, extent_u / spacing), max(1.0, extent_v / spacing)
    check_budget(f"{what} meshed every {spacing:g} mm: vertices", (cells_u + 1) * (cells_v + 1), "mesh_vertices",
                 "use a larger spacing (coat --spacing, the scenario's coating.spacing_mm)")
    return max(min_u, steps_over(extent_u, spacing)), max(1, steps_over(extent_v, spacing))


def _grid_faces(nu: int, nv: int) -> np.ndarray:
    """Two counter-clockwise triangles per cell of an (nu+1) x (nv+1) node grid, u fastest."""
    i, j = np.meshgrid(np.arange(nu), np.arange(nv))
    n00 = (j * (nu + 1) + i).ravel()
    n10, n01, n11 = n00 + 1, n00 + nu + 1, n00 + nu + 2
    return np.concatenate([np.column_stack([n00, n10, n11]), np.column_stack([n00, n11, n01])])


def _transform(points: np.ndarray, pose: np.ndarray, vectors: bool = False) -> np.ndarray:
    out = points @ pose[:3, :3].T
    return out if vectors else out + pose[:3, 3]


def _pose(pose: np.ndarray | None) -> np.ndarray:
    pose = np.eye(4) if pose is None else np.asarray(pose, dtype=float)
    rot = pose[:3, :3]
    if pose.shape != (4, 4) or not np.allclose(rot @ rot.T, np.eye(3), atol=ROUND_OFF) or np.linalg.det(rot) < 0:
        raise InputError("workpiece pose must be a 4x4 rigid transform (rotation + translation)")
    return pose


def plate(width: float, height: float, spacing: float, pose: np.ndarray | None = None) -> Surface:
    """Flat W x H plate centred on the pose origin, normal +z of the pose, structured grid."""
    _check_spacing(spacing)
    if not (MIN_PART_MM <= width <= MAX_ABS_COORDINATE_MM and MIN_PART_MM <= height <= MAX_ABS_COORDINATE_MM):
        raise InputError(f"plate size must be between {MIN_PART_MM:g} and {MAX_ABS_COORDINATE_MM:g} mm, "
                         f"found {width:g} x {height:g} mm")
    pose = _pose(pose)
    nu, nv = _grid_size(f"plate {width:g} x {height:g} mm", width, height, spacing)
    x = np.linspace(-width / 2, width / 2, nu + 1)
    y = np.linspace(-height / 2, height / 2, nv + 1)
    xx, yy = np.meshgrid(x, y)
    local = np.column_stack([xx.ravel(), yy.ravel(), np.zeros(xx.size)])
    faces = _grid_faces(nu, nv)
    vertices = _transform(local, pose)
    normals = np.tile(pose[:3, 2], (len(local), 1))
    return Surface(f"plate:{width:g}x{height:g}", "plate", vertices, faces, normals,
                   vertex_areas(vertices, faces), vertices[:, :2].copy(), ("x (mm)", "y (mm)"))


_CYLINDER_FRAMES = {  # axis letter -> (axis direction, radial direction at phi=0, at phi=90 deg)
    "x": ((1.0, 0, 0), (0, 0, 1.0), (0, 1.0, 0)),
    "y": ((0, 1.0, 0), (0, 0, 1.0), (1.0, 0, 0)),
    "z": ((0, 0, 1.0), (1.0, 0, 0), (0, 1.0, 0)),
}


def cylinder(radius: float, length: float, spacing: float, axis: str = "x",
             pose: np.ndarray | None = None) -> Surface:
    """Outside of a cylinder of radius R and length L centred on the pose origin, along its
    ``axis``; angle 0 is +z (+x for a z axis). The seam at ±180° carries duplicated vertices
    so the unrolled view (along-axis, R·angle) has no wrap-around."""
    _check_spacing(spacing)
    if not (MIN_PART_MM <= radius <= MAX_ABS_COORDINATE_MM and MIN_PART_MM <= length <= MAX_ABS_COORDINATE_MM):
        raise InputError(f"cylinder size must be between {MIN_PART_MM:g} and {MAX_ABS_COORDINATE_MM:g} mm, "
                         f"found R={radius:g} x L={length:g} mm")
    if axis not in _CYLINDER_FRAMES:
        raise InputError(f"cylinder axis must be x, y or z, found {axis!r}")
    pose = _pose(pose)
    ax, r0, r90 = (np.array(v) for v in _CYLINDER_FRAMES[axis])
    n_phi, n_len = _grid_size(f"cylinder R {radius:g} x {length:g} mm", 2 * math.pi * radius, length, spacing, 3)
    phi = np.linspace(-math.pi, math.pi, n_phi + 1)
    s = np.linspace(-length / 2, length / 2, n_len + 1)
    ss, pp = np.meshgrid(s, phi)  # rows: phi, columns: along the axis
    radial = np.cos(pp.ravel())[:, None] * r0 + np.sin(pp.ravel())[:, None] * r90
    local = ss.ravel()[:, None] * ax + radius * radial
    faces = _grid_faces(n_len, n_phi)
    if np.dot(np.cross(ax, r90), r0) < 0:  # keep triangles counter-clockwise seen from outside
        faces = faces[:, ::-1]
    vertices = _transform(local, pose)
    normals = _transform(radial, pose, vectors=True)
    view = np.column_stack([ss.ravel(), radius * pp.ravel()])
    return Surface(f"cylinder:{radius:g}x{length:g}", "cylinder", vertices, faces, normals,
                   vertex_areas(vertices, faces), view, (f"along {axis} (mm)", "unrolled arc (mm)"))


def mesh_file(path: str | Path, spacing: float, pose: np.ndarray | None = None, units: str = "mm") -> Surface:
    """Triangle mesh from an STL / PLY / OBJ / GLB file in ``units`` (mm, cm, m, in, or auto: the
    file's, else guessed from its extent as ``plan`` guesses it, with a warning), refined so no
    edge exceeds spacing."""
    import trimesh
    import trimesh.remesh

    _check_spacing(spacing)
    path = Path(path)
    check_input(path, "surface mesh file")  # a FIFO, device or folder named as such, not "not found"
    try:
        mesh = trimesh.load(str(path), force="mesh")
    except Exception as exc:  # trimesh raises many types for malformed files
        raise InputError(f"{path}: cannot read mesh ({type(exc).__name__}: {exc})".splitlines()[0]) from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise InputError(f"{path}: mesh has no triangles; export the part surface as a triangle mesh")
    if not np.all(np.isfinite(mesh.vertices)):
        raise InputError(f"{path}: mesh has non-finite vertex coordinates")
    mesh.update_faces(mesh.nondegenerate_faces())
    if len(mesh.faces) == 0:
        raise InputError(f"{path}: every triangle of the mesh is degenerate (zero area)")
    if units not in UNIT_CHOICES:
        raise InputError(f"units must be one of {', '.join(UNIT_CHOICES)}, found {units!r}", parameters=("units",))
    extent = float(np.ptp(mesh.vertices, axis=0).max())
    unit, guess = length_unit(extent, units, units_of(mesh))
    if guess:
        warnings.warn(f"{path}: {guessed_unit_note(unit, guess)}", CoatsimWarning, stacklevel=2)
    vertices = np.asarray(mesh.vertices, dtype=float) * UNITS_MM[unit]
    return mesh_surface(vertices, np.asarray(mesh.faces), spacing, pose, str(path))


def mesh_surface(vertices: np.ndarray, faces: np.ndarray, spacing: float, pose: np.ndarray | None = None,
                 name: str = "mesh") -> Surface:
    """A part's triangles (mm, its own frame) refined so no edge exceeds ``spacing`` and placed
    by ``pose`` (4x4) in the base frame; the refined size is checked against the budget first."""
    import trimesh
    import trimesh.remesh

    _check_spacing(spacing)
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    estimate = max(len(mesh.faces), mesh.area / (math.sqrt(3) / 4 * spacing**2))
    check_budget(f"{name} refined to edges of {spacing:g} mm: vertices (half the triangles)", estimate / 2, "mesh_vertices",
                 "use a larger spacing (coat --spacing, the scenario's coating.spacing_mm)")
    vertices, faces = trimesh.remesh.subdivide_to_size(mesh.vertices, mesh.faces, max_edge=spacing, max_iter=20)
    refined = trimesh.Trimesh(vertices, faces, process=True)
    refined.remove_unreferenced_vertices()
    pose = _pose(pose)
    vertices = _transform(np.asarray(refined.vertices, dtype=float), pose)
    faces = np.asarray(refined.faces, dtype=np.int64)
    normals = _transform(np.asarray(refined.vertex_normals, dtype=float), pose, vectors=True)
    return Surface(name, "mesh", vertices, faces, normals, vertex_areas(vertices, faces),
                   vertices[:, :2].copy(), ("x (mm)", "y (mm)"))


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_PRIMITIVE = re.compile(rf"^(plate|cylinder):\s*({_NUMBER})\s*[xX]\s*({_NUMBER})\s*(?:@(.*))?$")


def _placement(text: str | None, spec: str, allow_axis: bool) -> tuple[np.ndarray, str]:
    """Translation pose and axis letter from ``x,y,z[,axis]``."""
    pose, axis = np.eye(4), "x"
    if text is None:
        return pose, axis
    items = [t.strip() for t in text.split(",")]
    if allow_axis and len(items) == 4:
        axis = items.pop().lower()
        if axis not in _CYLINDER_FRAMES:
            raise InputError(f"surface {spec!r}: cylinder axis must be x, y or z, found {axis!r}")
    try:
        xyz = [float(t) for t in items]
    except ValueError:
        xyz = []
    if len(xyz) != 3 or not all(map(math.isfinite, xyz)):
        form = "x,y,z[,axis]" if allow_axis else "x,y,z"
        raise InputError(f"surface {spec!r}: placement after '@' must be {form} in mm, found {text!r}")
    pose[:3, 3] = xyz
    return pose, axis


def _mesh_spec(spec: str) -> tuple[str, str | None]:
    """A mesh file spec split into its path and the text after '@' (None without one)."""
    path, at, place = spec.rpartition("@") if "@" in spec else (spec, "", "")
    if at and Path(spec).suffix.lower() not in MESH_SUFFIXES:
        return path, place
    return spec, None


def surface_file(spec: str) -> Path | None:
    """The mesh file a surface spec reads (None for ``plate:`` and ``cylinder:``)."""
    spec = spec.strip()
    if spec.split(":", 1)[0].lower() in ("plate", "cylinder"):
        return None
    return Path(_mesh_spec(spec)[0])


def parse_surface_spec(spec: str, spacing: float, units: str = "mm") -> Surface:
    """Surface from ``plate:WxH@x,y,z`` (normal +z), ``cylinder:RxL@x,y,z[,axis]`` (axis x by
    default) or a mesh file path in ``units`` (mesh_file) with an optional ``@x,y,z``
    translation; all in mm."""
    spec = spec.strip()
    match = _PRIMITIVE.match(spec)
    if match:
        kind, a, b, at = match.groups()
        pose, axis = _placement(at, spec, allow_axis=kind == "cylinder")
        if kind == "plate":
            surface = plate(float(a), float(b), spacing, pose)
        else:
            surface = cylinder(float(a), float(b), spacing, axis, pose)
        return Surface(spec, surface.kind, surface.vertices, surface.faces, surface.normals,
                       surface.areas, surface.view, surface.view_labels)
    if surface_file(spec) is None:
        raise InputError(f"surface {spec!r}: expected plate:WxH@x,y,z or cylinder:RxL@x,y,z[,axis] (mm)")
    path, place = _mesh_spec(spec)
    if place is not None:
        pose, _ = _placement(place, spec, allow_axis=False)
        return mesh_file(path, spacing, pose, units)
    return mesh_file(path, spacing, units=units)


def merged_vertices(vertices: np.ndarray) -> np.ndarray:
    """Vertex ids with coincident vertices (within 1e-7 of the part size) sharing one id."""
    scale = float(np.ptp(vertices, axis=0).max()) or 1.0
    key = np.round(vertices / (1e-7 * scale)).astype(np.int64)
    order = np.lexsort(key.T[::-1])
    ordered = key[order]
    ids = np.cumsum(np.r_[True, np.any(ordered[1:] != ordered[:-1], axis=1)]) - 1
    merged = np.empty(len(vertices), dtype=np.int64)
    merged[order] = ids
    return merged


def border_distance(surface: Surface, spacing: float | None = None, within_mm: float = math.inf) -> np.ndarray:
    """3-D distance (mm) from every vertex to the part border (edges with one adjacent
    triangle, after merging coincident vertices such as a cylinder seam); inf if closed or
    not within ``within_mm`` (the search stops there, so an edge band costs time in
    proportion to the vertices it holds). Accurate to spacing/16 (border edges are sampled
    at spacing/8)."""
    merged = merged_vertices(surface.vertices)
    faces = merged[surface.faces]
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    key = edges[:, 0] * (int(merged.max()) + 1) + edges[:, 1]
    values, counts = np.unique(key, return_counts=True)
    once = values[counts == 1]  # an edge of one triangle only
    if not len(once):
        return np.full(surface.n_vertices, np.inf)
    slot = np.minimum(np.searchsorted(once, key), len(once) - 1)
    all_edges = np.concatenate([surface.faces[:, [0, 1]], surface.faces[:, [1, 2]], surface.faces[:, [2, 0]]])
    border = all_edges[once[slot] == key]
    a, b = surface.vertices[border[:, 0]], surface.vertices[border[:, 1]]
    lengths = np.linalg.norm(b - a, axis=1)
    step = (spacing if spacing else float(np.median(lengths))) / 8
    n = np.maximum(1, np.ceil(lengths / step).astype(np.int64))
    edge = np.repeat(np.arange(len(border)), n + 1)
    frac = (np.arange(len(edge)) - np.repeat(np.cumsum(n + 1) - (n + 1), n + 1)) / np.repeat(n, n + 1)
    samples = a[edge] + frac[:, None] * (b - a)[edge]
    if not math.isfinite(within_mm):
        return cKDTree(samples).query(surface.vertices)[0]
    bound = within_mm * (1 + ROUND_OFF) + TINY
    # A search from far inside the part is slow (the tree's boxes hold the interior); one sample
    # per cell of a coarse grid bounds every distance from below, so only vertices that may lie
    # within the band go to the fine samples.
    cell = max(within_mm / 16, step)
    _, keep = np.unique(np.floor(samples / cell).astype(np.int64), axis=0, return_index=True)
    reach = cell * math.sqrt(3) + step / 2
    # bounded too, so a vertex far inside stops searching early; any vertex it leaves at inf is
    # beyond bound + reach, hence not near either way
    coarse = cKDTree(samples[np.sort(keep)]).query(surface.vertices, distance_upper_bound=(bound + reach) * (1 + ROUND_OFF) + TINY)[0]
    near = np.flatnonzero(coarse - reach < bound)
    distance = np.full(surface.n_vertices, np.inf)
    distance[near] = cKDTree(samples).query(surface.vertices[near], distance_upper_bound=bound)[0]
    return distance

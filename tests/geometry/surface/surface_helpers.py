"""Meshes from formulas for the surface-path tests, and small checks computed here (not with the
planner's helpers)."""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.surface import Part, PlanOptions, SurfacePaths, part_from_arrays, plan

SIGMA = 5.0
SPACING = 10.0


def grid(width: float, height: float, nx: int, ny: int) -> tuple[np.ndarray, np.ndarray]:
    """A flat width x height grid in z = 0 from (0, 0), two counter-clockwise triangles per cell."""
    x, y = np.meshgrid(np.linspace(0, width, nx + 1), np.linspace(0, height, ny + 1))
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    a = (j * (nx + 1) + i).ravel()
    faces = np.concatenate([np.column_stack([a, a + 1, a + nx + 2]), np.column_stack([a, a + nx + 2, a + nx + 1])])
    return vertices, faces


def tube(radius: float, length: float, n_around: int, n_along: int) -> tuple[np.ndarray, np.ndarray]:
    """The open side of a cylinder about z, from z = -length/2 to length/2, normals outward."""
    phi = np.linspace(0, 2 * math.pi, n_around, endpoint=False)
    z = np.linspace(-length / 2, length / 2, n_along + 1)
    p, zz = np.meshgrid(phi, z)
    vertices = np.column_stack([radius * np.cos(p.ravel()), radius * np.sin(p.ravel()), zz.ravel()])
    j, i = np.meshgrid(np.arange(n_along), np.arange(n_around), indexing="ij")
    a = (j * n_around + i).ravel()
    b = (j * n_around + (i + 1) % n_around).ravel()
    faces = np.concatenate([np.column_stack([a, b, b + n_around]), np.column_stack([a, b + n_around, a + n_around])])
    return vertices, faces


def cone(base_radius: float, height: float, n_around: int, n_along: int) -> tuple[np.ndarray, np.ndarray]:
    """The open side of a cone with its apex cut off at a tenth of the height: base at z = 0,
    apex at z = height, normals outward."""
    phi = np.linspace(0, 2 * math.pi, n_around, endpoint=False)
    z = np.linspace(0, 0.9 * height, n_along + 1)
    p, zz = np.meshgrid(phi, z)
    r = base_radius * (1 - zz.ravel() / height)
    vertices = np.column_stack([r * np.cos(p.ravel()), r * np.sin(p.ravel()), zz.ravel()])
    j, i = np.meshgrid(np.arange(n_along), np.arange(n_around), indexing="ij")
    a = (j * n_around + i).ravel()
    b = (j * n_around + (i + 1) % n_around).ravel()
    faces = np.concatenate([np.column_stack([a, b, b + n_around]), np.column_stack([a, b + n_around, a + n_around])])
    return vertices, faces


def plate_with_hole(width: float, height: float, hole_radius: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    """A flat plate centred on the origin with a round hole, Delaunay-triangulated."""
    from scipy.spatial import Delaunay

    x, y = np.meshgrid(np.arange(-width / 2, width / 2 + 1e-9, step), np.arange(-height / 2, height / 2 + 1e-9, step))
    points = np.column_stack([x.ravel(), y.ravel()])
    points = points[np.linalg.norm(points, axis=1) > hole_radius + 0.7 * step]
    n_ring = math.ceil(2 * math.pi * hole_radius / step)
    angle = np.linspace(0, 2 * math.pi, n_ring, endpoint=False)
    points = np.vstack([points, hole_radius * np.column_stack([np.cos(angle), np.sin(angle)])])
    triangles = Delaunay(points).simplices
    centres = points[triangles].mean(axis=1)
    triangles = triangles[np.linalg.norm(centres, axis=1) > hole_radius]
    a, b, c = (points[triangles[:, k]] for k in range(3))
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    triangles = np.where((cross < 0)[:, None], triangles[:, ::-1], triangles)
    return np.column_stack([points, np.zeros(len(points))]), triangles


def box_part(size: tuple[float, float, float]) -> Part:
    import trimesh

    box = trimesh.creation.box(size)
    return part_from_arrays(np.asarray(box.vertices), np.asarray(box.faces), "box")


def options(**kw) -> PlanOptions:
    kw.setdefault("footprint_sigma_mm", SIGMA)
    kw.setdefault("standoff_mm", 100.0)
    kw.setdefault("spacing_mm", SPACING)
    return PlanOptions(**kw)


def planned(vertices: np.ndarray, faces: np.ndarray, **kw) -> SurfacePaths:
    return plan(part_from_arrays(vertices, faces, "part"), options(**kw))


def arc_gaps(values: list[float]) -> np.ndarray:
    return np.diff(np.sort(np.asarray(values)))

"""Trajectory builders and constants shared by the coating-stage tests (defaults of spray_model §5.6)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from coatsim.robot.trajectory_log import TrajectoryLog
from coatsim.spray.deposition import SprayModel
from coatsim.spray.footprints import Footprint, Gaussian
from coatsim.spray.surfaces import Surface, plate

SIGMA = 5.0
H0 = 100.0
Q = 40.0
V = 500.0
DOWN = (0.0, 0.0, -1.0)


def make_log(t, position, axis=DOWN, spray=True) -> TrajectoryLog:
    """TrajectoryLog from times (n,), positions (n, 3), one axis or (n, 3) axes, spray flag(s)."""
    t = np.asarray(t, dtype=float)
    n = len(t)
    position = np.asarray(position, dtype=float)
    axis = np.broadcast_to(np.asarray(axis, dtype=float), (n, 3)).copy()
    spray = np.broadcast_to(np.asarray(spray, dtype=bool), (n,)).copy()
    speed = np.r_[np.linalg.norm(np.diff(position, axis=0), axis=1) / np.diff(t), 0.0]
    zeros = np.zeros(n)
    return TrajectoryLog(t=t, position=position, axis=axis, speed=speed, spray=spray,
                         progress=zeros, path_error=zeros, q=np.zeros((n, 6)))


def stationary_log(point, duration: float, axis=DOWN) -> TrajectoryLog:
    return make_log([0.0, duration], [point, point], axis)


def line_log(start, end, speed: float = V, step_mm: float = 1.0) -> TrajectoryLog:
    """Constant-speed straight pass, one row per ``step_mm``."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    length = float(np.linalg.norm(end - start))
    n = max(1, round(length / step_mm))
    f = np.linspace(0.0, 1.0, n + 1)
    return make_log(f * length / speed, start + f[:, None] * (end - start))


def join_logs(*logs: TrajectoryLog, gap_s: float = 0.0) -> TrajectoryLog:
    """Logs one after the other; each later log is shifted to start ``gap_s`` after the previous end.
    The last row of every log but the final one sprays off, so the transfer between them is dry."""
    t, p, a, s = [], [], [], []
    offset = 0.0
    for k, log in enumerate(logs):
        t.append(log.t - log.t[0] + offset)
        p.append(log.position)
        a.append(log.axis)
        spray = log.spray.copy()
        if k < len(logs) - 1:
            spray[-1] = False
        s.append(spray)
        offset = t[-1][-1] + max(gap_s, 1e-3)
    return make_log(np.concatenate(t), np.concatenate(p), np.concatenate(a), np.concatenate(s))


# Paths stay within 50 mm of the origin at heights up to 140 mm, the axis tilted by up to
# atan(0.4 * sqrt(2)) = 29.5 deg; the 6-sigma footprint cone opens atan(30 / 100) = 16.7 deg more, so
# spray lands up to 50 + 140 tan(46.2 deg) = 196 mm from the origin: a 400 mm plate catches all of it.
PLATE = plate(400, 400, SIGMA / 2)


@st.composite
def random_paths(draw):
    n = draw(st.integers(2, 12))
    xy = draw(st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50)), min_size=n, max_size=n))
    z = draw(st.lists(st.floats(80, 140), min_size=n, max_size=n))
    tilt = draw(st.lists(st.tuples(st.floats(-0.4, 0.4), st.floats(-0.4, 0.4)), min_size=n, max_size=n))
    dt = draw(st.lists(st.floats(0.001, 0.2), min_size=n - 1, max_size=n - 1))
    spray = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    axis = np.array([[tx, ty, -1.0] for tx, ty in tilt])
    return make_log(np.r_[0, np.cumsum(dt)], np.column_stack([np.array(xy), z]), axis / np.linalg.norm(axis, axis=1)[:, None], spray)


def gun(footprint: Footprint | None = None, **kwargs) -> SprayModel:
    return SprayModel(footprint or Gaussian(SIGMA), kwargs.pop("rate_mm3_s", Q), kwargs.pop("standoff_mm", H0), **kwargs)


def volume(surface: Surface, thickness_mm: np.ndarray) -> float:
    return float(surface.areas @ thickness_mm)


def merge_surfaces(*surfaces: Surface) -> Surface:
    """One surface made of several parts (e.g. a part and a blocker in front of it)."""
    offsets = np.cumsum([0] + [s.n_vertices for s in surfaces[:-1]])
    return Surface(
        "+".join(s.name for s in surfaces), "mesh",
        np.concatenate([s.vertices for s in surfaces]),
        np.concatenate([s.faces + o for s, o in zip(surfaces, offsets)]),
        np.concatenate([s.normals for s in surfaces]),
        np.concatenate([s.areas for s in surfaces]),
        np.concatenate([s.view for s in surfaces]), surfaces[0].view_labels,
    )


def stationary_peak_um(t: float = 1.0, sigma: float = SIGMA) -> float:
    return Q * t / (2 * math.pi * sigma**2) * 1000


def pass_profile_um(y, speed: float = V, sigma: float = SIGMA):
    return Q / (math.sqrt(2 * math.pi) * sigma * speed) * np.exp(-np.asarray(y) ** 2 / (2 * sigma**2)) * 1000


def mesh_surface(name: str, vertices, faces, normals) -> Surface:
    """A surface from arrays (normals are normalised; areas from the triangles)."""
    from coatsim.spray.surfaces import vertex_areas

    vertices, faces = np.asarray(vertices, float), np.asarray(faces, np.int64)
    normals = np.asarray(normals, float)
    normals = normals / np.linalg.norm(normals, axis=1)[:, None]
    return Surface(name, "mesh", vertices, faces, normals, vertex_areas(vertices, faces), vertices[:, :2].copy(),
                   ("x (mm)", "y (mm)"))


def sphere(radius: float, subdivisions: int, centre=(0.0, 0.0, 0.0), inward: bool = False) -> Surface:
    """Icosphere with its vertices on the sphere and exact normals (inward: the inside of a shell)."""
    import trimesh

    unit = trimesh.creation.icosphere(subdivisions=subdivisions)
    faces = unit.faces[:, ::-1] if inward else unit.faces
    normals = -unit.vertices if inward else unit.vertices
    return mesh_surface(f"sphere:{radius:g}", radius * unit.vertices + np.asarray(centre, float), faces, normals)


def translated(surface: Surface, offset) -> Surface:
    return mesh_surface(surface.name, surface.vertices + np.asarray(offset, float), surface.faces, surface.normals)


def shelf_over_floor(spacing: float, height: float = 40.0) -> tuple[Surface, int]:
    """A 200 x 160 mm floor at z = 0 and a 100 x 160 mm shelf at z = ``height`` over its x < 0
    half (edge along x = 0), both facing +z; returns the surface and the floor's vertex count."""
    floor = plate(200, 160, spacing)
    pose = np.eye(4)
    pose[:3, 3] = (-50.0, 0.0, height)
    shelf = plate(100, 160, spacing, pose)
    return merge_surfaces(floor, shelf), floor.n_vertices

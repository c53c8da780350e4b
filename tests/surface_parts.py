"""Analytic 3-D test parts: a parametric surface, its mesh, and raster passes on it with exact
outward normals, written as ``coatsim.surfacepaths/1`` files (also used by scripts/bench_twin3d.py).

Each part is a map S(u, v) -> (x, y, z) mm in the part's own frame with the side the gun sees
facing +z; passes run along u at fixed v, normals are the unit cross product of the partial
derivatives (central differences of the exact map, 1e-4 of the parameter range).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

Surface = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Part:
    """A parametric surface over [u0, u1] x [v0, v1] and the v of each pass."""

    name: str
    surface: Surface
    u_range: tuple[float, float]
    v_range: tuple[float, float]
    pass_v: tuple[float, ...]
    flip: bool = False  # the normal is -(S_u x S_v): the side the gun sees
    pose: tuple[float, ...] = (900.0, 0.0, 300.0, 0.0, 0.0, 0.0)  # in the shipped cell, within reach

    def normals(self, u: np.ndarray, v: np.ndarray) -> np.ndarray:
        du = 1e-4 * (self.u_range[1] - self.u_range[0])
        dv = 1e-4 * (self.v_range[1] - self.v_range[0])
        su = (self.surface(u + du, v) - self.surface(u - du, v)) / (2 * du)
        sv = (self.surface(u, v + dv) - self.surface(u, v - dv)) / (2 * dv)
        n = np.cross(su, sv) * (-1.0 if self.flip else 1.0)
        return n / np.linalg.norm(n, axis=1)[:, None]

    def passes(self, points_per_pass: int = 400, lead_mm: float = 20.0) -> list[dict]:
        out = []
        for k, v0 in enumerate(self.pass_v):
            u = np.linspace(*self.u_range, points_per_pass)
            if k % 2:
                u = u[::-1]  # serpentine
            v = np.full_like(u, v0)
            p, n = self.surface(u, v), self.normals(u, v)
            t_in, t_out = p[0] - p[1], p[-1] - p[-2]
            t_in, t_out = t_in / np.linalg.norm(t_in), t_out / np.linalg.norm(t_out)
            out.append({"points": p.tolist(), "normals": n.tolist(), "closed": False,
                        "lead_in": [(p[0] + lead_mm * t_in).tolist()], "lead_out": [(p[-1] + lead_mm * t_out).tolist()]})
        return out

    def mesh(self, nu: int = 60, nv: int = 30) -> tuple[np.ndarray, np.ndarray]:
        """Vertices (m, 3) and faces (k, 3) of the surface over its parameter box."""
        u, v = np.meshgrid(np.linspace(*self.u_range, nu), np.linspace(*self.v_range, nv), indexing="ij")
        vertices = self.surface(u.ravel(), v.ravel())
        idx = np.arange(nu * nv).reshape(nu, nv)
        a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
        faces = np.vstack((np.column_stack((a, b, c)), np.column_stack((a, c, d))))
        if self.flip:
            faces = faces[:, ::-1]
        return vertices, faces


def cylinder(radius: float = 60.0, concave: bool = False) -> Part:
    """Passes around a cylinder of radius R and axis y (u the angle from the top, rad; v along
    the axis), seen from outside; ``concave``: the bottom of a pipe of radius R seen from its axis."""
    if concave:
        def surf(u, v):
            return np.column_stack((radius * np.sin(u), v, radius - radius * np.cos(u)))
        return Part(f"pipe_r{radius:g}", surf, (-0.5, 0.5), (-60.0, 60.0), (-40.0, 0.0, 40.0), flip=False)

    def surf(u, v):
        return np.column_stack((radius * np.sin(u), v, radius * np.cos(u)))
    return Part(f"cylinder_r{radius:g}", surf, (-0.7, 0.7), (-60.0, 60.0), (-40.0, 0.0, 40.0),
                pose=(900.0, 0.0, 300.0, 90.0, 0.0, 0.0))


def torus_section(major: float = 150.0, tube: float = 50.0) -> Part:
    """The outer top quarter of a torus about z: u the angle about z, v the tube angle."""
    def surf(u, v):
        ring = major + tube * np.cos(v)
        return np.column_stack((ring * np.cos(u) - major, ring * np.sin(u), tube * np.sin(v)))
    return Part("torus_section", surf, (-0.6, 0.6), (0.2, 1.5), (0.8, 1.1, 1.4))


def saddle(c: float = 250.0) -> Part:
    """z = (x² − y²) / 2c over 200 x 160 mm; passes along x."""
    def surf(u, v):
        return np.column_stack((u, v, (u * u - v * v) / (2 * c)))
    return Part("saddle", surf, (-100.0, 100.0), (-80.0, 80.0), (-60.0, -20.0, 20.0, 60.0))


def blade(span: float = 200.0, chord: float = 80.0, camber: float = 12.0, twist: float = 0.5) -> Part:
    """A cambered sheet twisted along its span (x): passes along the span at fixed chord positions."""
    def surf(u, v):
        z = camber * (1.0 - (2 * v / chord) ** 2)
        th = twist * (u / span - 0.5)
        return np.column_stack((u - span / 2, v * np.cos(th) - z * np.sin(th), v * np.sin(th) + z * np.cos(th)))
    return Part("blade", surf, (0.0, span), (-chord / 2, chord / 2), (-30.0, -10.0, 10.0, 30.0))


PARTS = {"cylinder": cylinder, "torus_section": torus_section, "saddle": saddle, "blade": blade}


def write_surfacepaths(folder: Path, part: Part, pose: tuple[float, ...] | None = None, standoff_mm: float = 100.0, points_per_pass: int = 400) -> tuple[Path, Path]:
    """The part's mesh (STL) and a surfacepaths file of its passes; returns both paths."""
    import trimesh

    folder.mkdir(parents=True, exist_ok=True)
    vertices, faces = part.mesh()
    mesh_path = folder / f"{part.name}.stl"
    trimesh.Trimesh(vertices, faces, process=False).export(mesh_path)
    doc = {"format": "coatsim.surfacepaths/1", "units": "mm",
           "mesh": {"file": mesh_path.name, "sha256": "", "vertices": len(vertices), "faces": len(faces),
                    "pose": list(part.pose if pose is None else pose)},
           "pattern": "raster", "spacing_mm": 20.0, "standoff_mm": standoff_mm, "ripple_pct": 0.0,
           "passes": part.passes(points_per_pass), "stats": {"passes": len(part.pass_v)}}
    path = folder / f"{part.name}.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    return path, mesh_path


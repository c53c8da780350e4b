"""Coating outputs: PLY with a per-vertex ``thickness`` property, GLB (glTF) with vertex colours,
heat maps, cross-section profiles.

The plotting functions take no matplotlib objects and return PNG bytes (and write them when
given a path), so the report stage can reuse them: ``heatmap_png`` draws several thickness
fields side by side on one colour scale, ``profile_png`` several profiles on one plot.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.numeric import ROUND_OFF
from coatsim.core.fileio import write_bytes
from coatsim.spray.surfaces import Surface

COLOUR_MAP = "viridis"


@dataclass(frozen=True, eq=False)
class HeatPanel:
    """One heat map: view coordinates (n, 2) mm, triangles (m, 3) to draw, thickness (n,) µm."""

    title: str
    view: np.ndarray
    faces: np.ndarray
    thickness_um: np.ndarray
    labels: tuple[str, str] = ("x (mm)", "y (mm)")


@dataclass(frozen=True)
class Profile:
    """One cross-section curve: distance along the section (mm) and thickness (µm, NaN off the part)."""

    label: str
    distance_mm: np.ndarray
    thickness_um: np.ndarray


def view_faces(surface: Surface) -> np.ndarray:
    """Triangles shown in the 2-D view: all for plates and cylinders, upward-facing for meshes."""
    if surface.kind != "mesh":
        return surface.faces
    v = surface.vertices
    f = surface.faces
    up = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])[:, 2] > 0
    return f[up]


def panel(surface: Surface, thickness_um: np.ndarray, title: str = "") -> HeatPanel:
    """Heat-map panel of a surface: top view for plates and meshes, unrolled for cylinders."""
    return HeatPanel(title, surface.view, view_faces(surface), thickness_um, surface.view_labels)


def colours(values: np.ndarray, vmin: float, vmax: float) -> np.ndarray:
    """(n, 3) uint8 RGB of ``values`` on the colour map between vmin and vmax."""
    import matplotlib

    span = vmax - vmin if vmax > vmin else 1.0
    rgba = matplotlib.colormaps[COLOUR_MAP](np.clip((values - vmin) / span, 0.0, 1.0))
    return np.round(rgba[:, :3] * 255).astype(np.uint8)


def ply_bytes(surface: Surface, thickness_um: np.ndarray, vmin: float | None = None,
              vmax: float | None = None, exposure_s: np.ndarray | None = None) -> bytes:
    """Binary little-endian PLY: x y z nx ny nz (float32, mm), thickness (float32, µm),
    optionally exposure (float32, s under the spray), and RGB of the thickness colour map."""
    vmin = float(thickness_um.min()) if vmin is None else vmin
    vmax = float(thickness_um.max()) if vmax is None else vmax
    n, m = surface.n_vertices, len(surface.faces)
    scalars = ["thickness"] + ([] if exposure_s is None else ["exposure"])
    header = "\n".join([
        "ply", "format binary_little_endian 1.0",
        f"comment coatsim coating thickness in um; colours {COLOUR_MAP} from {vmin:.6g} to {vmax:.6g} um",
        f"element vertex {n}",
        *(f"property float {name}" for name in ("x", "y", "z", "nx", "ny", "nz", *scalars)),
        "property uchar red", "property uchar green", "property uchar blue",
        f"element face {m}", "property list uchar int vertex_indices", "end_header", "",
    ])
    vertex = np.zeros(n, dtype=[("xyz", "<f4", 3), ("n", "<f4", 3), ("s", "<f4", len(scalars)), ("rgb", "u1", 3)])
    vertex["xyz"] = surface.vertices
    vertex["n"] = surface.normals
    vertex["s"] = np.column_stack([thickness_um] + ([] if exposure_s is None else [exposure_s]))
    vertex["rgb"] = colours(thickness_um, vmin, vmax)
    face = np.zeros(m, dtype=[("k", "u1"), ("idx", "<i4", 3)])
    face["k"] = 3
    face["idx"] = surface.faces
    return header.encode("ascii") + vertex.tobytes() + face.tobytes()


def write_thickness_ply(path: str | Path, surface: Surface, thickness_um: np.ndarray,
                        vmin: float | None = None, vmax: float | None = None,
                        exposure_s: np.ndarray | None = None) -> None:
    write_bytes(path, ply_bytes(surface, thickness_um, vmin, vmax, exposure_s))


def glb_bytes(surface: Surface, thickness_um: np.ndarray, vmin: float, vmax: float,
              exposure_s: np.ndarray | None = None, path_mm: Sequence[np.ndarray] = ()) -> bytes:
    """Binary glTF of the coated part, in metres as glTF requires (base frame, z up as coatsim's):
    vertex colours COLOR_0 on the colour map from vmin to vmax µm, the values themselves as the
    vertex attributes _THICKNESS_UM (and _EXPOSURE_S), and each polyline of ``path_mm`` (k, 3)
    as a line node ``tool_path_N`` (the sprayed tool path, for instance)."""
    import trimesh

    rgba = np.column_stack((colours(thickness_um, vmin, vmax), np.full(len(thickness_um), 255, np.uint8)))
    mesh = trimesh.Trimesh(surface.vertices / 1000.0, surface.faces, vertex_normals=surface.normals,
                           vertex_colors=rgba, process=False)
    mesh.vertex_attributes["_THICKNESS_UM"] = np.asarray(thickness_um, dtype=np.float32)
    if exposure_s is not None:
        mesh.vertex_attributes["_EXPOSURE_S"] = np.asarray(exposure_s, dtype=np.float32)
    scene = trimesh.Scene()
    scene.add_geometry(mesh, geom_name="thickness", node_name="thickness")
    for k, points in enumerate(path_mm):
        if len(points) > 1:
            name = f"tool_path_{k + 1}"
            scene.add_geometry(trimesh.load_path(np.asarray(points, float) / 1000.0), geom_name=name, node_name=name)
    return scene.export(file_type="glb")


def write_thickness_glb(path: str | Path, surface: Surface, thickness_um: np.ndarray, vmin: float, vmax: float,
                        exposure_s: np.ndarray | None = None, path_mm: Sequence[np.ndarray] = ()) -> None:
    write_bytes(path, glb_bytes(surface, thickness_um, vmin, vmax, exposure_s, path_mm))


def _png(fig, path: str | Path | None) -> bytes:
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=120, metadata={"Software": None})
    plt.close(fig)
    data = buffer.getvalue()
    if path is not None:
        write_bytes(path, data)
    return data


def heatmap_png(panels: Sequence[HeatPanel], vmin: float | None = None, vmax: float | None = None,
                path: str | Path | None = None, title: str | None = None,
                section: tuple[np.ndarray, np.ndarray] | None = None) -> bytes:
    """Side-by-side heat maps on one colour scale (default: min and max over all panels);
    ``section`` (start, end in view mm) is drawn as a dashed line on every panel."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    vmin = min(float(p.thickness_um.min()) for p in panels) if vmin is None else vmin
    vmax = max(float(p.thickness_um.max()) for p in panels) if vmax is None else vmax
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels) + 1.2, 4.4), squeeze=False,
                             layout="constrained")
    image = None
    for ax, p in zip(axes[0], panels):
        image = ax.tripcolor(p.view[:, 0], p.view[:, 1], p.faces, p.thickness_um, shading="gouraud",
                             cmap=COLOUR_MAP, vmin=vmin, vmax=vmax)
        if section is not None:
            ax.plot(*np.column_stack(section), "w--", lw=0.8)
        ax.set_aspect("equal")
        ax.set_title(p.title, fontsize=10)
        ax.set_xlabel(p.labels[0])
        ax.set_ylabel(p.labels[1])
    fig.colorbar(image, ax=list(axes[0]), label="thickness (µm)")
    if title:
        fig.suptitle(title)
    return _png(fig, path)


def default_section(surface: Surface) -> tuple[np.ndarray, np.ndarray]:
    """Section line across the view: along view x through the centre of the view's extent."""
    lo, hi = surface.view.min(axis=0), surface.view.max(axis=0)
    y = 0.5 * (lo[1] + hi[1])
    return np.array([lo[0], y]), np.array([hi[0], y])


def section_profile(view: np.ndarray, faces: np.ndarray, thickness_um: np.ndarray,
                    start: Sequence[float], end: Sequence[float], n: int = 601) -> tuple[np.ndarray, np.ndarray]:
    """Thickness interpolated linearly inside the view triangles at n points from start to end
    (view mm); returns (distance along the line, thickness), NaN where the line leaves the part."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    frac = np.linspace(0.0, 1.0, n)
    points = start + frac[:, None] * (end - start)
    a, b, c = (view[faces[:, k]] for k in range(3))
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    keep = np.abs(det) > 1e-12 * max(1.0, float(np.ptp(view)) ** 2)
    faces, a, b, c, det = faces[keep], a[keep], b[keep], c[keep], det[keep]
    if len(faces) == 0:  # a part too thin to draw: no profile
        return frac * float(np.linalg.norm(end - start)), np.full(n, np.nan)
    k = min(16, len(faces))
    _, near = cKDTree((a + b + c) / 3).query(points, k=k)
    near = np.minimum(near.reshape(n, k), len(faces) - 1)  # a missing neighbour comes back as len(faces)
    p = points[:, None, :]
    l1 = ((p[..., 0] - a[near, 0]) * (c[near, 1] - a[near, 1])
          - (c[near, 0] - a[near, 0]) * (p[..., 1] - a[near, 1])) / det[near]
    l2 = ((b[near, 0] - a[near, 0]) * (p[..., 1] - a[near, 1])
          - (p[..., 0] - a[near, 0]) * (b[near, 1] - a[near, 1])) / det[near]
    l0 = 1.0 - l1 - l2
    inside = (l0 >= -ROUND_OFF) & (l1 >= -ROUND_OFF) & (l2 >= -ROUND_OFF)
    first = np.argmax(inside, axis=1)
    rows = np.arange(n)
    tri = faces[near[rows, first]]
    value = (l0[rows, first] * thickness_um[tri[:, 0]] + l1[rows, first] * thickness_um[tri[:, 1]]
             + l2[rows, first] * thickness_um[tri[:, 2]])
    value = np.where(inside.any(axis=1), value, np.nan)
    return frac * float(np.linalg.norm(end - start)), value


def profile_png(profiles: Sequence[Profile], path: str | Path | None = None, title: str | None = None,
                xlabel: str = "distance along section (mm)") -> bytes:
    """Several cross-section profiles on one plot."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    for p in profiles:
        ax.plot(p.distance_mm, p.thickness_um, lw=1.2, label=p.label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("thickness (µm)")
    ax.grid(alpha=0.3)
    if len(profiles) > 1 or profiles[0].label:
        ax.legend()
    if title:
        ax.set_title(title)
    fig.tight_layout()
    return _png(fig, path)

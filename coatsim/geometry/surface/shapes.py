"""Parts built from formulas: the meshes of the shipped 3-D scenarios, made deterministically.

Each function returns vertices (n, 3) mm and triangles (m, 3) in the part's own frame, with the
side a gun sprays facing +z, and depends on nothing but its arguments (the scan's noise comes
from a seeded generator), so ``scripts/make_scenario_parts.py`` rebuilds the committed files
byte for byte:

- ``tube``: the outside of a cylinder along x, open at both ends;
- ``twisted_blade``: a closed airfoil (NACA 00xx thickness, cambered) twisted along its span,
  a turbine-blade stand-in;
- ``wear_plate``: a corrugated plate (rounded ridges across x), as a jaw crusher's wear plate;
- ``scan_patch``: a gently dished open sheet on scattered points (Delaunay), with measurement
  noise along z and a round hole, as a scanner delivers a part.
"""

from __future__ import annotations

import math

import numpy as np

Mesh = tuple[np.ndarray, np.ndarray]


def grid_faces(nu: int, nv: int, wrap_u: bool = False) -> np.ndarray:
    """Two triangles per cell of an nu x nv node grid (index u * nv + v), counter-clockwise seen
    from the side the u x v cross product points to; ``wrap_u`` joins the last row to the first."""
    rows = nu if wrap_u else nu - 1
    i, j = np.meshgrid(np.arange(rows), np.arange(nv - 1), indexing="ij")
    a = (i * nv + j).ravel()
    b = (((i + 1) % nu) * nv + j).ravel()
    c, d = b + 1, a + 1
    return np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])]).astype(np.int64)


def tube(radius_mm: float = 60.0, length_mm: float = 200.0, around: int = 64, along: int = 41) -> Mesh:
    """The outside of a cylinder of ``radius_mm`` along x, centred on the origin, open ends."""
    phi = np.linspace(0.0, 2 * math.pi, around, endpoint=False)
    x = np.linspace(-length_mm / 2, length_mm / 2, along)
    pp, xx = np.meshgrid(phi, x, indexing="ij")
    vertices = np.column_stack([xx.ravel(), radius_mm * np.sin(pp.ravel()), radius_mm * np.cos(pp.ravel())])
    # u = angle (from +z toward +y), v = x: d/dphi x d/dx points inward; flip to outward
    return vertices, grid_faces(around, along, wrap_u=True)[:, ::-1].copy()


def _airfoil(chord_mm: float, thickness: float, camber: float, samples: int) -> np.ndarray:
    """A closed airfoil outline (k, 2) counter-clockwise from the trailing edge: NACA 4-digit
    thickness (closed trailing edge) about a parabolic camber line, chord along x centred on 0."""
    beta = np.linspace(0.0, math.pi, samples)
    s = 0.5 * (1 - np.cos(beta))  # cosine spacing: dense at the edges
    half = 5 * thickness * (0.2969 * np.sqrt(s) - 0.1260 * s - 0.3516 * s**2 + 0.2843 * s**3 - 0.1036 * s**4)
    line = 4 * camber * s * (1 - s)
    slope = np.arctan(4 * camber * (1 - 2 * s))
    upper = np.column_stack([s - half * np.sin(slope), line + half * np.cos(slope)])
    lower = np.column_stack([s + half * np.sin(slope), line - half * np.cos(slope)])
    outline = np.vstack([upper[::-1], lower[1:-1]])  # trailing edge, over the top, round the nose, back
    return (outline - [0.5, 0.0]) * chord_mm


def twisted_blade(chord_mm: float = 120.0, span_mm: float = 180.0, twist_deg: float = 30.0, thickness: float = 0.12,
                  camber: float = 0.04, samples: int = 41, stations: int = 31) -> Mesh:
    """A blade: the airfoil in the x-z plane (chord along x, its top side +z), swept along y over
    ``span_mm`` and turned about y by up to ``twist_deg`` (linearly, centred); the ends are closed
    by fans so the part is watertight."""
    outline = _airfoil(chord_mm, thickness, camber, samples)
    k = len(outline)
    y = np.linspace(-span_mm / 2, span_mm / 2, stations)
    turn = np.radians(twist_deg) * (y / span_mm)
    cos, sin = np.cos(turn)[:, None], np.sin(turn)[:, None]
    x = cos * outline[None, :, 0] + sin * outline[None, :, 1]
    z = -sin * outline[None, :, 0] + cos * outline[None, :, 1]
    skin = np.column_stack([x.T.ravel(), np.repeat(y[None, :], k, axis=0).ravel(), z.T.ravel()])
    faces = grid_faces(k, stations, wrap_u=True)  # u round the outline (counter-clockwise in x-z), v along +y
    centres = np.array([[0.0, y[0], 0.0], [0.0, y[-1], 0.0]])
    vertices = np.vstack([skin, centres])
    c0, c1 = len(skin), len(skin) + 1
    ring = np.arange(k) * stations
    nxt = np.roll(ring, -1)
    caps = np.vstack([np.column_stack([np.full(k, c0), nxt, ring]),
                      np.column_stack([np.full(k, c1), ring + stations - 1, nxt + stations - 1])])
    faces = np.vstack([faces, caps])
    return vertices, _outward(vertices, faces)


def _outward(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """A closed mesh's triangles wound so that its signed volume is positive (normals outward)."""
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    volume = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum()) / 6
    return faces if volume > 0 else faces[:, ::-1].copy()


def wear_plate(length_mm: float = 300.0, width_mm: float = 160.0, pitch_mm: float = 150.0, height_mm: float = 6.0,
               per_pitch: int = 32, across: int = 21) -> Mesh:
    """The top of a corrugated plate: rounded ridges across x, ``height_mm`` from valley to
    crest every ``pitch_mm`` (a raised cosine). The defaults keep the valleys' radius of curvature
    (pitch² / (2 pi² height) = 190 mm) above the 100 mm stand-off and the 50 mm the tool departs
    beyond it between passes: over a tighter valley the tool points, offset along the normals,
    cross over one another (at a 120 mm pitch, 122 mm, the arm could not follow the departure
    over the first valley at 300 mm/s)."""
    nx = int(round(length_mm / pitch_mm * per_pitch)) + 1
    x = np.linspace(-length_mm / 2, length_mm / 2, nx)
    y = np.linspace(-width_mm / 2, width_mm / 2, across)
    wave = 0.5 * (1 + np.cos(2 * math.pi * x / pitch_mm))
    z = height_mm * wave
    xx, yy = np.meshgrid(x, y, indexing="ij")
    zz = np.repeat(z[:, None], across, axis=1)
    vertices = np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()])
    return vertices, grid_faces(nx, across)  # x then y: +z up


def scan_patch(size_mm: float = 400.0, spacing_mm: float = 4.0, noise_mm: float = 0.15, hole_mm: float = 25.0,
               sag_mm: float = 20.0, seed: int = 7) -> Mesh:
    """An open sheet as a scan gives it: scattered samples at least ``spacing_mm`` apart (Poisson
    disk, as a scanner resolves points no closer than its resolution; the square's border every
    ``spacing_mm``) of z = -sag (r / half size)² + a gentle wave, triangulated (Delaunay), z noise
    of standard deviation ``noise_mm``, the triangles inside a circle of radius ``hole_mm`` off the
    centre removed. Uniform random points instead leave pairs a hair apart: slivers whose noise
    tilts them by up to 95 deg, which no scanner's mesh has at this noise."""
    from scipy.spatial import Delaunay
    from scipy.stats import qmc

    half = size_mm / 2
    inner = (qmc.PoissonDisk(d=2, radius=spacing_mm / size_mm, seed=seed).fill_space() - 0.5) * size_mm
    inner = inner[(np.abs(inner) < half - spacing_mm / 2).all(axis=1)]
    edge = np.linspace(-half, half, int(math.ceil(size_mm / spacing_mm)) + 1)
    border = np.vstack([np.column_stack([edge, np.full_like(edge, s)]) for s in (-half, half)]
                       + [np.column_stack([np.full_like(edge[1:-1], s), edge[1:-1]]) for s in (-half, half)])
    xy = np.vstack([border, inner])
    r2 = (xy**2).sum(axis=1) / half**2
    rng = np.random.default_rng(seed)
    z = -sag_mm * r2 + 3.0 * np.sin(xy[:, 0] / 35.0) * np.cos(xy[:, 1] / 50.0) + rng.normal(0.0, noise_mm, len(xy))
    faces = Delaunay(xy).simplices.astype(np.int64)
    a, b, c = (xy[faces[:, i]] for i in range(3))
    ccw = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]) > 0
    faces[~ccw] = faces[~ccw][:, ::-1]
    centre = np.array([0.25 * half, -0.2 * half])
    keep = np.linalg.norm(xy[faces].mean(axis=1) - centre, axis=1) > hole_mm
    faces = faces[keep]
    used = np.unique(faces)
    remap = np.full(len(xy), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    return np.column_stack([xy, z])[used], remap[faces]


def stl_bytes(vertices: np.ndarray, faces: np.ndarray, name: str) -> bytes:
    """A binary STL of the triangles (float32, face normals from the winding), header naming the part."""
    tri = vertices[faces].astype(np.float64)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
    record = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    record["n"], record["v"] = normal, tri
    header = f"coatsim part {name} (mm)".encode("ascii").ljust(80, b" ")[:80]
    return header + np.uint32(len(faces)).tobytes() + record.tobytes()


SHAPES = {"tube": tube, "twisted_blade": twisted_blade, "wear_plate": wear_plate, "scan_patch": scan_patch}

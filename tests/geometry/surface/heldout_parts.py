"""Parts like the ones users bring, built here (no file from outside the repository): a CAD
bracket of flat faces and sharp edges with a through-hole, a slab with filleted edges and a
bore, a scanned dome with noise and a hole, a plate with a narrow arm."""

from __future__ import annotations

import math

import numpy as np


def voxel_solid(occupied: np.ndarray, step_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """The closed surface of a union of cubes ``step_mm`` wide (occupied[i, j, k] fills the cube
    at i, j, k), every exposed cube face two triangles wound outward; shared corners are one
    vertex, so the mesh is watertight (cubes must not touch along an edge only)."""
    grid = np.pad(occupied.astype(bool), 1)
    quads = []
    for axis in range(3):
        for side in (-1, 1):
            neighbour = np.roll(grid, -side, axis=axis)
            cells = np.argwhere(grid & ~neighbour)
            base = cells.astype(float)
            if side > 0:
                base[:, axis] += 1
            u, w = (axis + 1) % 3, (axis + 2) % 3
            du, dw = np.eye(3)[u], np.eye(3)[w]
            corners = np.stack([base, base + du, base + du + dw, base + dw], axis=1)
            quads.append(corners if side > 0 else corners[:, ::-1])
    quads = np.concatenate(quads) - 1.0
    points, index = np.unique(quads.reshape(-1, 3), axis=0, return_inverse=True)
    q = index.reshape(-1, 4)
    faces = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    return points * step_mm, faces


def l_bracket(step_mm: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
    """An L bracket (base 100 x 50 x 8 mm on z = 0, upright 8 mm thick and 60 mm high at x = 0)
    with a 20 x 14 mm through-hole in the base: flat faces, sharp edges, genus 1."""
    def n(mm: float) -> int:
        return round(mm / step_mm)

    occupied = np.zeros((n(100), n(50), n(60)), dtype=bool)
    occupied[:, :, : n(8)] = True
    occupied[: n(8), :, :] = True
    occupied[n(50): n(70), n(18): n(32), : n(8)] = False
    return voxel_solid(occupied, step_mm)


def filleted_slab(length: float = 160.0, width: float = 100.0, thickness: float = 30.0, fillet: float = 10.0,
                  bore: float = 8.0, n_profile: int = 192, n_along: int = 80) -> tuple[np.ndarray, np.ndarray]:
    """A slab along y, its four long edges rounded with ``fillet`` (the profile in x, z a rounded
    rectangle), a bore of radius ``bore`` through it along y, flat end faces: smooth fillets, sharp
    end edges, genus 1. The profile is sampled at equal angles round its centre so that each end
    face is a strip of triangles between the outline and the bore."""
    angles = 2 * math.pi * np.arange(n_profile) / n_profile
    outline = np.array([_rounded_rectangle_hit(a, width / 2, thickness / 2, fillet) for a in angles])
    hole = bore * np.column_stack([np.cos(angles), np.sin(angles)])
    ys = np.linspace(0.0, length, n_along + 1)

    def tube(profile: np.ndarray, inward: bool) -> tuple[np.ndarray, np.ndarray]:
        v = np.array([[x, y, z] for y in ys for x, z in profile])
        i, j = np.meshgrid(np.arange(n_along), np.arange(n_profile), indexing="ij")
        a, b = i * n_profile + j, i * n_profile + (j + 1) % n_profile
        c, d = a + n_profile, b + n_profile
        f = np.concatenate([np.stack([a, c, b], -1).reshape(-1, 3), np.stack([b, c, d], -1).reshape(-1, 3)])
        return v, (f[:, ::-1] if inward else f)

    outer_v, outer_f = tube(outline, False)
    inner_v, inner_f = tube(hole, True)
    vertices = np.vstack([outer_v, inner_v])
    faces = [outer_f, inner_f + len(outer_v)]
    ring = np.arange(n_profile)
    for k, flip in ((0, True), (n_along, False)):  # the end faces: strips from outline to bore
        o, h = k * n_profile + ring, len(outer_v) + k * n_profile + ring
        o1, h1 = np.roll(o, -1), np.roll(h, -1)
        strip = np.concatenate([np.column_stack([o, h, o1]), np.column_stack([o1, h, h1])])
        faces.append(strip[:, ::-1] if flip else strip)
    return vertices, np.concatenate(faces)


def _rounded_rectangle_hit(angle: float, half_x: float, half_z: float, radius: float) -> tuple[float, float]:
    """Where the ray from the centre at ``angle`` (in x, z) meets a rounded rectangle."""
    d = np.array([math.cos(angle), math.sin(angle)])
    lo, hi = 0.0, 2 * (half_x + half_z)
    for _ in range(60):  # bisection on the signed distance of the rounded rectangle
        mid = 0.5 * (lo + hi)
        p = np.abs(mid * d)
        q = p - np.array([half_x - radius, half_z - radius])
        inside = np.linalg.norm(np.maximum(q, 0)) + min(max(q[0], q[1]), 0.0) - radius <= 0
        lo, hi = (mid, hi) if inside else (lo, mid)
    return tuple(0.5 * (lo + hi) * d)


def noisy_dome(radius: float = 120.0, cap_deg: float = 40.0, n: int = 90, noise_mm: float = 0.1,
               hole: tuple[float, float, float] = (25.0, 10.0, 12.0), seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """An open spherical cap (centre at the origin, pole +z) sampled like a scan: a grid in x, y
    lifted onto the sphere, each point moved along the radius by Gaussian noise of ``noise_mm``,
    with a hole of radius hole[2] at (hole[0], hole[1]) in x, y."""
    reach = radius * math.sin(math.radians(cap_deg))
    xs = np.linspace(-reach, reach, n + 1)
    x, y = np.meshgrid(xs, xs, indexing="ij")
    keep_point = x**2 + y**2 <= reach**2
    z = np.sqrt(np.maximum(radius**2 - x**2 - y**2, 0))
    rng = np.random.default_rng(seed)
    scale = (radius + rng.normal(0.0, noise_mm, x.shape)) / radius
    vertices = np.column_stack([(x * scale).ravel(), (y * scale).ravel(), (z * scale).ravel()])
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a = (i * (n + 1) + j).ravel()
    b, c, d = a + n + 1, a + 1, a + n + 2
    faces = np.concatenate([np.column_stack([a, b, d]), np.column_stack([a, d, c])])
    flat = keep_point.ravel()
    centre = vertices[faces, :2].mean(axis=1)
    outside_hole = np.hypot(centre[:, 0] - hole[0], centre[:, 1] - hole[1]) > hole[2]
    return vertices, faces[flat[faces].all(axis=1) & outside_hole]


def domed_flange(height: float = 35.0, base: float = 70.0, rim: float = 100.0, rings: int = 14,
                 around: int = 72) -> tuple[np.ndarray, np.ndarray]:
    """A spherical cap of base radius ``base`` and ``height`` standing on a flat ring out to
    ``rim`` (z = 0), as a lathe profile is meshed: rings of ``around`` vertices, a fan at the
    pole. The cap meets the ring at a sharp crease (53 deg for the defaults)."""
    sphere = (base**2 + height**2) / (2 * height)
    top = math.asin(base / sphere)
    profile = [(sphere * math.sin(p), sphere * math.cos(p) - (sphere - height)) for p in np.linspace(0, top, rings)[1:]]
    profile += [(r, 0.0) for r in np.linspace(base, rim, 5)[1:]]
    t = np.linspace(0, 2 * math.pi, around, endpoint=False)
    vertices = np.vstack([[0.0, 0.0, height]] + [np.column_stack([r * np.cos(t), r * np.sin(t), np.full(around, z)])
                                                 for r, z in profile])
    k = np.arange(around)
    faces = [np.column_stack([np.zeros(around, int), 1 + k, 1 + (k + 1) % around])]
    for ring in range(len(profile) - 1):
        a, b = 1 + ring * around + k, 1 + ring * around + (k + 1) % around
        faces += [np.column_stack([a, a + around, b + around]), np.column_stack([a, b + around, b])]
    return vertices, np.vstack(faces)


def plate_with_arm(step_mm: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
    """A plate 100 x 60 x 6 mm with an arm 8 mm wide and 50 mm long (narrower than a spacing
    of 10 mm) off one side, as a closed solid of flat faces."""
    def n(mm: float) -> int:
        return round(mm / step_mm)

    occupied = np.zeros((n(150), n(60), n(6)), dtype=bool)
    occupied[: n(100)] = True
    occupied[n(100):, n(26): n(34)] = True
    return voxel_solid(occupied, step_mm)

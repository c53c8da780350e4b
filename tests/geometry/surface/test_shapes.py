"""The parts of the shipped 3-D scenarios: built from their formulas byte for byte as committed,
with the shape each formula promises (closed forms for the tube and the plate, a watertight
blade, an open scan with one hole)."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

from coatsim.geometry.surface.shapes import SHAPES, stl_bytes, tube, twisted_blade, wear_plate, scan_patch

ROOT = Path(__file__).resolve().parents[3]


def mesh(vertices: np.ndarray, faces: np.ndarray) -> trimesh.Trimesh:
    return trimesh.Trimesh(vertices, faces, process=True)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_the_committed_parts_are_their_formulas(name: str) -> None:
    vertices, faces = SHAPES[name]()
    assert (ROOT / "scenarios" / "parts" / f"{name}.stl").read_bytes() == stl_bytes(vertices, faces, name)


def test_the_script_checks_the_committed_files() -> None:
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_scenario_parts.py"), "--check"],
                          capture_output=True, text=True, env={"PYTHONPATH": str(ROOT)})
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_tube_is_a_faceted_cylinder_with_outward_normals() -> None:
    r, length, around = 60.0, 200.0, 64
    m = mesh(*tube(r, length, around))
    assert m.area == pytest.approx(around * 2 * r * math.sin(math.pi / around) * length, rel=1e-12)
    centres = m.triangles_center
    radial = centres[:, 1:] / np.linalg.norm(centres[:, 1:], axis=1)[:, None]
    assert (np.einsum("ij,ij->i", m.face_normals[:, 1:], radial) > 0.99).all()
    assert len(m.outline().entities) == 2  # open at both ends


def test_the_blade_is_watertight_outward_and_twisted() -> None:
    vertices, faces = twisted_blade(twist_deg=30.0)
    m = mesh(vertices, faces)
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    # the chord line (trailing edge to nose) turns by the twist from root to tip
    chord = []
    for y in (vertices[:, 1].min(), vertices[:, 1].max()):
        ring = vertices[np.isclose(vertices[:, 1], y)]
        tail, nose = ring[np.argmax(ring[:, 0])], ring[np.argmin(ring[:, 0])]
        chord.append(math.degrees(math.atan2(tail[2] - nose[2], tail[0] - nose[0])))
    assert abs(chord[1] - chord[0]) == pytest.approx(30.0, abs=0.5)


def test_the_wear_plate_has_its_ridges() -> None:
    vertices, faces = wear_plate(height_mm=12.0, pitch_mm=60.0)
    m = mesh(vertices, faces)
    assert vertices[:, 2].max() == pytest.approx(12.0) and vertices[:, 2].min() == pytest.approx(0.0, abs=1e-12)
    crests = np.unique(np.round(vertices[np.isclose(vertices[:, 2], 12.0), 0], 6))
    assert np.allclose(np.diff(crests), 60.0)
    x = np.linspace(-30, 30, 2001)  # the default's valleys are wider than the stand-off (122 mm radius)
    z = 3.0 * (1 + np.cos(2 * np.pi * x / 120.0))
    curvature = np.abs(np.gradient(np.gradient(z, x), x)) / (1 + np.gradient(z, x) ** 2) ** 1.5
    assert 1 / curvature.max() == pytest.approx(120.0**2 / (2 * np.pi**2 * 6.0), rel=1e-3)
    assert 1 / curvature.max() > 100.0
    assert (m.face_normals[:, 2] > 0).all()


def test_the_scan_is_open_with_one_hole_and_its_noise() -> None:
    vertices, faces = scan_patch(noise_mm=0.15, hole_mm=22.0)
    m = mesh(vertices, faces)
    assert len(m.outline().entities) == 2  # the square's border and the hole
    assert (m.face_normals[:, 2] > 0).all()
    smooth, _ = scan_patch(noise_mm=0.0, hole_mm=22.0)
    assert np.std(vertices[:, 2] - smooth[:, 2]) == pytest.approx(0.15, rel=0.1)


def test_the_scans_points_keep_its_resolution_and_its_noise_makes_no_sharp_edge() -> None:
    """Points at least the resolution apart (Poisson disk): no sliver that the 0.15 mm noise could
    tilt into a crease, so the planner finds no sharp edge on the sheet (uniform random points
    left 65 edges of up to 95 deg on the earlier 200 mm sheet)."""
    from scipy.spatial import cKDTree

    from coatsim.geometry.surface.features import SHARP_EDGE_DEG, smooth_pairs
    from coatsim.geometry.surface.normals import face_normals
    from coatsim.geometry.surface.topology import face_pairs, mesh_edges

    vertices, faces = scan_patch(size_mm=200.0, spacing_mm=4.0, noise_mm=0.15, hole_mm=22.0)
    inner = vertices[(np.abs(vertices[:, :2]) < 100.0 - 1e-9).all(axis=1), :2]
    assert cKDTree(inner).query(inner, k=2)[0][:, 1].min() >= 4.0 * (1 - 1e-9)
    normals = face_normals(vertices, faces)[0]
    assert len(smooth_pairs(faces, normals)) == len(face_pairs(faces, mesh_edges(faces))[0])
    pairs = face_pairs(faces, mesh_edges(faces))[0]
    largest = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals[pairs[:, 0]], normals[pairs[:, 1]]), -1, 1)))
    assert 5.0 < largest.max() < SHARP_EDGE_DEG / 2  # noisy, yet far from a crease

"""Surfaces: plates, cylinders and mesh files (each format), placement, areas, normals, borders."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from coatsim.core.errors import InputError
from coatsim.spray.deposition import deposit
from coatsim.spray.surfaces import border_distance, cylinder, mesh_file, parse_surface_spec, plate
from spray_helpers import H0, Q, gun, stationary_log, volume


def face_normals(surface):
    v, f = surface.vertices, surface.faces
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    return n / np.linalg.norm(n, axis=1)[:, None]


def test_plate_grid_areas_normals_and_placement():
    s = parse_surface_spec("plate:300x200@10,-20,5", 5 / 3)
    assert s.kind == "plate" and s.name == "plate:300x200@10,-20,5"
    assert s.n_vertices == 181 * 121
    assert s.area_mm2 == pytest.approx(300 * 200, rel=1e-12)
    np.testing.assert_allclose(s.vertices.min(axis=0), [-140, -120, 5])
    np.testing.assert_allclose(s.vertices.max(axis=0), [160, 80, 5])
    np.testing.assert_array_equal(s.normals, np.tile([0, 0, 1.0], (s.n_vertices, 1)))
    np.testing.assert_allclose(face_normals(s), np.tile([0, 0, 1.0], (len(s.faces), 1)), atol=1e-12)
    interior = np.all(np.abs(s.vertices[:, :2] - [10, -20]) < [149, 99], axis=1)
    assert np.allclose(s.areas[interior], (300 / 180) * (200 / 120))


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_cylinder_normals_outward_and_unrolled_view(axis):
    s = parse_surface_spec(f"cylinder:40x120@0,0,-40,{axis}", 2.0)
    k = "xyz".index(axis)
    radial = s.vertices - [0, 0, -40]
    radial[:, k] = 0
    assert np.allclose(np.linalg.norm(radial, axis=1), 40)
    np.testing.assert_allclose(s.normals, radial / 40, atol=1e-12)
    centroid = s.vertices[s.faces].mean(axis=1) - [0, 0, -40]
    centroid[:, k] = 0
    assert np.all(np.einsum("ij,ij->i", face_normals(s), centroid) > 0)  # triangles face outward
    n_phi = math.ceil(2 * math.pi * 40 / 2.0)
    assert s.area_mm2 == pytest.approx(2 * math.pi * 40 * 120 * math.sin(math.pi / n_phi) / (math.pi / n_phi), rel=1e-9)
    assert s.view[:, 0].min() == pytest.approx(-60) and s.view[:, 1].max() == pytest.approx(40 * math.pi)
    top = np.argmin(np.abs(s.view).sum(axis=1))  # view origin: angle 0, middle of the length
    assert np.allclose(s.vertices[top], [40, 0, -40] if axis == "z" else [0, 0, 0])


def test_cylinder_seam_is_not_a_border():
    s = cylinder(30, 100, 2.5)
    d = border_distance(s, 2.5)
    along = s.vertices[:, 0]
    np.testing.assert_allclose(d, 50 - np.abs(along), atol=2.5 / 16 + 1e-9)


def test_plate_border_distance():
    s = plate(100, 60, 2.0)
    d = border_distance(s, 2.0)
    x, y = s.vertices[:, 0], s.vertices[:, 1]
    np.testing.assert_allclose(d, np.minimum(50 - np.abs(x), 30 - np.abs(y)), atol=2.0 / 16 + 1e-9)


def test_closed_mesh_has_no_border(tmp_path):
    path = tmp_path / "box.stl"
    trimesh.creation.box((40, 40, 10)).export(path)
    assert np.all(np.isinf(border_distance(mesh_file(path, 5.0))))


@pytest.mark.parametrize("ext", ["stl", "ply", "obj", "glb"])
def test_mesh_file_in_every_format_coats_like_the_builtin_plate(tmp_path, ext):
    box = trimesh.creation.box((120, 120, 4))
    box.apply_translation((0, 0, -2))  # top face at z = 0
    path = tmp_path / f"part.{ext}"
    box.export(path)
    surface = parse_surface_spec(f"{path}@0,0,-10", 2.0)
    assert surface.kind == "mesh"
    edges = surface.vertices[surface.faces] - surface.vertices[surface.faces[:, [1, 2, 0]]]
    assert np.linalg.norm(edges, axis=2).max() <= 2.0 + 1e-9
    assert surface.area_mm2 == pytest.approx(box.area, rel=1e-9)
    assert surface.vertices[:, 2].max() == pytest.approx(-10)
    result = deposit(surface, stationary_log((0, 0, H0 - 10), 1.0), gun())
    assert volume(surface, result.thickness_mm) == pytest.approx(Q, rel=1e-3)
    bottom = surface.vertices[:, 2] < -13
    assert np.all(result.thickness_mm[bottom] == 0)
    reference = deposit(plate(120, 120, 2.0), stationary_log((0, 0, H0), 1.0), gun())
    assert result.thickness_um.max() == pytest.approx(reference.thickness_um.max(), rel=0.02)


def test_mesh_rotated_by_pose(tmp_path):
    path = tmp_path / "sheet.stl"
    trimesh.creation.box((50, 20, 2)).export(path)
    pose = np.eye(4)
    pose[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]  # 90 degrees about z
    s = mesh_file(path, 5.0, pose)
    extent = np.ptp(s.vertices, axis=0)
    np.testing.assert_allclose(extent, [20, 50, 2], atol=1e-9)


@pytest.mark.parametrize("spec, words", [
    ("plate:0x100", "plate size must be between 0.001 and 1e\\+09 mm"),
    ("plate:1e-9x300", "plate size must be between"),
    ("cylinder:1e-300x300@0,0,0", "cylinder size must be between"),
    ("plate:1e12x300", "plate size must be between"),
    ("plate:100", "expected plate"),
    ("plate:100x100@1,2", "x,y,z"),
    ("cylinder:10x100@0,0,0,w", "axis must be x, y or z"),
    ("/nonexistent/part.stl", "no such file"),
])
def test_bad_surface_specs(spec, words):
    with pytest.raises(InputError, match=words):
        parse_surface_spec(spec, 2.0)


@pytest.mark.parametrize("spacing", [0.0, -1.0, float("nan")])
def test_non_positive_spacing_is_refused(spacing):
    with pytest.raises(InputError, match="spacing must be a positive"):
        parse_surface_spec("plate:100x100", spacing)


def test_empty_and_unreadable_meshes(tmp_path):
    empty = tmp_path / "empty.ply"
    empty.write_text("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n")
    with pytest.raises(InputError, match="no triangles"):
        mesh_file(empty, 2.0)
    garbage = tmp_path / "junk.stl"
    garbage.write_bytes(b"\x00\x01garbage")
    with pytest.raises(InputError, match="junk.stl"):
        mesh_file(garbage, 2.0)
    big = tmp_path / "big.stl"
    trimesh.creation.box((1000, 1000, 1000)).export(big)
    with pytest.raises(InputError, match="larger spacing"):
        mesh_file(big, 0.001)


@pytest.mark.parametrize("scale, units, said", [(1.0, "mm", False), (25.4, "in", False), (1000.0, "m", False),
                                               (1000.0, "auto", True), (1.0, "auto", True)])
def test_a_mesh_surface_is_read_in_its_units(tmp_path, scale, units, said):
    """A 120 x 80 mm sheet written in inches or metres is coated at its size in mm (read in the
    file's numbers, a sheet in metres was 0.12 mm wide and the spray missed it); auto guesses
    from the extent as plan does, with a warning."""
    import warnings as w

    from coatsim.core.errors import CoatsimWarning

    sheet = trimesh.creation.box(extents=(120.0 / scale, 80.0 / scale, 2.0 / scale))
    path = tmp_path / "sheet.stl"
    sheet.export(path)
    with w.catch_warnings(record=True) as caught:
        w.simplefilter("always")
        surface = parse_surface_spec(f"{path}@700,0,200", 4.0, units)
    assert np.allclose(np.ptp(surface.vertices, axis=0), [120.0, 80.0, 2.0], rtol=1e-6)
    assert np.allclose(surface.vertices.mean(axis=0)[:2], [700.0, 0.0], atol=1.0)
    assert any("units auto" in str(c.message) for c in caught if issubclass(c.category, CoatsimWarning)) is said
    with pytest.raises(InputError, match="units must be one of mm, cm, m, in, auto, found 'ft'"):
        parse_surface_spec(str(path), 4.0, "ft")

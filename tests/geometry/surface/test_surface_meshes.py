"""Real meshes: every file format, the repairs a scan or an export needs, and one line for each
mesh that cannot be used."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from coatsim.core.budgets import MAX_PLAN_MESH_BYTES
from coatsim.core.errors import InputError
from coatsim.geometry.surface import Everything, Facing, load_part, part_from_arrays, plan
from coatsim.geometry.surface.normals import face_normals, orient
from surface_helpers import grid, options


@pytest.mark.parametrize("suffix, kind", [(".stl", "stl"), (".stl", "stl_ascii"), (".ply", "ply"), (".obj", "obj"),
                                          (".off", "off"), (".glb", "glb")])
def test_every_format_reads_the_same_part(tmp_path, suffix, kind):
    box = trimesh.creation.box((100.0, 80.0, 20.0))
    path = tmp_path / f"box{suffix}"
    box.export(path, file_type=kind)
    part = load_part(path, units="mm")
    assert len(part.faces) == 12 and len(part.vertices_mm) == 8
    assert np.ptp(part.vertices_mm, axis=0) == pytest.approx([100.0, 80.0, 20.0])
    assert len(part.sha256) == 64


def test_glb_is_metres_by_its_specification(tmp_path):
    box = trimesh.creation.box((0.1, 0.08, 0.02))
    box.export(tmp_path / "box.glb")
    part = load_part(tmp_path / "box.glb")
    assert part.units == "m" and np.ptp(part.vertices_mm, axis=0) == pytest.approx([100.0, 80.0, 20.0])
    assert any("the file says m" in n for n in part.notes)


@pytest.mark.parametrize("units, scale", [("mm", 1.0), ("cm", 10.0), ("m", 1000.0), ("in", 25.4)])
def test_units_scale_the_part_to_millimetres(units, scale):
    vertices, faces = grid(2.0, 1.0, 2, 1)
    part = part_from_arrays(vertices, faces, units=units)
    assert np.ptp(part.vertices_mm, axis=0)[:2] == pytest.approx([2.0 * scale, 1.0 * scale])


def test_auto_units_say_what_they_chose():
    vertices, faces = grid(0.3, 0.2, 3, 2)
    assert "read as metres" in part_from_arrays(vertices, faces, units="auto").notes[0]
    assert "read as millimetres" in part_from_arrays(vertices * 1000, faces, units="auto").notes[0]


def _write(path, text: str | bytes):
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


BAD = {
    "missing.stl": (None, "no such file"),
    "part.txt": ("1 2 3", "not a mesh file"),
    "empty.stl": (b"", "no triangles"),
    "text.stl": ("hello\n", "no triangles"),
    "cloud.ply": ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "end_header\n0 0 0\n1 0 0\n0 1 0\n", "no triangles"),
    "nan.obj": ("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "not numbers"),
    "line.obj": ("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "degenerate"),
    "point.obj": ("v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n", "no extent"),
    "index.obj": ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "cannot read"),
    "broken.glb": (b"glTF\x02\x00\x00\x00garbage", "cannot read"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_every_bad_mesh_gets_its_one_line(tmp_path, name, run_cli):
    text, words = BAD[name]
    path = tmp_path / name if text is None else _write(tmp_path / name, text)
    with pytest.raises(InputError, match=words):
        load_part(path)
    code, out, err = run_cli(["plan", str(path), "-o", str(tmp_path / "paths.json")])
    assert code == 2 and out == "" and len(err.splitlines()) == 1 and err.startswith("coatsim: error: ")
    assert words in err and not (tmp_path / "paths.json").exists()


def test_a_truncated_binary_stl_is_refused(tmp_path):
    trimesh.creation.box((10.0, 20.0, 30.0)).export(tmp_path / "box.stl")
    data = (tmp_path / "box.stl").read_bytes()
    _write(tmp_path / "cut.stl", data[: len(data) // 2])
    with pytest.raises(InputError, match="truncated or damaged"):
        load_part(tmp_path / "cut.stl")


@pytest.mark.parametrize("cut", [0.5, 0.999])
def test_an_ascii_stl_cut_off_is_refused_as_truncated_not_as_a_point_cloud(tmp_path, cut):
    """A cut-off ASCII STL read as nothing at all: it was called a point cloud to mesh."""
    trimesh.creation.icosphere().export(tmp_path / "ball.stl", file_type="stl_ascii")
    data = (tmp_path / "ball.stl").read_bytes()
    assert len(load_part(tmp_path / "ball.stl").faces) == 1280
    _write(tmp_path / "cut.stl", data[: int(len(data) * cut)])
    with pytest.raises(InputError, match=r"the ASCII STL is cut off \(\d+ facets begun, \d+ ended.*truncated or damaged"):
        load_part(tmp_path / "cut.stl")


def test_a_file_over_the_budget_is_refused_before_reading(tmp_path):
    path = tmp_path / "huge.stl"
    with open(path, "wb") as handle:
        handle.truncate(MAX_PLAN_MESH_BYTES + 1)
    with pytest.raises(InputError, match="over the budget"):
        load_part(path)


def test_a_tiny_spacing_is_refused_before_refining():
    vertices, faces = grid(1000.0, 1000.0, 2, 2)
    with pytest.raises(InputError, match="over the budget.*spacing_mm") as info:
        plan(part_from_arrays(vertices, faces), options(spacing_mm=0.05))
    assert "spacing_mm" in info.value.parameters


def test_duplicates_degenerate_and_duplicate_triangles_are_repaired():
    vertices, faces = grid(100.0, 50.0, 10, 5)
    soup = vertices[faces].reshape(-1, 3)  # every corner stored per triangle, as an STL does
    soup_faces = np.arange(len(soup)).reshape(-1, 3)
    extra = np.array([[0, 0, 0], [0, 1, 3]])  # a collapsed and a zero-area triangle
    twice = np.vstack([soup_faces, soup_faces[:5], extra])
    part = part_from_arrays(soup, twice)
    assert len(part.faces) == len(faces) and len(part.vertices_mm) == len(vertices)
    notes = " ".join(part.notes)
    assert "merged" in notes and "degenerate" in notes and "duplicate triangle" in notes


def test_slivers_along_an_edge_rounded_off_its_line_are_dropped_and_the_plan_is_the_clean_ones():
    """A triangle (a, midpoint of ab written to 6 decimals, b) is a sliver a micrometre thin lying on
    the edge ab: a third face on that edge, with a meaningless normal. It is degenerate at the
    part's resolution and dropped, so the plan is that of the part without it."""
    vertices, faces = grid(120.0, 60.0, 12, 6)
    vertices[:, 2] = 8.0 * np.sin(vertices[:, 0] / 40.0)
    rng = np.random.default_rng(3)
    extra_v, extra_f = [], []
    for k, f in enumerate(faces[rng.choice(len(faces), 20, replace=False)]):
        a, b = vertices[f[0]], vertices[f[1]]
        extra_v.append(np.round((a + b) / 2 + [1e-6, -1e-6, 1e-6], 6))
        extra_f.append([f[0], len(vertices) + k, f[1]])
    part = part_from_arrays(np.vstack([vertices, extra_v]), np.vstack([faces, extra_f]))
    assert len(part.faces) == len(faces) and "dropped 20 degenerate triangle(s)" in " ".join(part.notes)
    clean = plan(part_from_arrays(vertices, faces), options(region=Facing((0.0, 0.0, 1.0), 60.0)))
    dirty = plan(part, options(region=Facing((0.0, 0.0, 1.0), 60.0)))
    assert len(dirty.passes) == len(clean.passes)


def test_flipped_triangles_are_turned_and_the_passes_do_not_change():
    vertices, faces = grid(120.0, 80.0, 24, 16)
    rng = np.random.default_rng(3)
    flipped = faces.copy()
    some = rng.random(len(faces)) < 0.3
    flipped[some] = flipped[some][:, ::-1]
    clean = plan(part_from_arrays(vertices, faces), options(step_direction=(0, 1, 0)))
    messy = plan(part_from_arrays(vertices, flipped), options(step_direction=(0, 1, 0)))
    assert any("turned" in n for n in messy.notes)
    assert len(clean.passes) == len(messy.passes)
    for a, b in zip(clean.passes, messy.passes):
        assert np.allclose(a.points, b.points, atol=1e-6) and np.allclose(a.normals, b.normals, atol=1e-6)


def test_a_scan_facing_down_in_the_file_is_turned_toward_the_gun():
    vertices, faces = grid(120.0, 80.0, 12, 8)
    paths = plan(part_from_arrays(vertices, faces[:, ::-1]), options(region=Facing((0, 0, 1))))
    assert all(np.allclose(p.normals, [0, 0, 1]) for p in paths.passes)


def test_a_non_manifold_fin_and_a_bow_tie_are_split_and_planned():
    vertices, faces = grid(100.0, 60.0, 10, 6)
    n = len(vertices)
    # a fin standing on an inner edge of the plate (that edge gets three triangles)
    a, b = 3 * 11 + 2, 3 * 11 + 3
    fin = np.array([vertices[a] + [0, 0, 20.0]])
    # a second plate touching the first at its corner (100, 60): a bow-tie vertex
    corner = 6 * 11 + 10
    other = np.array([[110.0, 60.0, 0.0], [100.0, 70.0, 0.0], [110.0, 70.0, 0.0]])
    vertices = np.vstack([vertices, fin, other])
    faces = np.vstack([faces, [[a, b, n]], [[corner, n + 1, n + 3], [corner, n + 3, n + 2]]])
    paths = plan(part_from_arrays(vertices, faces), options(region=Everything(), step_direction=(0, 1, 0),
                                                            spacing_mm=10.0))
    assert any("not manifold" in note for note in paths.notes)
    points = np.concatenate([p.points for p in paths.passes])
    assert points[:, 1].min() == pytest.approx(5.0) and points[:, 0].max() <= 110.0 + 1e-9


def test_islands_smaller_than_a_spacing_squared_are_left_out():
    vertices, faces = grid(100.0, 60.0, 10, 6)
    speck = np.array([[200.0, 0, 0], [205.0, 0, 0], [200.0, 5.0, 0]])
    part = part_from_arrays(np.vstack([vertices, speck]), np.vstack([faces, [[len(vertices), len(vertices) + 1,
                                                                             len(vertices) + 2]]]))
    paths = plan(part, options(region=Facing((0, 0, 1)), step_direction=(0, 1, 0)))
    assert any("island" in n for n in paths.notes)
    assert max(p.points[:, 0].max() for p in paths.passes) <= 100.0 + 1e-9
    assert paths.stats.coverage < 1.0  # the speck is part of the region's area and is not covered


def test_a_box_round_one_side_of_a_closed_part_is_sprayed_from_that_side():
    """A box region round the +x side face of a closed box: the gun comes from +x (the mean normal
    of the faces in the box), so the whole side face is planned, not only what a ray to the part's
    default side (+z) leaves."""
    from coatsim.geometry.surface import Box

    box = trimesh.creation.box((100.0, 80.0, 60.0))
    box = box.subdivide().subdivide()
    part = part_from_arrays(np.asarray(box.vertices), np.asarray(box.faces), "box")
    side = plan(part, options(region=Box((45.0, -50.0, -40.0), (55.0, 50.0, 40.0))))
    points = np.vstack([p.points for p in side.passes])
    assert np.allclose(points[:, 0], 50.0, atol=1e-6)  # on the +x face
    assert np.ptp(points[:, 2]) > 40.0  # across its height, not a strip along its top edge
    assert any("box region: the gun comes from (1, 0, 0)" in n for n in side.notes), side.notes


@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (0.6, 0.0, 0.8)])
def test_caps_that_the_raster_planes_cross_edge_on_get_their_own_passes(axis):
    """Region all on a closed cylinder, stepping along its axis: the rings cover the side and
    each cap (flat, facing the step) is rastered across its own longest axis, with a note; with
    one step for all the caps got no pass (coverage 72 % on a held-out part)."""
    axis = np.asarray(axis) / np.linalg.norm(axis)
    cylinder = trimesh.creation.cylinder(radius=50.0, height=120.0, sections=64)
    cylinder.apply_transform(trimesh.geometry.align_vectors([0.0, 0.0, 1.0], axis))
    cylinder = cylinder.subdivide_to_size(8.0)
    part = part_from_arrays(np.asarray(cylinder.vertices), np.asarray(cylinder.faces), "cylinder")
    paths = plan(part, options(region=Everything(), step_direction=tuple(axis)))
    height = np.vstack([p.points for p in paths.passes]) @ axis
    for cap in (-60.0, 60.0):
        on_cap = [p for p in paths.passes if np.allclose(p.points @ axis, cap, atol=1e-6)]
        assert len(on_cap) >= 5, f"cap at {cap}: {len(on_cap)} passes"
    assert np.isclose(height.min(), -60.0) and np.isclose(height.max(), 60.0)
    assert paths.stats.coverage > 0.95
    assert any("rastered along their own longest axis" in n for n in paths.notes), paths.notes


@pytest.mark.parametrize("length", [200.0, 60.0])
def test_an_open_pipe_wound_inwards_is_turned_outwards_when_seen_from_its_side(length):
    """A tube without its ends, its axis across the gun's way: its net facing towards the gun is
    nil, so the facing decides nothing; its volume about its own centre does (a short stub too)."""
    t = np.linspace(0, 2 * np.pi, 49)[:-1]
    ring = np.column_stack((np.zeros_like(t), 40 * np.cos(t), 40 * np.sin(t)))
    vertices = np.vstack([ring + [x, 0, 0] for x in np.linspace(0, length, 11)])
    faces = []
    for i in range(10):
        for k in range(48):
            a, b, c, d = i * 48 + k, i * 48 + (k + 1) % 48, (i + 1) * 48 + k, (i + 1) * 48 + (k + 1) % 48
            faces += [[a, b, d], [a, d, c]]
    faces = np.array(faces)
    for wound in (faces, faces[:, ::-1]):
        oriented = orient(vertices, wound, np.array([0.0, 0.0, 1.0]))
        normals, _ = face_normals(vertices, oriented.faces)
        centres = vertices[oriented.faces].mean(axis=1)
        radial = centres * [0.0, 1.0, 1.0]
        assert (np.einsum("ij,ij->i", normals, radial) > 0).all()

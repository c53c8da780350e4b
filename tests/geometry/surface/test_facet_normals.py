"""Parts exported in flat facets: the pass points and normals of the smooth surface the facets
approximate, not of the facets."""

from __future__ import annotations

import numpy as np
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry.surface import Facing
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.geometry.surface.normals import Facets, corner_normals, face_normals
from surface_helpers import box_part, planned, tube


def dome(radius: float, subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    """The faces of an icosphere above z = 0 (a CAD dome's STL: facets of about 6.6 mm at radius
    100 and 4 subdivisions, 0.05-0.1 mm from the sphere)."""
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    keep = sphere.triangles_center[:, 2] > 0
    used, faces = np.unique(sphere.faces[keep], return_inverse=True)
    return np.asarray(sphere.vertices)[used], faces.reshape(-1, 3)


def angle_deg(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", a, b), -1.0, 1.0)))


def test_corner_normals_are_exact_on_a_sphere_and_keep_a_box_faces_apart():
    vertices, faces = dome(100.0, 3)
    split, corner = corner_normals(vertices, faces)
    assert len(corner) == len(vertices)  # no sharp edge on a dome: one fan a vertex
    radial = vertices / np.linalg.norm(vertices, axis=1)[:, None]
    inner = vertices[faces, 2] > 20.0  # corners with a full fan of faces (Max's weights are exact there)
    assert angle_deg(corner[split[inner]], radial[faces[inner]]).max() < 1e-5
    box = box_part((80.0, 60.0, 20.0))
    split, corner = corner_normals(box.vertices_mm, box.faces)
    face_n = face_normals(box.vertices_mm, box.faces)[0]
    for k in range(3):  # every corner of a box's face carries that face's own normal
        assert angle_deg(corner[split[:, k]], face_n).max() < 1e-5


@settings(max_examples=25, deadline=None)
@given(st.floats(0.05, 0.95), st.floats(0.05, 0.95), st.integers(0, 10**6))
def test_points_in_a_facet_get_the_sphere_normal_through_them(u: float, v: float, seed: int):
    """Linear interpolation of exact corner normals across a facet of a sphere gives the
    direction of the point itself: sum b_i v_i / R."""
    vertices, faces = dome(100.0, 2)
    inner = np.flatnonzero((vertices[faces, 2] > 30.0).all(axis=1))  # corners with full fans
    face = inner[np.random.default_rng(seed).integers(len(inner))]
    w = np.array([u, (1 - u) * v, (1 - u) * (1 - v)])
    point = (w @ vertices[faces[face]])[None, :]
    side = face_normals(vertices, faces)[0][[face]]
    facets = Facets.of(vertices, faces, 5.0)
    assert angle_deg(facets.normals(point, side), point / np.linalg.norm(point))[0] < 1e-5
    # lifted onto the sphere: 1.8 mm below it on these 26 mm facets, within 0.05 mm after
    lifted = facets.lifted(point, side)
    assert abs(np.linalg.norm(lifted) - 100.0) < 0.05 + 1e-3 * (100.0 - np.linalg.norm(point))
    assert np.linalg.norm(lifted - point) <= facets.largest_lift_mm()


@settings(max_examples=25, deadline=None)
@given(st.floats(0.0, 1.0), st.floats(0.0, 1.0), st.integers(0, 10**6))
def test_a_chord_of_a_faceted_cylinder_is_lifted_onto_its_circle_and_a_box_face_stays(u: float, v: float, seed: int):
    vertices, faces = tube(60.0, 200.0, 48, 4)
    facets = Facets.of(vertices, faces, 5.0)
    face = np.random.default_rng(seed).integers(len(faces))
    w = np.array([u, (1 - u) * v, (1 - u) * (1 - v)])
    point = (w @ vertices[faces[face]])[None, :]
    lifted = facets.lifted(point, facets.face_n[[face]])
    assert abs(np.hypot(*lifted[0, :2]) - 60.0) < 1e-3  # the chords sag by up to 0.128 mm
    assert abs(lifted[0, 2] - point[0, 2]) < 1e-9
    box = box_part((80.0, 60.0, 20.0))
    facets = Facets.of(box.vertices_mm, box.faces, 5.0)
    on_face = (w @ box.vertices_mm[box.faces[face % len(box.faces)]])[None, :]
    assert np.allclose(facets.lifted(on_face, facets.face_n[[face % len(box.faces)]]), on_face, atol=1e-12)


def test_a_dome_in_coarse_facets_plans_with_the_sphere_normals():
    """The refined mesh's vertices lie on the file's facets; before, their normals stepped from
    facet to facet (0.1-0.3 deg here: 0.2-0.5 mm at a 100 mm stand-off)."""
    vertices, faces = dome(100.0, 4)
    paths = planned(vertices, faces, region=Facing((0, 0, 1), 60.0))
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    radial = points / np.linalg.norm(points, axis=1)[:, None]
    inner = np.linalg.norm(points[:, :2], axis=1) < 60.0  # a smoothing length and more inside the region's rim
    assert inner.sum() > 100
    assert angle_deg(normals[inner], radial[inner]).max() < 0.02


def test_a_faceted_cylinder_plans_circles_a_single_arc_each():
    """A tube in 48 facets (its chords sag by 0.128 mm, more than the 0.1 mm tolerance from the
    circle): passes round it lie on the circle, and the tool points 100 mm out fit one arc each
    (they fitted 10 to 12 arcs each before)."""
    vertices, faces = tube(60.0, 120.0, 48, 6)
    paths = planned(vertices, faces, region=Facing((1, 0, 0), 60.0), step_direction=(0, 0, 1))
    assert len(paths.passes) >= 8
    for p in paths.passes:
        assert np.abs(np.hypot(p.points[:, 0], p.points[:, 1]) - 60.0).max() < 1e-3
        fit = segment_space_curve(make_space_curve(p.points + 100.0 * p.normals, "pass", "no"), 0.1)
        assert fit.chain.n_segments == fit.chain.n_arcs == 1


def test_points_lifted_into_a_concave_waist_pass_the_check():
    """A closed spool whose waist is concave along its axis, in coarse rings (their chords along
    the axis sag 0.2 mm outward of the smooth waist): the points lifted onto the waist lie inside
    the facets, and the check still finds every normal pointing out of the part."""
    z = np.linspace(0.0, 100.0, 9)
    profile = np.column_stack([40.0 - 10.0 * np.sin(np.pi * z / 100.0), z])
    outline = np.vstack([[0.0, 0.0], profile, [0.0, 100.0]])
    spool = trimesh.creation.revolve(outline, sections=64)
    assert spool.is_watertight
    paths = planned(np.asarray(spool.vertices), np.asarray(spool.faces), region=Facing((1, 0, 0), 60.0),
                    step_direction=(0, 0, 1))
    points = np.concatenate([p.points for p in paths.passes])
    waist = 40.0 - 10.0 * np.sin(np.pi * points[:, 2] / 100.0)
    assert np.abs(np.hypot(points[:, 0], points[:, 1]) - waist).max() < 0.05  # on the smooth waist


@settings(max_examples=20, deadline=None)
@given(st.floats(-75.0, 75.0), st.floats(-35.0, 35.0))
def test_a_capsule_side_of_long_strips_gets_the_cylinder_normal(x: float, y: float):
    """CAD's capsule: a cylinder in strips 160 mm long between two domes in small facets. The
    strips' end corners are shared with the domes, whose facets tilt them along the axis; the
    tilt interpolated along a strip put the normal 1.7 deg off 10 mm from a dome (0 in the middle)."""
    capsule = trimesh.creation.capsule(height=160.0, radius=40.0, count=[48, 48])
    capsule.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    capsule.merge_vertices()
    facets = Facets.of(np.asarray(capsule.vertices), np.asarray(capsule.faces), 5.0)
    hit, _, _ = capsule.ray.intersects_location([[x, y, 100.0]], [[0.0, 0.0, -1.0]], multiple_hits=False)
    radial = hit * [0.0, 1.0, 1.0]
    radial /= np.linalg.norm(radial)
    assert angle_deg(facets.normals(hit, np.array([[0.0, 0.0, 1.0]])), radial)[0] < 0.2

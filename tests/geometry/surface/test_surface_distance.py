"""Distances on meshes against exact ones: the heat method (and where it bends near open borders),
fast marching, the arc estimate; and the mesh machinery under the patterns."""

from __future__ import annotations

import math

import numpy as np
import potpourri3d as pp3d
import pytest
import trimesh

from coatsim.geometry.surface.boxes import SmallTriangles
from coatsim.geometry.surface.contours import level_curves
from coatsim.geometry.surface.distance import (
    NearestOnCurves,
    arc_length,
    distance_levels,
    heat_distance,
    marching_distance,
)
from coatsim.geometry.surface.geodesic import FromBoundary, FromPlane, FromPoints, assign_points, geodesic_piece
from coatsim.geometry.surface.normals import vertex_normals
from coatsim.geometry.surface.piece import Piece
from coatsim.geometry.surface.refine import delaunay_flips, refined
from coatsim.geometry.surface.topology import border_vertices, manifold_split, mesh_edges
from surface_helpers import grid, plate_with_hole


def _piece(vertices, faces) -> Piece:
    border = border_vertices(len(vertices), mesh_edges(faces))
    return Piece(vertices, faces, vertex_normals(vertices, faces), np.where(border, 0.0, 1.0))


@pytest.fixture(scope="module")
def jittered():
    """A 100 x 100 mm plate, 1 mm grid with every inner vertex moved up to 0.25 mm: a scan-like mesh."""
    vertices, faces = grid(100.0, 100.0, 100, 100)
    inner = (vertices[:, 0] > 0) & (vertices[:, 0] < 100) & (vertices[:, 1] > 0) & (vertices[:, 1] < 100)
    vertices[inner, :2] += np.random.default_rng(0).uniform(-0.25, 0.25, (inner.sum(), 2))
    to_border = np.minimum.reduce([vertices[:, 0], vertices[:, 1], 100 - vertices[:, 0], 100 - vertices[:, 1]])
    return vertices, faces, to_border


def test_heat_method_from_a_point_and_where_it_bends_near_open_borders(jittered):
    vertices, faces, to_border = jittered
    start = (50.3, 50.2, 0.0)
    piece = _piece(vertices, faces)
    points = assign_points([piece], FromPoints((start,)), 10.0)[0]
    field = geodesic_piece(piece, FromPoints((start,)), 10.0, 0.0, points).field
    error = np.abs(field - np.linalg.norm(vertices - start, axis=1))
    near, inside, border = np.linalg.norm(vertices - start, axis=1) < 20, to_border > 15, to_border < 5
    assert error[near].max() < 0.5  # half an edge within 20 mm of the start
    assert error[inside].max() < 1.0
    assert 1.0 < error[border].max() < 1.6  # where the border is not part of the start it bends the field
    # fast marching on the same irregular mesh is worse far from a point
    exact = np.linalg.norm(vertices - vertices[np.argmin(error + np.linalg.norm(vertices - start, axis=1))], axis=1)
    marching = marching_distance(vertices, faces, source_vertices=np.array([int(np.argmin(exact))]))
    assert np.abs(marching - exact)[inside].max() > 2.0


def test_heat_method_from_a_plane(jittered):
    vertices, faces, to_border = jittered
    angle = 0.4
    normal = (math.cos(angle), math.sin(angle), 0.0)
    piece = geodesic_piece(_piece(vertices, faces), FromPlane((40 / math.cos(angle), 0.0, 0.0), normal), 10.0, 0.0)
    signed = vertices @ np.array(normal) - 40.0
    error = np.abs(piece.field - signed)
    assert error[(np.abs(signed) < 20) & (to_border > 15)].max() < 1.0
    assert error[to_border > 15].max() < 2.0
    assert error[to_border < 5].max() > error[to_border > 15].max()  # it bends near the open border
    # the section is a pass, the others every 10 mm from it, the outermost half a spacing from the ends
    gaps = np.diff(piece.levels)
    assert 0.0 in piece.levels and np.allclose(gaps[2:-2], 10.0) and np.all((gaps >= 5.0) & (gaps <= 10.0))
    assert piece.levels[0] - signed.min() <= 5.0 + 1.0 and signed.max() - piece.levels[-1] <= 5.0 + 1.0


def test_heat_method_from_a_border_with_a_hole_holds_the_border_at_zero():
    vertices, faces = plate_with_hole(200.0, 160.0, 25.0, 2.0)
    vertices, faces, _ = refined(vertices, faces, 2.5, "plate", "")
    x, y = vertices[:, 0], vertices[:, 1]
    exact = np.minimum.reduce([np.hypot(x, y) - 25.0, 100 - np.abs(x), 80 - np.abs(y)])
    near_hole = np.hypot(x, y) < 45
    field = geodesic_piece(_piece(vertices, faces), FromBoundary(), 10.0, 0.0).field
    assert np.abs(field - exact)[near_hole].max() < 0.5
    # potpourri3d's own solver shifts a free solution: on this start its values drift by an edge or more
    border = np.flatnonzero(border_vertices(len(vertices), mesh_edges(faces)))
    theirs = pp3d.MeshHeatMethodDistanceSolver(vertices, faces).compute_distance_multisource(list(border))
    assert np.ptp(theirs[border]) > 2.0 and np.abs(theirs - exact)[near_hole].max() > 0.5


def test_heat_method_on_a_sphere_within_a_percent():
    sphere = trimesh.creation.icosphere(5, radius=50.0)
    vertices, faces = np.asarray(sphere.vertices), np.asarray(sphere.faces)
    top = int(np.argmax(vertices[:, 2]))
    exact = 50.0 * np.arccos(np.clip(vertices @ vertices[top] / 2500.0, -1, 1))
    field = heat_distance(vertices, faces, np.array([top]))
    far = exact < 150
    assert np.abs(field - exact)[far].max() < 0.01 * 157.1
    assert np.abs(field - exact)[exact < 20].max() < 0.35


def test_fast_marching_is_exact_along_grid_lines():
    vertices, faces = grid(100.0, 100.0, 50, 50)
    curves = level_curves(vertices, faces, vertices[:, 1], 30.0)
    distance = marching_distance(vertices, faces, curves=curves)
    assert distance == pytest.approx(np.abs(vertices[:, 1] - 30.0), abs=1e-9)


def test_fast_marching_leaves_unreached_pieces_at_infinity():
    vertices, faces = grid(10.0, 10.0, 2, 2)
    far = vertices + [100.0, 0, 0]
    both = np.vstack([vertices, far])
    distance = marching_distance(both, np.vstack([faces, faces + len(vertices)]), source_vertices=np.array([0]))
    assert np.isfinite(distance[: len(vertices)]).all() and np.isinf(distance[len(vertices):]).all()


def test_the_arc_is_exact_on_a_cylinder_and_a_sphere():
    radius, angle = 50.0, 0.4
    a = np.array([[radius, 0, 0]])
    b = np.array([[radius * math.cos(angle), radius * math.sin(angle), 7.0]])
    cylinder = arc_length(b - a, a / radius, np.array([[math.cos(angle), math.sin(angle), 0]]))
    chord_round = 2 * radius * math.sin(angle / 2)
    assert cylinder[0] == pytest.approx(math.hypot(chord_round, 7.0) * (angle / 2) / math.sin(angle / 2))
    b = np.array([[radius * math.cos(angle), radius * math.sin(angle), 0]])
    assert arc_length(b - a, a / radius, b / radius)[0] == pytest.approx(radius * angle)


def test_across_a_sharp_edge_fast_marching_replaces_the_arc():
    box = trimesh.creation.box((40.0, 40.0, 40.0))
    vertices, faces, _ = refined(np.asarray(box.vertices), np.asarray(box.faces), 1.0, "box", "")
    top = level_curves(vertices, faces, vertices[:, 0], 15.0)  # a loop round the box at x = 15
    curve = [c for c in top if c.closed][0]
    normals = vertex_normals(vertices, faces)
    nearest = NearestOnCurves([(curve.points, curve.sample(faces, normals), True)])
    probe = np.array([[20.0, 0.0, 15.0]])  # on the end face x = 20, 5 mm in from the loop's edge
    marching = marching_distance(vertices, faces, curves=[curve])
    face_probe = np.argmin(np.linalg.norm(vertices - probe, axis=1))
    surface = SmallTriangles(vertices, faces)
    d, _ = nearest.distance(vertices[[face_probe]], normals[[face_probe]], surface, lambda: marching[[face_probe]])
    # the way round the edge is 5 + 5 mm; the straight chord would say 7.1
    assert d[0] == pytest.approx(10.0, abs=0.5)
    # on a face the arc stands (fast marching is not asked)
    flat = np.argmin(np.linalg.norm(vertices - [15.0 + 4.0, 0.0, 20.0], axis=1))
    d, _ = nearest.distance(vertices[[flat]], normals[[flat]], surface, lambda: 1 / 0)
    assert d[0] == pytest.approx(vertices[flat, 0] - 15.0, abs=1e-6)


def test_distance_levels():
    assert list(distance_levels(0.0, 40.0, 5.0, 10.0)) == [5.0, 15.0, 25.0, 35.0]
    # 10 and 8 left over: one more level at each end, the one next to 43 moved to the middle
    assert list(distance_levels(0.0, 48.0, 0.0, 10.0)) == [5.0, 10.0, 20.0, 30.0, 36.5, 43.0]
    assert list(distance_levels(-23.0, 23.0, 0.0, 10.0)) == [-20.0, -10.0, 0.0, 10.0, 20.0]
    assert list(distance_levels(-28.0, 28.0, 0.0, 10.0)) == [-23.0, -16.5, -10.0, 0.0, 10.0, 16.5, 23.0]
    assert list(distance_levels(0.0, 4.0, 5.0, 10.0)) == [2.0]  # narrower than a spacing: its middle


def test_level_curves_run_with_higher_values_on_their_left():
    vertices, faces = grid(10.0, 10.0, 10, 10)
    (curve,) = level_curves(vertices, faces, vertices[:, 1], 4.5)
    assert not curve.closed and curve.points[0, 0] < curve.points[-1, 0]  # +y on the left (seen from +z): runs +x
    (through,) = level_curves(vertices, faces, vertices[:, 1], 4.0)  # through a row of vertices
    assert len(through.points) == 11 and np.allclose(through.points[:, 1], 4.0)
    sphere = trimesh.creation.icosphere(3, radius=10.0)
    (loop,) = level_curves(np.asarray(sphere.vertices), np.asarray(sphere.faces), sphere.vertices[:, 2], 3.0)
    assert loop.closed and np.allclose(np.linalg.norm(loop.points[:, :2], axis=1), math.sqrt(91), rtol=0.02)


def test_manifold_split_separates_a_bow_tie():
    faces = np.array([[0, 1, 2], [0, 3, 4]])
    split, parent = manifold_split(faces)
    assert len(parent) == 6 and sorted(parent.tolist()) == [0, 0, 1, 2, 3, 4]
    assert len(set(split[0]) & set(split[1])) == 0


def test_delaunay_flips_keep_the_surface_and_fix_long_thin_fans():
    vertices = np.array([[0, 0, 0], [10, 0, 0], [10, 1, 0], [0, 1, 0.0]])
    faces = np.array([[0, 1, 2], [0, 2, 3]])
    fine, fine_faces, _ = refined(vertices, faces, 0.6, "strip", "")
    flipped = delaunay_flips(fine, fine_faces, np.zeros(len(fine_faces), dtype=int))
    a, b, c = (fine[flipped[:, k]] for k in range(3))
    assert 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum() == pytest.approx(10.0)
    angles = [np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", q - p, r - p) / np.linalg.norm(q - p, axis=1)
                                           / np.linalg.norm(r - p, axis=1), -1, 1))) for p, q, r in
              ((a, b, c), (b, c, a), (c, a, b))]
    assert max(map(np.max, angles)) <= 120.0

"""Clear cosines: the incidence above which no part of the surface can hide a vertex, checked
against points spread over every triangle and against Embree's rays; on a scan-like dished sheet
they spare nearly every ray and change no thickness."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.spray import visibility
from coatsim.spray.deposition import deposit
from coatsim.geometry.rays import RayCaster
from coatsim.spray.visibility import CLEAR_FLOOR, clear_cosines
from spray_helpers import gun, line_log, mesh_surface

#: Barycentric weights spread over a triangle, its corners and edges included.
_W = np.array([(a, b, 8 - a - b) for a in range(9) for b in range(9 - a)], float) / 8.0


def _sheet(rng: np.random.Generator, n: int, dish_mm: float, noise_mm: float, size_mm: float = 200.0,
           even: bool = False) -> trimesh.Trimesh:
    """A dished height field on scattered points (Delaunay triangles of all shapes; ``even``:
    about n points on a jittered grid, as a scanner spaces them), with noise."""
    from scipy.spatial import Delaunay

    if even:
        step = size_mm / np.sqrt(n)
        grid = np.arange(-size_mm / 2, size_mm / 2, step) + step / 2
        xy = np.stack(np.meshgrid(grid, grid), axis=-1).reshape(-1, 2) + rng.uniform(-0.3, 0.3, (len(grid) ** 2, 2)) * step
    else:
        xy = rng.uniform(-size_mm / 2, size_mm / 2, (n, 2))
    z = dish_mm * (xy**2).sum(axis=1) / (size_mm / 2) ** 2 + rng.normal(0.0, noise_mm, len(xy))
    faces = Delaunay(xy).simplices
    if even:  # without the long slivers along the hull, as a scanner's mesh ends
        faces = faces[np.linalg.norm(xy[faces[:, [1, 2, 0]]] - xy[faces], axis=2).max(axis=1) < 2.0 * step]
    return trimesh.Trimesh(np.column_stack((xy, z)), faces, process=False)


@st.composite
def meshes(draw):
    rng = np.random.default_rng(draw(st.integers(0, 2**31 - 1)))
    kind = draw(st.sampled_from(["sheet", "dented hull", "folded"]))
    if kind == "sheet":
        mesh = _sheet(rng, draw(st.integers(12, 100)), draw(st.floats(-30.0, 30.0)), draw(st.floats(0.0, 2.0)),
                      even=draw(st.booleans()))
    elif kind == "dented hull":
        hull = trimesh.convex.convex_hull(rng.normal(size=(draw(st.integers(8, 50)), 3)) * rng.uniform(5, 50, 3))
        mesh = trimesh.Trimesh(hull.vertices * rng.uniform(0.4, 1.0, (len(hull.vertices), 1)), hull.faces, process=False)
    else:  # a sheet and a second one hung over it
        low, high = _sheet(rng, 30, 5.0, 0.5), _sheet(rng, 20, -5.0, 0.5, 80.0)
        high.vertices[:, 2] += draw(st.floats(3.0, 40.0))
        mesh = trimesh.util.concatenate([low, high])
    normals = np.asarray(mesh.vertex_normals)
    if draw(st.booleans()):  # any unit vector may stand for the normal (a smoothed one, say)
        normals = normals + rng.normal(0.0, 0.2, normals.shape)
        normals /= np.linalg.norm(normals, axis=1)[:, None]
    return np.asarray(mesh.vertices, float), normals, np.asarray(mesh.faces)


@given(meshes())
@settings(max_examples=40, deadline=None)
def test_no_point_of_the_surface_rises_above_a_vertex_more_steeply_than_its_clear_cosine(case):
    vertices, normals, faces = case
    bound = clear_cosines(vertices, normals, faces)
    assert bound.shape == (len(vertices),) and np.all((bound >= CLEAR_FLOOR) & (bound <= 1.0))
    points = np.einsum("wk,fkj->fwj", _W, vertices[faces]).reshape(-1, 3)
    for x in range(len(vertices)):
        d = points - vertices[x]
        length = np.linalg.norm(d, axis=1)
        away = length > 1e-9 * max(1.0, float(np.abs(vertices).max()))
        rise = d[away] @ normals[x]
        assert np.all(rise <= bound[x] * length[away] + 1e-9 * length[away]), (x, float((rise / length[away]).max()), bound[x])


@given(meshes(), st.integers(0, 2**31 - 1))
@settings(max_examples=30, deadline=None)
def test_a_nozzle_seen_more_steeply_than_the_clear_cosine_is_never_hidden(case, seed):
    """Embree's rays against the bound: every pair it spares is clear."""
    vertices, normals, faces = case
    bound = clear_cosines(vertices, normals, faces)
    nozzles = vertices.mean(axis=0) + np.random.default_rng(seed).normal(size=(60, 3)) * 150.0
    x = np.repeat(np.arange(len(vertices)), len(nozzles))
    p = np.tile(nozzles, (len(vertices), 1))
    d = vertices[x] - p
    length = np.linalg.norm(d, axis=1)
    spared = -np.einsum("ij,ij->i", d, normals[x]) > bound[x] * length
    assert not RayCaster(vertices, faces).blocked(p[spared], d[spared], length[spared]).any()


@pytest.mark.parametrize("tilt_deg", [35.0, 50.0, 80.0])
def test_a_normal_tilted_off_its_own_triangles_is_bounded_by_their_rise(tilt_deg):
    """A flat fan round x whose normal leans off the fan's plane: the fan rises towards the
    lean's side at the complement of the tilt, with no other triangle anywhere."""
    turn = np.linspace(0.0, 2 * np.pi, 7)[:-1]
    vertices = np.vstack(([0.0, 0.0, 0.0], np.column_stack((10 * np.cos(turn), 10 * np.sin(turn), np.zeros(6)))))
    faces = np.array([(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)])
    lean = np.radians(tilt_deg)
    normals = np.tile((np.sin(lean), 0.0, np.cos(lean)), (7, 1))
    assert clear_cosines(vertices, normals, faces)[0] == pytest.approx(max(np.sin(lean), CLEAR_FLOOR), rel=1e-12)


def test_a_floor_under_a_shelf_is_not_called_clear_of_it():
    """A floor vertex 1 mm from under a shelf 20 mm above it: the shelf's edge rises at 87 deg."""
    floor = trimesh.creation.box(extents=(100.0, 100.0, 1.0))
    shelf = trimesh.creation.box(extents=(50.0, 100.0, 1.0)).apply_translation((-25.0, 0.0, 20.0))
    mesh = trimesh.util.concatenate([floor.subdivide().subdivide(), shelf])
    bound = clear_cosines(np.asarray(mesh.vertices), np.asarray(mesh.vertex_normals), np.asarray(mesh.faces))
    up = np.isclose(mesh.vertex_normals[:, 2], 1.0)  # not on the floor's rim
    top = np.flatnonzero(np.isclose(mesh.vertices[:, 2], 0.5) & up & (np.abs(mesh.vertices[:, 0]) < 13.0))
    assert len(top) and np.all(bound[top] >= np.sin(np.arctan2(19.0, 13.0)))


class _ProvesNothing:
    """Clear cosines of 1: every pair gets its ray."""

    def __init__(self, *surface):
        pass

    def __call__(self, which):
        return np.ones(len(which))


@pytest.fixture(scope="module")
def dished_scan() -> trimesh.Trimesh:
    return _sheet(np.random.default_rng(7), 6000, 20.0, 0.15, 300.0, even=True)


def test_on_a_noisy_dished_sheet_nearly_every_vertex_is_clear_and_no_thickness_changes(dished_scan, monkeypatch):
    """Noise and the dish rise above almost every tangent plane (no vertex is exposed), yet from a
    gun on the normal nearly no pair needs a ray; the coat is the one every pair's ray gives."""
    mesh = dished_scan
    surface = mesh_surface("dished scan", mesh.vertices, mesh.faces, mesh.vertex_normals)
    assert not visibility.exposed_vertices(surface.vertices, surface.normals).any()
    assert np.mean(clear_cosines(surface.vertices, surface.normals, surface.faces) < 0.7) > 0.95
    log = line_log((-60, -60, 120), (60, 60, 120))
    spared = deposit(surface, log, gun())
    monkeypatch.setattr(visibility, "ClearCosines", _ProvesNothing)
    again = mesh_surface("dished scan", mesh.vertices, mesh.faces, mesh.vertex_normals)  # not the cached one
    every = deposit(again, log, gun())
    assert every.rays > 0 and spared.rays < 0.02 * every.rays
    np.testing.assert_allclose(spared.thickness_mm, every.thickness_mm, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(spared.shadowed_mm, every.shadowed_mm)


def test_bounds_asked_for_in_parts_are_the_bounds_asked_for_at_once(dished_scan):
    """The coat asks batch by batch, in any order and with repeats."""
    mesh = dished_scan
    args = (np.asarray(mesh.vertices), np.asarray(mesh.vertex_normals), np.asarray(mesh.faces))
    whole = clear_cosines(*args)
    parts = visibility.ClearCosines(*args)
    order = np.random.default_rng(3).permutation(np.r_[np.arange(len(whole)), np.arange(0, len(whole), 7)])
    for chunk in np.array_split(order, 13):
        np.testing.assert_array_equal(parts(chunk), whole[chunk])

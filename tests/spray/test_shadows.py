"""Shadows: a shelf over a floor (the shadow's edge in closed form), the mass balance, which
surfaces can shadow themselves, one ray per pair in reach, dwells, the memory budget and a
missing Embree binding."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.spray.coating_metrics import coating_metrics
from coatsim.spray.deposition import deposit
from coatsim.spray.surfaces import cylinder, plate
from coatsim.geometry.rays import RayCaster
from coatsim.spray.visibility import exposed_vertices
from spray_helpers import (
    H0, Q, gun, line_log, make_log, mesh_surface, shelf_over_floor, sphere, stationary_log, volume,
)

TILT = math.radians(15)  # the gun leans towards -x, under the shelf
AXIS = (-math.sin(TILT), 0.0, -math.cos(TILT))
GUN_X = 6.0  # the pass runs along y at x = 6 mm, 100 mm above the floor, 60 mm above the shelf
SHADOW_EDGE_X = GUN_X - GUN_X * H0 / (H0 - 40.0)  # rays through the shelf's edge (x = 0, z = 40) meet the floor here


def shelf_pass():
    log = line_log((GUN_X, -40, H0), (GUN_X, 40, H0), step_mm=1.0)
    return make_log(log.t, log.position, AXIS)


@pytest.fixture(scope="module")
def shelf():
    surface, n_floor = shelf_over_floor(0.5)
    log = shelf_pass()
    return surface, n_floor, log, deposit(surface, log, gun(shadows="off")), deposit(surface, log, gun())


def test_the_shelf_casts_its_shadow_exactly_where_rays_through_its_edge_meet_the_floor(shelf):
    surface, n_floor, _, bare, shaded = shelf
    assert SHADOW_EDGE_X == pytest.approx(-4.0)
    x = surface.vertices[:n_floor, 0]
    hidden, seen = x < SHADOW_EDGE_X - 0.05, x > SHADOW_EDGE_X + 0.05
    floor_bare, floor_shaded = bare.thickness_um[:n_floor], shaded.thickness_um[:n_floor]
    assert np.count_nonzero(floor_bare[hidden] > 0) > 5000  # the spray reaches far into the shadow
    assert np.all(floor_shaded[hidden] == 0.0)
    np.testing.assert_array_equal(floor_shaded[seen], floor_bare[seen])
    np.testing.assert_array_equal(shaded.thickness_um[n_floor:], bare.thickness_um[n_floor:])  # nothing over the shelf
    assert shaded.shadows and not bare.shadows


def test_what_the_shadow_hides_is_what_the_bare_coat_puts_there(shelf):
    _, _, _, bare, shaded = shelf
    np.testing.assert_allclose(shaded.thickness_mm + shaded.shadowed_mm, bare.thickness_mm, rtol=1e-12, atol=0)
    assert np.all(bare.shadowed_mm == 0)


def test_mass_balance_under_a_shelf(shelf):
    """All spray lands on the floor or the shelf: without shadows the floor under the shelf counts
    it twice; with them, sprayed = deposited + missed with missed only the quadrature error of
    vertex-wise visibility along the shadow's edge (half a 0.5 mm cell on a 80 mm edge)."""
    surface, _, _, bare, shaded = shelf
    sprayed = Q * shaded.steps.spray_time_s
    assert volume(surface, bare.thickness_mm) > 1.3 * sprayed
    m = coating_metrics(surface, shaded, gun(), np.ones(surface.n_vertices, bool))
    assert m["sprayed_volume_mm3"] == pytest.approx(sprayed, rel=1e-12)
    assert m["deposited_volume_mm3"] + m["lost_volume_mm3"] + m["missed_volume_mm3"] == pytest.approx(sprayed, rel=1e-12)
    assert abs(m["missed_volume_mm3"]) / sprayed < 3e-3
    assert m["shadowed_volume_mm3"] == pytest.approx(volume(surface, bare.thickness_mm) - m["deposited_volume_mm3"], rel=1e-9)
    assert m["coated_fraction"] < 1.0  # the floor far under the shelf stays bare


def test_one_ray_per_pair_in_reach_and_none_for_vertices_nothing_can_hide(shelf):
    """Constant sub-steps: exposure / dt counts the sub-steps that sprayed a vertex. The shelf is
    exposed (the floor lies behind it); every floor vertex needs one ray per sub-step in reach."""
    surface, n_floor, _, bare, shaded = shelf
    exposed = exposed_vertices(surface.vertices, surface.normals)
    assert not exposed[:n_floor].any() and exposed[n_floor:].all()
    dt = bare.steps.dt[0]
    assert np.allclose(bare.steps.dt, dt, rtol=1e-12)
    in_reach = np.round(bare.exposure_s[:n_floor] / dt).astype(int)
    assert shaded.rays == in_reach.sum()
    assert shaded.rays < shaded.evaluations


def test_a_dwell_casts_one_ray_per_vertex():
    """Forty log rows at one gun position: the visibility of each vertex is cast once and the
    coat equals one interval of the same length."""
    surface, n_floor = shelf_over_floor(1.0)
    t = np.linspace(0.0, 0.4, 41)
    held = deposit(surface, make_log(t, np.tile((GUN_X, 0.0, H0), (41, 1)), AXIS), gun())
    once = deposit(surface, stationary_log((GUN_X, 0.0, H0), 0.4, AXIS), gun())
    np.testing.assert_allclose(held.thickness_mm, once.thickness_mm, rtol=1e-12, atol=0)
    assert held.rays == once.rays == np.count_nonzero(once.exposure_s[:n_floor] > 0) + np.count_nonzero(once.shadowed_mm)


def box(size=(80.0, 60.0, 30.0)) -> trimesh.Trimesh:
    return trimesh.creation.box(extents=size)


def from_trimesh(mesh: trimesh.Trimesh, name: str = "mesh"):
    return mesh_surface(name, mesh.vertices, mesh.faces, mesh.vertex_normals)


@pytest.mark.parametrize("surface", [
    plate(100, 60, 2.0), cylinder(30, 80, 2.0), sphere(40, 3), from_trimesh(box()),
    from_trimesh(trimesh.creation.cylinder(radius=20, height=50, sections=48)),
], ids=["plate", "cylinder", "sphere", "box", "capped cylinder"])
def test_convex_surfaces_cannot_shadow_themselves(surface):
    assert exposed_vertices(surface.vertices, surface.normals).all()
    log = line_log((-20, 0, 120), (20, 0, 120))
    result = deposit(surface, log, gun())
    assert not result.shadows and result.rays == 0
    forced = deposit(surface, log, gun(shadows="on"))
    assert not forced.shadows  # no vertex can be hidden: no ray is needed even when asked for


@pytest.mark.parametrize("surface", [
    shelf_over_floor(4.0)[0], sphere(40, 3, inward=True),
    from_trimesh(trimesh.util.concatenate([box((100, 100, 10)), box((20, 100, 40)).apply_translation((0, 0, 20))])),
], ids=["shelf", "bowl", "ribbed plate"])
def test_concave_surfaces_can(surface):
    assert not exposed_vertices(surface.vertices, surface.normals).all()


@st.composite
def nozzles_and_meshes(draw):
    seed = draw(st.integers(0, 2**31 - 1))
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(draw(st.integers(8, 60)), 3)) * rng.uniform(5, 50, 3)
    dented = draw(st.booleans())
    if dented:  # pull some points towards the centre: a star-shaped, non-convex surface
        hull = trimesh.convex.convex_hull(points)
        verts = hull.vertices * rng.uniform(0.4, 1.0, (len(hull.vertices), 1))
        mesh = trimesh.Trimesh(verts, hull.faces, process=False)
    else:
        mesh = trimesh.convex.convex_hull(points)
    nozzles = rng.normal(size=(40, 3)) * 200
    return mesh, nozzles, dented


@given(nozzles_and_meshes())
@settings(max_examples=30, deadline=None)
def test_no_ray_from_a_nozzle_in_front_ever_reaches_an_exposed_vertex_blocked(case):
    """Real rays against the exposure test: whatever the mesh, a vertex it calls exposed is never
    hidden from a nozzle in front of its tangent plane (incidence cosine > 0.05)."""
    mesh, nozzles, dented = case
    normals = np.asarray(mesh.vertex_normals)
    exposed = exposed_vertices(mesh.vertices, normals)
    if not dented:
        assert exposed.all()
    caster = RayCaster(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    v = np.repeat(np.asarray(mesh.vertices)[exposed], len(nozzles), axis=0)
    n = np.repeat(normals[exposed], len(nozzles), axis=0)
    p = np.tile(nozzles, (int(exposed.sum()), 1))
    front = np.einsum("ij,ij->i", p - v, n) > 0.05 * np.linalg.norm(p - v, axis=1)  # not grazing: float32 rounding
    d = v[front] - p[front]
    assert not caster.blocked(p[front], d, np.linalg.norm(d, axis=1)).any()


def test_the_budget_refuses_a_scene_before_it_is_built(monkeypatch):
    surface, _ = shelf_over_floor(4.0)
    monkeypatch.setenv("COATSIM_BUDGET", "shadow_bytes=1000")
    with pytest.raises(InputError, match="shadows: convex hull and ray-casting scene of .* triangles, bytes: .* over the budget of 1,000"):
        deposit(surface, shelf_pass(), gun())
    assert not deposit(surface, shelf_pass(), gun(shadows="off")).shadows


def test_a_surface_at_the_vertex_budget_fits_the_shadow_budget():
    """A mesh file's surface has about twice as many triangles as vertices."""
    from coatsim.core.budgets import MAX_MESH_VERTICES, MAX_SHADOW_BYTES
    from coatsim.spray.visibility import shadow_memory_bytes

    assert shadow_memory_bytes(MAX_MESH_VERTICES, 2 * MAX_MESH_VERTICES) <= MAX_SHADOW_BYTES


def test_without_embreex_auto_warns_and_on_refuses(monkeypatch):
    surface, _ = shelf_over_floor(4.0)
    monkeypatch.setitem(sys.modules, "embreex", None)  # what an interpreter without the package raises
    with pytest.warns(CoatsimWarning, match="embreex .* cannot be imported: coating without shadows"):
        auto = deposit(surface, shelf_pass(), gun())
    np.testing.assert_array_equal(auto.thickness_mm, deposit(surface, shelf_pass(), gun(shadows="off")).thickness_mm)
    with pytest.raises(InputError, match=r"pip install embreex\) or set shadows off"):
        deposit(surface, shelf_pass(), gun(shadows="on"))


def test_bad_shadow_mode():
    with pytest.raises(InputError, match="shadows must be one of auto, on, off"):
        gun(shadows="sometimes")


def test_on_a_flat_sheet_with_leaning_normals_only_the_far_edge_is_exposed():
    """n.(y - x) = sin(10 deg) (y_x - x_x): positive towards +x, so only the +x edge is a support point."""
    sheet = plate(100, 60, 5.0)
    lean = math.radians(10)
    normals = np.tile((math.sin(lean), 0.0, math.cos(lean)), (sheet.n_vertices, 1))
    exposed = exposed_vertices(sheet.vertices, normals)
    np.testing.assert_array_equal(exposed, np.isclose(sheet.vertices[:, 0], 50.0))


def test_a_solid_step_shadows_the_floor_behind_it():
    """A 40 mm high block on a floor (x from -40 to 0), the gun at x = 30 leaning 25 deg towards
    it: its reach on the floor, x in (-59, 15), holds the block's foot and the floor behind it
    (x < 0: under or behind the block, hidden), and the open floor in front (x > 0, untouched)."""
    from spray_helpers import merge_surfaces

    floor = plate(200, 160, 1.0)
    block = trimesh.creation.box(extents=(40.0, 160.0, 40.0))
    block.apply_translation((-20.0, 0.0, 20.0))
    scene = merge_surfaces(floor, from_trimesh(block))
    lean = math.radians(25)
    log = line_log((30, -40, H0), (30, 40, H0))
    log = make_log(log.t, log.position, (-math.sin(lean), 0.0, -math.cos(lean)))
    bare, shaded = deposit(scene, log, gun(shadows="off")), deposit(scene, log, gun())
    x = floor.vertices[:, 0]
    n = floor.n_vertices
    behind = (x < -0.05) & (bare.thickness_um[:n] > 0)
    assert np.count_nonzero(behind & (x < -40)) > 1000  # the spray reaches past the block
    assert np.all(shaded.thickness_um[:n][behind] == 0.0)
    np.testing.assert_array_equal(shaded.thickness_um[:n][x > 0.05], bare.thickness_um[:n][x > 0.05])

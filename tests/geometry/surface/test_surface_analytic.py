"""Passes on parts whose answer is known in closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.geometry.surface import Box, Everything, Facing, FromBoundary, FromPoints, part_from_arrays, plan
from surface_helpers import SPACING, box_part, cone, grid, options, planned, plate_with_hole, tube


def test_plane_gives_equidistant_straight_passes():
    vertices, faces = grid(200.0, 100.0, 10, 5)
    paths = planned(vertices, faces, step_direction=(0, 1, 0))
    ys = [p.points[:, 1] for p in paths.passes]
    assert [round(float(y.mean()), 6) for y in ys] == [5.0 + 10.0 * k for k in range(10)]
    assert all(np.ptp(y) < 1e-6 for y in ys)  # straight, along x
    for p in paths.passes:
        assert p.points[:, 0].min() == pytest.approx(0.0, abs=1e-9) and p.points[:, 0].max() == pytest.approx(200.0)
        assert np.allclose(p.normals, [0, 0, 1])
        assert not p.closed and len(p.lead_in) == 1 and len(p.lead_out) == 1
    # serpentine: every other pass reversed; lead-in and lead-out 3 sigma past the edges along the pass
    assert paths.passes[0].points[0, 0] < paths.passes[0].points[-1, 0]
    assert paths.passes[1].points[0, 0] > paths.passes[1].points[-1, 0]
    assert paths.passes[0].lead_in[0] == pytest.approx([-15.0, 5.0, 0.0])
    assert paths.passes[0].lead_out[0] == pytest.approx([215.0, 5.0, 0.0])
    s = paths.stats
    assert s.coverage == pytest.approx(1.0)
    assert (s.spacing_min_mm, s.spacing_median_mm, s.spacing_max_mm) == pytest.approx((10.0, 10.0, 10.0), abs=1e-6)
    assert s.region_area_mm2 == pytest.approx(20000.0)
    assert paths.ripple_pct == pytest.approx(400 * math.exp(-2 * math.pi**2 * 25 / 100))


def test_oneway_keeps_every_pass_running_one_way():
    vertices, faces = grid(200.0, 100.0, 10, 5)
    paths = planned(vertices, faces, step_direction=(0, 1, 0), order="oneway")
    starts = [p.points[0, 0] for p in paths.passes]
    assert len(set(np.round(starts, 6))) == 1


def test_tilted_plate_plane_step_is_smaller_than_the_spacing():
    tilt = math.radians(35.0)
    vertices, faces = grid(120.0, 100.0, 12, 10)
    rotation = np.array([[1, 0, 0], [0, math.cos(tilt), -math.sin(tilt)], [0, math.sin(tilt), math.cos(tilt)]])
    paths = planned(vertices @ rotation.T, faces, step_direction=(0, 1, 0),
                    region=Facing(tuple(rotation @ [0, 0, 1.0])))
    ys = np.array([p.points[:, 1].mean() for p in paths.passes])
    assert np.diff(ys) == pytest.approx(SPACING * math.cos(tilt), rel=1e-6)
    assert paths.stats.spacing_median_mm == pytest.approx(SPACING, rel=1e-6)
    assert len(paths.passes) == 10


def test_cylinder_along_its_axis_gives_straight_lines_at_arc_length_spacing():
    radius = 50.0
    vertices, faces = tube(radius, 200.0, 180, 20)
    paths = planned(vertices, faces, region=Facing((1, 0, 0), 80.0), step_direction=(0, 1, 0))
    angles = []
    for p in paths.passes:
        phi = np.arctan2(p.points[:, 1], p.points[:, 0])
        assert np.ptp(phi) < 1e-3  # a straight line along the axis
        assert np.ptp(p.points[:, 2]) == pytest.approx(200.0)
        # radial to 0.2 deg (smoothing near the tube's open ends leans them a little)
        assert np.allclose(p.normals[:, :2] / np.linalg.norm(p.normals[:, :2], axis=1)[:, None],
                           np.column_stack([np.cos(phi), np.sin(phi)]), atol=3e-3)
        angles.append(float(phi.mean()))
    arcs = radius * np.diff(np.sort(angles))
    assert arcs == pytest.approx(arcs.mean(), rel=0.01)  # the region's width shared evenly
    assert arcs.max() <= SPACING * 1.01
    # the first and last pass half a spacing in from the 80-degree rim (to a facet)
    rim = math.radians(80.0)
    assert radius * (min(angles) + rim) == pytest.approx(SPACING / 2, abs=0.05 * SPACING)


def test_cylinder_around_its_axis_gives_circles():
    vertices, faces = tube(50.0, 200.0, 128, 20)
    paths = planned(vertices, faces, region=Everything(), step_direction=(0, 0, 1))
    assert [p.closed for p in paths.passes] == [True] * 20
    for k, p in enumerate(paths.passes):
        assert p.points[:, 2] == pytest.approx(-95.0 + 10.0 * k, abs=1e-6)
        assert np.linalg.norm(p.points[:, :2], axis=1).max() == pytest.approx(50.0, rel=1e-6)
        assert len(p.lead_in) == len(p.lead_out) == 0
    assert paths.stats.coverage == pytest.approx(1.0)


def test_cone_circles_step_by_the_spacing_along_the_slant():
    base, height = 60.0, 120.0
    vertices, faces = cone(base, height, 160, 40)
    paths = planned(vertices, faces, region=Everything(), step_direction=(0, 0, 1))
    z = np.array([p.points[:, 2].mean() for p in paths.passes])
    # plane sections of the facets, lifted along the normal onto the smooth cone: out of their
    # planes by at most the facets' sagitta (0.012 mm) times the normal's z (0.45)
    assert all(p.closed and np.ptp(p.points[:, 2]) < 0.006 for p in paths.passes)
    first = paths.passes[0].points  # on the cone itself, within a micrometre
    assert np.abs(np.hypot(first[:, 0], first[:, 1]) - base * (1 - first[:, 2] / height)).max() < 1e-3
    slant = math.hypot(base, height) / height  # surface length per unit of height
    # the slant is no whole number of spacings: every gap is the same, at most the spacing
    assert np.diff(z) == pytest.approx(np.diff(z).mean(), rel=1e-3)
    assert np.diff(z).mean() * slant <= SPACING * 1.005


def test_sphere_from_a_pole_gives_latitude_circles_at_the_arc_distance():
    import trimesh

    radius = 50.0
    sphere = trimesh.creation.icosphere(5, radius=radius)
    top = np.argmax(sphere.vertices[:, 2])
    pole = tuple(sphere.vertices[top])
    paths = plan(part_from_arrays(sphere.vertices, sphere.faces), options(
        pattern="geodesic", region=Everything(), start=FromPoints((pole,))))
    axis = np.asarray(pole) / radius
    for k, p in enumerate(paths.passes[:-1]):
        arc = radius * np.arccos(np.clip(p.points @ axis / np.linalg.norm(p.points, axis=1), -1, 1))
        expected = (k + 0.5) * SPACING
        assert p.closed
        assert np.ptp(arc) < 0.05 * SPACING  # a latitude circle
        # the heat method stretches distance by about half a percent on this mesh
        assert arc.mean() == pytest.approx(expected, abs=0.006 * expected + 0.05 * SPACING)
    assert len(paths.passes) == 16


def test_closed_box_is_cut_on_the_side_the_gun_sees():
    paths = plan(box_part((100.0, 80.0, 20.0)), options(region=Facing((0, 0, 1))))
    assert len(paths.passes) == 8
    assert all(np.allclose(p.points[:, 2], 10.0) and np.allclose(p.normals, [0, 0, 1]) for p in paths.passes)
    # a box region around the whole part still sees one skin only (the default gun side, +z)
    boxed = plan(box_part((100.0, 80.0, 20.0)), options(region=Box((-60, -60, -60), (60, 60, 60))))
    points = np.concatenate([p.points for p in boxed.passes])
    assert points[:, 2].min() == pytest.approx(10.0)
    # all of it: the planes would run round the part, but a gun cannot follow a normal round a
    # right-angled edge: each side the planes cross gets its own 10 passes, each on one face
    # with that face's normal, and the plan says why; the two 80 x 20 ends facing the step, which
    # the planes cross edge-on, get 2 passes each across their own longest axis
    around = plan(box_part((100.0, 80.0, 20.0)), options(region=Everything(), step_direction=(1, 0, 0)))
    assert len(around.passes) == 44 and not any(p.closed for p in around.passes)
    for p in around.passes:
        assert np.allclose(p.normals, p.normals[0], atol=1e-9) and np.isclose(np.abs(p.normals[0]).max(), 1.0)
    ends = [p for p in around.passes if abs(p.normals[0][0]) > 0.5]
    assert len(ends) == 4 and all(np.ptp(p.points[:, 1]) > 60.0 for p in ends)
    assert any("sharp edges" in note for note in around.notes)
    assert any("2 piece(s) of the region that the raster planes cross edge-on" in n for n in around.notes)


def test_plate_with_hole_geodesic_passes_bend_around_it():
    vertices, faces = plate_with_hole(200.0, 160.0, 25.0, 2.0)
    paths = planned(vertices, faces, pattern="geodesic", start=FromBoundary(), region=Facing((0, 0, 1)))
    loops = [p for p in paths.passes if p.closed and np.hypot(*p.points[:, :2].T).max() < 60]
    # loops round the hole at (k + 1/2) spacings from its edge: circles to 0.15 spacing (the
    # outer fronts pull on the third), at their radius to a twentieth of a spacing
    radii = [np.hypot(*p.points[:, :2].T) for p in loops]
    assert len(radii) == 3
    assert all(np.ptp(r) < 0.15 * SPACING for r in radii)
    assert all(abs(r.mean() - 25.0 - (k + 0.5) * SPACING) < 0.05 * SPACING for k, r in enumerate(radii))
    # away from the outer corners (where the heat method rounds the distance's sharp ridge) every
    # pass follows the distance to the nearest border within a tenth of a spacing
    half_w, half_h = 100.0, 80.0
    for p in paths.passes:
        x, y = p.points[:, 0], p.points[:, 1]
        to_border = np.minimum.reduce([np.hypot(x, y) - 25.0, half_w - np.abs(x), half_h - np.abs(y)])
        corner = np.minimum(half_w - np.abs(x), half_h - np.abs(y)) < 0.9 * np.maximum(half_w - np.abs(x), half_h - np.abs(y))
        off = np.abs(to_border - np.median(to_border))[~corner & (to_border > 0)]
        assert off.max() < 0.1 * SPACING


def test_plate_with_hole_raster_passes_stop_at_the_hole():
    vertices, faces = plate_with_hole(200.0, 160.0, 25.0, 2.0)
    paths = planned(vertices, faces, step_direction=(0, 1, 0))
    through = [p for p in paths.passes if abs(p.points[:, 1].mean()) < 20]
    assert len(through) >= 4  # the passes that meet the hole are split in two
    edge = 25.0 * math.cos(math.pi / math.ceil(2 * math.pi * 25.0 / 2.0))  # the hole is a polygon
    assert all(np.hypot(*p.points[:, :2].T).min() >= edge - 1e-6 for p in paths.passes)


def test_mesh_in_metres_plans_like_millimetres():
    vertices, faces = grid(200.0, 100.0, 10, 5)
    in_mm = planned(vertices, faces, step_direction=(0, 1, 0))
    in_m = plan(part_from_arrays(vertices / 1000.0, faces, "plate_m", units="auto"),
                options(step_direction=(0, 1, 0)))
    assert any("read as metres" in n for n in in_m.notes)
    assert len(in_m.passes) == len(in_mm.passes)
    for a, b in zip(in_m.passes, in_mm.passes):
        assert np.allclose(a.points, b.points, atol=1e-6)


def test_noisy_plane_gives_steady_normals():
    rng = np.random.default_rng(7)
    vertices, faces = grid(120.0, 120.0, 120, 120)
    vertices[:, 2] = rng.normal(0.0, 0.1, len(vertices))
    paths = planned(vertices, faces, region=Facing((0, 0, 1)))
    normals = np.concatenate([p.normals for p in paths.passes])
    tilt = np.degrees(np.arccos(np.clip(normals[:, 2], -1, 1)))
    assert tilt.max() < 2.0
    assert paths.stats.normal_max_angle_deg > 10.0  # the faces themselves are rough


def test_a_torus_splits_its_sections_in_two():
    """Genus 1: every plane across the hole cuts the torus in two loops (inside and outside)."""
    import trimesh

    torus = trimesh.creation.torus(40.0, 15.0, major_sections=96, minor_sections=48)
    paths = plan(part_from_arrays(torus.vertices, torus.faces), options(region=Everything(), step_direction=(0, 0, 1)))
    levels: dict[float, list] = {}
    for p in paths.passes:
        assert p.closed
        # lifted along the normal off the facets onto the torus: out of their planes by microns
        levels.setdefault(round(float(p.points[:, 2].mean()), 1), []).append(p)
    assert len(levels) >= 3 and all(len(loops) == 2 for loops in levels.values())
    for z, loops in levels.items():
        radii = sorted(float(np.linalg.norm(p.points[:, :2], axis=1).mean()) for p in loops)
        half = math.sqrt(15.0**2 - z**2)
        assert radii == pytest.approx([40.0 - half, 40.0 + half], abs=0.3)  # a 48-gon's facets


def test_the_edge_band_keeps_passes_off_the_border():
    vertices, faces = grid(200.0, 100.0, 40, 20)
    paths = planned(vertices, faces, step_direction=(0, 1, 0), edge_band_mm=7.0)
    # cut where the border distance (fast marching, interpolated along the pass) is the band: to 0.2 mm
    # (the 75 mm between the end passes are 8 even gaps of 9.375 mm: most passes run between the
    # rows of vertices, where the linear interpolation of the marched distance errs most)
    for p in paths.passes:
        x, y = p.points[:, 0], p.points[:, 1]
        assert np.minimum.reduce([x, y, 200 - x, 100 - y]).min() >= 7.0 - 0.2
        assert (x.min(), x.max()) == pytest.approx((7.0, 193.0), abs=0.2)
    # the end passes half a spacing in from the band's inner edge, which runs along vertices (2.5 mm)
    ys = [p.points[0, 1] for p in paths.passes]
    assert 12.0 <= ys[0] <= 12.0 + 2.5 and 88.0 - 2.5 <= ys[-1] <= 88.0
    assert paths.stats.coverage < 0.9  # the band is part of the region and is not covered

"""Coating metrics, regions of interest, PLY / PNG outputs and cross-section profiles."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from coatsim.core.errors import InputError
from coatsim.spray.coating_metrics import (
    coating_metrics, region_of_interest, thickness_statistics, weighted_quantile,
)
from coatsim.spray.deposition import deposit
from coatsim.spray.outputs import (
    Profile, colours, heatmap_png, panel, ply_bytes, profile_png, section_profile, write_thickness_ply,
)
from coatsim.spray.surfaces import cylinder, plate
from spray_helpers import H0, SIGMA, V, gun, line_log, make_log, stationary_log


def test_statistics_are_area_weighted():
    t = np.array([1.0, 3.0, 3.0])
    areas = np.array([2.0, 1.0, 1.0])
    stats = thickness_statistics(t, areas, np.ones(3, bool), 2.0)
    assert stats["thickness_mean_um"] == 2.0 and stats["thickness_std_um"] == 1.0
    assert stats["thickness_cv"] == 0.5 and stats["roi_area_mm2"] == 4.0
    assert (stats["thickness_min_um"], stats["thickness_max_um"]) == (1.0, 3.0)
    assert stats["coverage_fraction"] == 0.5 and stats["thick_spot_fraction"] == 0.5
    assert stats["thickness_p05_um"] == 1.0 and stats["thickness_p95_um"] == 3.0


@given(arrays(float, st.integers(2, 40), elements=st.floats(0, 100)),
       st.floats(0.01, 0.99), st.integers(0, 2**16))
@settings(max_examples=60, deadline=None)
def test_splitting_vertices_leaves_statistics_unchanged(t, q, seed):
    areas = np.random.default_rng(seed).uniform(0.5, 2.0, len(t))
    whole = thickness_statistics(t, areas, np.ones(len(t), bool), 10.0)
    split = thickness_statistics(np.r_[t, t], np.r_[areas, areas] / 2, np.ones(2 * len(t), bool), 10.0)
    for key, value in whole.items():
        if key != "roi_vertices":
            assert split[key] == pytest.approx(value, rel=1e-9, abs=1e-12)
    quantile = weighted_quantile(t, areas, q)
    assert t.min() <= quantile <= t.max()


def test_part_roi_is_the_part_minus_the_edge_band():
    surface = plate(200, 100, 2.0)
    result = deposit(surface, stationary_log((0, 0, H0), 1.0), gun())
    roi = region_of_interest(surface, result, gun(), "part", spacing=2.0)
    x, y = surface.vertices[:, 0], surface.vertices[:, 1]
    np.testing.assert_array_equal(roi, (np.abs(x) <= 100 - 3 * SIGMA) & (np.abs(y) <= 50 - 3 * SIGMA))


def test_band_roi_of_an_open_pass_leaves_out_run_in_and_run_out():
    surface = plate(300, 100, 1.0)
    result = deposit(surface, line_log((-100, 0, H0), (100, 0, H0)), gun())
    roi = region_of_interest(surface, result, gun(), "band", spacing=1.0)
    x, y = surface.vertices[:, 0], surface.vertices[:, 1]
    centre = np.clip(np.floor(x) + 0.5, -99.5, 99.5)  # sub-step centres: ±0.5, ±1.5, ..., ±99.5
    near_track = np.hypot(x - centre, y) <= 2 * SIGMA + 1e-9
    ends = np.minimum(np.hypot(x + 99.5, y), np.hypot(x - 99.5, y))
    expected = near_track & (ends >= 3 * SIGMA)
    np.testing.assert_array_equal(roi, expected)


def test_band_roi_of_a_closed_circle_is_a_full_ring():
    rho, n = 50.0, 600
    phase = np.linspace(0, 2 * math.pi, n + 1)
    log = make_log(phase * rho / V, np.column_stack([rho * np.cos(phase), rho * np.sin(phase), np.full(n + 1, H0)]))
    surface = plate(160, 160, 1.0)
    result = deposit(surface, log, gun())
    roi = region_of_interest(surface, result, gun(), "band", spacing=1.0)
    r = np.linalg.norm(surface.vertices[:, :2], axis=1)
    sure = np.abs(r - rho) <= 2 * SIGMA - 0.05  # chords lie up to 0.05 mm inside the circle
    outside = np.abs(r - rho) > 2 * SIGMA + 0.05
    assert np.all(roi[sure]) and not np.any(roi[outside])
    metrics = coating_metrics(surface, result, gun(), roi)
    assert metrics["on_part_efficiency"] == pytest.approx(1.0, abs=1e-6)
    assert metrics["target_um"] == metrics["thickness_mean_um"]


def test_efficiency_counts_overspray_past_the_edge():
    surface = plate(100, 100, 1.0)
    result = deposit(surface, stationary_log((50, 0, H0), 2.0), gun())  # gun over the right edge
    metrics = coating_metrics(surface, result, gun(), region_of_interest(surface, result, gun(), "part"), 50.0)
    assert metrics["sprayed_volume_mm3"] == pytest.approx(80.0)
    assert metrics["on_part_efficiency"] == pytest.approx(0.5, abs=1e-6)
    assert metrics["deposited_volume_mm3"] == pytest.approx(40.0, rel=1e-5)


def test_metric_errors_are_input_errors():
    surface = plate(100, 100, 2.0)
    dry = deposit(surface, make_log([0, 1], [(0, 0, H0)] * 2, spray=False), gun())
    with pytest.raises(InputError, match="never sprays"):
        coating_metrics(surface, dry, gun(), np.ones(surface.n_vertices, bool))
    away = deposit(surface, stationary_log((0, 0, -H0), 1.0), gun())  # gun below, pointing away
    with pytest.raises(InputError, match="no coating landed"):
        coating_metrics(surface, away, gun(), np.ones(surface.n_vertices, bool))
    wet = deposit(surface, stationary_log((0, 0, H0), 1.0), gun())
    with pytest.raises(InputError, match="region of interest is empty"):
        coating_metrics(surface, wet, gun(), np.zeros(surface.n_vertices, bool))
    with pytest.raises(InputError, match="ROI must be one of"):
        region_of_interest(surface, wet, gun(), "everything")


def test_ply_round_trip_through_trimesh(tmp_path):
    surface = plate(20, 10, 2.5)
    thickness = np.linspace(0, 7, surface.n_vertices)
    path = tmp_path / "t.ply"
    write_thickness_ply(path, surface, thickness, 0.0, 7.0)
    assert path.read_bytes() == ply_bytes(surface, thickness, 0.0, 7.0)
    loaded = trimesh.load(path, process=False)
    np.testing.assert_allclose(loaded.vertices, surface.vertices, atol=1e-5)
    np.testing.assert_array_equal(loaded.faces, surface.faces)
    raw = loaded.metadata["_ply_raw"]["vertex"]["data"]
    np.testing.assert_allclose(raw["thickness"].ravel(), thickness, rtol=1e-6)
    np.testing.assert_array_equal(loaded.visual.vertex_colors[:, :3], colours(thickness, 0.0, 7.0))
    exposure = np.linspace(0, 1, surface.n_vertices)
    both = tmp_path / "both.ply"
    write_thickness_ply(both, surface, thickness, 0.0, 7.0, exposure)
    raw = trimesh.load(both, process=False).metadata["_ply_raw"]["vertex"]["data"]
    np.testing.assert_allclose(raw["thickness"].ravel(), thickness, rtol=1e-6)
    np.testing.assert_allclose(raw["exposure"].ravel(), exposure, rtol=1e-6, atol=1e-7)


def test_colour_scale_ends():
    import matplotlib

    rgb = colours(np.array([-1.0, 0.0, 10.0, 11.0]), 0.0, 10.0)
    lo = np.round(np.array(matplotlib.colormaps["viridis"](0.0)[:3]) * 255)
    hi = np.round(np.array(matplotlib.colormaps["viridis"](1.0)[:3]) * 255)
    np.testing.assert_array_equal(rgb, [lo, lo, hi, hi])


def test_section_profile_interpolates_linear_fields_exactly():
    surface = plate(100, 60, 3.0)
    x, y = surface.vertices[:, 0], surface.vertices[:, 1]
    field = 2 * x - 3 * y + 1
    s, t = section_profile(surface.view, surface.faces, field, (-60, -10), (40, 20), n=101)
    fx = np.linspace(-60, 40, 101)
    fy = np.linspace(-10, 20, 101)
    inside = fx >= -50
    np.testing.assert_allclose(t[inside], (2 * fx - 3 * fy + 1)[inside], atol=1e-9)
    assert np.all(np.isnan(t[~inside]))
    assert s[-1] == pytest.approx(math.hypot(100, 30))


def test_section_across_an_unrolled_cylinder():
    surface = cylinder(20, 80, 2.0)
    field = surface.view[:, 1] ** 2
    _, t = section_profile(surface.view, surface.faces, field, (0, -50), (0, 50), n=11)
    arc = np.linspace(-50, 50, 11)
    ok = np.abs(arc) < 20 * math.pi
    assert np.all(np.isnan(t[~ok]))
    np.testing.assert_allclose(t[ok], arc[ok] ** 2, atol=2.0)


def test_pngs_are_deterministic_and_written(tmp_path):
    a, b = plate(40, 20, 2.0), cylinder(10, 40, 2.0)
    panels = [panel(a, np.hypot(*a.view.T), "plate"), panel(b, np.abs(b.view[:, 1]), "cylinder")]
    line = (np.array([-20, 0]), np.array([20, 0]))
    data = heatmap_png(panels, 0.0, 30.0, tmp_path / "h.png", "two variants", line)
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and (tmp_path / "h.png").read_bytes() == data
    assert heatmap_png(panels, 0.0, 30.0, None, "two variants", line) == data
    assert heatmap_png(panels, 0.0, 60.0, None, "two variants", line) != data
    curves = [Profile("a", np.arange(5.0), np.arange(5.0)), Profile("b", np.arange(5.0), np.full(5, np.nan))]
    png = profile_png(curves, tmp_path / "p.png", "profiles")
    assert png[:4] == b"\x89PNG" and png == profile_png(curves, None, "profiles")


def test_specification_and_coated_shares_are_area_weighted():
    t = np.array([0.0, 9.0, 10.0, 11.5, 20.0])
    areas = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    stats = thickness_statistics(t, areas, np.ones(5, bool), 10.0, tolerance_pct=10.0)
    assert stats["coated_fraction"] == pytest.approx(14 / 15)
    assert stats["within_spec_fraction"] == pytest.approx(5 / 15)  # 9 and 10 are within +-1, 11.5 is not
    assert stats["tolerance_pct"] == 10.0
    wide = thickness_statistics(t, areas, np.ones(5, bool), 10.0, tolerance_pct=20.0)
    assert wide["within_spec_fraction"] == pytest.approx(9 / 15)


def test_spray_angle_and_standoff_on_a_tilted_plate_under_a_still_gun():
    """One nozzle position: every vertex's spray angle and stand-off are its own geometry."""
    tilt = math.radians(50)
    pose = np.eye(4)
    pose[:3, :3] = [[math.cos(tilt), 0, math.sin(tilt)], [0, 1, 0], [-math.sin(tilt), 0, math.cos(tilt)]]
    surface = plate(140, 80, 1.0, pose)
    result = deposit(surface, stationary_log((0, 0, H0), 1.0), gun())
    landed = result.thickness_mm > 0
    ray = surface.vertices[landed] - (0, 0, H0)
    cos_gamma = -(ray @ surface.normals[0]) / np.linalg.norm(ray, axis=1)
    np.testing.assert_allclose(result.spray_angle_deg[landed], np.degrees(np.arcsin(cos_gamma)), rtol=1e-12)
    np.testing.assert_allclose(result.standoff_mm[landed], -ray[:, 2], rtol=1e-12)
    assert np.all(np.isnan(result.spray_angle_deg[~landed]))
    roi = np.ones(surface.n_vertices, bool)
    m = coating_metrics(surface, result, gun(), roi)
    flat = landed & (result.spray_angle_deg < 60)
    assert 0 < m["low_angle_fraction"] == pytest.approx(surface.areas[flat].sum() / surface.area_mm2)
    assert (m["standoff_min_mm"], m["standoff_max_mm"]) == (result.standoff_mm[landed].min(), result.standoff_mm[landed].max())
    assert m["coated_fraction"] == pytest.approx(surface.areas[landed].sum() / surface.area_mm2)
    assert m["deposition_efficiency"] == pytest.approx(m["deposited_volume_mm3"] / m["sprayed_volume_mm3"])

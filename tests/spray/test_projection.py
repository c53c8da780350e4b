"""The projection model on 3-D geometry against closed forms: a tilted plate, a plate beyond the
stand-off, a pass along a cylinder's axis, a sphere (σ = 5, h0 = 100, Q = 40, v = 500)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.spray.coating_metrics import coating_metrics
from coatsim.spray.deposition import deposit
from coatsim.spray.footprints import Gaussian
from coatsim.spray.surfaces import cylinder, plate
from spray_helpers import H0, Q, SIGMA, V, gun, line_log, sphere, stationary_log, stationary_peak_um, volume


def rotation_y(angle: float, origin=(0.0, 0.0, 0.0)) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    pose = np.eye(4)
    pose[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    pose[:3, 3] = origin
    return pose


def tilted_plate_um(s, w, alpha: float, h0: float, seconds: float = 1.0):
    """Thickness at plate coordinates (s along the tilt, w across) of a plate through the axis
    point at h0, tilted by alpha, under a stationary nozzle: the ray to (s, w) meets the
    reference plane at lambda (s cos alpha, -w) with lambda = h0 / (h0 + s sin alpha), and the
    area ratio of that map is cos alpha lambda^3 (flux conserved through the projection)."""
    lam = h0 / (h0 + s * math.sin(alpha))
    return Q * seconds * Gaussian(SIGMA).density(lam * s * math.cos(alpha), -lam * w) * math.cos(alpha) * lam**3 * 1000


@pytest.mark.parametrize("degrees", [30, 45, 60])
def test_a_tilted_plate_follows_the_projection_exactly(degrees):
    alpha = math.radians(degrees)
    surface = plate(30 / math.cos(alpha) * 2 + 30, 80, 0.5, rotation_y(alpha))
    t = deposit(surface, stationary_log((0, 0, H0), 1.0), gun()).thickness_um
    c, s = math.cos(alpha), math.sin(alpha)
    along = surface.vertices @ np.array([c, 0.0, -s])
    np.testing.assert_allclose(t, tilted_plate_um(along, surface.vertices[:, 1], alpha, H0), rtol=1e-9,
                               atol=1e-7 * stationary_peak_um())


@pytest.mark.parametrize("degrees", [30, 45, 60])
def test_a_tilted_plate_has_cos_alpha_of_the_peak_and_a_footprint_stretched_by_one_over_cos_alpha(degrees):
    """Far from the nozzle (h0 = 2000 mm = 400 sigma) the projection is nearly parallel: peak
    cos alpha of the normal plate's, spread sigma / cos alpha along the tilt and sigma across,
    up to O(sigma tan alpha / h0)^2 = 2e-5 (and the peak's sampling on a 0.25 mm grid, 2e-4)."""
    alpha, h0 = math.radians(degrees), 2000.0
    model = gun(standoff_mm=h0)
    log = stationary_log((0, 0, h0), 1.0)
    flat = deposit(plate(70, 70, 0.25), log, model).thickness_um.max()
    surface = plate(6.5 * SIGMA / math.cos(alpha) * 2, 70, 0.25, rotation_y(alpha))
    t = deposit(surface, log, model).thickness_um
    assert t.max() / flat == pytest.approx(math.cos(alpha), rel=2e-4)
    along = surface.vertices @ np.array([math.cos(alpha), 0.0, -math.sin(alpha)])
    w = surface.areas * t / np.sum(surface.areas * t)
    for coordinate, expected in ((along, SIGMA / math.cos(alpha)), (surface.vertices[:, 1], SIGMA)):
        mean = np.sum(w * coordinate)
        assert math.sqrt(np.sum(w * (coordinate - mean) ** 2)) == pytest.approx(expected, rel=1e-4)


@pytest.mark.parametrize("factor", [1.5, 2.5])
def test_a_plate_beyond_the_standoff_gets_a_wider_flatter_bead_of_the_same_area(factor):
    """A pass at distance d = factor h0: the footprint widens to sigma d / h0 and the
    stationary rate falls as (h0 / d)^2, so the bead is Q / (sqrt(2 pi) sigma' v) exp(-y^2 / 2 sigma'^2)."""
    sigma = SIGMA * factor
    half = 6 * sigma + 10  # the pass reaches 6 sigma' past the middle either way
    surface = plate(2 * (half + 6 * sigma + 5), 14 * sigma, sigma / 10)
    result = deposit(surface, line_log((-half, 0, factor * H0), (half, 0, factor * H0)), gun())
    mid = np.abs(surface.vertices[:, 0]) < 1e-9
    y = surface.vertices[mid, 1]
    bead = Q / (math.sqrt(2 * math.pi) * sigma * V) * np.exp(-y**2 / (2 * sigma**2)) * 1000
    np.testing.assert_allclose(result.thickness_um[mid], bead, rtol=1e-6, atol=1e-7 * bead.max())
    still = deposit(surface, stationary_log((0, 0, factor * H0), 1.0), gun()).thickness_um.max()
    assert still == pytest.approx(stationary_peak_um() / factor**2, rel=1e-7)  # 1.5e-8: the 6-sigma cut
    assert volume(surface, result.thickness_mm) == pytest.approx(Q * 2 * half / V, rel=1e-6)


def cylinder_profile_um(phi, radius: float, height: float):
    """Thickness around a cylinder of radius R after a long pass along its axis at speed V, the
    nozzle ``height`` above the top line and spraying at the axis: integrating the projected
    footprint along the axis leaves (Q / V) h0 ((R + h) cos phi - R) / D^2 times the Gaussian of
    the projected lateral offset h0 R sin phi / D, D = R + h - R cos phi (zero past the horizon)."""
    depth = radius + height - radius * np.cos(phi)
    facing = (radius + height) * np.cos(phi) - radius
    lateral = H0 * radius * np.sin(phi) / depth
    gauss = np.exp(-lateral**2 / (2 * SIGMA**2)) / (math.sqrt(2 * math.pi) * SIGMA)
    return np.where(facing > 0, Q / V * H0 * facing / depth**2 * gauss, 0.0) * 1000


@pytest.fixture(scope="module")
def cylinder_pass():
    radius = 50.0
    surface = cylinder(radius, 300, 1.0, "x")
    return surface, radius, deposit(surface, line_log((-100, 0, radius + H0), (100, 0, radius + H0)), gun())


def test_a_pass_along_a_cylinder_has_the_closed_form_profile_across_the_axis(cylinder_pass):
    surface, radius, result = cylinder_pass
    mid = np.abs(surface.vertices[:, 0]) < 1e-9
    phi = np.arctan2(surface.vertices[mid, 1], surface.vertices[mid, 2])
    exact = cylinder_profile_um(phi, radius, H0)
    np.testing.assert_allclose(result.thickness_um[mid], exact, rtol=1e-6, atol=1e-7 * exact.max())
    straight = Q / (math.sqrt(2 * math.pi) * SIGMA * V) * 1000
    assert cylinder_profile_um(np.array(0.0), radius, H0) == pytest.approx(straight, rel=1e-12)  # top line: a plate at h0


def test_all_the_spray_lands_on_the_cylinder(cylinder_pass):
    """The 6-sigma cone (16.7 deg) stays inside the cylinder's silhouette (19.5 deg from 150 mm):
    the volume is Q L / v up to the facets' area deficit, 1 - sin(dphi)/dphi = 7e-5 at 1 mm."""
    surface, _, result = cylinder_pass
    assert volume(surface, result.thickness_mm) == pytest.approx(Q * 200 / V, rel=2e-4)


@pytest.fixture(scope="module")
def ball():
    radius = 60.0
    surface = sphere(radius, 6)
    nozzle = np.array([0.0, 0.0, radius + H0])
    return surface, radius, nozzle, deposit(surface, stationary_log(nozzle, 1.0), gun())


def test_a_sphere_under_a_stationary_gun(ball):
    """Per vertex, the reference footprint through the solid angle: the ray x - p meets the
    reference plane at (u, v) and the plane's area per steradian there is h0^2 / cos^3 theta;
    the sphere's element takes cos gamma / r^2 steradians per area."""
    surface, _, nozzle, result = ball
    ray = surface.vertices - nozzle
    r = np.linalg.norm(ray, axis=1)
    cos_theta = -ray[:, 2] / r
    cos_gamma = -np.einsum("ij,ij->i", ray, surface.normals) / r
    on_plane = ray * (H0 / (r * cos_theta))[:, None]
    g = Gaussian(SIGMA).density(on_plane[:, 0], -on_plane[:, 1])
    exact = np.where(cos_gamma > 0, Q * g * H0**2 / cos_theta**3 * cos_gamma / r**2, 0.0) * 1000
    np.testing.assert_allclose(result.thickness_um, exact, rtol=1e-9, atol=1e-7 * stationary_peak_um())
    apex = np.argmax(surface.vertices[:, 2])
    assert result.thickness_um[apex] == pytest.approx(Q * Gaussian(SIGMA).density(0.0, 0.0) * 1000, rel=1e-12)  # a plate at h0
    assert not result.shadows  # a sphere cannot shadow itself


def test_the_sphere_catches_the_whole_cone_and_spreads_it(ball):
    """The cone (16.7 deg) lies inside the silhouette (22 deg): the volume is Q t up to the
    icosphere's area deficit; the convex surface spreads the footprint: along every ray it is
    thinner than a plate normal to the axis at h0, which receives the footprint itself."""
    surface, radius, nozzle, result = ball
    m = coating_metrics(surface, result, gun(), np.ones(surface.n_vertices, bool))
    assert m["deposited_volume_mm3"] == pytest.approx(Q, rel=5e-4)
    assert abs(m["missed_volume_mm3"]) < 5e-4 * Q
    ray = surface.vertices - nozzle
    on_plane = ray * (H0 / -ray[:, 2])[:, None]
    plate_um = Q * Gaussian(SIGMA).density(on_plane[:, 0], -on_plane[:, 1]) * 1000
    off_axis = (result.thickness_um > 1e-6 * stationary_peak_um()) & (np.hypot(on_plane[:, 0], on_plane[:, 1]) > 0.5)
    assert off_axis.sum() > 1000 and np.all(result.thickness_um[off_axis] < plate_um[off_axis])
    assert m["standoff_min_mm"] == pytest.approx(H0, abs=0.01) and m["standoff_max_mm"] < radius + H0

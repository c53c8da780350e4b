"""The closed-form validation cases of spray_model.md §5.6 (σ = 5, h0 = 100, Q = 40, v = 500)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.special import i0e

from coatsim.spray.coating_metrics import thickness_statistics
from coatsim.spray.deposition import deposit
from coatsim.spray.efficiency import CosinePower
from coatsim.spray.footprints import Beta, Gaussian
from coatsim.spray.surfaces import plate
from spray_helpers import (
    H0, Q, SIGMA, V, gun, join_logs, line_log, make_log, pass_profile_um, stationary_log,
    stationary_peak_um, volume,
)


def rotation_y(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    pose = np.eye(4)
    pose[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    return pose


def test_1_stationary_footprint_peak_profile_and_volume():
    surface = plate(100, 100, SIGMA / 4)
    result = deposit(surface, stationary_log((0, 0, H0), 1.0), gun())
    r = np.linalg.norm(surface.vertices[:, :2], axis=1)
    expected = stationary_peak_um() * np.exp(-r**2 / (2 * SIGMA**2)) * (r <= 6 * SIGMA)
    assert result.thickness_um.max() == pytest.approx(254.6479, rel=1e-5)
    np.testing.assert_allclose(result.thickness_um, expected, rtol=1e-5, atol=1e-9)
    assert volume(surface, result.thickness_mm) == pytest.approx(Q * 1.0, rel=1e-3)


@pytest.fixture(scope="module")
def single_pass():
    surface = plate(400, 80, SIGMA / 4)
    return surface, deposit(surface, line_log((-150, 0, H0), (150, 0, H0)), gun())


def test_2_single_pass_bead_peak_width_area_and_volume(single_pass):
    surface, result = single_pass
    mid = np.abs(surface.vertices[:, 0]) < 1e-9
    y = surface.vertices[mid, 1]
    t = result.thickness_um[mid]
    np.testing.assert_allclose(t, pass_profile_um(y), rtol=1e-6, atol=1e-7)
    assert t.max() == pytest.approx(6.383, abs=5e-4)
    spline = CubicSpline(y, t - t.max() / 2)
    crossings = [r for r in spline.roots(extrapolate=False)]
    assert max(crossings) - min(crossings) == pytest.approx(2 * math.sqrt(2 * math.log(2)) * SIGMA, abs=1e-3)
    assert np.sum(t) * (SIGMA / 4) / 1000 == pytest.approx(Q / V, rel=1e-6)  # mm²
    assert volume(surface, result.thickness_mm) == pytest.approx(Q * 300 / V, rel=1e-5)


def test_3_thickness_scales_as_inverse_speed(single_pass):
    surface, slow = single_pass
    fast = deposit(surface, line_log((-150, 0, H0), (150, 0, H0), speed=2 * V), gun())
    hit = slow.thickness_um > 1e-3
    np.testing.assert_allclose(fast.thickness_um[hit] / slow.thickness_um[hit], 0.5, rtol=1e-6)
    switching = join_logs(line_log((-150, 0, H0), (0, 0, H0)), line_log((0, 0, H0), (150, 0, H0), speed=V / 2))
    switching = make_log(switching.t, switching.position, spray=True)  # spray on through the join
    both = deposit(surface, switching, gun())
    at = lambda x: both.thickness_um[np.argmin(np.linalg.norm(surface.vertices - (x, 0, 0), axis=1))]
    assert at(-80) / at(80) == pytest.approx(0.5, rel=1e-6)


def test_4_beta_pass_is_a_parabola():
    surface = plate(300, 40, 0.5)
    result = deposit(surface, line_log((-100, 0, H0), (100, 0, H0)), gun(Beta(10, 1.5)))
    mid = np.abs(surface.vertices[:, 0]) < 1e-9
    y, t = surface.vertices[mid, 1], result.thickness_um[mid]
    expected = 0.75 * Q / (10 * V) * 1000 * np.clip(1 - y**2 / 100, 0, None)
    assert t.max() == pytest.approx(6.0, rel=2e-3)  # rim sampling bias ~(h/R)^1.5, see footprints
    np.testing.assert_allclose(t, expected, atol=0.015)


def raster_cv(pitch: float, spacing: float = SIGMA / 4, passes: int = 9) -> tuple[float, float, float, float]:
    """Snake raster of dry-linked passes along x; statistics over whole periods in the interior."""
    legs = []
    for k in range(passes):
        y = (k - passes // 2) * pitch
        ends = ((-100, y, H0), (100, y, H0))
        legs.append(line_log(*(ends if k % 2 == 0 else ends[::-1])))
    surface = plate(260, passes * pitch + 80, spacing)
    t = deposit(surface, join_logs(*legs, gap_s=0.05), gun()).thickness_um
    x, y = surface.vertices[:, 0], surface.vertices[:, 1]
    roi = (np.abs(x) <= 40) & (y >= -2 * pitch - 1e-9) & (y < 2 * pitch - 1e-9)
    stats = thickness_statistics(t, surface.areas, roi, 1.0)
    return stats["thickness_mean_um"], stats["thickness_cv"], stats["thickness_min_um"], stats["thickness_max_um"]


@pytest.mark.parametrize("pitch, cv", [(10.0, 0.0102), (12.5, 0.060), (15.0, 0.158)])
def test_5_raster_mean_and_ripple(pitch, cv):
    mean, measured, _, _ = raster_cv(pitch)
    exact = math.sqrt(2 * sum(math.exp(-4 * math.pi**2 * m**2 * SIGMA**2 / pitch**2) for m in (1, 2, 3)))
    assert mean == pytest.approx(Q / (V * pitch) * 1000, rel=1e-5)
    assert measured == pytest.approx(exact, rel=1e-3)
    assert measured == pytest.approx(cv, rel=0.01)


@pytest.mark.parametrize("step, ripple", [(2 * SIGMA, 2 * math.exp(-math.pi**2 / 2)), (SIGMA, 2 * math.exp(-2 * math.pi**2))])
def test_6_time_discretisation_ripple(step, ripple):
    surface = plate(300, 40, SIGMA / 4)
    log = line_log((-140, 0, H0), (140, 0, H0), step_mm=step)
    t = deposit(surface, log, gun(substep_mm=step)).thickness_um
    track = (np.abs(surface.vertices[:, 1]) < 1e-9) & (np.abs(surface.vertices[:, 0]) <= 60)
    values = t[track]
    measured = (values.max() - values.min()) / 2 / values.mean()
    if step > SIGMA:
        assert measured == pytest.approx(0.0144, abs=1e-4)
        assert measured == pytest.approx(ripple, rel=1e-3)
    else:
        assert measured < 1e-7


def test_7_double_standoff_quarter_peak_double_width_same_volume():
    surface = plate(200, 200, SIGMA / 4)
    near = deposit(surface, stationary_log((0, 0, H0), 1.0), gun()).thickness_um
    far_result = deposit(surface, stationary_log((0, 0, 2 * H0), 1.0), gun())
    far = far_result.thickness_um
    r = np.linalg.norm(surface.vertices[:, :2], axis=1)
    assert far.max() / near.max() == pytest.approx(0.25, rel=1e-12)
    expected = 0.25 * stationary_peak_um() * np.exp(-r**2 / (2 * (2 * SIGMA) ** 2)) * (r <= 12 * SIGMA)
    np.testing.assert_allclose(far, expected, rtol=1e-5, atol=1e-9)
    assert volume(surface, far_result.thickness_mm) == pytest.approx(Q, rel=1e-6)


def flux_weighted_de(gamma: float, n: float) -> float:
    """Independent quadrature on the reference plane: ∫ g(u, v) cos^(n-1) γ(u, v) du dv for a
    plate tilted by gamma about y under a nozzle looking down."""
    x = np.linspace(-5 * SIGMA, 5 * SIGMA, 801)
    u, v = np.meshgrid(x, x)
    g = Gaussian(SIGMA).density(u, v) * (x[1] - x[0]) ** 2
    rays = np.stack([u, -v, -np.full_like(u, H0)], axis=-1)  # e1 = +x, e2 = a × e1 = -y
    rays /= np.linalg.norm(rays, axis=-1, keepdims=True)
    normal = np.array([math.sin(gamma), 0.0, math.cos(gamma)])
    return float(np.sum(g * (-(rays @ normal)) ** (n - 1)))


@pytest.mark.parametrize("degrees, ratio", [(30, 0.869), (45, 0.715), (60, 0.517)])
def test_8_tilted_plate_volume_and_peak(degrees, ratio):
    gamma = math.radians(degrees)
    big = plate(400, 200, SIGMA / 3, rotation_y(gamma))
    log = stationary_log((0, 0, H0), 1.0)
    assert volume(big, deposit(big, log, gun()).thickness_mm) == pytest.approx(Q, rel=1e-4)
    de = deposit(big, log, gun(efficiency=CosinePower(2.0)))
    assert volume(big, de.thickness_mm) == pytest.approx(Q * flux_weighted_de(gamma, 2.0), rel=1e-4)
    assert volume(big, de.thickness_mm) == pytest.approx(Q * math.cos(gamma), rel=0.01)
    coarse = deposit(big, log, gun()).thickness_um
    centre = big.vertices[np.argmax(coarse)]
    pose = rotation_y(gamma)
    pose[:3, 3] = centre
    fine = plate(4, 4, 0.02, pose)
    peak = deposit(fine, log, gun()).thickness_um.max()
    assert peak / stationary_peak_um() == pytest.approx(ratio, abs=1e-3)


def test_9_full_circle_inner_side_thicker():
    rho, n = 50.0, 2400  # 0.13 mm chords: sagitta 4e-5 mm
    phase = np.linspace(0, 2 * math.pi, n + 1)
    log = make_log(phase * rho / V, np.column_stack([rho * np.cos(phase), rho * np.sin(phase), np.full(n + 1, H0)]))
    surface = plate(180, 180, SIGMA / 4)
    result = deposit(surface, log, gun())
    line = (np.abs(surface.vertices[:, 1]) < 1e-9) & (surface.vertices[:, 0] >= 30) & (surface.vertices[:, 0] <= 70)
    r = surface.vertices[line, 0]
    exact = Q * rho / (V * SIGMA**2) * np.exp(-(r - rho) ** 2 / (2 * SIGMA**2)) * i0e(r * rho / SIGMA**2) * 1000
    np.testing.assert_allclose(result.thickness_um[line], exact, rtol=5e-5, atol=1e-7)
    at = dict(zip(np.round(r, 6), result.thickness_um[line]))
    straight = pass_profile_um(5.0)
    assert at[45.0] / straight == pytest.approx(1.056, abs=1e-3)
    assert at[55.0] / straight == pytest.approx(0.955, abs=1e-3)
    assert volume(surface, result.thickness_mm) == pytest.approx(Q * 2 * math.pi * rho / V, rel=1e-5)


def test_10_dwell_adds_the_stationary_footprint():
    surface = plate(300, 80, SIGMA / 4)
    first, second = line_log((-100, 0, H0), (0, 0, H0)), line_log((0, 0, H0), (100, 0, H0))
    plain = deposit(surface, make_log(np.r_[first.t, second.t[1:] + first.t[-1]],
                                      np.r_[first.position, second.position[1:]]), gun())
    dwell_log = make_log(np.r_[first.t, second.t + first.t[-1] + 0.1], np.r_[first.position, second.position])
    dwell = deposit(surface, dwell_log, gun())
    r = np.linalg.norm(surface.vertices[:, :2], axis=1)
    footprint = 0.1 * stationary_peak_um() * np.exp(-r**2 / (2 * SIGMA**2)) * (r <= 6 * SIGMA)
    np.testing.assert_allclose(dwell.thickness_um - plain.thickness_um, footprint, atol=1e-9)
    assert (dwell.thickness_um - plain.thickness_um).max() == pytest.approx(25.46, abs=0.01)


def trapezoid_stop_log(v: float = V, a: float = 2000.0, dt: float = 0.0005):
    """Straight pass along x from -200 to 200 that brakes at a to a stop at x = 0 and re-accelerates."""
    t_cruise, t_ramp = (200 - v**2 / (2 * a)) / v, v / a
    total = 2 * (t_cruise + t_ramp)
    t = np.r_[np.arange(0, total, dt), total]

    def x_of(time):
        half = np.minimum(time, total - time)
        dist = np.where(half <= t_cruise, v * half, v * t_cruise + v * (half - t_cruise) - 0.5 * a * (half - t_cruise) ** 2)
        return np.where(time <= total / 2, -200 + dist, 200 - dist)

    x = x_of(t)
    return make_log(t, np.column_stack([x, np.zeros_like(x), np.full_like(x, H0)]))


@pytest.mark.parametrize("footprint", [Gaussian(SIGMA), Beta(10, 2)])
def test_11_corner_stop_costs_q_v_over_a_of_volume(footprint):
    surface = plate(440, 40 if isinstance(footprint, Beta) else 80, footprint.spacing_mm)
    stop = deposit(surface, trapezoid_stop_log(), gun(footprint))
    steady = deposit(surface, line_log((-200, 0, H0), (200, 0, H0)), gun(footprint))
    assert stop.steps.spray_time_s - steady.steps.spray_time_s == pytest.approx(0.25, abs=1e-9)
    extra = volume(surface, stop.thickness_mm) - volume(surface, steady.thickness_mm)
    assert extra == pytest.approx(Q * V / 2000.0, rel=1e-3)


def test_13_back_side_and_shadow_receive_nothing():
    from spray_helpers import merge_surfaces

    part = plate(80, 80, 1.0)
    back_pose = np.diag([1.0, -1.0, -1.0, 1.0])  # same plate, facing down (its back side)
    back_pose[2, 3] = -1.0
    back = plate(80, 80, 1.0, back_pose)
    blocker_pose = np.eye(4)
    blocker_pose[2, 3] = 50.0
    blocker = plate(10, 10, 1.0, blocker_pose)
    scene = merge_surfaces(part, back, blocker)
    log = stationary_log((0, 0, H0), 1.0)
    open_view = deposit(scene, log, gun(shadows="off")).thickness_um
    shaded = deposit(scene, log, gun()).thickness_um  # auto: the blocker can shadow the part
    n = part.n_vertices
    assert np.all(open_view[n:2 * n] == 0) and np.all(shaded[n:2 * n] == 0)
    x, y = np.abs(part.vertices[:, 0]), np.abs(part.vertices[:, 1])
    inside = (x < 9.5) & (y < 9.5)  # shadow of the blocker: ±5 mm at 50 mm projects to ±10 mm
    outside = (x > 10.5) | (y > 10.5)
    assert np.all(shaded[:n][inside] == 0) and np.all(open_view[:n][inside] > 0)
    np.testing.assert_array_equal(shaded[:n][outside], open_view[:n][outside])
    np.testing.assert_array_equal(shaded[2 * n:], open_view[2 * n:])


def test_14_halving_the_spacing_changes_mean_and_cv_little():
    coarse = raster_cv(12.5, spacing=SIGMA / 2)
    fine = raster_cv(12.5, spacing=SIGMA / 4)
    assert fine[0] == pytest.approx(coarse[0], rel=5e-3)
    assert fine[1] == pytest.approx(coarse[1], rel=5e-3)
    bound = math.exp(-((SIGMA / 2) ** 2) / (8 * SIGMA**2))
    assert coarse[3] <= fine[3] * (1 + 1e-9) and coarse[3] >= fine[3] * bound
    assert coarse[2] >= fine[2] * (1 - 1e-9) and coarse[2] <= fine[2] / bound

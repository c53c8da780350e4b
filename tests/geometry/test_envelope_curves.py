"""The curvature estimate against the analytic curvature of smooth curves it was not tuned on:
open 3:2 Lissajous figures with a phase (stopped anywhere, near a tight turn too), roses,
epitrochoids and periodic cubic splines, sampled evenly, unevenly and with jitter. The
curve's tightest radius is resolvable (at least 4 input edges and 20 σ)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import Phase, assume, given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline
from scipy.ndimage import maximum_filter1d, minimum_filter1d

from coatsim.geometry.envelope import curvature_profile

TAU = 2 * math.pi
FINE = 200_001  # formula samples the truth is computed on
NEIGHBOURHOOD_WINDOWS = 5  # the estimate is compared with the truth within ± this many windows
FACTOR = 2.0  # ... and must be within this factor of it (never tighter than the curve by more)
SMOOTHED = 3.0  # ... or below it by at most this factor (a turn smoothed over about three windows)
SOME = settings(max_examples=12, deadline=None, derandomize=True, database=None,
                phases=[Phase.explicit, Phase.generate])


def _lissajous(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, bool]:
    a, b, phase, stop = rng.uniform(80, 200), rng.uniform(80, 200), rng.uniform(0, TAU), rng.uniform(0.6, 0.97)
    t = np.linspace(0.0, stop * TAU, FINE)
    return np.column_stack((a * np.sin(3 * t + phase), b * np.sin(2 * t))), t, False


def _rose(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, bool]:
    a, k = rng.uniform(40, 120), int(rng.integers(2, 6))
    t = np.linspace(0.0, TAU if k % 2 == 0 else math.pi, FINE)
    r = a * np.cos(k * t)
    return np.column_stack((r * np.cos(t), r * np.sin(t))), t, True


def _epitrochoid(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, bool]:
    r = rng.uniform(8, 20)
    big, d = r * int(rng.integers(2, 6)), rng.uniform(0.2, 0.8) * r
    t = np.linspace(0.0, TAU, FINE)
    q = (big + r) / r
    return np.column_stack(((big + r) * np.cos(t) - d * np.cos(q * t), (big + r) * np.sin(t) - d * np.sin(q * t))), t, True


def _spline(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, bool]:
    m = int(rng.integers(5, 10))
    angle, radius = np.sort(rng.uniform(0, TAU, m)), rng.uniform(40, 100, m)
    knots = np.column_stack((radius * np.cos(angle), radius * np.sin(angle)))
    spline = CubicSpline(np.linspace(0.0, 1.0, m + 1), np.vstack((knots, knots[:1])), bc_type="periodic")
    t = np.linspace(0.0, 1.0, FINE)
    return spline(t), t, True


FAMILIES = {"lissajous": _lissajous, "rose": _rose, "epitrochoid": _epitrochoid, "spline": _spline}


def _truth(p: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Arc length and |κ| of the formula's fine samples."""
    d1 = np.gradient(p, t, axis=0)
    d2 = np.gradient(d1, t, axis=0)
    kappa = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
    return np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1)))), kappa


def _sampled(p: np.ndarray, s: np.ndarray, closed: bool, count: int, how: str, tol: float,
             rng: np.random.Generator) -> np.ndarray:
    """``count`` points along the curve: evenly, unevenly (gaps 0.3–1.7 of the mean) or
    evenly with jitter of std σ/20."""
    if how == "uneven":
        at = np.concatenate(([0.0], np.cumsum(rng.uniform(0.3, 1.7, count - 1))))
        at *= s[-1] / at[-1]
    else:
        at = np.linspace(0.0, s[-1], count)
    q = np.column_stack((np.interp(at, s, p[:, 0]), np.interp(at, s, p[:, 1])))
    if how == "jitter":
        q[1:-1] += rng.normal(0.0, tol / 20, (count - 2, 2))
    if closed:
        q[-1] = q[0]
    return q


def _compare(family: str, count: int, tol: float, how: str, seed: int) -> tuple[bool, float, float, float]:
    """(whether the tightest turn is resolvable, the estimate's tightest radius over the
    truth's, the largest estimate over the truth's largest |κ| nearby, the truth's smallest
    |κ| nearby over the estimate)."""
    rng = np.random.default_rng(seed)
    p, t, closed = FAMILIES[family](rng)
    s, kappa = _truth(p, t)
    tightest = 1.0 / kappa[2:-2].max()
    profile = curvature_profile(_sampled(p, s, closed, count, how, tol, rng), closed, tol)
    estimate = np.abs(profile.kappa)
    at = np.clip(np.searchsorted(s, np.arange(len(estimate)) * profile.step * s[-1] / profile.length), 0, len(s) - 1)
    size = 2 * int(NEIGHBOURHOOD_WINDOWS * profile.window_mm / (s[1] - s[0])) + 1
    mode = "wrap" if closed else "nearest"
    high, low = maximum_filter1d(kappa, size, mode=mode)[at], minimum_filter1d(kappa, size, mode=mode)[at]
    return (tightest >= 4 * s[-1] / count and tightest >= 20 * tol, profile.tightest_radius_mm / tightest, float((estimate / high).max()),
            float((low / np.maximum(estimate, 1e-12)).max()))


@SOME
@given(family=st.sampled_from(sorted(FAMILIES)), count=st.sampled_from([800, 2000, 4000]),
       tol=st.sampled_from([0.05, 0.1, 0.2]), how=st.sampled_from(["even", "uneven"]), seed=st.integers(0, 2**16))
def test_the_estimate_is_within_a_small_factor_of_the_curvature(family, count, tol, how, seed):
    """Evenly or unevenly sampled: never above 2× the true |κ| nearby (no spike the curve
    does not have), never below a third of it (no turn smoothed away), tightest radius
    within 2×."""
    resolvable, radius, over, under = _compare(family, count, tol, how, seed)
    assume(resolvable)
    assert 1 / FACTOR <= radius <= FACTOR
    assert over <= FACTOR, f"an estimate {over:.3g}× the curve's largest |κ| nearby"
    assert under <= SMOOTHED, f"an estimate {under:.3g}× below the curve's smallest |κ| nearby"


@SOME
@given(family=st.sampled_from(sorted(FAMILIES)), count=st.sampled_from([800, 2000, 4000]),
       tol=st.sampled_from([0.05, 0.1, 0.2]), seed=st.integers(0, 2**16))
def test_the_tightest_radius_of_a_jittered_curve_is_within_a_small_factor(family, count, tol, seed):
    """Jitter of σ/20: the tightest radius the fit is capped by stays within 2× of the curve's."""
    resolvable, radius, _, _ = _compare(family, count, tol, "jitter", seed)
    assume(resolvable)
    assert 1 / FACTOR <= radius <= FACTOR


@pytest.mark.xfail(strict=True, reason="measured limit: under jitter of σ/20 the estimate of a 3:2 Lissajous "
                   "figure spikes locally to ~8× the curve's |κ| nearby (still below its tightest)")
def test_a_jittered_lissajous_figure_has_no_local_spike():
    resolvable, _, over, _ = _compare("lissajous", 4000, 0.05, "jitter", 0)
    assert resolvable and over <= FACTOR

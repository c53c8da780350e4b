"""The scatter of a dense curve's points (measurement noise) and the note it gives a fit."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.geometry import make_curve, segment_curve
from coatsim.geometry.scatter import scatter_mm


def _curve(kind: str, n: int) -> tuple[np.ndarray, bool]:
    t = np.linspace(0.0, 1.0, n, endpoint=kind != "ellipse")
    if kind == "ellipse":
        return np.column_stack([80 * np.cos(2 * math.pi * t), 45 * np.sin(2 * math.pi * t)]), True
    if kind == "damped":
        x = 300 * t
        return np.column_stack([x, 15 * np.exp(-x / 200) * np.sin(x / 12)]), False
    return np.column_stack([200 * t, 40 * t * t]), False  # parabola


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["ellipse", "damped", "parabola"]), st.integers(800, 5000),
       st.floats(0.005, 0.2), st.integers(0, 2**31 - 1))
def test_the_scatter_of_noisy_points_is_their_noise(kind, n, sigma, seed):
    points, closed = _curve(kind, n)
    clean = scatter_mm(points, closed)
    noisy = points + np.random.default_rng(seed).normal(0.0, sigma, points.shape)
    assert clean < 1e-3 * sigma + 1e-6
    assert 0.75 * sigma < scatter_mm(noisy, closed) < 1.3 * sigma


def test_a_fit_that_follows_noise_says_so():
    points, _ = _curve("damped", 2000)
    noisy = points + np.random.default_rng(7).normal(0.0, 0.05, points.shape)
    seg = segment_curve(make_curve(noisy, "noisy", "no"), 0.2)
    assert not seg.limits_kept
    note = next(n for n in seg.notes if "scatter" in n)
    found = float(note.split("scatter about ")[1].split(" mm")[0])
    assert 0.04 < found < 0.06
    # the clean curve at the same tolerance has no such note
    assert not any("scatter" in n for n in segment_curve(make_curve(points, "clean", "no"), 0.2).notes)


@settings(max_examples=6, deadline=None)
@given(st.sampled_from(["ellipse", "lemniscate"]), st.floats(0.4, 0.7), st.integers(0, 2**31 - 1))
def test_points_whose_noise_turns_their_chords_back_are_fitted_through_every_kth_and_checked_against_all(
        kind, noise_per_spacing, seed):
    """A measured curve sampled finer than its noise doubles back at a quarter of its points
    (refused by the curve_reversals budget as it is): thinned to a few scatters apart, it is
    fitted like the smooth curve it is, within the tolerance of every point."""
    from coatsim.core.budgets import BudgetExceeded
    from coatsim.geometry.deviation import hausdorff
    from coatsim.geometry.sampling_check import check_sampling

    n = 10_000
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    if kind == "lemniscate":
        clean = 80 * np.column_stack([np.cos(t), np.sin(t) * np.cos(t)]) / (1 + np.sin(t) ** 2)[:, None]
    else:
        clean = np.column_stack([80 * np.cos(t), 45 * np.sin(t)])
    spacing = float(np.median(np.linalg.norm(np.diff(clean, axis=0), axis=1)))
    sigma = noise_per_spacing * spacing
    noisy = clean + np.random.default_rng(seed).normal(0.0, sigma, clean.shape)
    noisy = np.vstack([noisy, noisy[:1]])
    with pytest.raises(BudgetExceeded):
        check_sampling(noisy, "noisy")
    tol = 16 * sigma
    seg = segment_curve(make_curve(noisy, "noisy", "yes"), tol)
    assert seg.polysegment.n_segments <= 20 and seg.limits_kept
    assert hausdorff(noisy, seg.polysegment).hausdorff <= tol * (1 + 1e-9)
    assert any("fitted through" in n and "checked against all" in n for n in seg.notes), seg.notes


def test_a_refusal_of_noisy_points_names_their_scatter_and_the_tolerance_that_fits_them():
    from coatsim.core.budgets import BudgetExceeded

    t = np.linspace(0.0, 2 * math.pi, 10_000, endpoint=False)
    clean = np.column_stack([80 * np.cos(t), 45 * np.sin(t)])
    noisy = clean + np.random.default_rng(3).normal(0.0, 0.02, clean.shape)
    curve = make_curve(np.vstack([noisy, noisy[:1]]), "noisy", "yes")
    with pytest.raises(BudgetExceeded) as refused:
        segment_curve(curve, 0.1)
    m = re.search(r"its points scatter about ([0-9.]+) mm across it: from a tolerance of ([0-9.]+) mm they are "
                  r"fitted through every k-th point", str(refused.value))
    assert m and 0.015 < float(m.group(1)) < 0.025, str(refused.value)
    assert segment_curve(curve, 1.01 * float(m.group(2))).polysegment.n_segments <= 20


@pytest.mark.parametrize("even", [True, False])
@pytest.mark.parametrize("tol", [0.2, 0.5])
@pytest.mark.parametrize("seed", [11, 12])
def test_a_circle_whose_noise_is_a_small_share_of_its_spacing_is_still_one_circle(even, tol, seed):
    """Noise of σ/20 on points 0.15 mm apart (a sixth of the spacing at σ 0.5): the fit of all the
    points loosened its caps and came back as 50–110 lines and arcs; where it has to, the fit of
    every k-th point is tried (scatter.NOISY_FALLBACK) and checked against all: one circle."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 2 * math.pi, 1500) if even else np.sort(rng.uniform(0.0, 2 * math.pi, 1500))
    pts = np.column_stack((20 + 35 * np.cos(t), -7 + 35 * np.sin(t))) + rng.normal(scale=tol / 20, size=(1500, 2))
    pts = np.vstack((pts, pts[:1]))
    seg = segment_curve(make_curve(pts, "circle", "yes"), tol)
    poly = seg.polysegment
    assert poly.n_segments <= 8 and poly.n_lines == 0 and seg.limits_kept and seg.max_deviation_mm <= tol

"""The band fit's batched look-ahead gives, state by state, the knot _reach and _farthest give
(the same arithmetic element by element), on curves sampled evenly and unevenly, inside the
block and past it."""

import dataclasses
import warnings

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry.band_fit import BandProblem, _farthest, _farthest_of, _reach
from coatsim.geometry.limits import fit_limits


def _problem(seed: int, n: int, narrowed: bool = False) -> BandProblem:
    """A band problem; ``narrowed``: the band open by a share of its width at each knot (as
    along a sparse run's channels)."""
    rng = np.random.default_rng(seed)
    s = np.cumsum(rng.uniform(0.02, 0.3, n))
    points = np.column_stack((s, 2.0 * np.sin(s / 3.0) + 0.02 * rng.normal(size=n)))
    width = rng.uniform(0.1, 1.0, n) if narrowed else None
    return BandProblem.from_points(points, fit_limits(points, False, 0.05, None, None), width)[0]


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(10, 700), st.sampled_from([8, 64, 256]), st.floats(0.005, 0.5),
       st.booleans())
def test_batched_lookahead_matches_reach(seed, n, width, band, narrowed):
    prob = _problem(seed, n, narrowed)
    rng = np.random.default_rng(seed + 1)
    knots = [int(k) for k in rng.integers(0, n, 12)]
    values = [float(prob.phi[k] + rng.uniform(-band, band)) for k in knots]
    ahead = [min(k + 1, n - 1) for k in knots]  # near the curve's own slope: states that reach far
    slopes = [float((prob.phi[j] - prob.phi[k]) / max(prob.s[j] - prob.s[k], 1e-9) + rng.normal(scale=0.02))
              for k, j in zip(knots, ahead)]
    expected = [_farthest(prob, k, *_reach(prob, k, v, t, band)[1:]) for k, v, t in zip(knots, values, slopes)]
    assert _farthest_of(prob, knots, values, slopes, band, width=width) == expected


def test_no_states():
    assert _farthest_of(_problem(0, 20), [], [], [], 0.1) == []


@given(st.integers(0, 2**32 - 1), st.booleans())
@settings(max_examples=20, deadline=None)
def test_a_knot_at_no_distance_bounds_no_curvature(seed, on_edge):
    """Coincident points (closer than float64 resolves at their arc length) give a knot at u = 0:
    it bounds no curvature (no warning, no NaN), one by one as in the batched look-ahead."""
    prob = _problem(seed, 60)
    s, phi = prob.s.copy(), prob.phi.copy()
    s[6], phi[6] = s[5], phi[5]
    prob = dataclasses.replace(prob, s=s, phi=phi, first_steps={})
    band = 0.05
    value = float(phi[5] + (band * prob.width[6] if on_edge else 0.0))  # on the band's edge: 0/0
    slope = float((phi[8] - phi[5]) / (s[8] - s[5]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        b, lo, hi = _reach(prob, 5, value, slope, band)
        batched = _farthest_of(prob, [5], [value], [slope], band, width=8)
    assert not np.isnan(lo).any() and not np.isnan(hi).any()
    assert b > 6 and lo[0] == -prob.cap[5] and hi[0] == prob.cap[5]  # the knot at u = 0 left the caps alone
    assert batched == [_farthest(prob, 5, lo, hi)]

"""The band fit's batched look-ahead gives, state by state, the knot _reach and _farthest give
(the same arithmetic element by element), on curves sampled evenly and unevenly, inside the
block and past it."""

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

"""A junction given up and bent back onto the chain: one segment fewer, the segments after the
window (and the chain's end pose) where they were; the plain merge keeps the length and turn."""

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry.merge import bent_merge, plain_merge
from coatsim.geometry.polysegment import chain
from coatsim.geometry.refine import ChainParams


def _params(seed: int, n: int) -> ChainParams:
    rng = np.random.default_rng(seed)
    return ChainParams(float(rng.uniform(-math.pi, math.pi)), rng.uniform(-0.03, 0.03, n), rng.uniform(10.0, 40.0, n))


def _end_pose(p: ChainParams) -> np.ndarray:
    last = chain((0.0, 0.0), p.heading, p.kappa, p.length)[-1]
    return np.array([*last.end, last.end_heading])


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(3, 9), st.data())
def test_a_bent_merge_leaves_the_rest_of_the_chain_where_it_was(seed, n, data):
    params = _params(seed, n)
    j = data.draw(st.integers(0, n - 2))
    plain = plain_merge(params, j)
    assert len(plain.kappa) == n - 1
    assert math.isclose(plain.length.sum(), params.length.sum(), rel_tol=1e-12)
    assert math.isclose(float(plain.kappa @ plain.length), float(params.kappa @ params.length), rel_tol=1e-9, abs_tol=1e-12)
    bent = bent_merge(params, j)
    if bent is None:  # (no bending within the lengths' limits converged)
        return
    assert len(bent.kappa) == n - 1
    after = slice(min(j + 2, n - 1), n - 1)  # the merged chain's segments past the window
    np.testing.assert_array_equal(bent.kappa[after], params.kappa[after.start + 1:])
    np.testing.assert_array_equal(bent.length[after], params.length[after.start + 1:])
    gap = _end_pose(bent) - _end_pose(params)
    gap[2] = math.remainder(gap[2], 2 * math.pi)
    assert np.abs(gap).max() < 1e-6 * params.length.sum()

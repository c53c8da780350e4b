"""The fitter's LP solver: analytic optima, infeasible and unbounded problems, and the same
solutions as scipy's linprog (the same HiGHS dual simplex) on random minimax problems."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.optimize import linprog

from coatsim.geometry.lp import solve_lp


def test_analytic_vertex():
    # max x + y s.t. x + 2y <= 4, 3x + y <= 6, x, y >= 0: optimum at (1.6, 1.2)
    x = solve_lp(np.array([-1.0, -1.0]), np.array([[1.0, 2.0], [3.0, 1.0]]), np.array([4.0, 6.0]),
                 np.zeros(2), np.full(2, np.inf))
    assert x == pytest.approx([1.6, 1.2], abs=1e-12)


def test_bounds_only_and_free_columns():
    x = solve_lp(np.array([1.0, -2.0]), np.zeros((1, 2)), np.array([1.0]), np.array([-3.0, -np.inf]),
                 np.array([5.0, 7.0]))
    assert x == pytest.approx([-3.0, 7.0])


def test_infeasible_and_unbounded_give_none():
    assert solve_lp(np.array([1.0]), np.array([[1.0], [-1.0]]), np.array([-1.0, -1.0]), np.array([-np.inf]),
                    np.array([np.inf])) is None  # x <= -1 and x >= 1
    assert solve_lp(np.array([-1.0]), np.array([[-1.0]]), np.array([0.0]), np.array([0.0]),
                    np.array([np.inf])) is None


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 7), st.integers(3, 60))
def test_same_solution_as_linprog_on_minimax_steps(seed, d, m):
    # the refinement's step: min t s.t. |r + J dz| <= t, |dz| <= 1
    rng = np.random.default_rng(seed)
    jr, r = rng.normal(size=(m, d)), rng.normal(size=m)
    a_ub = np.vstack((np.hstack((jr, -np.ones((m, 1)))), np.hstack((-jr, -np.ones((m, 1))))))
    b_ub = np.concatenate((-r, r))
    cost = np.concatenate((np.zeros(d), [1.0]))
    lower, upper = np.concatenate((-np.ones(d), [0.0])), np.concatenate((np.ones(d), [np.inf]))
    ours = solve_lp(cost, a_ub, b_ub, lower, upper)
    theirs = linprog(cost, A_ub=a_ub, b_ub=b_ub, bounds=list(zip(lower, [None if u == np.inf else u for u in upper])),
                     method="highs-ds")
    assert theirs.status == 0 and ours is not None
    assert ours[-1] == pytest.approx(theirs.fun, rel=1e-9, abs=1e-12)
    assert np.all(a_ub @ ours <= b_ub + 1e-9)

"""The timing stage's fast paths against toppra's own: the vectorised constant-acceleration
sampling, the single spline, the shared joint-limit constraints and the direct seidel solver."""

from __future__ import annotations

import numpy as np
import pytest
import toppra
import toppra.algorithm
import toppra.constraint as tc
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline
from toppra.parametrizer import ParametrizeConstAccel

from coatsim.core.budgets import MAX_SIM_STEPS
from coatsim.robot.cell import load_cell
from coatsim.robot.timing import PLANNING_FRACTION, _sample, time_cartesian
from coatsim.robot.timing_toppra import Spline as _Spline, joint_limits


@pytest.fixture(scope="module")
def cell():
    return load_cell()


@st.composite
def pieces(draw):
    n = draw(st.integers(3, 40))
    steps = np.array(draw(st.lists(st.floats(1e-4, 5e-3), min_size=n - 1, max_size=n - 1)))
    s = np.concatenate(([0.0], np.cumsum(steps)))
    q = np.array(draw(st.lists(st.lists(st.floats(-2, 2), min_size=6, max_size=6), min_size=n, max_size=n)))
    sd = np.array(draw(st.lists(st.floats(1e-3, 0.5), min_size=n, max_size=n)))
    sd[0] = sd[-1] = 0.0  # rest to rest
    return s, q, sd


@settings(max_examples=60, deadline=None)
@given(pieces(), st.sampled_from([0.002, 0.0005]))
def test_sampling_matches_toppra_parametrize_const_accel(piece, dt):
    s, q, sd = piece
    path = _Spline(s, q)
    mine = _sample(path, s, sd, dt, 1000.0, "piece", MAX_SIM_STEPS)
    reference = ParametrizeConstAccel(toppra.SplineInterpolator(s, q), s, sd)
    assert mine.duration == pytest.approx(reference.duration, rel=1e-12)
    for k, got in enumerate((mine.q, mine.qd, mine.qdd)):
        np.testing.assert_allclose(got, reference(mine.t, k), rtol=1e-7, atol=1e-7 * (1 + np.abs(got).max()))
    ss, vs, _ = reference._eval_params(mine.t)
    np.testing.assert_allclose(mine.s, ss * 1000.0, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(mine.sd, vs * 1000.0, rtol=1e-12, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(pieces())
def test_one_spline_gives_every_derivative_of_the_cubic_through_the_samples(piece):
    s, q, _ = piece
    path, cubic = _Spline(s, q), CubicSpline(s, q)
    x = np.linspace(s[0], s[-1], 97)
    for order in (0, 1, 2):
        scale = 1 + np.abs(cubic(x, order)).max()
        np.testing.assert_allclose(path(x, order), cubic(x, order), atol=1e-8 * scale)
    assert path.dof == 6 and tuple(path.path_interval) == (s[0], s[-1])


def test_a_piece_at_rest_throughout_is_an_execution_error():
    from coatsim.core.errors import ExecutionError

    s = np.array([0.0, 0.004])
    with pytest.raises(ExecutionError, match="no room to move"):
        _sample(_Spline(s, np.zeros((2, 6))), s, np.zeros(2), 0.002, 1000.0, "piece", MAX_SIM_STEPS)


def test_joint_limit_constraints_are_built_once_per_cell(cell):
    assert joint_limits(cell, PLANNING_FRACTION) is joint_limits(cell, PLANNING_FRACTION)
    velocity, acceleration = joint_limits(cell, PLANNING_FRACTION)
    np.testing.assert_array_equal(velocity.vlim[:, 1], PLANNING_FRACTION * cell.v_max)
    np.testing.assert_array_equal(acceleration.alim[:, 1], PLANNING_FRACTION * cell.a_max)


def test_a_cartesian_piece_is_timed_as_stock_toppra_times_it(cell):
    """The direct seidel solver and shared constraints give toppra's own answer."""
    n = 30
    s_mm = np.linspace(0.0, 60.0, n)
    q = cell.home + np.outer(np.sin(np.linspace(0, 1, n)), [0.2, -0.1, 0.15, 0.05, -0.2, 0.3])
    speed, kappa = np.full(n, 200.0), np.full(n, 1 / 40)
    timed = time_cartesian(cell, s_mm, q, speed, kappa, "test")
    s = s_mm / 1000.0
    stock = toppra.algorithm.TOPPRA(
        [tc.JointVelocityConstraint(PLANNING_FRACTION * cell.v_max),
         tc.JointAccelerationConstraint(PLANNING_FRACTION * cell.a_max,
                                        discretization_scheme=tc.DiscretizationType.Interpolation)],
        toppra.SplineInterpolator(s, q), gridpoints=s, solver_wrapper="seidel", parametrizer="ParametrizeConstAccel")
    # same joint limits alone cannot be slower than with the tool limits too
    stock.compute_parameterization(0.0, 0.0)
    assert timed.duration >= ParametrizeConstAccel(stock.path, s, stock.problem_data.sd_vec).duration - 1e-12
    assert np.all(np.abs(timed.qd) <= PLANNING_FRACTION * cell.v_max * (1 + 2e-3))
    assert np.all(timed.sd <= 200.0 * (1 + 1e-6))
    assert timed.s[0] == 0.0 and timed.s[-1] == pytest.approx(60.0, abs=1e-9)

"""Playback lands on the reference: the simulated arm follows a timed joint path within
micro-radians, and never overshoots the accelerations it was commanded, at the steps of
acceleration of exact stops and reversals included (a feed-forward from the reference's own
velocity and acceleration at each row overshot them by 10 % and dipped the speed after ramps)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.robot.cell import load_cell
from coatsim.robot.checks import SUSTAINED_S, joint_ratios
from coatsim.robot.playback import play, stepped_reference
from coatsim.robot.timing import PLANNING_FRACTION, time_joint


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def joined(pieces):
    """Rest-to-rest pieces one after the other, sharing their rest rows (as the twin joins them)."""
    q = np.vstack([pieces[0].q] + [p.q[1:] for p in pieces[1:]])
    qd = np.vstack([pieces[0].qd] + [p.qd[1:] for p in pieces[1:]])
    return q, qd


@settings(max_examples=6, deadline=None)
@given(st.lists(st.lists(st.floats(-0.5, 0.5), min_size=6, max_size=6), min_size=2, max_size=4))
def test_exact_stops_are_played_within_the_commanded_accelerations(cell, steps):
    q_at = [cell.home.copy()]
    for step in steps:
        q_at.append(q_at[-1] + np.array(step))
    pieces = [time_joint(cell, a, b, 2000.0, "test") for a, b in zip(q_at[:-1], q_at[1:])]
    q, qd = joined(pieces)
    run = play(cell, q, qd)
    assert np.abs(run.q - q).max() < 1e-5  # rad: on the reference at every row
    window = max(1, round(SUSTAINED_S / cell.timestep / 2))
    _, commanded, commanded_mean = joint_ratios(q, cell.timestep, cell.v_max, cell.a_max, window)
    _, simulated, simulated_mean = joint_ratios(run.q, cell.timestep, cell.v_max, cell.a_max, window)
    assert simulated_mean.max() <= commanded_mean.max() + 0.01
    assert simulated_mean.max() <= PLANNING_FRACTION + 0.01


def test_the_stepped_reference_integrates_back_to_the_positions(cell):
    dt = cell.timestep
    t = np.arange(200) * dt
    q = np.outer(np.sin(7.0 * t) + t**2, np.ones(6))
    qd = np.outer(7.0 * np.cos(7.0 * t) + 2 * t, np.ones(6))
    arrive, held = stepped_reference(q, qd, dt)
    v, p = arrive[0].copy(), q[0].copy()
    for k in range(len(t) - 1):  # velocity first, then position from the new velocity
        v = v + dt * held[k]
        p = p + dt * v
        assert np.allclose(p, q[k + 1], atol=1e-12) and np.allclose(v, arrive[k + 1], atol=1e-9)

"""Stop counting: a servo settling around zero is one stop, not several."""

from __future__ import annotations

import numpy as np

from coatsim.robot.motion_metrics import _stops


def test_one_dip_is_one_stop():
    speed = np.array([100, 100, 50, 2, 1, 50, 100, 100], float)
    assert _stops(speed, 100.0) == 1


def test_settling_chatter_below_moving_is_one_stop():
    # dips below 5 %, rises to 10 % (not moving again: < 20 %), dips again
    speed = np.array([100, 100, 3, 10, 3, 10, 2, 60, 100], float)
    assert _stops(speed, 100.0) == 1


def test_two_real_stops_and_rest_at_the_ends():
    speed = np.array([0, 1, 50, 100, 1, 100, 100, 2, 100, 50, 0], float)
    assert _stops(speed, 100.0) == 2

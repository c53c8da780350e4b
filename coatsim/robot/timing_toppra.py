"""toppra's side of the timing stage (imported only when a piece is timed: toppra imports
matplotlib at import, which no command that times nothing should pay for).

The constraints coatsim adds (the programmed tool speed, the tool acceleration), the joint
limits built once per cell, the joint path as one spline serving every derivative, and TOPPRA
with the seidel solver chosen directly. See :mod:`coatsim.robot.timing` for the model.
"""

from __future__ import annotations

import functools
import logging
import math

import numpy as np
import toppra
import toppra.algorithm
import toppra.constraint as tc
from scipy.interpolate import CubicSpline, make_interp_spline
from toppra.algorithm.algorithm import ParameterizationAlgorithm
from toppra.constraint.linear_constraint import canlinear_colloc_to_interpolate
from toppra.interpolator import AbstractGeometricPath
from toppra.solverwrapper.cy_seidel_solverwrapper import seidelWrapper

from coatsim.core.errors import ExecutionError
from coatsim.robot.cell import Cell

_FACETS = 8  # the tool-acceleration disc is approximated by an inscribed 16-gon


class PathSpeedBound(tc.LinearConstraint):
    """First-order bound sd <= bound(s) on the path speed (toppra's x = sd^2 <= bound^2)."""

    def __init__(self, s: np.ndarray, bound: np.ndarray):
        super().__init__()
        self._s, self._bound = s, bound

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        xbound = np.zeros((len(gridpoints), 2))
        xbound[:, 1] = np.interp(gridpoints, self._s, self._bound) ** 2
        return None, None, None, None, None, None, xbound


@functools.lru_cache(maxsize=16)
def _facets(accel: float) -> tuple[np.ndarray, np.ndarray]:
    """The tool-acceleration disc of radius ``accel`` as an inscribed polygon: (F, g) with F x <= g."""
    phi = np.linspace(0.0, math.pi, _FACETS + 1)
    return np.column_stack((np.cos(phi), np.sin(phi))), np.full(_FACETS + 1, accel * math.cos(math.pi / (2 * _FACETS)))


class ToolAcceleration(tc.LinearConstraint):
    """|(sdd, kappa * sd^2)| <= a_max: tangential and centripetal TCP acceleration together.

    Valid when s is the TCP arc length; the disc is replaced by an inscribed polygon, which is
    linear in (u, x) = (sdd, sd^2) as toppra requires.
    """

    def __init__(self, s: np.ndarray, kappa: np.ndarray, accel: float):
        super().__init__()
        self._s, self._kappa = s, np.abs(kappa)
        self._F, self._g = _facets(float(accel))
        self.identical = True
        self.set_discretization_type(tc.DiscretizationType.Interpolation)

    def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
        n = len(gridpoints)
        kappa = np.interp(gridpoints, self._s, self._kappa)
        a = np.column_stack((np.ones(n), np.zeros(n)))
        b = np.column_stack((np.zeros(n), kappa))
        return canlinear_colloc_to_interpolate(a, b, np.zeros((n, 2)), self._F, self._g, None, None,
                                               gridpoints, identical=True)


@functools.lru_cache(maxsize=8)
def joint_limits(cell: Cell, planning_fraction: float) -> tuple[tc.LinearConstraint, tc.LinearConstraint]:
    """The cell's joint speed and acceleration constraints at the planning fraction (they hold
    no path state)."""
    return (tc.JointVelocityConstraint(planning_fraction * cell.v_max),
            tc.JointAccelerationConstraint(planning_fraction * cell.a_max,
                                           discretization_scheme=tc.DiscretizationType.Interpolation))


class Spline(AbstractGeometricPath):
    """Cubic spline (not-a-knot) through the samples, every derivative evaluated from the one
    spline (a B-spline: three times cheaper to build than scipy's CubicSpline, the same curve)."""

    def __init__(self, s: np.ndarray, q: np.ndarray):
        self._spline = make_interp_spline(s, q, k=3) if len(s) >= 4 else CubicSpline(s, q)
        self._s, self._q = s, q

    def __call__(self, path_positions, order=0):
        return self._spline(path_positions, order)

    @property
    def dof(self) -> int:
        return self._q.shape[1]

    @property
    def path_interval(self) -> np.ndarray:
        return np.array([self._s[0], self._s[-1]])

    @property
    def waypoints(self):
        return self._s, self._q


class _TOPPRA(toppra.algorithm.TOPPRA):
    """TOPPRA with the seidel solver, chosen directly: the stock constructor probes for every
    other solver (cvxpy, qpOASES) on each call."""

    def __init__(self, constraints: list, path: AbstractGeometricPath, gridpoints: np.ndarray):
        ParameterizationAlgorithm.__init__(self, constraints, path, gridpoints=gridpoints,
                                           parametrizer="ParametrizeConstAccel")
        self.solver_wrapper = seidelWrapper(self.constraints, self.path, self.gridpoints, solve_lp1d=True)


def parametrize(cell: Cell, path: AbstractGeometricPath, extra: list, gridpoints: np.ndarray, label: str,
                planning_fraction: float):
    """Gridpoints and path speeds sd >= 0 of the time-optimal parametrisation; ExecutionError naming
    ``label`` when toppra finds none."""
    toppra_log = logging.getLogger("toppra")
    if toppra_log.level != logging.ERROR:  # coatsim reports a failure itself (setLevel clears caches)
        toppra_log.setLevel(logging.ERROR)
    algo = _TOPPRA([*joint_limits(cell, planning_fraction), *extra], path, gridpoints)
    algo.compute_parameterization(0.0, 0.0)
    data = algo.problem_data
    code = data.return_code
    if code != toppra.algorithm.ParameterizationReturnCode.Ok or data.sd_vec is None \
            or not np.all(np.isfinite(data.sd_vec)):
        raise ExecutionError(
            f"{label}: timing failed (toppra {code.name if hasattr(code, 'name') else code}); the path is "
            "not feasible under the joint limits, e.g. it passes too close to a singularity"
        )
    return data.gridpoints, np.maximum(data.sd_vec, 0.0)

"""After playback: did the simulated arm do what the controller commanded, within its limits?

Two checks, each naming the program step where it fails:
- tracking: the distance from the simulated TCP to the commanded TCP path (the forward
  kinematics of the commanded joint trajectory, blends included; searched within
  ``WINDOW_S`` of the same instant, so a servo lag is not counted as an error);
- joint limits: joint speed and acceleration of the simulated arm (finite differences of the
  logged joint positions, as the motion metrics compute them) against the cell's limits.
Above the failure thresholds the run cannot be trusted: ExecutionError (exit 3). Smaller
excesses are warnings (the run's events). The acceleration that fails a run is the mean over
``SUSTAINED_S`` (a velocity change over that time): a step or two of excess while the servo
corrects a disturbance is a warning, no failure; an arm that hits something or cannot follow
exceeds the limits for far longer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import mujoco
import numpy as np

from coatsim.core.errors import ExecutionError
from coatsim.robot.cell import Cell
from coatsim.robot.chain import tcp_positions_mm

TRACKING_FAIL_MM = 1.0    # the simulated tool is off the commanded path by more: failure
TRACKING_WARN_MM = 0.25   # ... by more than this: a warning (normal runs stay below 0.15 mm)
LIMIT_FAIL_RATIO = 1.05   # a joint speed or acceleration above 105 % of its limit: failure
LIMIT_WARN_RATIO = 1.0    # ... above the limit: a warning
WINDOW_S = 0.05
SUSTAINED_S = 0.02


@dataclass(frozen=True)
class Finding:
    """One check's row: what, how much, the limit it is compared with, where (row, and the
    joint for joint checks, 0-based; -1 for the tracking check)."""

    what: str
    value: float
    limit: float
    row: int
    joint: int = -1


def tracking_error(simulated_mm: np.ndarray, commanded_mm: np.ndarray, window: int) -> np.ndarray:
    """Distance (n,) from each simulated point to the commanded polyline between rows
    i - window and i + window."""
    n = len(simulated_mm)
    best = np.linalg.norm(simulated_mm - commanded_mm, axis=1)
    if n < 2:
        return best
    a, b = commanded_mm[:-1], commanded_mm[1:]
    ab = b - a
    den = np.einsum("ij,ij->i", ab, ab)
    rows = np.arange(n)
    for k in range(-window, window):
        j = np.clip(rows + k, 0, n - 2)
        rel = simulated_mm - a[j]
        u = np.clip(np.einsum("ij,ij->i", rel, ab[j]) / np.where(den[j] > 0, den[j], 1.0), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(rel - u[:, None] * ab[j], axis=1))
    return best


def joint_ratios(q: np.ndarray, dt: float, v_max: np.ndarray, a_max: np.ndarray,
                 sustained: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint speed, acceleration and sustained acceleration (the velocity change over 2
    ``sustained`` rows) over their limits, (n, 6) each (finite differences of q)."""
    qd = np.gradient(q, dt, axis=0)
    qdd = np.gradient(qd, dt, axis=0)
    w = max(1, min(sustained, (len(q) - 1) // 2))
    mean = np.zeros_like(qd)
    if len(q) > 2 * w:
        mean[w:-w] = (qd[2 * w:] - qd[:-2 * w]) / (2 * w * dt)
    return np.abs(qd) / v_max, np.abs(qdd) / a_max, np.abs(mean) / a_max


def contacts(cell: Cell, q: np.ndarray) -> list[str]:
    """Names of the geom pairs in contact with the arm at configuration ``q``."""
    data = mujoco.MjData(cell.model)
    data.qpos[:] = q
    mujoco.mj_forward(cell.model, data)
    pairs = []
    for c in data.contact[:data.ncon]:
        names = sorted(cell.model.geom(int(g)).name or f"geom {int(g)}" for g in (c.geom1, c.geom2))
        if " and ".join(names) not in pairs:
            pairs.append(" and ".join(names))
    return pairs


def check_playback(cell: Cell, t: np.ndarray, q_sim: np.ndarray, tcp_sim_mm: np.ndarray, q_cmd: np.ndarray,
                   label: Callable[[int], str]) -> list[str]:
    """Warnings for small excesses; ExecutionError naming the step (``label(row)``) for large ones."""
    dt = float(np.median(np.diff(t))) if len(t) > 1 else cell.timestep
    error = tracking_error(tcp_sim_mm, tcp_positions_mm(cell, q_cmd), max(1, int(round(WINDOW_S / dt))))
    speed, accel, sustained = joint_ratios(q_sim, dt, cell.v_max, cell.a_max, max(1, int(round(SUSTAINED_S / dt / 2))))
    checks = (("tracking", error[:, None], TRACKING_FAIL_MM, TRACKING_WARN_MM),
              ("joint speed", speed, LIMIT_FAIL_RATIO, LIMIT_WARN_RATIO),
              ("joint acceleration", accel, math.inf, LIMIT_WARN_RATIO),
              ("sustained joint acceleration", sustained, LIMIT_FAIL_RATIO, math.inf))

    def finding(name: str, values: np.ndarray, limit: float, row: int) -> Finding:
        joint = int(np.argmax(values[row])) if values.shape[1] > 1 else -1
        return Finding(name, float(values[row].max()), limit, row, joint)

    fail = [finding(name, values, limit, int(rows[0])) for name, values, limit, _ in checks
            for rows in [np.flatnonzero(values.max(axis=1) > limit)] if len(rows)]
    if fail:
        raise ExecutionError(_failure(cell, min(fail, key=lambda f: f.row), t, q_sim, tcp_sim_mm, label))
    warnings = []
    for name, values, _, limit in checks:
        worst = values.max(axis=1)
        if np.any(worst > limit):
            f = finding(name, values, limit, int(np.argmax(worst)))
            warnings.append(f"{label(f.row)}: {_measure(f)} at t = {t[f.row]:.3f} s")
    return warnings


def _measure(f: Finding) -> str:
    if f.what == "tracking":
        return f"the simulated tool is {f.value:.3f} mm off the commanded path (more than {f.limit:g} mm)"
    mean = f" (mean over {1000 * SUSTAINED_S:g} ms)" if f.what.startswith("sustained") else ""
    return (f"JT{f.joint + 1} {f.what.removeprefix('sustained ')}{mean} at {100 * f.value:.1f} % of its limit "
            f"(more than {100 * f.limit:.0f} %)")


def _failure(cell: Cell, f: Finding, t: np.ndarray, q: np.ndarray, tcp_mm: np.ndarray, label: Callable[[int], str]) -> str:
    x, y, z = tcp_mm[f.row]
    touching = contacts(cell, q[f.row])
    if touching:
        cause = f"the arm touches the cell ({', '.join(touching)}): move the path away from it"
    elif f.what == "tracking":
        cause = "the simulated arm cannot follow the commanded motion: slow down or move the path"
    else:
        cause = "slow down, or move the path away from singularities and joint limits"
    return (f"{label(f.row)}: the simulation diverged: {_measure(f)} at t = {t[f.row]:.3f} s, tool at "
            f"x={x:.1f} y={y:.1f} z={z:.1f} mm; {cause}")

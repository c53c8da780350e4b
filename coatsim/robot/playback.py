"""Play a timed joint trajectory on the MuJoCo arm and record what the tool really does.

Each joint's ``pid`` actuator gets, at every step, the reference position and velocity of the
current time plus an inverse-dynamics feed-forward torque (``mj_inverse`` on the reference
position, velocity and acceleration), which keeps the tracking error to a few hundredths of a
millimetre. The stepping itself is MuJoCo's ``mj_step`` loop run in C by ``mujoco.rollout``;
the TCP position, spray axis and velocity come from the model's site sensors.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np
from mujoco import rollout

from coatsim.robot.cell import M_TO_MM, Cell

_FULL = mujoco.mjtState.mjSTATE_FULLPHYSICS


@dataclass(frozen=True, eq=False)
class Playback:
    """Simulated run, one row per step: t (n,) s, q and qd (n, 6), tcp (n, 3) mm,
    axis (n, 3) unit spray axis, speed (n,) mm/s."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    tcp: np.ndarray
    axis: np.ndarray
    speed: np.ndarray


def feed_forward(cell: Cell, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
    """Joint torques (n, 6) that realise (q, qd, qdd) exactly (passive forces included)."""
    model, data = cell.model, mujoco.MjData(cell.model)
    out = np.empty_like(q)
    qpos, qvel, qacc, force = data.qpos, data.qvel, data.qacc, data.qfrc_inverse  # views, bound once
    for k in range(len(q)):
        qpos[:] = q[k]
        qvel[:] = qd[k]
        qacc[:] = qdd[k]
        mujoco.mj_inverse(model, data)
        out[k] = force
    return out


def play(cell: Cell, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> Playback:
    """Simulate the arm following the reference (n rows on the model's time grid)."""
    model = cell.model
    data = mujoco.MjData(model)
    n = len(q)
    ctrl = np.empty((n, model.nu))
    ff = feed_forward(cell, q, qd, qdd)
    for j in range(6):
        adr = model.actuator_ctrladr[j]
        ctrl[:, adr], ctrl[:, adr + 1], ctrl[:, adr + 2] = q[:, j], qd[:, j], ff[:, j]
    data.qpos[:] = q[0]
    data.qvel[:] = qd[0]
    mujoco.mj_forward(model, data)
    state0 = np.empty(mujoco.mj_stateSize(model, _FULL))
    mujoco.mj_getState(model, data, state0, _FULL)
    states, sensors = rollout.rollout(model, data, state0, ctrl)
    states, sensors = states[0], sensors[0]
    # sensors of step k describe the state before that step: row 0 is the initial state,
    # row k > 0 the state after step k - 1
    qpos = np.vstack((state0[None, 1:7], states[:-1, 1:7]))
    qvel = np.vstack((state0[None, 7:13], states[:-1, 7:13]))
    adr = {name: model.sensor(name).adr[0] for name in ("tcp_pos", "tcp_axis", "tcp_vel")}
    tcp = sensors[:, adr["tcp_pos"]:adr["tcp_pos"] + 3] * M_TO_MM
    axis = sensors[:, adr["tcp_axis"]:adr["tcp_axis"] + 3]
    vel = sensors[:, adr["tcp_vel"]:adr["tcp_vel"] + 3] * M_TO_MM
    return Playback(t=np.arange(n) * cell.timestep, q=qpos, qd=qvel, tcp=tcp, axis=axis,
                    speed=np.linalg.norm(vel, axis=1))

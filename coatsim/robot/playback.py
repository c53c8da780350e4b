"""Play a timed joint trajectory on the MuJoCo arm and record what the tool really does.

Each joint's ``pid`` actuator gets, at every step, the reference position, the velocity with
which the integrator arrives there, and a feed-forward torque: discrete-time inverse dynamics
(``mj_inverse`` with ``invdiscrete``, so the implicit damping of the servo is accounted for) of
the acceleration held over the step. The arm then lands on every reference position, and the
servo only corrects what the model cannot foresee. The stepping itself is MuJoCo's ``mj_step``
loop run in C by ``mujoco.rollout``; the TCP position, spray axis and velocity come from the
model's site sensors.
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
    """Joint torques (n, 6) with which one step of the model's integrator from (q, qd) gives the
    acceleration qdd (discrete-time inverse dynamics: the implicit damping of joints and servos
    included, passive forces too)."""
    model, data = cell.model, mujoco.MjData(cell.model)
    flags = model.opt.enableflags
    model.opt.enableflags = flags | mujoco.mjtEnableBit.mjENBL_INVDISCRETE
    out = np.empty_like(q)
    qpos, qvel, qacc, force = data.qpos, data.qvel, data.qacc, data.qfrc_inverse  # views, bound once
    try:
        for k in range(len(q)):
            qpos[:] = q[k]
            qvel[:] = qd[k]
            qacc[:] = qdd[k]
            mujoco.mj_inverse(model, data)
            out[k] = force
    finally:
        model.opt.enableflags = flags
    return out


def stepped_reference(q: np.ndarray, qd: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """The velocities (n, 6) on arrival at each row and the accelerations (n, 6) held over each
    step with which MuJoCo's integrator (velocity first, then position from the new velocity) lands
    on every reference position q exactly. The reference's own velocity and acceleration at a row
    drive the arm off it wherever the acceleration changes (by a fraction of a step of that change)
    and wherever it speeds up (half a step of the speed gained); the servo's correction then
    overshot the limits at every exact stop (JT4 of a twisted blade: 113 % for a step, 105 % over
    20 ms, where the reference asked 95 %) and dipped the tool's speed by 3 % after each ramp."""
    arrive = np.vstack((qd[:1], np.diff(q, axis=0) / dt))
    held = np.vstack((np.diff(arrive, axis=0) / dt, np.zeros((1, q.shape[1]))))
    return arrive, held


def play(cell: Cell, q: np.ndarray, qd: np.ndarray) -> Playback:
    """Simulate the arm following the reference (n rows on the model's time grid)."""
    model = cell.model
    data = mujoco.MjData(model)
    n = len(q)
    ctrl = np.empty((n, model.nu))
    arrive, held = stepped_reference(q, qd, cell.timestep)
    ff = feed_forward(cell, q, arrive, held)
    for j in range(6):
        adr = model.actuator_ctrladr[j]
        ctrl[:, adr], ctrl[:, adr + 1], ctrl[:, adr + 2] = q[:, j], arrive[:, j], ff[:, j]
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

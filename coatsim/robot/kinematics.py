"""Vectorised forward kinematics and Jacobians of the arm, for many configurations at once.

MuJoCo computes kinematics one configuration per call; checking or refining an IK solution at
every path sample that way costs a Python round trip per sample. ``Chain`` reads the serial chain
from the world to the TCP site out of the model (body offsets, hinge axes and anchors) and
evaluates the site poses and the site's geometric Jacobian for (N, 6) configurations with numpy.
It is checked against ``mj_kinematics`` when built; a model it does not reproduce (a joint that
is not a hinge on the way to the TCP, say) gets no chain and the callers use MuJoCo alone.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

_CHECK_M = 1e-9  # agreement with MuJoCo required at build time (m, and rad via the rotation)


def _quat_matrix(quat_wxyz: np.ndarray) -> np.ndarray:
    out = np.empty(9)
    mujoco.mju_quat2Mat(out, np.asarray(quat_wxyz, float))
    return out.reshape(3, 3)


def axis_rotations(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) about the unit ``axis`` (3,) by ``angle`` (N,) rad (Rodrigues)."""
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


@dataclass(frozen=True)
class _Link:
    """One body on the way to the TCP: its offset from the parent body, and its hinge (if any)."""

    pos: np.ndarray
    rot: np.ndarray
    joint: int          # index into q, -1 for a body without a joint
    axis: np.ndarray
    anchor: np.ndarray
    zero: float         # qpos0 of the joint (MuJoCo rotates by q - qpos0)


@dataclass(frozen=True)
class Poses:
    """Site poses of N configurations, metres: TCP position (N, 3), rotation (N, 3, 3), the
    Jacobian of the TCP position and rotation (N, 6, 6) when asked for, and the positions (N, 3)
    of the extra sites."""

    tcp: np.ndarray
    rotation: np.ndarray
    jacobian: np.ndarray | None
    sites: dict[int, np.ndarray]


class Chain:
    """The serial chain from the world to one site (the TCP), evaluated for many configurations."""

    def __init__(self, links: tuple[_Link, ...], site_pos: np.ndarray, site_rot: np.ndarray,
                 extra: dict[int, tuple[int, np.ndarray]]):
        self._links, self._site_pos, self._site_rot, self._extra = links, site_pos, site_rot, extra

    @classmethod
    def build(cls, model: mujoco.MjModel, site: int, extra_sites: tuple[int, ...] = ()) -> Chain | None:
        """The chain of ``model`` to ``site`` (with the positions of ``extra_sites`` on it), or
        None when the model is not a chain of hinges this class reproduces exactly."""
        path = []
        body = int(model.site_bodyid[site])
        while body != 0:
            path.append(body)
            body = int(model.body_parentid[body])
        path.reverse()
        links = []
        for b in path:
            start, count = int(model.body_jntadr[b]), int(model.body_jntnum[b])
            if count > 1 or (count == 1 and model.jnt_type[start] != mujoco.mjtJoint.mjJNT_HINGE):
                return None
            j = start if count == 1 else -1
            links.append(_Link(model.body_pos[b].copy(), _quat_matrix(model.body_quat[b]),
                               int(model.jnt_qposadr[j]) if j >= 0 else -1,
                               model.jnt_axis[j].copy() if j >= 0 else np.zeros(3),
                               model.jnt_pos[j].copy() if j >= 0 else np.zeros(3),
                               float(model.qpos0[model.jnt_qposadr[j]]) if j >= 0 else 0.0))
        if sorted(link.joint for link in links if link.joint >= 0) != list(range(model.nq)):
            return None
        extra = {}
        for s in extra_sites:
            if int(model.site_bodyid[s]) not in path:
                return None
            extra[s] = (path.index(int(model.site_bodyid[s])), model.site_pos[s].copy())
        chain = cls(tuple(links), model.site_pos[site].copy(), _quat_matrix(model.site_quat[site]), extra)
        return chain if chain._agrees(model, site) else None

    def _agrees(self, model: mujoco.MjModel, site: int) -> bool:
        rng = np.random.default_rng(0)
        lo, hi = model.jnt_range[:model.nq, 0], model.jnt_range[:model.nq, 1]
        qs = np.vstack((model.qpos0, rng.uniform(lo, hi, size=(4, model.nq))))
        mine = self.poses(qs)
        data = mujoco.MjData(model)
        for k, q in enumerate(qs):
            data.qpos[:] = q
            mujoco.mj_kinematics(model, data)
            if np.abs(data.site_xpos[site] - mine.tcp[k]).max() > _CHECK_M:
                return False
            if np.abs(data.site_xmat[site].reshape(3, 3) - mine.rotation[k]).max() > _CHECK_M:
                return False
            if any(np.abs(data.site_xpos[s] - mine.sites[s][k]).max() > _CHECK_M for s in self._extra):
                return False
        return True

    def poses(self, q: np.ndarray, jacobian: bool = False) -> Poses:
        """Site poses (and the TCP Jacobian) for configurations q (N, nq), rad; metres out."""
        q = np.atleast_2d(np.asarray(q, float))
        n = len(q)
        p = np.zeros((n, 3))
        r = np.broadcast_to(np.eye(3), (n, 3, 3))
        axes, anchors, frames = [], [], []
        for link in self._links:
            p = p + r @ link.pos
            r = r @ link.rot
            if link.joint >= 0:
                turn = axis_rotations(link.axis, q[:, link.joint] - link.zero)
                p = p + r @ link.anchor - (r @ turn) @ link.anchor
                r = r @ turn
                axes.append((link.joint, r @ link.axis))
                anchors.append(p + r @ link.anchor)
            frames.append((p, r))
        tcp = p + r @ self._site_pos
        sites = {s: frames[i][0] + frames[i][1] @ offset for s, (i, offset) in self._extra.items()}
        jac = None
        if jacobian:
            jac = np.zeros((n, 6, len(axes)))
            for (j, z), a in zip(axes, anchors):
                jac[:, :3, j] = np.cross(z, tcp - a)
                jac[:, 3:, j] = z
        return Poses(tcp, r @ self._site_rot, jac, sites)

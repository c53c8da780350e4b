"""Vectorised forward kinematics and Jacobians of the arm, for many configurations at once.

MuJoCo computes kinematics one configuration per call; checking or refining an IK solution at
every path sample that way costs a Python round trip per sample. ``Chain`` reads the serial chain
from the world to the TCP site out of the model (body offsets, hinge axes and anchors) and
evaluates the site poses and the site's geometric Jacobian for (N, 6) configurations with numpy.
It is checked against ``mj_kinematics`` when built; a model it does not reproduce (a joint that
is not a hinge on the way to the TCP, say) gets no chain and the callers use MuJoCo alone.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import mujoco
import numpy as np

from coatsim.robot.cell import M_TO_MM

if TYPE_CHECKING:
    from coatsim.robot.cell import Cell

_CHECK_M = 1e-9  # agreement with MuJoCo required at build time (m, and rad via the rotation)
_BLOCK = 4096    # configurations per vectorised call (bounds the temporaries of long trajectories)


def _quat_matrix(quat_wxyz: np.ndarray) -> np.ndarray:
    out = np.empty(9)
    mujoco.mju_quat2Mat(out, np.asarray(quat_wxyz, float))
    return out.reshape(3, 3)


@dataclass(frozen=True)
class _Link:
    """One hinge on the way to the TCP: the fixed transform (pos, rot) from the previous hinge's
    frame to its body (jointless bodies between folded in), and its rotation by q - zero about
    ``axis`` through ``anchor``; with Rodrigues' turn I + sin K + (1 - cos) K^2, the body's
    rotation is rot + sin A + (1 - cos) B and its anchor shift sin a + (1 - cos) b."""

    pos: np.ndarray
    rot: np.ndarray
    joint: int
    axis: np.ndarray
    anchor: np.ndarray
    zero: float

    def products(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        x, y, z = self.axis
        k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
        a, b = self.rot @ k, self.rot @ k @ k
        return a, b, a @ self.anchor, b @ self.anchor, self.rot @ self.axis


@dataclass(frozen=True)
class Poses:
    """Site poses of N configurations, metres: TCP position (N, 3), rotation (N, 3, 3), the
    positions (N, 3) of the extra sites, and the world joint axes and anchors (N, nq, 3) from
    which ``jacobian`` builds the TCP's geometric Jacobian."""

    tcp: np.ndarray
    rotation: np.ndarray
    sites: dict[int, np.ndarray]
    axes: np.ndarray
    anchors: np.ndarray

    def jacobian(self, rows: np.ndarray | slice = slice(None)) -> np.ndarray:
        """(n, 6, nq): TCP linear velocity (m/rad) over orientation rate, for the ``rows`` asked."""
        z, lever = self.axes[rows], self.tcp[rows][:, None, :] - self.anchors[rows]
        linear = np.stack((z[..., 1] * lever[..., 2] - z[..., 2] * lever[..., 1],
                           z[..., 2] * lever[..., 0] - z[..., 0] * lever[..., 2],
                           z[..., 0] * lever[..., 1] - z[..., 1] * lever[..., 0]), axis=1)
        return np.concatenate((linear, np.swapaxes(z, 1, 2)), axis=1)


class Chain:
    """The serial chain from the world to one site (the TCP), evaluated for many configurations."""

    def __init__(self, links: tuple[_Link, ...], site_pos: np.ndarray, site_rot: np.ndarray,
                 extra: dict[int, tuple[int, np.ndarray]]):
        self._links, self._site_pos, self._site_rot, self._extra = links, site_pos, site_rot, extra
        self._joints = np.array([link.joint for link in links])
        self._zeros = np.array([link.zero for link in links])
        # per link, stacked (L, ...): rot, A, B (3, 3); pos, A anchor, B anchor, the axis in the
        # rotated frame and the anchor (3,): every link's turn for N configurations in one go
        products = [link.products() for link in links]
        self._rot = np.array([link.rot for link in links])
        self._a, self._b = np.array([pr[0] for pr in products]), np.array([pr[1] for pr in products])
        self._pos = np.array([link.pos for link in links])
        self._a_anchor, self._b_anchor = np.array([pr[2] for pr in products]), np.array([pr[3] for pr in products])
        self._rot_axis = np.array([pr[4] for pr in products])
        self._anchor = np.array([link.anchor for link in links])

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
        links: list[_Link] = []
        extra: dict[int, tuple[int, np.ndarray]] = {}
        fixed_p, fixed_r = np.zeros(3), np.eye(3)  # from the last hinge's frame to the current body
        for b in path:
            start, count = int(model.body_jntadr[b]), int(model.body_jntnum[b])
            if count > 1 or (count == 1 and model.jnt_type[start] != mujoco.mjtJoint.mjJNT_HINGE):
                return None
            fixed_p, fixed_r = fixed_p + fixed_r @ model.body_pos[b], fixed_r @ _quat_matrix(model.body_quat[b])
            if count == 1:
                adr = int(model.jnt_qposadr[start])
                links.append(_Link(fixed_p, fixed_r, adr, model.jnt_axis[start].copy(), model.jnt_pos[start].copy(),
                                   float(model.qpos0[adr])))
                fixed_p, fixed_r = np.zeros(3), np.eye(3)
            for s in extra_sites:
                if int(model.site_bodyid[s]) == b:
                    extra[s] = (len(links) - 1, fixed_p + fixed_r @ model.site_pos[s])
        if sorted(link.joint for link in links) != list(range(model.nq)) or len(extra) != len(extra_sites):
            return None
        site_pos = fixed_p + fixed_r @ model.site_pos[site]
        site_rot = fixed_r @ _quat_matrix(model.site_quat[site])
        chain = cls(tuple(links), site_pos, site_rot, extra)
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

    def poses(self, q: np.ndarray) -> Poses:
        """Site poses (and what the TCP Jacobian needs) for configurations q (N, nq), rad; metres."""
        q = np.atleast_2d(np.asarray(q, float))
        n, nq = q.shape
        angle = q[:, self._joints] - self._zeros
        sin, vers = np.sin(angle)[..., None], 1.0 - np.cos(angle)[..., None]
        turns = self._rot + sin[..., None] * self._a + vers[..., None] * self._b  # (n, L, 3, 3)
        shifts = (self._pos - sin * self._a_anchor - vers * self._b_anchor)[..., None]  # (n, L, 3, 1)
        axes, anchors = np.empty((n, nq, 3)), np.empty((n, nq, 3))
        frames = []
        p, r = np.zeros((n, 3)), None
        for k, joint in enumerate(self._joints):
            if r is None:  # the world frame: no rotation to apply
                axes[:, joint] = self._rot_axis[k]
                p = p + shifts[:, k, :, 0]
                r = turns[:, k]
            else:
                axes[:, joint] = r @ self._rot_axis[k]
                p = p + (r @ shifts[:, k])[..., 0]
                r = r @ turns[:, k]
            anchors[:, joint] = p + r @ self._anchor[k]
            frames.append((p, r))
        sites = {i: (frames[k][0] + frames[k][1] @ offset) if k >= 0 else np.broadcast_to(offset, (n, 3))
                 for i, (k, offset) in self._extra.items()}
        return Poses(p + r @ self._site_pos, r @ self._site_rot, sites, axes, anchors)


@functools.lru_cache(maxsize=8)
def cell_chain(cell: Cell) -> Chain | None:
    """The cell's chain to its TCP site (with the wrist centre), built and checked once per cell."""
    return Chain.build(cell.model, cell.tcp_site, (cell.wrist_site,))


def tcp_positions_mm(cell: Cell, q: np.ndarray) -> np.ndarray:
    """TCP positions (n, 3) mm of configurations q (n, 6): the vectorised chain, in blocks; MuJoCo
    row by row for a model without one."""
    q = np.asarray(q, float)
    chain = cell_chain(cell)
    if chain is None:
        data = mujoco.MjData(cell.model)
        out = np.empty((len(q), 3))
        for k in range(len(q)):
            data.qpos[:] = q[k]
            mujoco.mj_kinematics(cell.model, data)
            out[k] = data.site_xpos[cell.tcp_site]
        return out * M_TO_MM
    blocks = [chain.poses(q[i:i + _BLOCK]).tcp for i in range(0, len(q), _BLOCK)]
    return np.concatenate(blocks) * M_TO_MM if blocks else np.zeros((0, 3))

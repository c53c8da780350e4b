"""The input run as coordinates: a point, a tangent and a rotation-minimising normal frame at
every arc length, so that a state of the fitted chain (its offset y and tangent tilt a in the
curve's normal plane) is measured relative to the curve.

The tangent at a vertex is the chord over ± ``window_mm`` (smoothing digitising noise); the
normal vectors (u, v) are carried from vertex to vertex by the smallest rotation that takes
one tangent to the next (a discrete rotation-minimising frame: it does not spin about the
tangent, so a chain's curvature vector keeps about the same coordinates in it along an arc).
Between vertices everything is interpolated linearly (the normals re-orthogonalised). The
frames are only coordinates: a state is turned into a point and a tangent in space with the
same frame on both sides of a junction, so the chain's continuity never depends on them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.space.vectors import cross3, norm3

MAX_VERTICES = 4000  # the frame field keeps at most about this many vertices of a run


def _unit(v: np.ndarray) -> np.ndarray:
    return v / norm3(v, keepdims=True)


def _locate(s: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The edge of every arc length ``at`` in ``s`` and the share of the way along it."""
    i = np.clip(np.searchsorted(s, at, side="right") - 1, 0, len(s) - 2)
    width = s[i + 1] - s[i]
    return i, np.clip((at - s[i]) / np.where(width > 0, width, 1.0), 0.0, 1.0)


def _lerp(values: np.ndarray, i: np.ndarray, u: np.ndarray) -> np.ndarray:
    return values[i] + u[..., None] * (values[i + 1] - values[i])


def _interp(s: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    return _lerp(values, *_locate(s, at))


def _carried(tangent: np.ndarray) -> np.ndarray:
    """A unit normal at every tangent, each the one before turned by the smallest rotation
    onto its tangent (Rodrigues about a × b: v cos + (a × b) × v + (a × b) ((a × b)·v) / (1 + cos)).
    Sequential, so on plain floats: a numpy call per vertex would cost fifty times as much."""
    seed = np.eye(3)[int(np.argmin(np.abs(tangent[0])))]
    u = [list(seed - (seed @ tangent[0]) * tangent[0])]
    t = tangent.tolist()
    for (ax, ay, az), (bx, by, bz) in zip(t[:-1], t[1:]):
        ux, uy, uz = u[-1]
        cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
        cos = ax * bx + ay * by + az * bz
        k = (cx * ux + cy * uy + cz * uz) / max(1.0 + cos, 1e-12)
        u.append([ux * cos + cy * uz - cz * uy + cx * k, uy * cos + cz * ux - cx * uz + cy * k,
                  uz * cos + cx * uy - cy * ux + cz * k])
    u_arr = np.array(u)
    return _unit(u_arr - np.einsum("ij,ij->i", u_arr, tangent)[:, None] * tangent)


@dataclass(frozen=True, eq=False)
class Reference:
    """Frames along a run: arc length ``s`` (n,), ``points``, unit ``tangent``, normals
    ``u`` and ``v`` (n, 3) at n vertices of the run."""

    s: np.ndarray
    points: np.ndarray
    tangent: np.ndarray
    u: np.ndarray
    v: np.ndarray

    @property
    def length(self) -> float:
        return float(self.s[-1])

    def frame(self, at: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(point, tangent, u, v) at arc lengths ``at`` (any shape; vectors get a last axis of 3)."""
        i, w = _locate(self.s, np.asarray(at, dtype=float))
        t = _unit(_lerp(self.tangent, i, w))
        u = _lerp(self.u, i, w)
        u = _unit(u - np.einsum("...i,...i->...", u, t)[..., None] * t)
        return _lerp(self.points, i, w), t, u, cross3(t, u)


def _smoothed(points: np.ndarray, s: np.ndarray, at: np.ndarray, window_mm: float) -> np.ndarray:
    """The mean of the polyline over ± ``window_mm`` of arc length around every ``at``, the
    window narrowed toward the ends so that they stay where they are (digitising noise would
    otherwise make the frames, and with them the knots' derivatives, jitter)."""
    edge = np.linalg.norm(np.diff(points, axis=0), axis=1)
    area = np.vstack((np.zeros((1, 3)), np.cumsum(edge[:, None] * (points[:-1] + points[1:]) / 2, axis=0)))

    def integral(x: np.ndarray) -> np.ndarray:
        i = np.clip(np.searchsorted(s, x, side="right") - 1, 0, len(s) - 2)
        u = np.where(edge[i] > 0, (x - s[i]) / np.where(edge[i] > 0, edge[i], 1.0), 0.0)
        p = points[i] + u[:, None] * (points[i + 1] - points[i])
        return area[i] + (x - s[i])[:, None] * (points[i] + p) / 2

    half = np.minimum(window_mm, np.minimum(at - s[0], s[-1] - at))
    mean = (integral(at + half) - integral(at - half)) / np.where(half > 0, 2 * half, 1.0)[:, None]
    exact = half <= 0
    mean[exact] = _interp(s, points, at[exact])
    return mean


def reference(points: np.ndarray, s: np.ndarray, window_mm: float,
              start_tangent: np.ndarray | None = None, end_tangent: np.ndarray | None = None) -> Reference:
    """The frame field of a run of ``points`` (n, 3) at arc lengths ``s`` (see the module
    text); ``start_tangent``/``end_tangent`` replace the chord tangents at the ends."""
    keep = np.unique(np.linspace(0, len(points) - 1, min(len(points), MAX_VERTICES)).astype(int))
    pts, ss = _smoothed(points, s, s[keep], window_mm), s[keep]
    ahead = _smoothed(points, s, np.minimum(ss + window_mm, s[-1]), window_mm)
    behind = _smoothed(points, s, np.maximum(ss - window_mm, 0.0), window_mm)
    tangent = _unit(ahead - behind)
    if start_tangent is not None:
        tangent[0] = _unit(np.asarray(start_tangent, dtype=float))
    if end_tangent is not None:
        tangent[-1] = _unit(np.asarray(end_tangent, dtype=float))
    u = _carried(tangent)
    return Reference(ss, pts, tangent, u, np.cross(tangent, u))

"""The arcs of a G1 chain as states relative to the input curve, vectorised.

A piece starts at arc length s0 of the run in the state (y, a): at the point
γ(s0) + y_u u + y_v v with the tangent along t + a_u u + a_v v (the frame of
coatsim.geometry.space.reference at s0), and turns with the curvature vector c_u u + c_v v
(made normal to its tangent); it ends where it crosses the curve's normal plane at s1. Its
end state is measured in the frame at s1, and so is its offset y from every input point in
between, in that point's normal plane. Two pieces join G1 exactly when the end state of the
first is the start state of the second: both are turned into a point and a tangent with the
same frame. An arc is written through the start point and tangent (never centre + r·…) as

    x(ℓ) = x0 + ℓ sinc(κℓ) t + ℓ²/2 sinc²(κℓ/2) c,   t(ℓ) = cos(κℓ) t + ℓ sinc(κℓ) c,

which stays exact as the curvature goes to zero (a line).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.geometry.space.primitives import Arc3, Line3, Segment3
from coatsim.geometry.space.reference import Reference
from coatsim.geometry.space.vectors import norm3

NEWTON_STEPS = 4  # steps to land an arc on a normal plane (quadratic convergence from ~1 % off)
LINE_TURN = 1e-12  # a piece turning less than this (rad) is a line
_EPS = float(np.finfo(float).eps)  # np.sinc's stand-in for 0


def _sinc(x: np.ndarray) -> np.ndarray:
    """sin(x) / x: ``np.sinc(x / π)`` written out (the same floats, without its overhead)."""
    y = np.pi * (x / math.pi)
    y = np.where(y, y, _EPS)
    return np.sin(y) / y


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


def arc_point(start: np.ndarray, t: np.ndarray, c: np.ndarray, ell: np.ndarray) -> np.ndarray:
    theta = norm3(c) * ell
    return start + (ell * _sinc(theta))[..., None] * t + (ell * ell / 2 * _sinc(theta / 2) ** 2)[..., None] * c


def arc_tangent(t: np.ndarray, c: np.ndarray, ell: np.ndarray) -> np.ndarray:
    theta = norm3(c) * ell
    return np.cos(theta)[..., None] * t + (ell * _sinc(theta))[..., None] * c


def land(start: np.ndarray, t: np.ndarray, c: np.ndarray, origin: np.ndarray, normal: np.ndarray,
         ell: np.ndarray) -> np.ndarray:
    """Arc lengths at which the arcs cross the planes through ``origin`` normal to ``normal``,
    by Newton from ``ell``."""
    for _ in range(NEWTON_STEPS):
        gap = _dot(arc_point(start, t, c, ell) - origin, normal)
        rate = _dot(arc_tangent(t, c, ell), normal)
        ell = ell - gap / np.where(np.abs(rate) > 0.1, rate, 0.1)
    return ell


Frame = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # (point, tangent, u, v): Reference.frame's


def state_point(frame: Frame, y: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(point, unit tangent) of states (y, a) in ``frame`` (at their arc lengths)."""
    p, tg, u, v = frame
    t = tg + a[..., :1] * u + a[..., 1:] * v
    return p + y[..., :1] * u + y[..., 1:] * v, t / norm3(t, keepdims=True)


def curvature_vector(frame: Frame, c: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The curvature vector c_u u + c_v v of ``frame``, made normal to the tangent t."""
    _, _, u, v = frame
    vec = c[..., :1] * u + c[..., 1:] * v
    return vec - _dot(vec, t)[..., None] * t


def state_of(frame: Frame, point: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """The state (y_u, y_v, a_u, a_v) of a point on the normal plane of ``frame`` with a tangent."""
    p, tg, u, v = frame
    rel = point - p
    along = _dot(tangent, tg)[..., None]
    return np.concatenate((np.stack((_dot(rel, u), _dot(rel, v)), axis=-1),
                           np.stack((_dot(tangent, u), _dot(tangent, v)), axis=-1) / along), axis=-1)


@dataclass(frozen=True, eq=False)
class Samples:
    """Input points (m, 3) at arc lengths ``s`` (m,) with the normal-plane frame there
    (``normal`` the curve's tangent, ``u``, ``v``), computed once."""

    points: np.ndarray
    s: np.ndarray
    normal: np.ndarray
    u: np.ndarray
    v: np.ndarray

    @classmethod
    def of(cls, ref: Reference, points: np.ndarray, s: np.ndarray) -> Samples:
        _, normal, u, v = ref.frame(s)
        return cls(points, s, normal, u, v)

    def take(self, pick: np.ndarray) -> Samples:
        return Samples(self.points[pick], self.s[pick], self.normal[pick], self.u[pick], self.v[pick])


def end_states(ref: Reference, params: np.ndarray) -> np.ndarray:
    """End states (..., n, 4) of pieces ``params`` (..., n, 8) = (s0, s1, y_u, y_v, a_u, a_v,
    c_u, c_v)."""
    return evaluate(ref, params, None, np.zeros(0, dtype=int))[0]


def evaluate(ref: Reference, params: np.ndarray, samples: Samples | None,
             piece: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """End states (..., n, 4) of pieces ``params`` (..., n, 8), and the offsets (..., m, 2)
    of the chain from the ``samples`` in their normal planes, each measured on its piece
    ``piece`` (m,) (extended beyond its ends if the point lies outside)."""
    s0, s1 = params[..., 0], params[..., 1]
    here, there = ref.frame(s0), ref.frame(s1)
    start, t = state_point(here, params[..., 2:4], params[..., 4:6])
    c = curvature_vector(here, params[..., 6:8], t)
    origin, normal, _, _ = there
    ell = land(start, t, c, origin, normal, s1 - s0)
    ends = state_of(there, arc_point(start, t, c, ell), arc_tangent(t, c, ell))
    if samples is None:
        return ends, np.zeros(ends.shape[:-2] + (0, 2))
    j = piece
    ell_i = land(start[..., j, :], t[..., j, :], c[..., j, :], samples.points, samples.normal, samples.s - s0[..., j])
    rel = arc_point(start[..., j, :], t[..., j, :], c[..., j, :], ell_i) - samples.points
    return ends, np.stack((_dot(rel, samples.u), _dot(rel, samples.v)), axis=-1)


def segment(start: np.ndarray, t: np.ndarray, c: np.ndarray, ell: float) -> Segment3:
    """The Line3/Arc3 leaving ``start`` along unit ``t`` with curvature vector ``c`` (normal
    to t) for ``ell`` mm."""
    kappa = float(np.linalg.norm(c))
    end = arc_point(start, t, c, np.float64(ell))
    if kappa * ell < LINE_TURN:
        return Line3(start, end)
    normal = np.cross(t, c)
    return Arc3(start, end, start + c / kappa**2, normal / np.linalg.norm(normal), 1.0 / kappa, kappa * ell)

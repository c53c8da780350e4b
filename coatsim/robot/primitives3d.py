"""Programmed 3-D path primitives (lines and circular arcs, mm) and exact point-to-path distance.

An arc is stored as p(phi) = centre + radius * (cos(phi) u + sin(phi) v), phi in [0, sweep],
with u, v orthonormal and sweep > 0, so arc length s maps to phi = s / radius.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.path.arcs import DegenerateArc, circle_through


@dataclass(frozen=True, eq=False)
class Primitive:
    """A straight line (``radius`` = inf) or a circular arc from ``start`` to ``end``."""

    start: np.ndarray
    end: np.ndarray
    length: float
    centre: np.ndarray | None = None
    u: np.ndarray | None = None
    v: np.ndarray | None = None
    radius: float = math.inf
    sweep: float = 0.0

    @property
    def is_arc(self) -> bool:
        return self.centre is not None

    @property
    def curvature(self) -> float:
        return 1.0 / self.radius if self.is_arc else 0.0

    def points(self, s: np.ndarray) -> np.ndarray:
        """Points at arc lengths ``s`` (n,) from the start, shape (n, 3)."""
        s = np.asarray(s, dtype=float)
        if not self.is_arc:
            frac = s / self.length if self.length > 0 else np.zeros_like(s)
            return self.start + frac[:, None] * (self.end - self.start)
        phi = s / self.radius
        return self.centre + self.radius * (np.cos(phi)[:, None] * self.u + np.sin(phi)[:, None] * self.v)

    def tangents(self, s: np.ndarray) -> np.ndarray:
        """Unit tangents at arc lengths ``s``, shape (n, 3)."""
        s = np.asarray(s, dtype=float)
        if not self.is_arc:
            t = (self.end - self.start) / self.length if self.length > 0 else np.zeros(3)
            return np.tile(t, (len(s), 1))
        phi = s / self.radius
        return -np.sin(phi)[:, None] * self.u + np.cos(phi)[:, None] * self.v

    def closest(self, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Distance (n,) from points ``p`` (n, 3) to this primitive, and the arc length (n,)
        of the closest point."""
        if not self.is_arc:
            if self.length == 0:
                return np.linalg.norm(p - self.start, axis=1), np.zeros(len(p))
            t = (self.end - self.start) / self.length
            s = np.clip((p - self.start) @ t, 0.0, self.length)
            return np.linalg.norm(p - (self.start + s[:, None] * t), axis=1), s
        rel = p - self.centre
        phi = np.mod(np.arctan2(rel @ self.v, rel @ self.u), 2 * math.pi)
        beyond = phi > self.sweep
        # outside the swept range: the nearer end point wins
        to_end, to_start = phi - self.sweep, 2 * math.pi - phi
        phi = np.where(beyond, np.where(to_end < to_start, self.sweep, 0.0), phi)
        s = phi * self.radius
        return np.linalg.norm(p - self.points(s), axis=1), s


def line(start: np.ndarray, end: np.ndarray) -> Primitive:
    start, end = np.asarray(start, float), np.asarray(end, float)
    return Primitive(start=start, end=end, length=float(np.linalg.norm(end - start)))


def arc_through(start: np.ndarray, via: np.ndarray, end: np.ndarray) -> Primitive | None:
    """The circular arc from ``start`` through ``via`` to ``end``; None if the points are
    collinear or coincide (no unique circle). The test is the interpreter's, so a program that
    reads is a program the robot stage can build."""
    a, c = np.asarray(start, float), np.asarray(end, float)
    try:
        circle = circle_through(a, via, c)
    except DegenerateArc:
        return None
    centre, normal, radius, sweep = circle.center, circle.normal, circle.radius, circle.sweep
    u = (a - centre) / radius
    v = np.cross(normal, u)
    return Primitive(start=a, end=c, length=radius * sweep, centre=centre, u=u, v=v, radius=radius, sweep=sweep)

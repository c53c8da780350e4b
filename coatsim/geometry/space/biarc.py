"""Spatial biarcs: two arcs, tangent to each other, joining two points with given tangents.

Given (p0, t0) and (p1, t1), the biarc's tangent polygon is p0, q0 = p0 + α t0,
q1 = p1 − β t1, p1 with |q1 − q0| = α + β; the junction J = (β q0 + α q1) / (α + β) splits the
middle leg in the ratio of the two arcs' tangent lengths, so the first arc has the tangent
triangle p0, q0, J (legs α) and the second J, q1, p1 (legs β), and both share the tangent
q1 − q0 at J: G1 by construction. With β = λ α the condition is a quadratic in α with one
positive root (Šír, Feichtinger, Jüttler 2006 on biarcs; the same family in space).
A leg that is straight gives a line.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.space.primitives import DegenerateArc, Line3, Segment3, arc_from_tangent


def tangent_segment(start: np.ndarray, tangent: np.ndarray, end: np.ndarray) -> Segment3:
    """The arc leaving ``start`` along ``tangent`` to ``end``, or the line when ``end`` lies
    on the tangent's line (ahead)."""
    try:
        return arc_from_tangent(start, tangent, end)
    except DegenerateArc:
        return Line3(start, end)


def biarc(p0: np.ndarray, t0: np.ndarray, p1: np.ndarray, t1: np.ndarray, ratio: float = 1.0) -> tuple[Segment3, Segment3] | None:
    """The biarc from (p0, unit t0) to (p1, unit t1) with β = ``ratio`` · α, or None when the
    data admit none with positive legs (the end behind the start, turning back)."""
    v = p1 - p0
    tt = t0 + ratio * t1
    a = 2.0 * ratio * (float(t0 @ t1) - 1.0)
    b = -2.0 * float(v @ tt)
    c = float(v @ v)
    root = math.sqrt(max(b * b - 4.0 * a * c, 0.0))
    if not -b + root > 1e-12 * math.sqrt(c):
        return None
    alpha = 2.0 * c / (-b + root)
    beta = ratio * alpha
    q0, q1 = p0 + alpha * t0, p1 - beta * t1
    junction = (beta * q0 + alpha * q1) / (alpha + beta)
    middle = q1 - q0
    norm = float(np.linalg.norm(middle))
    t_mid = middle / norm if norm > 0 else t0
    return tangent_segment(p0, t0, junction), tangent_segment(junction, t_mid, p1)

"""Moves as a language can write them: an arc outside the planes the language has circular
moves in becomes the lines through poses on it whose chords stay within the tolerance."""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.space.primitives import Line3
from coatsim.path.placement import PlacedMove


def _principal(normal: np.ndarray) -> bool:
    return bool(np.isclose(np.abs(normal).max(), 1.0, rtol=0.0, atol=1e-9))


def expressible(moves: list[PlacedMove], arc_planes: str, tolerance_mm: float) -> tuple[list[PlacedMove], int]:
    """The moves as a language with native arcs in ``arc_planes`` ("any", "principal" or "none")
    can write them: every other arc as the lines through poses on it whose chords stay within
    ``tolerance_mm`` of it; and how many arcs became lines."""
    if arc_planes == "any":
        return moves, 0
    out: list[PlacedMove] = []
    changed = 0
    for m in moves:
        arc = m.geometry
        if not m.is_arc or (arc_planes == "principal" and _principal(arc.normal)):
            out.append(m)
            continue
        changed += 1
        step = 2.0 * math.acos(max(-1.0, 1.0 - tolerance_mm / arc.radius))
        n = max(1, math.ceil(arc.sweep / step))
        poses = [m.pose_at(k / n) for k in range(n + 1)]
        out += [PlacedMove(Line3(a.translation_mm, b.translation_mm), a, b, m.part, speed_mm_s=m.speed_mm_s)
                for a, b in zip(poses[:-1], poses[1:])]
    return out, changed

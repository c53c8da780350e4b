"""From level curves to passes: the edge band cut off, spraying order, lead-in and lead-out.

Every pattern yields, per connected piece of the region, curves on the surface tagged with the
rank of their level (0, 1, 2, ... from one end of the field to the other). Here they lose what
lies within the edge band of the region's border (cut exactly where the border distance equals
the band), and are put in spraying order: level by level, within a level each next curve the one starting nearest
to where the last ended; ``serpentine`` reverses the open curves of every other level,
``oneway`` keeps them all running one way (higher field values on their left). A closed loop
starts at its point nearest to the last pass's end. Open passes get a straight lead-in and
lead-out along their end tangents (in the surface's tangent plane), ``margin_mm`` long.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from coatsim.geometry.surface.contours import SurfaceCurve

Order = Literal["serpentine", "oneway"]
ORDERS: tuple[str, ...] = ("serpentine", "oneway")


@dataclass(frozen=True, eq=False)
class Trace:
    """A curve on one region piece's mesh, with the rank of its level and the piece's index."""

    curve: SurfaceCurve
    rank: int
    piece: int


def barycentric(vertices: np.ndarray, faces: np.ndarray, face_ids: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Barycentric weights (k, 3) of points lying in the faces ``face_ids``."""
    a, b, c = (vertices[faces[face_ids, k]] for k in range(3))
    e1, e2, d = b - a, c - a, points - a
    g11, g12, g22 = (e1 * e1).sum(1), (e1 * e2).sum(1), (e2 * e2).sum(1)
    r1, r2 = (d * e1).sum(1), (d * e2).sum(1)
    det = np.where(np.abs(g11 * g22 - g12**2) > 0, g11 * g22 - g12**2, 1.0)
    u, v = (g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det
    return np.column_stack([1 - u - v, u, v])


def clip(curve: SurfaceCurve, border_mm: np.ndarray, band_mm: float, vertices: np.ndarray,
         faces: np.ndarray) -> list[SurfaceCurve]:
    """The pieces of ``curve`` at least ``band_mm`` from the border (``border_mm`` per vertex)."""
    if band_mm <= 0:
        return [curve]
    value = curve.sample(faces, border_mm)
    inside = value >= band_mm
    if inside.all():
        return [curve]
    n = len(value)
    order = np.arange(n)
    if curve.closed:  # start at a point outside so that every piece is one run
        order = np.roll(order, -int(np.flatnonzero(~inside)[0]))
    runs = np.split(order, np.flatnonzero(np.diff(inside[order].astype(int)) != 0) + 1)
    pieces = []
    for run in runs:
        if not inside[run[0]]:
            continue
        before = run[0] - 1 if run[0] > 0 else (n - 1 if curve.closed else None)
        after = run[-1] + 1 if run[-1] < n - 1 else (0 if curve.closed else None)
        parts = [curve.take(run, closed=False)]
        if before is not None:
            parts.insert(0, _crossing(curve, before, run[0], value, band_mm, vertices, faces))
        if after is not None:
            parts.append(_crossing(curve, run[-1], after, value, band_mm, vertices, faces))
        points = np.concatenate([p.points for p in parts])
        if len(points) >= 2:
            pieces.append(SurfaceCurve(points, np.concatenate([p.faces for p in parts]),
                                       np.concatenate([p.bary for p in parts]), False))
    return pieces


def _crossing(curve: SurfaceCurve, i: int, j: int, value: np.ndarray, band_mm: float, vertices: np.ndarray,
              faces: np.ndarray) -> SurfaceCurve:
    """The point between points i and j (neighbours) where the border distance is the band;
    it lies in the face of the segment from i to j (the face stored with the earlier point)."""
    face = curve.faces[i if (j == i + 1 or (j == 0 and i == len(value) - 1)) else j]
    tau = (band_mm - value[i]) / (value[j] - value[i]) if value[j] != value[i] else 0.5
    point = curve.points[i] + tau * (curve.points[j] - curve.points[i])
    bary = barycentric(vertices, faces, np.array([face]), point[None])[0]
    return SurfaceCurve(point[None], np.array([face]), bary[None], False)


def spraying_order(traces: list[Trace], order: Order) -> list[tuple[SurfaceCurve, int]]:
    """The curves of ``traces`` in spraying order (see the module docstring), each with its
    piece; pieces in the order given, each piece's levels from the lowest rank up."""
    ordered: list[tuple[SurfaceCurve, int]] = []
    here: np.ndarray | None = None
    for piece in dict.fromkeys(t.piece for t in traces):
        ranks = sorted({t.rank for t in traces if t.piece == piece})
        for turn, rank in enumerate(ranks):
            level = [t.curve for t in traces if t.piece == piece and t.rank == rank]
            if order == "serpentine" and turn % 2:
                level = [c if c.closed else c.reversed() for c in level]
            while level:
                k = 0 if here is None else int(np.argmin([np.linalg.norm(c.points[0] - here) for c in level]))
                curve = level.pop(k)
                if curve.closed and here is not None:
                    curve = curve.rolled(int(np.argmin(np.linalg.norm(curve.points - here, axis=1))))
                ordered.append((curve, piece))
                here = curve.points[-1] if not curve.closed else curve.points[0]
    return ordered


def leads(points: np.ndarray, normals: np.ndarray, margin_mm: float,
          tangent_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Lead-in (ending before the first point) and lead-out (after the last) of an open pass:
    one point each, ``margin_mm`` along the end tangents measured over ``tangent_mm`` of the pass."""
    if margin_mm <= 0:
        return np.zeros((0, 3)), np.zeros((0, 3))
    start = _end_tangent(points, normals[0], tangent_mm)
    end = _end_tangent(points[::-1], normals[-1], tangent_mm)
    return (points[0] - margin_mm * start)[None], (points[-1] - margin_mm * end)[None]


def _end_tangent(points: np.ndarray, normal: np.ndarray, tangent_mm: float) -> np.ndarray:
    """Unit direction into the pass at its first point, in the tangent plane of ``normal``."""
    reach = np.linalg.norm(points - points[0], axis=1)
    far = np.flatnonzero(reach >= min(tangent_mm, 0.5 * float(reach.max())))
    direction = points[far[0] if len(far) else -1] - points[0]
    direction = direction - (direction @ normal) * normal
    norm = float(np.linalg.norm(direction))
    return direction / norm if norm > 0 else direction

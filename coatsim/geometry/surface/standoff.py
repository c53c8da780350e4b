"""Whether the gun stands clear of the part along each pass: the segment from a pass point out
along its normal to the tool centre point, the stand-off away, must meet no triangle of the part.
Where one does, the part lies between the nozzle and the spot it sprays, or the nozzle inside the
part (an inner wall facing another nearer than the stand-off, a flange under a wall's foot): the
spot gets no coat there, and the twin stops on the collision. The plan names where, in a note."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from coatsim.geometry.rays import RayCaster
from coatsim.geometry.surface.surfacepaths import Pass


@dataclass(frozen=True)
class Blocked:
    """A pass whose gun would meet the part: its index, how many of its points, the first of
    them and how far out along its normal the part is met there (mm)."""

    pass_index: int
    points: int
    first_point: int
    distance_mm: float


def blocked_standoff(vertices_mm: np.ndarray, faces: np.ndarray, passes: Sequence[Pass], standoff_mm: float,
                     above_mm: float) -> list[Blocked]:
    """The passes where the part meets the segment from a point's tool centre point to
    ``above_mm`` over the point (a point lifted onto the smooth surface lies that near its own
    facets), in pass order."""
    caster = RayCaster(np.asarray(vertices_mm, float), np.asarray(faces))
    found = []
    for k, p in enumerate(passes):
        near = p.points + above_mm * p.normals
        tcp = p.tcp_mm(standoff_mm)
        hit = np.flatnonzero(caster.blocked(tcp, near - tcp, np.full(len(tcp), standoff_mm - above_mm)))
        if len(hit):
            j = int(hit[0])
            found.append(Blocked(k, len(hit), j, _first_hit(caster, near[j], p.normals[j], standoff_mm - above_mm)
                                 + above_mm))
    return found


def _first_hit(caster: RayCaster, start: np.ndarray, normal: np.ndarray, length: float) -> float:
    """The distance from ``start`` along ``normal`` (within ``length``) of the first triangle met,
    to a thousandth of the length."""
    lo, hi = 0.0, length
    while hi - lo > 1e-3 * length:
        mid = 0.5 * (lo + hi)
        if caster.blocked(start[None], (mid * normal)[None], np.array([mid]))[0]:
            hi = mid
        else:
            lo = mid
    return hi

"""Pass spacing: from the footprint's overlap ripple, and as measured along the surface.

For Gaussian tracks of standard deviation s repeated every D, the thickness is a Fourier series
whose first harmonic dominates: peak-to-valley ripple / mean = 4 exp(-2 pi^2 s^2 / D^2)
(D = 2s: 2.9 %, 2.5s: 17 %, 3s: 45 %), so the largest spacing for a ripple r is
D = pi s sqrt(2 / ln(4 / r)). Other footprints use their own standard deviation in the same
formula (an estimate).

Measured: the gap at a point of a pass is the distance along the surface (distance.NearestOnCurves:
the arc through the nearest point, or fast marching where the arc does not hold) to the nearest pass of a
neighbouring level (levels alternate between two sets, each measured from the other), skipping
points whose nearest point on that pass is one of its open ends. Coverage is the share of the
region's area (lumped at the vertices) within half a spacing of a pass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.surface.distance import NearestOnCurves
from coatsim.geometry.surface.passes import Trace
from coatsim.geometry.surface.piece import Piece

#: a vertex counts as covered up to this fraction beyond half a spacing (rounding, not method error)
COVERAGE_SLACK = 1e-6


def ripple_pct(spacing_mm: float, sigma_mm: float) -> float:
    """Peak-to-valley thickness ripple (% of the mean) of Gaussian tracks ``spacing_mm`` apart."""
    return 400.0 * math.exp(-2.0 * math.pi**2 * sigma_mm**2 / spacing_mm**2)


def spacing_for_ripple(ripple: float, sigma_mm: float) -> float:
    """The largest spacing (mm) whose ripple stays at or below ``ripple`` %."""
    if not (math.isfinite(ripple) and 0 < ripple < 100):
        raise InputError(f"ripple_pct must be between 0 and 100 %, found {ripple:g}", parameters=("ripple_pct",))
    return math.pi * sigma_mm * math.sqrt(2.0 / math.log(400.0 / ripple))


@dataclass(frozen=True, eq=False)
class Measured:
    """Gaps (mm) between neighbouring passes at their points, and the covered area (mm^2)."""

    gaps_mm: np.ndarray
    covered_mm2: float


def measure(piece: Piece, traces: list[Trace], spacing_mm: float) -> Measured:
    """Gaps and coverage of the passes ``traces`` on one region piece."""
    faces, normals = piece.faces, piece.normals
    groups = [[t.curve for t in traces if t.rank % 2 == p] for p in (0, 1)]
    reach = [_Reach(piece, g) for g in groups]
    nearest = [NearestOnCurves([(c.points, _unit(c.sample(faces, normals)), c.closed) for c in g]) for g in groups]
    gaps = [np.zeros(0)]
    for p in (0, 1):
        for curve in groups[p]:
            d, on_end = nearest[1 - p].distance(curve.points, _unit(curve.sample(faces, normals)), piece.surface,
                                                lambda: curve.sample(faces, reach[1 - p]()))
            gaps.append(d[np.isfinite(d) & ~on_end])
    half = 0.5 * spacing_mm * (1 + COVERAGE_SLACK)
    nearest_pass = np.minimum(*(n.distance(piece.vertices, normals, piece.surface, r, within=half)[0]
                                for n, r in zip(nearest, reach)))
    covered = nearest_pass <= half
    return Measured(np.concatenate(gaps), float(piece.vertex_areas_mm2()[covered].sum()))


class _Reach:
    """Fast-marching distance on a piece from curves, solved the first time it is needed."""

    def __init__(self, piece: Piece, curves: list):
        self.piece, self.curves, self.values = piece, curves, None

    def __call__(self) -> np.ndarray:
        if self.values is None:
            self.values = self.piece.marching.distance(curves=self.curves)
        return self.values


def _unit(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.linalg.norm(vectors, axis=1)[:, None]

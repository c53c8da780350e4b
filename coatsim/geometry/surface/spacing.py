"""Pass spacing: from the footprint's overlap ripple, and as measured along the surface.

For Gaussian tracks of standard deviation s repeated every D, the thickness is a Fourier series
whose first harmonic dominates: peak-to-valley ripple / mean = 4 exp(-2 pi^2 s^2 / D^2)
(D = 2s: 2.9 %, 2.5s: 17 %, 3s: 45 %), so the largest spacing for a ripple r is
D = pi s sqrt(2 / ln(4 / r)). Other footprints use their own standard deviation in the same
formula (an estimate).

Measured: the gap at a point of a pass is the distance along the surface (distance.NearestOnCurves:
the arc through the nearest point, or fast marching where the arc does not hold) to the nearest pass of a
neighbouring level, skipping points whose nearest point on that pass is one of its open ends.
Raster levels alternate between two sets, each measured from the other. The levels of a
distance from a start (geodesic, boundary) are each measured to the level next to them on the
start's side, which a path down the distance always crosses: the innermost loop in an arm of
the part is not measured against a level that never enters the arm, and passes added where the
levels leave a patch uncovered (fill.py) count for coverage, not for gaps. Coverage is the share
of the region's area (lumped at the vertices) within half a spacing of a pass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.surface.distance import NearestOnCurves
from coatsim.geometry.surface.passes import Trace
from coatsim.geometry.surface.piece import Piece
from coatsim.geometry.vectors import unit_rows

#: a vertex counts as covered up to this fraction beyond half a spacing (rounding, not method error)
COVERAGE_SLACK = 1e-6
#: gaps within this fraction of the spacing count as on target (band_note)
SPACING_BAND = 0.15


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
    """Gaps (mm) between neighbouring passes at their points, whether each was measured from
    a pass next to the first or the last level of the piece (where the ends of a region share
    out what is left of a spacing), and the covered area (mm^2)."""

    gaps_mm: np.ndarray
    at_end: np.ndarray
    covered_mm2: float


def measure(piece: Piece, traces: list[Trace], spacing_mm: float, toward_start: bool = False) -> Measured:
    """Gaps and coverage of the passes ``traces`` on one region piece. With ``toward_start``
    (the levels of a distance from a start) each level's gaps are measured to the level next
    to it on the start's side only (see the module docstring)."""
    faces, normals = piece.faces, piece.normals
    last = len(piece.levels) - 1
    every = [t.curve for t in traces]
    traces = [t for t in traces if t.rank <= last]  # passes that fill a patch count for coverage only
    if toward_start:
        pairs = [([t for t in traces if t.rank == k], [t.curve for t in traces if t.rank == j])
                 for k, j in enumerate(_start_side(np.asarray(piece.levels, dtype=float))) if j >= 0]
    else:
        groups = [[t for t in traces if t.rank % 2 == p] for p in (0, 1)]
        pairs = [(groups[0], [t.curve for t in groups[1]]), (groups[1], [t.curve for t in groups[0]])]
    gaps, ends = [np.zeros(0)], [np.zeros(0, dtype=bool)]
    for measured, neighbours in pairs:
        if not measured or not neighbours:
            continue
        reach = _Reach(piece, neighbours)
        nearest = NearestOnCurves([(c.points, unit_rows(c.sample(faces, normals)), c.closed) for c in neighbours])
        for trace in measured:
            curve = trace.curve
            d, on_end = nearest.distance(curve.points, unit_rows(curve.sample(faces, normals)), piece.surface,
                                         lambda curve=curve, reach=reach: curve.sample(faces, reach()))
            gaps.append(d[np.isfinite(d) & ~on_end])
            ends.append(np.full(len(gaps[-1]), trace.rank in (0, 1, last - 1, last)))
    half = 0.5 * spacing_mm * (1 + COVERAGE_SLACK)
    nearest_pass = NearestOnCurves([(c.points, unit_rows(c.sample(faces, normals)), c.closed) for c in every]).distance(
        piece.vertices, normals, piece.surface, _Reach(piece, every), within=half)[0]
    covered = nearest_pass <= half
    return Measured(np.concatenate(gaps), np.concatenate(ends), float(piece.vertex_areas_mm2()[covered].sum()))


def band_note(gaps_mm: np.ndarray, at_end: np.ndarray, spacing_mm: float) -> str | None:
    """A note on the gaps outside the spacing plus or minus ``SPACING_BAND``, and where they
    lie; None when all lie inside."""
    outside = np.abs(gaps_mm - spacing_mm) > SPACING_BAND * spacing_mm
    if not outside.any():
        return None
    share = 100.0 * outside.mean()
    at_ends = 100.0 * (outside & at_end).mean()
    low, high = (1 - SPACING_BAND) * spacing_mm, (1 + SPACING_BAND) * spacing_mm
    return (f"{share:.1f} % of the gaps between neighbouring passes lie outside {low:.3g} .. {high:.3g} mm (the "
            f"spacing +-{100 * SPACING_BAND:g} %): {at_ends:.1f} % next to the first or last passes of a piece (a "
            f"region's end shares out the last gap; a piece narrower than two spacings), {share - at_ends:.1f} % "
            "elsewhere (passes bending round a hole, a sharp edge or a turn of the surface, where a pass ends)")


def _start_side(levels: np.ndarray) -> list[int]:
    """For each level of a distance field, the rank of its neighbour nearer the start (the
    smaller magnitude), -1 for none: the pass a level follows."""
    side = []
    for k, level in enumerate(levels.tolist()):
        candidates = [j for j in (k - 1, k + 1) if 0 <= j < len(levels) and abs(levels[j]) < abs(level)]
        side.append(candidates[0] if candidates else -1)
    return side


class _Reach:
    """Fast-marching distance on a piece from curves, solved the first time it is needed."""

    def __init__(self, piece: Piece, curves: list):
        self.piece, self.curves, self.values = piece, curves, None

    def __call__(self) -> np.ndarray:
        if self.values is None:
            self.values = self.piece.marching.distance(curves=self.curves)
        return self.values

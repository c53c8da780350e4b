"""Raster passes: sections of the region by parallel planes, spaced along the surface.

The planes are the level sets of h = s . x for the step direction s (the planes' normal). On a
flat region facing the planes edge-on their step is the spacing; on a tilted or curved region
the gap between two sections measured along the surface is larger than the step, so each plane
is placed by measurement: the distance along the surface from the last pass (the arc through
the nearest pass point, or fast marching where the arc does not hold, distance.NearestOnCurves) is read on
candidate sections, and the next plane is the one whose section lies at most the spacing from
it (false position on h). Points whose nearest point on the last pass is one of its open ends do not
count (beyond a shorter pass's end the gap is a coverage question, not a spacing one).

The first plane lies half a spacing (along the surface) from the region's lowest point and the
last half a spacing from its highest. In between, the planes first follow each other at the
spacing to count the gaps: n gaps reach the last plane, unless what is left after n - 1 is
within a tenth of a step (no sliver of a pass: the end then lies a little more than half a
spacing from a pass). The n gaps then share the width evenly: the planes are marched again at
the gap g <= spacing whose n-th plane lands on the last one (false position on g), so every
gap is at most the spacing and all are equal to within twice ``EVEN_FRACTION`` of it. A region narrower
than a spacing gets one pass through its middle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np

from coatsim.core.budgets import check_budget
from coatsim.geometry.surface.boxes import SmallTriangles
from coatsim.geometry.surface.contours import crossing_edges, edge_points, level_curves
from coatsim.geometry.surface.distance import Marching, NearestOnCurves
from coatsim.geometry.surface.region import principal_axes, sign_fixed
from coatsim.geometry.surface.topology import submesh
from coatsim.geometry.vectors import unit_rows

#: the search stops when the plane (or the gap) is known to this fraction of the spacing
BISECTION_FRACTION = 1e-9
#: the smallest plane step, as a fraction of the spacing (a region almost parallel to the planes)
MIN_STEP_FRACTION = 1e-3
#: no last plane is added within this fraction of a full step of the one before (a sliver of a pass)
END_SLIVER_FRACTION = 0.1
#: the even gap is found to this fraction of the spacing (the last gap equals the others to it)
EVEN_FRACTION = 1e-4


def raster_step(vertices: np.ndarray, faces: np.ndarray, inside: np.ndarray, step: np.ndarray,
                spacing_mm: float) -> np.ndarray:
    """The step direction for one region piece: ``step``, unless its planes would cut the piece at
    most once (its ``inside`` vertices span less than a spacing along it) while the piece is wider
    than a spacing across its own longest axis (a cap facing the step: one section or none would
    leave it bare); then the piece's own step, across its longest axis."""
    if not inside.any() or np.ptp(vertices[inside] @ step) >= spacing_mm:
        return step
    own = sign_fixed(principal_axes(vertices, faces)[1])
    return own if np.ptp(vertices[inside] @ own) > spacing_mm else step


def raster_levels(vertices: np.ndarray, faces: np.ndarray, normals: np.ndarray, step_direction: np.ndarray,
                  inside: np.ndarray, spacing_mm: float, surface: SmallTriangles) -> np.ndarray:
    """Heights h = step_direction . x of the raster planes for one connected region piece with
    unit vertex ``normals`` (its triangles in ``surface``); ``inside`` (n,) marks the vertices
    passes must cover (the region without its edge band)."""
    h = vertices @ step_direction
    if not inside.any():
        return np.zeros(0)
    low, high = float(h[inside].min()), float(h[inside].max())
    mesh = _Mesh(vertices, faces, normals, h, inside)
    first = _end_level(mesh, low, +1, spacing_mm, surface)
    last = _end_level(mesh, high, -1, spacing_mm, surface)
    if last <= first:
        return np.array([0.5 * (low + high)])
    levels, beyond = _march(mesh, first, last, spacing_mm, surface, None)
    if last - levels[-1] <= END_SLIVER_FRACTION * (beyond - levels[-1]):
        return np.array(levels)
    gaps, tolerance = len(levels), EVEN_FRACTION * spacing_mm
    if gaps == 1 or beyond - last <= tolerance:
        return np.array([*levels, last])
    marches: dict[float, tuple[list[float], float]] = {}

    def landing(minus_gap: float) -> float:
        # rising in -g: how far the n-th plane marched at the gap g lies short of the last plane,
        # less the tolerance (so that the gap found never lets the last one exceed the others)
        marches[minus_gap] = _march(mesh, first, last, -minus_gap, surface, gaps)
        return last - marches[minus_gap][1] + tolerance

    found = _root(landing, -spacing_mm, -spacing_mm * (gaps - 1) / gaps, tolerance / gaps)
    levels = (marches[found] if found in marches else _march(mesh, first, last, -found, surface, gaps))[0]
    return np.array([*levels, last])


def _march(mesh: _Mesh, first: float, last: float, spacing: float, surface: SmallTriangles,
           count: int | None) -> tuple[list[float], float]:
    """Planes from ``first`` at ``spacing`` along the surface: those short of ``last`` (at most
    ``count`` of them, if given) and the plane after them."""
    levels = [first]
    while True:
        check_budget("raster passes", len(levels), "plan_passes", "use a larger spacing_mm", ("spacing_mm",))
        step = _next_level(mesh, levels[-1], spacing, surface)
        if step >= last or len(levels) == count:
            return levels, step
        levels.append(step)


@dataclass(eq=False)
class _Mesh:
    """A piece, or a band of it, with its normals, heights and inside vertices."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    h: np.ndarray
    inside: np.ndarray

    @cached_property
    def face_range(self) -> tuple[np.ndarray, np.ndarray]:
        """The lowest and highest h of each face."""
        fh = self.h[self.faces]
        return fh.min(axis=1), fh.max(axis=1)

    def band(self, lo: float, hi: float) -> _Mesh:
        """The faces that reach into lo <= h <= hi."""
        low, high = self.face_range
        v, f, parent = submesh(self.vertices, self.faces, (high >= lo) & (low <= hi))
        return _Mesh(v, f, self.normals[parent], self.h[parent], self.inside[parent])

    def section(self, level: float) -> tuple[np.ndarray, np.ndarray, Callable[[np.ndarray], np.ndarray]]:
        """Points of the section at ``level`` between inside vertices, their unit normals, and
        how to interpolate per-vertex values there."""
        edges = crossing_edges(self.faces, self.h, level)
        edges = edges[self.inside[edges].all(axis=1)] if len(edges) else edges
        if not len(edges):
            return np.zeros((0, 3)), np.zeros((0, 3)), lambda values: np.zeros(0)
        points, t = edge_points(self.vertices, self.h, level, edges)
        n = self.normals[edges[:, 0]] * (1 - t)[:, None] + self.normals[edges[:, 1]] * t[:, None]
        return points, unit_rows(n), lambda values: values[edges[:, 0]] * (1 - t) + values[edges[:, 1]] * t


class _Lazy:
    """Fast-marching distance on a band, solved the first time it is needed."""

    def __init__(self, band: _Mesh, **sources):
        self.band, self.sources, self.values = band, sources, None

    def __call__(self) -> np.ndarray:
        if self.values is None:
            self.values = Marching(self.band.vertices, self.band.faces).distance(**self.sources)
        return self.values


def _root(fn, lo: float, hi: float, tolerance: float) -> float:
    """Where ``fn`` (<= 0 at ``lo``, rising) crosses zero in [lo, hi], to ``tolerance`` in x or
    in fn: false position with the Illinois halving while fn is finite at both ends, bisection
    where it is not; the end where fn <= 0."""
    f_lo, f_hi = fn(lo), fn(hi)
    if f_hi <= 0:
        return hi
    kept = 0
    while hi - lo > tolerance:
        finite = math.isfinite(f_lo) and math.isfinite(f_hi) and f_hi > f_lo
        x = hi - f_hi * (hi - lo) / (f_hi - f_lo) if finite else 0.5 * (lo + hi)
        x = min(max(x, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
        fx = fn(x)
        if abs(fx) <= tolerance:
            return x
        if fx <= 0:
            lo, f_lo = x, fx
            f_hi, kept = (0.5 * f_hi, -1) if kept == -1 else (f_hi, -1)
        else:
            hi, f_hi = x, fx
            f_lo, kept = (0.5 * f_lo, 1) if kept == 1 else (f_lo, 1)
    return lo


def _end_level(mesh: _Mesh, extreme: float, sign: int, spacing: float, surface: SmallTriangles) -> float:
    """The plane half a spacing along the surface in from the region's lowest (sign +1) or
    highest (sign -1) inside point: the nearest point of its section to the extreme lies half
    a spacing away."""
    half = 0.5 * spacing
    band = mesh.band(*((extreme, extreme + half) if sign > 0 else (extreme - half, extreme)))
    at = np.flatnonzero(band.inside & (np.abs(band.h - extreme) <= 1e-9 * max(1.0, abs(extreme))))
    marching = _Lazy(band, source_vertices=at)
    nearest = NearestOnCurves([(band.vertices[[k]], band.normals[[k]], True) for k in at])

    def short(offset: float) -> float:
        points, normals, lerp = band.section(extreme + sign * offset)
        d = nearest.distance(points, normals, surface, lambda: lerp(marching()))[0]
        d = d[np.isfinite(d)]
        return float(d.min()) - half if len(d) else -math.inf

    return extreme + sign * _root(short, 0.0, half, BISECTION_FRACTION * spacing)


def _next_level(mesh: _Mesh, level: float, spacing: float, surface: SmallTriangles) -> float:
    """The next plane after ``level``: its section lies at most ``spacing`` from the pass at
    ``level`` (beyond the region's top when nothing of it lies that far)."""
    band = mesh.band(level, level + spacing)
    passes = level_curves(band.vertices, band.faces, band.h, level)
    if not passes:
        return level + spacing
    marching = _Lazy(band, curves=passes)
    nearest = NearestOnCurves([(c.points, unit_rows(c.sample(band.faces, band.normals)), c.closed) for c in passes])

    def excess(height: float) -> float:
        points, normals, lerp = band.section(height)
        d, on_end = nearest.distance(points, normals, surface, lambda: lerp(marching()))
        ok = np.isfinite(d)
        if not ok.any():
            return math.inf
        d = d[ok & ~on_end] if (ok & ~on_end).any() else d[ok]
        return float(d.max()) - spacing

    found = _root(excess, level, level + spacing, BISECTION_FRACTION * spacing)
    return max(found, level + MIN_STEP_FRACTION * spacing)

"""What every report section reads: the run's variants, its metrics document, its events, the
one thickness colour scale, the track's centre line on the part, and what several sections
draw from (the tracks in the heat maps' view, the coarse mesh of the 3-D view and the video,
the heat maps' pixel grid), each computed once from the run's results: the report recomputes no stage.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any, Mapping, Optional, Protocol, Sequence

import numpy as np

from coatsim.report.events import Event, run_events
from coatsim.geometry.segment import Segmentation
from coatsim.report.raster import ViewRaster, view_raster
from coatsim.report.results import VariantRun
from coatsim.robot.trajectory_log import TrajectoryLog
from coatsim.spray.decimate import Coarse, decimate
from coatsim.spray.locate import SurfacePoints, locate
from coatsim.spray.outputs import view_faces
from coatsim.spray.surfaces import Surface

SCALE_PERCENTILE = 99.5  # the colour scale's top: the largest of the variants' 99.5th percentiles
CENTRE_STEP_MM = 0.5     # sampling of the centre line, at most CENTRE_POINTS samples over all
CENTRE_POINTS = 4000     # (about 4 per pixel across the track figure; a part's many passes are longer)
TRACK_POINTS = 1500      # aim points per variant drawn on the heat maps (about: 4 per pixel across)
VIEW_FACES = 12_000      # the coarse mesh of the 3-D view and the video (about this many triangles)
HEAT_COLUMNS = 320       # pixels across a heat map's view


def aim_paths(log: TrajectoryLog, standoff_mm: float, max_points: Optional[int] = None) -> list[np.ndarray]:
    """The sprayed aim points (tool centre point + stand-off along the spray axis, mm), one (k, 3)
    polyline per stretch of the gun open; at most about ``max_points`` points over all."""
    rows = np.flatnonzero(np.asarray(log.spray, bool))
    if not len(rows):
        return []
    aim = log.position + standoff_mm * log.axis
    step = max(1, len(rows) // max_points) if max_points else 1
    stretches = np.split(rows, np.flatnonzero(np.diff(rows) > 1) + 1)
    return [aim[np.append(stretch[::step], stretch[-1])] for stretch in stretches]


def thickness_scale(thickness_um: Sequence[np.ndarray]) -> tuple[float, float]:
    """One colour scale (µm) for every variant: 0 to the largest 99.5th percentile (thicker
    spots saturate); (0, 1) when nothing was deposited."""
    top = max((float(np.percentile(t, SCALE_PERCENTILE)) for t in thickness_um if len(t)), default=0.0)
    return 0.0, top if top > 0.0 else 1.0


@dataclass(frozen=True, eq=False)
class CentreLine:
    """The track's centre line on the part: arc length (n,) mm from the start of the curve
    proper (negative on the run-in), the closest surface points (aim points of the reference
    variant's tool: TCP + stand-off along the spray axis), the curve proper's length and
    whether the contour is closed."""

    s_mm: np.ndarray
    points: SurfacePoints
    curve_length_mm: float
    closed: bool


def centre_samples(run: VariantRun, standoff_mm: float, lead_in_mm: float, lead_out_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """The reference run's aim points (TCP + stand-off along the spray axis) from the run-in
    start to the run-out end, every CENTRE_STEP_MM along the curve (coarser past CENTRE_POINTS):
    (s (k,) mm from the start of the curve proper, points (k, 3) mm)."""
    log, (a, b) = run.execution.log, run.execution.curve
    reach = np.maximum.accumulate(log.progress)
    i0 = int(np.searchsorted(reach, a - lead_in_mm, side="left"))
    i1 = int(np.searchsorted(reach, b + lead_out_mm - 1e-6, side="left"))
    rows = np.arange(min(i0, len(reach) - 1), min(i1, len(reach) - 1) + 1)
    rows = rows[np.concatenate(([True], np.diff(reach[rows]) > 1e-9))]
    aim = log.position[rows] + standoff_mm * log.axis[rows]
    s = reach[rows] - a
    grid = np.arange(s[0], s[-1] + 1e-9, max(CENTRE_STEP_MM, (s[-1] - s[0]) / CENTRE_POINTS))
    return grid, np.column_stack([np.interp(grid, s, aim[:, k]) for k in range(3)])


def track_samples(run: VariantRun, standoff_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """At most TRACK_POINTS of ``run``'s aim points (k, 3) mm, with whether the gun is open there (k,)."""
    log = run.execution.log
    rows = np.arange(0, len(log.t), max(1, -(-len(log.t) // TRACK_POINTS)))  # at most TRACK_POINTS
    return log.position[rows] + standoff_mm * log.axis[rows], np.asarray(log.spray[rows], bool)


class LoadedScenario(Protocol):
    """A scenario as the pipeline loaded it: ``spec`` is the validated scenario
    (coatsim.run.scenario.Scenario, above the report), ``path`` its file."""

    spec: Any
    path: Path


@dataclass(frozen=True, eq=False)
class ReportData:
    """A finished run as the report sections see it. ``runs`` are the pipeline's variant runs
    (name, program, execution, coating, toolpath); ``contours`` the segmentations of the
    input (one, or one per contour of a part); ``notes`` what reading a drawing noted."""

    loaded: LoadedScenario
    contours: tuple[Segmentation, ...]
    runs: tuple[VariantRun, ...]
    document: Mapping[str, Any]
    notes: tuple[str, ...] = ()

    @property
    def spec(self) -> Any:
        return self.loaded.spec

    @property
    def standoff_mm(self) -> float:
        """The programmed stand-off: the planned passes' on a 3-D part, else the gun's."""
        paths = getattr(self.spec, "paths", None)
        return paths.standoff_mm if paths is not None and paths.standoff_mm else self.spec.gun.standoff_mm

    @property
    def surface(self) -> Surface:
        return self.runs[0].coating.surface

    @property
    def reference(self) -> VariantRun:
        """The variant the others are compared with: the polysegment, else the first."""
        return next((r for r in self.runs if r.name == "polysegment"), self.runs[0])

    @property
    def best_polyline(self) -> Optional[VariantRun]:
        """The other variant with the lowest thickness CV (None when there is no other)."""
        others = [r for r in self.runs if r is not self.reference]
        cv = lambda r: self.document["variants"][r.name]["coating"]["thickness_cv"]  # noqa: E731
        return min(others, key=lambda r: (cv(r) is None, cv(r) if cv(r) is not None else 0.0), default=None)

    @cached_property
    def scale_um(self) -> tuple[float, float]:
        return thickness_scale([r.coating.thickness_um for r in self.runs])

    @cached_property
    def events(self) -> tuple[Event, ...]:
        return tuple(e for r in self.runs for e in run_events(r.name, r.execution, r.toolpath))

    @cached_property
    def numbers(self) -> dict[Event, int]:
        """Each event's number in the Warnings section (1, 2, ...)."""
        return {e: k + 1 for k, e in enumerate(dict.fromkeys(self.events))}

    @cached_property
    def _samples(self) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """The centre line's (s, points), then each run's track (points, gun open)."""
        spec = self.spec
        centre = centre_samples(self.reference, self.standoff_mm, spec.motion.lead_in_mm, spec.motion.lead_out_mm)
        return (centre, *(track_samples(r, self.standoff_mm) for r in self.runs))

    @cached_property
    def _located(self) -> tuple[SurfacePoints, ...]:
        """The centre line's and every track's samples on the part, found in one search."""
        points = [self._samples[0][1], *(pts for pts, _ in self._samples[1:])]
        found = locate(self.surface, np.vstack(points))
        parts = np.split(np.arange(len(found.faces)), np.cumsum([len(p) for p in points])[:-1])
        return tuple(SurfacePoints(found.faces[k], found.weights[k], found.distance_mm[k]) for k in parts)

    @cached_property
    def centre(self) -> CentreLine:
        closed = len(self.contours) == 1 and bool(self.contours[0].curve.closed)
        a, b = self.reference.execution.curve
        return CentreLine(self._samples[0][0], self._located[0], float(b - a), closed)

    def track_view(self, run: VariantRun) -> np.ndarray:
        """The sprayed aim points of ``run`` in the heat maps' view coordinates (k, 2) mm, NaN
        rows where the gun is closed (lines break there)."""
        return self._track_views[run.name]

    @cached_property
    def _track_views(self) -> dict[str, np.ndarray]:
        out = {}
        for run, found, (_, gun_open) in zip(self.runs, self._located[1:], self._samples[1:]):
            view = found.field(self.surface, self.surface.view)
            view[~gun_open] = np.nan
            out[run.name] = view
        return out

    @cached_property
    def coarse(self) -> Coarse:
        """The coating mesh clustered to about VIEW_FACES triangles: the 3-D view's and the video's part."""
        return decimate(self.surface, VIEW_FACES)

    @cached_property
    def raster(self) -> ViewRaster:
        """The heat maps' pixel grid over the surface's 2-D view."""
        return view_raster(self.surface.view, view_faces(self.surface), HEAT_COLUMNS)

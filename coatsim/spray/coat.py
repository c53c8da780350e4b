"""The coating stage: trajectory + surface + gun -> per-vertex thickness, metrics and files.

``coat`` is the in-process entry (the scenario runner calls it per variant on one surface);
``write_coating`` writes thickness.ply, coating.json, heatmap.png and section.png;
``run_coat`` parses the command-line specs and does both (``coatsim coat``).
"""

from __future__ import annotations

import json
import math
import sys
from contextlib import contextmanager
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable, Iterator

import numpy as np

from coatsim.core import defaults
from coatsim.core.budgets import MAX_ABS_COORDINATE_MM
from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.robot.trajectory_log import TrajectoryLog, read_trajectory_csv
from coatsim.spray.coating_metrics import coating_metrics, edge_band_width, region_of_interest
from coatsim.spray.deposition import Deposit, SprayModel, deposit
from coatsim.spray.efficiency import parse_efficiency_spec
from coatsim.spray.footprints import parse_footprint_spec
from coatsim.spray.outputs import (
    Profile, default_section, heatmap_png, panel, profile_png, section_profile, write_thickness_ply,
)
from coatsim.spray.surfaces import Surface, parse_surface_spec, surface_file

COATING_FORMAT = "coatsim.coating/1"
COATING_FILES = ("thickness.ply", "coating.json", "heatmap.png", "section.png")


@dataclass(frozen=True, eq=False)
class CoatingResult:
    """Thickness field, ROI mask and metrics of one coating run on one surface."""

    surface: Surface
    model: SprayModel
    deposit: Deposit
    roi: np.ndarray
    roi_kind: str
    metrics: dict[str, float]

    @property
    def thickness_um(self) -> np.ndarray:
        return self.deposit.thickness_um


def coat(log: TrajectoryLog, surface: Surface, model: SprayModel, roi: str = "band",
         target_um: float | None = None, edge_band_mm: float | None = None,
         band_halfwidth_mm: float | None = None, spacing: float | None = None,
         progress: Callable[[float], None] | None = None, away: np.ndarray | None = None,
         tolerance_pct: float = defaults.TOLERANCE_PCT) -> CoatingResult:
    """Deposit the sprayed part of ``log`` on ``surface`` and measure it over the ROI
    (``away``: the surface's vertices clear of the edge band, if already computed;
    ``tolerance_pct``: the specification band around the target).

    Args:
        log: the executed trajectory (gun on/off and TCP per step).
        surface: the part's surface mesh.
        model: the gun's footprint, rate, efficiency and shadowing.
        roi: the region measured: ``band`` (around the sprayed path) or ``part`` (the whole part
            clear of its edge band).
        target_um: the specified thickness, µm (default the mean over the region).
        edge_band_mm: the border left out of the measured region, mm.
        band_halfwidth_mm: the half-width of the ``band`` region, mm.
        spacing: the integration sub-step along the path, mm.
        progress: called with the share done.
        away: precomputed vertices clear of the edge band.
        tolerance_pct: the specification band around the target, %.

    Returns:
        The CoatingResult: thickness per vertex, the region's metrics and the mass balance.

    Raises:
        InputError: an unknown ``roi`` or widths out of range; EmptyRegionOfInterest when the
            spray misses the measured region.
        BudgetExceeded: more sub-steps, vertices or shadow memory than their budgets.
    """
    result = deposit(surface, log, model, progress)
    mask = region_of_interest(surface, result, model, roi, edge_band_mm, band_halfwidth_mm, spacing, away)
    metrics = coating_metrics(surface, result, model, mask, target_um, tolerance_pct)
    return CoatingResult(surface, model, result, mask, roi, metrics)


def remeasured(result: CoatingResult, roi: np.ndarray, target_um: float | None = None,
               tolerance_pct: float = defaults.TOLERANCE_PCT) -> CoatingResult:
    """``result`` measured over another region of interest (a boolean vertex mask), e.g. the
    one every variant of a run shares."""
    metrics = coating_metrics(result.surface, result.deposit, result.model, roi, target_um, tolerance_pct)
    return replace(result, roi=roi, metrics=metrics)


def parse_section(text: str) -> tuple[np.ndarray, np.ndarray]:
    """Section line ``x0,y0,x1,y1`` in view coordinates (mm)."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 4 or not all(abs(v) <= MAX_ABS_COORDINATE_MM for v in values) or values[:2] == values[2:]:
        raise InputError(f"--section must be x0,y0,x1,y1 in mm (two distinct points within "
                         f"{MAX_ABS_COORDINATE_MM:g} mm of the origin), found {text!r}")
    return np.array(values[:2]), np.array(values[2:])


def write_coating(result: CoatingResult, outdir: str | Path, inputs: dict[str, object],
                  section: tuple[np.ndarray, np.ndarray] | None = None) -> list[Path]:
    """Write thickness.ply, coating.json (format, metrics, inputs), heatmap.png, section.png."""
    outdir = Path(outdir)
    surface, thickness = result.surface, result.thickness_um
    section = default_section(surface) if section is None else section
    files = [outdir / name for name in COATING_FILES]
    write_thickness_ply(files[0], surface, thickness, 0.0, float(thickness.max()), result.deposit.exposure_s)
    document = {"format": COATING_FORMAT, **result.metrics, "inputs": inputs,
                "mesh": {"vertices": surface.n_vertices, "triangles": len(surface.faces),
                         "area_mm2": surface.area_mm2}}
    write_text(files[1], json.dumps(document, indent=2) + "\n")
    title = f"{surface.name}  {result.model.footprint.spec}  Q={result.model.rate_mm3_s:g} mm³/s"
    heatmap_png([panel(surface, thickness)], 0.0, float(thickness.max()), files[2], title, section)
    s, t = section_profile(surface.view, surface.faces, thickness, *section)
    start, end = section
    label = f"({start[0]:g}, {start[1]:g}) -> ({end[0]:g}, {end[1]:g}) mm"
    profile_png([Profile(label, s, t)], files[3], f"cross-section of {surface.name}")
    return files


@contextmanager
def _progress(label: str) -> Iterator[Callable[[float], None] | None]:
    """A rich progress bar on a terminal, nothing otherwise."""
    if not sys.stderr.isatty():
        yield None
        return
    from rich.console import Console
    from rich.progress import Progress

    with Progress(console=Console(stderr=True), transient=True) as bar:
        task = bar.add_task(label, total=1.0)
        yield lambda fraction: bar.update(task, completed=fraction)


def run_coat(trajectory: str | Path, surface_spec: str, spacing: float | None = None,
             footprint: str = "gaussian:sigma=5", rate: float = 40.0, standoff: float = 100.0,
             target_um: float | None = None, roi: str = "band", edge_band_mm: float | None = None,
             efficiency: str = defaults.EFFICIENCY, shadows: str = defaults.SHADOWS, section: str | None = None,
             outdir: str | Path = "out/coat", force: bool = False,
             tolerance_pct: float = defaults.TOLERANCE_PCT,
             surface_units: str = defaults.PLAN_UNITS) -> tuple[CoatingResult, list[Path]]:
    """``coatsim coat``: read, build, deposit, measure and write (spacing: footprint default; a
    mesh surface in ``surface_units``); the output folder is held for the run (see
    coatsim.core.outputs_guard)."""
    from coatsim.core.outputs_guard import check_distinct, output_folder

    fp = parse_footprint_spec(footprint)
    de = parse_efficiency_spec(efficiency)
    model = SprayModel(fp, rate, standoff, de, shadows)
    spacing = fp.spacing_mm if spacing is None else spacing
    if edge_band_mm is not None and not (math.isfinite(edge_band_mm) and edge_band_mm >= 0):
        raise InputError(f"--edge-band {edge_band_mm}: must be a finite number of mm >= 0")
    line = parse_section(section) if section is not None else None
    outdir = Path(outdir)
    inputs = [("the trajectory", trajectory), ("the surface mesh", surface_file(surface_spec)),
              ("the footprint table", getattr(fp, "path", None)),
              ("the efficiency table", getattr(de, "source", None) or None)]
    check_distinct(inputs, [("output", outdir / name) for name in COATING_FILES])
    surface = parse_surface_spec(surface_spec, spacing, surface_units)
    log = read_trajectory_csv(trajectory)
    with output_folder(outdir, COATING_FILES, "coatsim coat", force):
        with _progress("coating") as progress:
            result = coat(log, surface, model, roi, target_um, edge_band_mm, spacing=spacing, progress=progress,
                          tolerance_pct=tolerance_pct)
        inputs = {"trajectory": str(trajectory), "surface": surface_spec, "spacing_mm": spacing,
                  "footprint": fp.spec, "rate_mm3_s": rate, "standoff_mm": standoff,
                  "efficiency": "none" if de is None else de.spec, "shadows": shadows,
                  "shadows_cast": result.deposit.shadows, "rays": result.deposit.rays, "substep_mm": model.step_mm,
                  "roi": roi, "edge_band_mm": edge_band_width(model, edge_band_mm),
                  "band_halfwidth_mm": 2 * fp.sigma_mm}
        return result, write_coating(result, outdir, inputs, line)

"""``coatsim plan``: passes on a 3-D part mesh, written as a surface paths JSON file.

Flags are parsed here into the library's options (coatsim.geometry.surface); the library's
errors name its own terms (``spacing_mm``), which this command says as its flags.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import typer

from coatsim.cli.flags import fail, speaking_flags
from coatsim.core import defaults

FLAGS = {"footprint_sigma_mm": "--gun", "spacing_mm": "--spacing", "ripple_pct": "--ripple",
         "standoff_mm": "--standoff", "margin_mm": "--margin", "edge_band_mm": "--edge-band",
         "step_direction": "--direction", "max_edge_mm": "--max-edge", "start": "--from", "region": "--region",
         "units": "--units", "pose": "--pose", "pattern": "--pattern", "order": "--order"}


def _numbers(text: str, count: int | tuple[int, ...], flag: str, form: str) -> tuple[float, ...]:
    """Comma-separated finite numbers, ``count`` of them (or one of several counts)."""
    try:
        values = tuple(float(t) for t in text.split(","))
    except ValueError:
        values = ()
    counts = (count,) if isinstance(count, int) else count
    if len(values) not in counts or not all(map(math.isfinite, values)):
        fail(f"{flag}: expected {form}, found {text!r}")
    return values


def _region(text: Optional[str]):
    from coatsim.geometry.surface import Box, Everything, Facing

    if text is None:
        return Facing()
    kind, _, body = text.partition(":")
    kind = kind.strip().lower()
    if kind == "all" and not body:
        return Everything()
    if kind == "facing":
        if not body:
            return Facing()
        values = _numbers(body, (3, 4), "--region facing", "X,Y,Z or X,Y,Z,DEG")
        return Facing(values[:3]) if len(values) == 3 else Facing(values[:3], values[3])
    if kind == "box":
        values = _numbers(body, 6, "--region box", "XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm)")
        return Box(values[:3], values[3:])
    fail(f"--region: expected facing:X,Y,Z[,DEG], box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX or all, found {text!r}")


def _start(text: str):
    from coatsim.geometry.surface import FromBoundary, FromPlane, FromPoints

    kind, _, body = text.partition(":")
    kind = kind.strip().lower()
    if kind == "boundary" and not body:
        return FromBoundary()
    if kind == "plane":
        values = _numbers(body, 6, "--from plane", "PX,PY,PZ,NX,NY,NZ (a point and the normal, mm)")
        return FromPlane(values[:3], values[3:])
    if kind == "points" and body:
        return FromPoints(tuple(_numbers(p, 3, "--from points", "X,Y,Z[;X,Y,Z...] (mm)") for p in body.split(";")))
    fail(f"--from: expected boundary, plane:PX,PY,PZ,NX,NY,NZ or points:X,Y,Z[;X,Y,Z...], found {text!r}")


def _gun(spec: str) -> tuple[float, str]:
    """The footprint's standard deviation (mm) and its spec; a CSV file is a measured table."""
    from coatsim.core.errors import InputError
    from coatsim.spray.footprints import parse_footprint_spec

    if spec.lower().endswith(".csv") and not spec.lower().startswith("table:"):
        spec = f"table:{spec}"
    try:
        footprint = parse_footprint_spec(spec)
    except InputError as exc:
        fail(f"--gun: {exc}")
    return footprint.sigma_mm, footprint.spec


def plan(
    part: Path = typer.Argument(..., help="Part mesh: STL (ASCII or binary), PLY, OBJ, OFF, GLB or glTF."),
    output: Path = typer.Option(..., "-o", "--output", help="Surface paths JSON to write (coatsim.surfacepaths/1)."),
    pattern: str = typer.Option(defaults.PLAN_PATTERN, "--pattern", help="raster (plane sections) | geodesic (heat-method distance from --from) | boundary (loops inward from the border)."),
    direction: Optional[str] = typer.Option(None, "--direction", help="Raster: normal X,Y,Z of the cutting planes, the direction from one pass to the next [default: the region's middle principal axis]."),
    start: str = typer.Option("boundary", "--from", help="Geodesic start: boundary (the region's border) | plane:PX,PY,PZ,NX,NY,NZ | points:X,Y,Z[;X,Y,Z...] (mm)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Pass spacing along the surface, mm [default: 2 sigma of the footprint, ripple 2.9 %]."),
    ripple: Optional[float] = typer.Option(None, "--ripple", help="Largest overlap ripple, % of the mean thickness: the spacing is the largest that keeps it."),
    gun: str = typer.Option(defaults.FOOTPRINT, "--gun", help="The gun's footprint (the shipped gun's by default): gaussian:sigma=MM | elliptic:sx=,sy= | beta:radius=,beta= | double-beta:... | table:FILE.csv or FILE.csv."),
    standoff: float = typer.Option(defaults.STANDOFF_MM, "--standoff", help="Stand-off of the TCP along the normal, mm (recorded; TCP = point + stand-off x normal)."),
    margin: Optional[float] = typer.Option(None, "--margin", help="Lead-in and lead-out past the region's edge along each open pass, mm [default: 3 sigma of the footprint]."),
    order: str = typer.Option(defaults.PLAN_ORDER, "--order", help="serpentine (every other pass reversed) | oneway."),
    region: Optional[str] = typer.Option(None, "--region", help="facing:X,Y,Z[,DEG] | box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX | all [default: faces within 80 deg of the part's thinnest axis, on the side its normals face]."),
    edge_band: float = typer.Option(defaults.PLAN_EDGE_BAND_MM, "--edge-band", help="Keep passes this far from the region's border, mm."),
    units: str = typer.Option(defaults.PLAN_UNITS, "--units", help="mm | cm | m | in | auto (from the file, else from the extent, with a note)."),
    pose: str = typer.Option(",".join(f"{v:g}" for v in defaults.WORKPIECE_FRAME), "--pose", help="The part in the cell, X,Y,Z,O,A,T (mm, deg O-A-T; in front of the robot by default, as a scenario's part); recorded in the file, paths stay in the part's frame."),
    max_edge: Optional[float] = typer.Option(None, "--max-edge", help="Refine the region to edges of at most this, mm [default: a quarter of the spacing]."),
    force: bool = typer.Option(False, "--force", help="Replace an output file that coatsim did not write."),
    timings: bool = typer.Option(False, "--timings", help="Print CPU times per stage and the wall time on stderr."),
) -> None:
    """Plan passes on a 3-D part (raster, geodesic or boundary) and write them with their
    normals, spraying order and lead-in/out; exit 2 for a mesh or a setting it cannot use."""
    import time

    from coatsim.core.outputs_guard import check_distinct, output_folder
    from coatsim.geometry.surface import PlanOptions, load_part, write_surfacepaths
    from coatsim.geometry.surface import plan as plan_passes

    started = time.perf_counter()
    check_distinct([("the part mesh", part)], [("-o", output)])
    sigma, spec = _gun(gun)
    with speaking_flags(FLAGS):
        options = PlanOptions(
            footprint_sigma_mm=sigma, standoff_mm=standoff, pattern=pattern, spacing_mm=spacing, ripple_pct=ripple,
            step_direction=None if direction is None else _numbers(direction, 3, "--direction", "X,Y,Z"),
            start=_start(start), region=_region(region), margin_mm=margin, edge_band_mm=edge_band, order=order,
            max_edge_mm=max_edge, pose=_numbers(pose, 6, "--pose", "X,Y,Z,O,A,T (mm, deg)"))
        paths = plan_passes(load_part(part, units), options)
    with output_folder(output.parent if str(output.parent) else Path("."), [output.name], "plan", force):
        write_surfacepaths(output, paths)
    for note in paths.notes:
        typer.echo(f"note: {note}", err=True)
    typer.echo(_summary(paths, spec))
    typer.echo(f"wrote {output}")
    if timings:
        stages = ", ".join(f"{name} {seconds:.2f} s" for name, seconds in paths.timings_s)
        typer.echo(f"timings: CPU {stages}; wall {time.perf_counter() - started:.2f} s in all", err=True)


def _summary(paths, spec: str) -> str:
    s = paths.stats
    length = sum(p.length_mm for p in paths.passes)
    gaps = ("no neighbouring passes" if s.spacing_median_mm is None else
            f"along the surface min {s.spacing_min_mm:.2f} / median {s.spacing_median_mm:.2f} / max "
            f"{s.spacing_max_mm:.2f} mm")
    return (f"{paths.pattern}: {s.passes} passes, {length:.0f} mm in all, on {s.region_area_mm2:.0f} mm2; spacing "
            f"{paths.spacing_mm:.3g} mm (ripple {paths.ripple_pct:.3g} % for {spec}), {gaps}; coverage "
            f"{100 * s.coverage:.1f} %; normals smoothed over {s.normal_smoothing_mm:.3g} mm (largest angle to a face "
            f"{s.normal_max_angle_deg:.1f} deg, {s.normal_off_faces_deg:.1f} deg outside the faces near a pass point)")

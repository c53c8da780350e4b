"""``coatsim segment``: a curve or a drawing in, tangent-continuous arcs and lines out."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from coatsim.cli.flags import fail, speaking_flags
from coatsim.core import defaults

FLAGS = {"tolerance_mm": "--tol", "min_segment_mm": "--min-segment", "speed_mm_s": "--speed",
         "tool_accel_mm_s2": "--tool-accel", "corner_deg": "--corner-deg", "method": "--method",
         "theta_tolerance": "--theta-tol", "join_tolerance_mm": "--join-tol", "layers": "--layer",
         "arc_planes": "--arc-planes"}


def segment(
    input: str = typer.Argument(..., help="Curve file (CSV/TXT/NPY: x,y columns, or x,y,z for a 3-D curve; a header may name them among others and give their unit, x_in), a drawing (DXF/SVG) or builtin:NAME[:key=value,...]."),
    tol: float = typer.Option(defaults.TOLERANCE_MM, "--tol", help="Tolerance sigma: max two-sided deviation, mm."),
    method: str = typer.Option("optimal", "--method", help="optimal (guaranteed tolerance, few segments) | paper (literal RDP on θ)."),
    corner_deg: float = typer.Option(defaults.CORNER_DEG, "--corner-deg", help="Turn within a short length that counts as a true corner, deg."),
    closed: str = typer.Option("auto", "--closed", help="auto | yes | no: whether the curve is a closed loop."),
    theta_tol: Optional[float] = typer.Option(None, "--theta-tol", help="paper method: fixed RDP tolerance on θ instead of searching for tol."),
    output: Optional[Path] = typer.Option(None, "-o", "--output", help="Polysegment JSON to write."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="PNG of the curve (arcs and lines) and of θ with its approximation; of a 3-D curve, the curve in space and its deviation along it."),
    timings: bool = typer.Option(False, "--timings", help="Print the fitter's wall time on stderr."),
    min_segment: Optional[float] = typer.Option(None, "--min-segment", help="Shortest fitted segment, mm [default: 5 x --tol or 1/500 of the curve between corners, the longer]."),
    speed: Optional[float] = typer.Option(None, "--speed", help="Programmed speed, mm/s: no arc tighter than speed²/tool-accel where the curve allows; the rest is listed as speed-limited."),
    tool_accel: Optional[float] = typer.Option(None, "--tool-accel", help="Tool acceleration limit with --speed, m/s² [default: the cell model's]."),
    layer: Optional[list[str]] = typer.Option(None, "--layer", help="Drawings: read only this layer (repeatable) [default: every visible layer]."),
    join_tol: Optional[float] = typer.Option(None, "--join-tol", help="Drawings: join piece ends this close, mm [default: tol/100]."),
    arc_planes: str = typer.Option(defaults.ARC_PLANES, "--arc-planes", help="3-D curves: any (arcs in any plane) | principal (every arc in a plane normal to X, Y or Z, as G-code's G17/G18/G19 write them: corners where the chain changes plane, lines elsewhere). A 2-D curve or a drawing lies in XY: its arcs already are."),
) -> None:
    """Approximate a curve by tangent-continuous arcs and lines within a tolerance; a drawing
    gives one polysegment per contour (a part JSON when there are several)."""
    from coatsim.cli.common import tool_accel_mm_s2
    from coatsim.core.outputs_guard import check_distinct
    from coatsim.geometry.cad.drawing import is_drawing
    from coatsim.geometry.space.principal import check_arc_planes

    if closed not in ("auto", "yes", "no"):
        fail(f"--closed: expected auto, yes or no, got {closed!r}")
    check_distinct([("the input curve", None if input.startswith("builtin:") else input)],
                   [("-o", output), ("--plot", plot)])
    if tool_accel is not None and speed is None:
        fail("--tool-accel: needs --speed")
    accel_mm_s2 = tool_accel_mm_s2(tool_accel) if speed is not None else None
    with speaking_flags(FLAGS):
        check_arc_planes(arc_planes)
        if is_drawing(input):
            if min_segment is not None:
                fail("--min-segment applies to point curves; a drawing keeps its lines and arcs as drawn")
            if method != "optimal" or theta_tol is not None:
                fail(f"{input}: --method paper and --theta-tol apply to point curves; a drawing keeps its lines and "
                     "arcs exactly and fits only its free-form pieces")
            if closed != "auto":
                fail(f"{input}: --closed applies to point curves; a drawn contour is closed where its ends meet")
            seconds = _segment_drawing(input, tol, layer, join_tol, output, plot, corner_deg, speed, accel_mm_s2)
            if timings:
                typer.echo(f"timings: reading, chaining and fitting {seconds:.3f} s", err=True)
            return
        if layer or join_tol is not None:
            fail("--layer and --join-tol apply to drawings (DXF, SVG)")
        seconds = _segment_curve(input, tol, method, corner_deg, closed, theta_tol, min_segment, speed, accel_mm_s2,
                                 output, plot, arc_planes)
    if timings:
        typer.echo(f"timings: fitter {seconds:.3f} s", err=True)


def _segment_curve(input: str, tol: float, method: str, corner_deg: float, closed: str, theta_tol: Optional[float],
                   min_segment: Optional[float], speed: Optional[float], accel_mm_s2: Optional[float],
                   output: Optional[Path], plot: Optional[Path], arc_planes: str) -> float:
    """Fit one curve (a file of x,y,z columns: in space), write what was asked, print the
    summary; the fitter's seconds. A planar curve lies in XY: its arcs are in a principal
    plane whatever ``arc_planes`` asks."""
    from coatsim.geometry import load_curve, segment_curve, write_polysegment_json
    from coatsim.geometry.space.curve import SpaceCurve, read_any_curve

    curve = load_curve(input, closed) if input.startswith("builtin:") else read_any_curve(input, closed)
    if isinstance(curve, SpaceCurve):
        if method != "optimal" or theta_tol is not None:
            fail(f"{curve.name}: a 3-D curve is fitted by the default method only (no --method paper or --theta-tol)")
        return _segment_space(curve, tol, corner_deg, min_segment, speed, accel_mm_s2, output, plot, arc_planes)
    seg = segment_curve(curve, tol, method=method, corner_deg=corner_deg,
                        theta_tolerance=theta_tol, min_segment_mm=min_segment, speed_mm_s=speed,
                        tool_accel_mm_s2=accel_mm_s2)
    if output is not None:
        write_polysegment_json(output, seg)
    if plot is not None:
        from coatsim.geometry.plots import write_segmentation_plot

        write_segmentation_plot(seg, plot)
    typer.echo(seg.summary())
    for path in (output, plot):
        if path is not None:
            typer.echo(f"wrote {path}")
    return seg.seconds


def _segment_space(curve, tol: float, corner_deg: float, min_segment: Optional[float], speed: Optional[float],
                   accel_mm_s2: Optional[float], output: Optional[Path], plot: Optional[Path], arc_planes: str) -> float:
    """Fit a 3-D curve as a G1 chain of 3-D lines and arcs (polysegment/2); the fitter's seconds."""
    from coatsim.geometry.space.polysegment_json import write_chain_json
    from coatsim.geometry.space.segment import segment_space_curve

    seg = segment_space_curve(curve, tol, corner_deg, min_segment, speed, accel_mm_s2, arc_planes)
    if output is not None:
        write_chain_json(output, seg.chain, seg.tolerance_mm, seg.stats())
    if plot is not None:
        from coatsim.geometry.space.plots import write_space_segmentation_plot

        write_space_segmentation_plot(seg, plot)
    typer.echo(seg.summary())
    for path in (output, plot):
        if path is not None:
            typer.echo(f"wrote {path}")
    return seg.seconds


def _segment_drawing(path: str, tol: float, layers: Optional[list[str]], join_tol: Optional[float],
                     output: Optional[Path], plot: Optional[Path], corner_deg: float, speed_mm_s: Optional[float],
                     tool_accel_mm_s2: Optional[float]) -> float:
    """Segment every contour of a DXF or SVG drawing, write the part (or polysegment) JSON and
    the plot, print the summary; the seconds it took."""
    from coatsim.geometry.cad.segment_drawing import segment_drawing
    from coatsim.geometry.part_json import write_part_json

    part = segment_drawing(path, tol, layers=layers or None, join_tolerance_mm=join_tol, corner_deg=corner_deg,
                           speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
    if output is not None:
        write_part_json(output, part)
    if plot is not None:
        if len(part.contours) == 1:
            from coatsim.geometry.plots import write_segmentation_plot

            write_segmentation_plot(part.contours[0], plot)
        else:
            from coatsim.geometry.part_plots import write_part_plot

            write_part_plot([c.polysegment for c in part.contours], Path(part.source).name, plot,
                            [c.curve.points for c in part.contours])
    typer.echo("\n".join([part.summary()] + [f"wrote {p}" for p in (output, plot) if p is not None]))
    return part.seconds

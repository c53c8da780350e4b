"""``coatsim segment`` on a drawing: segment every contour, write the part (or polysegment)
JSON and the plot, return the summary text."""

from __future__ import annotations

from pathlib import Path
from typing import Optional, Sequence

from coatsim.core.errors import InputError


def segment_drawing_command(path: str, tol: float, layers: Optional[Sequence[str]], join_tol: Optional[float],
                            method: str, closed: str, theta_tol: Optional[float], output: Optional[Path],
                            plot: Optional[Path], corner_deg: float = 20.0, speed_mm_s: Optional[float] = None,
                            tool_accel_mm_s2: Optional[float] = None) -> tuple[str, float]:
    """Run ``coatsim segment`` on a DXF or SVG file: the summary text and the seconds it
    took; flags that apply to point curves only are refused rather than ignored."""
    from coatsim.geometry.cad.segment_drawing import segment_drawing
    from coatsim.geometry.part_json import write_part_json

    if method != "optimal" or theta_tol is not None:
        raise InputError(f"{path}: --method paper and --theta-tol apply to point curves; a drawing keeps its "
                         "lines and arcs exactly and fits only its free-form pieces")
    if closed != "auto":
        raise InputError(f"{path}: --closed applies to point curves; a drawn contour is closed where its ends meet")
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
    lines = [part.summary()] + [f"wrote {p}" for p in (output, plot) if p is not None]
    return "\n".join(lines), part.seconds

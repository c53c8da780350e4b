"""The program section: the curve, its polysegment and θ, then each variant's program listing
(collapsed; the polysegment's first) with the lines the warnings point to highlighted and
linked from the Warnings section."""

from __future__ import annotations

from typing import Any

from coatsim.report import curve_figures
from coatsim.report.events import lines_of
from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.sections.warnings import line_anchor


def listing(variant: str, text: str, warned: set[int], numbers: dict[int, list[int]]) -> str:
    """The program text with line numbers, one anchor per line, warned lines highlighted."""
    rows = []
    for k, line in enumerate(text.splitlines(), start=1):
        mark = ' class="hit"' if k in warned else ""
        tag = f' <span class="tag">#{", #".join(map(str, numbers[k]))}</span>' if k in numbers else ""
        rows.append(f'<span id="{esc(line_anchor(variant, k))}"{mark}><i>{k:4d}</i> {esc(line)}{tag}</span>')
    return '<pre class="listing">' + "\n".join(rows) + "</pre>"


def _program_text(run: Any) -> str:
    return getattr(run.program, "text", "") or ""


def part_figure(data: Any) -> str:
    """A part: every contour with its polysegment in spray order, and the table per contour."""
    from coatsim.report.part_section import contours_table

    order = next((r.program.order for r in data.runs if hasattr(r.program, "order")), None)
    png = curve_figures.part_figure([c.polysegment for c in data.contours], [c.curve.points for c in data.contours],
                                    order)
    table = contours_table(data.document["contours"]) if data.document.get("contours") else ""
    return figure_html(Figure(
        "The part's contours and their polysegments", png,
        "Every contour of the drawing (grey) with its polysegment: arcs and lines in their own colours, true corners as "
        "crosses, the start of each contour as a dot with an arrow along the direction of travel, numbered in spray "
        "order. The gun is off between contours.")) + table


def curve_figure(data: Any) -> str:
    """One curve: its polysegment and θ, and the polyline program's vertices when one ran."""
    polyline = next((r for r in data.runs if r.name.startswith("polyline")), None)
    png = curve_figures.curve_figure(data.contours[0], None if polyline is None else polyline.program.curve)
    caption = ("Left: the polysegment over the input curve (grey), arcs and lines in their own colours, junctions as "
               "dots, true corners as crosses. Middle: the angular function θ(t) (cumulative turning angle against "
               "normalised arc length) of the input and of the polysegment, piecewise linear: each slope is an arc, "
               "each flat piece a line.")
    if polyline is not None:
        caption += " Right: the polyline variants' vertices on the input curve: without blending the arm stops at each."
    return figure_html(Figure("Input curve, polysegment, θ and polyline", png, caption))


def section(data: Any) -> Section:
    runs = sorted(data.runs, key=lambda r: r.name != "polysegment")
    parts = []
    for run in runs:
        text = _program_text(run)
        warned = lines_of(data.events, run.name)
        numbers: dict[int, list[int]] = {}
        for e in data.events:
            if e.variant == run.name and e.line is not None:
                numbers.setdefault(e.line, []).append(data.numbers[e])
        count = len(text.splitlines())
        what = (f"{len(warned)} line{'s' if len(warned) != 1 else ''} with warnings highlighted" if warned
                else "no line with a warning")
        file = getattr(run, "program_file", "") or f"{run.name}.as"
        parts.append(f"<details><summary><b>{esc(file)}</b>: {count} lines, {what}</summary>"
                     f"{listing(run.name, text, warned, numbers)}</details>")
    figure = part_figure(data) if len(data.contours) > 1 else curve_figure(data)
    note = ('<p class="muted">Each listing opens on a click; a line number in the Warnings table jumps to its line. '
            "Highlighted: the lines the warnings point to, tagged with their event numbers.</p>")
    return Section("program", "Programs", figure + note + "".join(parts))

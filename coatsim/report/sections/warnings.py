"""The warnings section: every event of every variant (tracking error, joint speed or
acceleration over the limit, joint-limit approach, singularity proximity, IK residual, TOOL
mismatch, speed dips, the curve's speed-limited stretches and corners, the seam) with its
program line, numbered, and marked on a plot of the track."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.events import Event
from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.labels import labels
from coatsim.report.plots import colour, figure, grid, png_bytes


def line_anchor(variant: str, line: int) -> str:
    """The id of a line of a variant's program listing (the program section)."""
    return f"prog-{variant}-L{line}"


def _line_cell(e: Event) -> str:
    if e.line is None:
        return "–"
    return f'<a href="#{esc(line_anchor(e.variant, e.line))}">{e.line}</a>'


def events_table(data: Any) -> str:
    rows = []
    for e in data.events:
        where = "–" if e.s_mm is None else f"{e.s_mm:.1f}"
        when = "–" if e.t_s is None else f"{e.t_s:.3f}"
        cls = "warn" if e.severity == "warning" else "note"
        rows.append(f'<tr class="{cls}"><td>{data.numbers[e]}</td><td class="l">{esc(e.variant)}</td>'
                    f'<td class="l">{esc(e.kind)}</td><td class="l">{esc(e.severity)}</td><td>{_line_cell(e)}</td>'
                    f'<td>{where}</td><td>{when}</td><td class="l">{esc(e.message)}</td></tr>')
    head = ('<tr><th>#</th><th class="l">variant</th><th class="l">event</th><th class="l">kind</th>'
            '<th>program line</th><th>s (mm)</th><th>t (s)</th><th class="l">what</th></tr>')
    return f'<table class="events">{head}{"".join(rows)}</table>'


def counts_line(data: Any) -> str:
    """Per variant: warnings and notes."""
    parts = []
    for r in data.runs:
        mine = [e for e in data.events if e.variant == r.name]
        warn = sum(e.severity == "warning" for e in mine)
        parts.append(f"{r.name}: {warn} warning{'s' if warn != 1 else ''}, {len(mine) - warn} "
                     f"note{'s' if len(mine) - warn != 1 else ''}")
    return "; ".join(parts) + "."


def curve_figure(data: Any) -> bytes:
    """The track of each variant on the part (view coordinates) with the events at their place."""
    fig = figure(8.5, 5.2)
    ax = grid(fig, 1, 1, margins=(0.7, 1.7, 0.2, 0.55))[0, 0]
    centre = data.centre
    for k, run in enumerate(data.runs):
        path = data.track_view(run)
        ax.plot(path[:, 0], path[:, 1], color=colour(run.name, k), lw=1.0, alpha=0.7, label=run.name)
    view = centre.points.field(data.surface, data.surface.view)
    placed = [e for e in data.events if e.s_mm is not None]
    s = np.array([e.s_mm for e in placed])
    xy = np.column_stack([np.interp(s, centre.s_mm, view[:, j]) for j in (0, 1)]) if placed else np.zeros((0, 2))
    warning = np.array([e.severity == "warning" for e in placed], bool)
    ax.plot(xy[warning, 0], xy[warning, 1], "o", color="#c0392b", ms=4.5)
    ax.plot(xy[~warning, 0], xy[~warning, 1], "s", color="#6a3d9a", ms=4.5, mfc="none")
    numbers = np.array([f" {data.numbers[e]}" for e in placed], dtype=object)
    for kind, tint in ((warning, "#c0392b"), (~warning, "#6a3d9a")):
        labels(ax, xy[kind], numbers[kind], ax.transData, fontsize=6.5, color=tint, ha="left", va="bottom")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(data.surface.view_labels[0], fontsize=8)
    ax.set_ylabel(data.surface.view_labels[1], fontsize=8)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    return png_bytes(fig)


def section(data: Any) -> Section:
    if not data.events:
        return Section("warnings", "Warnings and events", "<p><b>None</b>: no variant has a warning or event (TOOL as the "
                       "cell's gun, joints within their limits and away from singularities, the simulated tool on its "
                       "commanded path and at speed on the whole curve).</p>")
    body = f"<p>{esc(counts_line(data))}</p>" + events_table(data)
    if any(e.s_mm is not None for e in data.events):
        body += figure_html(Figure(
            "Where the events are", curve_figure(data),
            "Each variant's sprayed track on the part (view coordinates of the heat maps) with the events numbered as "
            "in the table: filled red dots are warnings, open purple squares notes (the curve's own speed limits and "
            "the seam). Speed dips and warnings are also marked on the speed plots."))
    return Section("warnings", "Warnings and events", body)

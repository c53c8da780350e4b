"""The speed section: tool speed along the path per variant, small multiples on one scale, the
run-in and run-out shaded, every dip below 95 % of the programmed speed marked with the program
line of the move where the speed is lowest, and the run's other warnings as numbered ticks."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

from coatsim.report.events import AT_SPEED, Event, curve_spans
from coatsim.report.html import Figure, Section, figure_html
from coatsim.report.labels import labels
from coatsim.report.plots import colour, figure, grid, png_bytes, title

MAX_LABELS = 8  # dips labelled with their line per panel (the deepest); the rest get a dot only


def profile(run: Any, lead_in_mm: float, lead_out_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """(s along the curve proper, mm, from -lead_in to length + lead_out; speed mm/s)."""
    log, (a, b) = run.execution.log, run.execution.curve
    reach = np.maximum.accumulate(log.progress)
    i0 = int(np.searchsorted(reach, a - lead_in_mm, side="left"))
    i1 = int(np.searchsorted(reach, b + lead_out_mm - 1e-6, side="left"))
    rows = slice(min(i0, len(reach) - 1), min(i1, len(reach) - 1) + 1)
    return log.progress[rows] - a, log.speed[rows]


def speed_figure(runs: Sequence[Any], events: Sequence[Event], numbers: Mapping[Event, int], lead_in_mm: float,
                 lead_out_mm: float) -> bytes:
    """One panel per variant, shared axes."""
    fig = figure(11, 1.7 * len(runs) + 0.75)
    axes = grid(fig, len(runs), 1, margins=(0.65, 0.2, 0.3, 0.5), gaps=(0.0, 0.4), sharex=True, sharey=True)[:, 0]
    top = max(max(float(np.nanmax(r.execution.log.speed)), r.execution.metrics.programmed_speed_mm_s) for r in runs)
    for k, (ax, run) in enumerate(zip(axes, runs)):
        s, v = profile(run, lead_in_mm, lead_out_mm)
        length = run.execution.curve[1] - run.execution.curve[0]
        programmed = run.execution.metrics.programmed_speed_mm_s
        spans = [(lo - run.execution.curve[0], hi - run.execution.curve[0]) for lo, hi in curve_spans(run.execution)]
        edges = [min(s[0], 0.0), *(x for span in spans for x in span), max(s[-1], length)]
        for lo, hi in zip(edges[::2], edges[1::2]):  # run-in, travel between contours, run-out
            ax.axvspan(lo, hi, color="#ececec", lw=0)
        ax.axhline(programmed, color="black", ls="--", lw=0.7)
        ax.axhline(AT_SPEED * programmed, color="#888888", ls=":", lw=0.7)
        ax.plot(s, v, color=colour(run.name, k), lw=1.0)
        dips = [e for e in events if e.variant == run.name and e.kind == "speed dip" and e.s_mm is not None]
        if dips:
            lows = np.array([np.interp(e.s_mm, s, v) for e in dips])
            ax.plot([e.s_mm for e in dips], lows, "o", color="#c0392b", ms=3.2, zorder=5)
            shown = [i for i in np.argsort(lows)[:MAX_LABELS] if dips[i].line is not None]
            labels(ax, [(dips[i].s_mm, lows[i] - 0.03 * top) for i in shown], [f"L{dips[i].line}" for i in shown],
                   ax.transData, fontsize=6.5, color="#c0392b", ha="center", va="top")
        warned = [e for e in events if e.variant == run.name and e.severity == "warning" and e.kind != "speed dip"
                  and e.s_mm is not None]
        if warned:
            ax.plot([e.s_mm for e in warned], [1.08 * top] * len(warned), "v", color="#b3121f", ms=5)
            labels(ax, [(e.s_mm, 1.08 * top) for e in warned], [f"  #{numbers[e]}" for e in warned], ax.transData,
                   fontsize=6.5, color="#b3121f", ha="left", va="center")
        title(ax, run.name, loc="left", color=colour(run.name, k))
        ax.set_ylabel("mm/s", fontsize=8)
    axes[0].set_ylim(0.0, 1.15 * top)
    axes[-1].set_xlabel("along the curve proper (mm); grey: run-in and run-out", fontsize=8)
    return png_bytes(fig)


def section(data: Any) -> Section:
    spec = data.spec
    png = speed_figure(data.runs, data.events, data.numbers, spec.motion.lead_in_mm, spec.motion.lead_out_mm)
    caption = (
        "Simulated tool-centre-point speed from the trajectory logs, one panel per variant on the same axes, from the "
        "start of the run-in to the end of the run-out (shaded; on a closed contour the gun is closed there and sprays "
        "exactly one lap). Dashed: the programmed speed; dotted: 95 % of it. Red dots: dips below 95 % on the curve "
        "proper, labelled with the program line (Lnn) of the move where the speed is lowest (the deepest "
        f"{MAX_LABELS} per panel); triangles: the other warnings, numbered as in the Warnings section.")
    return Section("speed", "Tool speed along the curve", figure_html(Figure("Tool speed, every variant", png, caption)))

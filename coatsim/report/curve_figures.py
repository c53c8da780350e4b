"""The programs section's figure: what each variant sprays, drawn from the run's segmentation and
programs. One curve: the polysegment over the input curve, θ of both, and the polyline's
vertices; a part: every contour with its polysegment, numbered in spray order. Arcs, lines,
corners and starts each go in one collection, however many segments there are."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from coatsim.geometry.primitives import Arc
from coatsim.geometry.theta import theta_of_polysegment
from coatsim.report.plots import colour, figure, grid, png_bytes, title

ARC_COLOUR, LINE_COLOUR, INPUT_COLOUR = "#d62728", "#1f77b4", "#c8c8c8"
ARC_POINTS_PER_RAD = 40  # samples of a drawn arc


def segment_paths(poly: Any) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The polysegment's arcs and lines as point arrays, for one LineCollection each."""
    arcs, lines = [], []
    for s in poly.segments:
        if isinstance(s, Arc):
            arcs.append(s.points(np.linspace(0.0, s.length, max(2, int(ARC_POINTS_PER_RAD * abs(s.sweep)) + 2))))
        else:
            lines.append(np.array([s.start, s.end], float))
    return arcs, lines


def _draw_polysegments(ax: Any, polys: Sequence[Any], samples: Sequence[np.ndarray]) -> None:
    """Input samples (grey), arcs and lines in their colours, corners as crosses."""
    from matplotlib.collections import LineCollection

    ax.add_collection(LineCollection(list(samples), colors=INPUT_COLOUR, linewidths=3.5, zorder=1))
    arcs, lines = [], []
    for poly in polys:
        a, b = segment_paths(poly)
        arcs += a
        lines += b
    ax.add_collection(LineCollection(arcs, colors=ARC_COLOUR, linewidths=1.4, zorder=2))
    ax.add_collection(LineCollection(lines, colors=LINE_COLOUR, linewidths=1.4, zorder=2))
    corners = np.array([p.segments[k].end for p in polys for k in p.corners] or np.zeros((0, 2)), float)
    ax.plot(corners[:, 0], corners[:, 1], "kx", ms=6, mew=1.5, zorder=4)
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    ax.plot([], [], color=ARC_COLOUR, label=f"arcs ({sum(p.n_arcs for p in polys)})")
    ax.plot([], [], color=LINE_COLOUR, label=f"lines ({sum(p.n_lines for p in polys)})")
    ax.plot([], [], "kx", label=f"true corners ({len(corners)})")


def curve_figure(seg: Any, polyline: Optional[Any] = None) -> bytes:
    """One contour: the polysegment over the input, θ of both, the polyline's vertices."""
    poly, pts = seg.polysegment, seg.curve.points
    n = 3 if polyline is not None else 2
    fig = figure(4.3 * n, 4.1)
    axes = grid(fig, 1, n, margins=(0.6, 0.15, 0.3, 0.5), gaps=(0.6, 0.0))[0]
    ax = axes[0]
    _draw_polysegments(ax, [poly], [pts])
    joints = np.array([s.start for s in poly.segments] + [poly.end], float)
    ax.plot(joints[:, 0], joints[:, 1], "k.", ms=4, zorder=3)
    title(ax, f"{poly.n_segments} segments, deviation {seg.max_deviation_mm:.3g} mm (σ = {seg.tolerance_mm:g} mm)")
    ax.legend(loc="best", fontsize=7)
    ax = axes[1]
    ax.plot(seg.theta.t, np.degrees(seg.theta.theta), color="0.6", lw=3, label="θ of the input")
    approx = seg.theta_approx if seg.theta_approx is not None else theta_of_polysegment(poly)
    ax.plot(approx.t, np.degrees(approx.theta), "o-", color=ARC_COLOUR, ms=2.5, lw=1.1,
            label="θ of the polysegment" if seg.theta_approx is None else "θ after RDP")
    ax.set_xlabel("t = s / L", fontsize=8)
    ax.set_ylabel("θ (degrees)", fontsize=8)
    title(ax, f"angular characteristic function ({seg.method})")
    ax.legend(loc="best", fontsize=7)
    if polyline is not None:
        ax = axes[2]
        xy = np.array([s.start for s in polyline.segments] + [polyline.end], float)
        ax.plot(pts[:, 0], pts[:, 1], color=INPUT_COLOUR, lw=3.5, label="input curve")
        ax.plot(xy[:, 0], xy[:, 1], "-o", color=colour("polyline-stop"), lw=0.9, ms=2.2, label="polyline vertices")
        ax.set_aspect("equal", adjustable="datalim")
        title(ax, f"polyline: {len(xy) - 1} straight moves")
        ax.legend(loc="best", fontsize=7)
    return png_bytes(fig)


def part_figure(polys: Sequence[Any], samples: Sequence[np.ndarray], order: Optional[Sequence[int]] = None) -> bytes:
    """A part: every contour (grey) with its polysegment, the start of each as a dot with an
    arrow along the direction of travel and its number (its place in ``order`` when given)."""
    fig = figure(8.5, 6.2)
    ax = grid(fig, 1, 1, margins=(0.65, 0.15, 0.3, 0.5))[0, 0]
    _draw_polysegments(ax, polys, samples)
    rank = {k: i for i, k in enumerate(order)} if order is not None else {k: k for k in range(len(polys))}
    span = max(1e-9, float(np.ptp(np.vstack(list(samples)), axis=0).max()))
    starts = np.array([p.start for p in polys], float)
    heading = np.array([p.segments[0].start_heading for p in polys])
    ax.plot(starts[:, 0], starts[:, 1], "o", color="#2ca02c", ms=4, zorder=4,
            label="start and direction (number: spray order)" if order is not None else "start and direction")
    ax.quiver(starts[:, 0], starts[:, 1], np.cos(heading), np.sin(heading), color="#2ca02c", angles="xy",
              scale_units="xy", scale=1.0 / (0.04 * span), width=0.004, zorder=4)
    for k, (x, y) in enumerate(starts):
        if k in rank:
            ax.text(x, y, f" {rank[k] + 1}", fontsize=7, va="bottom", zorder=5)
    title(ax, f"{len(polys)} contours, {sum(p.n_segments for p in polys)} segments")
    ax.set_xlabel("x (mm)", fontsize=8)
    ax.set_ylabel("y (mm)", fontsize=8)
    ax.legend(loc="best", fontsize=7)
    return png_bytes(fig)


"""Figures of a segmentation: the curve with its arcs and lines, θ and its approximation."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from coatsim.core.fileio import write_bytes
from coatsim.geometry.primitives import Arc
from coatsim.geometry.segment import Segmentation
from coatsim.geometry.theta import theta_of_polysegment

ARC_COLOUR, LINE_COLOUR = "#d62728", "#1f77b4"


def segmentation_figure_png(seg: Segmentation, dpi: int = 110) -> bytes:
    """PNG bytes: left the input curve with arcs and lines in two colours and the junctions;
    right θ(t) of the input and of the polysegment (the paper's Figs. 4, 7 and 8)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_curve, ax_theta) = plt.subplots(1, 2, figsize=(12, 5), constrained_layout=True)
    pts = seg.curve.points
    ax_curve.plot(pts[:, 0], pts[:, 1], color="0.75", lw=4, label="input curve", zorder=1)
    for s in seg.polysegment.segments:
        xy = s.points(np.linspace(0.0, s.length, max(2, int(60 * (abs(getattr(s, "sweep", 0.0)) + 0.1)))))
        ax_curve.plot(xy[:, 0], xy[:, 1], color=ARC_COLOUR if isinstance(s, Arc) else LINE_COLOUR, lw=1.6, zorder=2)
    joints = np.array([s.start for s in seg.polysegment.segments] + [seg.polysegment.end])
    ax_curve.plot(joints[:, 0], joints[:, 1], "k.", ms=5, zorder=3)
    corners = [seg.polysegment.segments[k].end for k in seg.polysegment.corners]
    if corners:
        c = np.array(corners)
        ax_curve.plot(c[:, 0], c[:, 1], "kx", ms=8, mew=2, zorder=4, label="corner")
    ax_curve.plot([], [], color=ARC_COLOUR, label=f"arc ({seg.polysegment.n_arcs})")
    ax_curve.plot([], [], color=LINE_COLOUR, label=f"line ({seg.polysegment.n_lines})")
    ax_curve.set_aspect("equal")
    ax_curve.set_xlabel("x (mm)")
    ax_curve.set_ylabel("y (mm)")
    ax_curve.set_title(f"{seg.curve.name}: {seg.polysegment.n_segments} segments, "
                       f"deviation {seg.max_deviation_mm:.4g} mm (σ = {seg.tolerance_mm:g} mm)")
    ax_curve.legend(loc="best", fontsize=8)

    ax_theta.plot(seg.theta.t, np.degrees(seg.theta.theta), color="0.6", lw=3, label="θ of the input")
    approx = seg.theta_approx if seg.theta_approx is not None else theta_of_polysegment(seg.polysegment)
    ax_theta.plot(approx.t, np.degrees(approx.theta), "o-", color=ARC_COLOUR, ms=3, lw=1.2,
                  label="θ of the polysegment" if seg.theta_approx is None else "θ after RDP")
    ax_theta.set_xlabel("t = s / L")
    ax_theta.set_ylabel("θ (degrees)")
    ax_theta.set_title(f"angular characteristic function ({seg.method})")
    ax_theta.legend(loc="best", fontsize=8)
    ax_theta.grid(alpha=0.3)
    return figure_png(fig, dpi)


def figure_png(fig, dpi: int) -> bytes:
    """PNG bytes of a matplotlib figure, which is closed; no version stamp: the same bytes everywhere."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def write_segmentation_plot(seg: Segmentation, path: str | Path) -> None:
    write_bytes(path, segmentation_figure_png(seg))

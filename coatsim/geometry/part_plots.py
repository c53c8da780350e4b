"""Figure of a part: every contour's arcs and lines, corners, starts, directions and numbers."""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.core.fileio import write_bytes
from coatsim.geometry.plots import ARC_COLOUR, LINE_COLOUR
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc


def part_figure_png(contours: Sequence[Polysegment], title: str, samples: Sequence[np.ndarray] | None = None,
                    order: Sequence[int] | None = None, dpi: int = 110) -> bytes:
    """PNG bytes: each contour's segments (arcs and lines in two colours) over its drawn
    samples (grey), corners as crosses, its start as a dot with an arrow along the direction
    of travel and its number (its place in ``order`` when given, else its index + 1)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 7), constrained_layout=True)
    rank = {k: i for i, k in enumerate(order)} if order is not None else {k: k for k in range(len(contours))}
    span = max(1e-9, max(max(np.ptp([p for s in c.segments for p in (s.start, s.end)], axis=0)) for c in contours))
    for k, poly in enumerate(contours):
        if samples is not None:
            pts = samples[k]
            ax.plot(pts[:, 0], pts[:, 1], color="0.8", lw=3.5, zorder=1)
        for s in poly.segments:
            n = max(2, int(40 * (abs(getattr(s, "sweep", 0.0)) + 0.1)))
            xy = s.points(np.linspace(0.0, s.length, n))
            ax.plot(xy[:, 0], xy[:, 1], color=ARC_COLOUR if isinstance(s, Arc) else LINE_COLOUR, lw=1.3, zorder=2)
        corners = [poly.segments[j].end for j in poly.corners]
        if corners:
            c = np.array(corners)
            ax.plot(c[:, 0], c[:, 1], "kx", ms=5, mew=1.2, zorder=3)
        x, y = poly.start
        h = poly.segments[0].start_heading
        ax.plot([x], [y], "o", color="#2ca02c", ms=4, zorder=4)
        ax.annotate("", xy=(x + 0.03 * span * math.cos(h), y + 0.03 * span * math.sin(h)), xytext=(x, y),
                    arrowprops={"arrowstyle": "->", "color": "#2ca02c", "lw": 1.2}, zorder=4)
        if k in rank:
            ax.annotate(str(rank[k] + 1), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7, zorder=5)
    n_seg = sum(c.n_segments for c in contours)
    ax.plot([], [], color=ARC_COLOUR, label=f"arcs ({sum(c.n_arcs for c in contours)})")
    ax.plot([], [], color=LINE_COLOUR, label=f"lines ({sum(c.n_lines for c in contours)})")
    ax.plot([], [], "kx", label=f"corners ({sum(len(c.corners) for c in contours)})")
    ax.plot([], [], "o", color="#2ca02c", label="start and direction (number: spray order)" if order is not None
            else "start and direction (number: contour)")
    ax.set_title(f"{title}: {len(contours)} contours, {n_seg} segments")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def write_part_plot(contours: Sequence[Polysegment], title: str, path: str | Path,
                    samples: Sequence[np.ndarray] | None = None) -> None:
    write_bytes(path, part_figure_png(contours, title, samples))

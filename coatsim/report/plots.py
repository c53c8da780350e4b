"""Report figure helpers: matplotlib on Agg, PNG bytes, the variants' colours, and the polyline
program's figure (the sections draw their own figures in :mod:`coatsim.report.sections`; the
curve, its polysegment and θ come from :mod:`coatsim.geometry.plots`).

Every function takes plain arrays, draws with matplotlib's Agg backend (imported here, inside
the functions, so importing coatsim stays light) and returns PNG bytes without a timestamp,
so equal inputs give equal bytes.
"""

from __future__ import annotations

import io

import numpy as np

VARIANT_COLOURS = {"polysegment": "#1b6ca8", "polyline-stop": "#c0392b", "polyline-blend": "#e08e0b"}


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported on first use)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def png_bytes(fig, dpi: int = 100) -> bytes:
    """The figure as PNG bytes without a timestamp (equal figures give equal bytes); closes it.
    The figure lays itself out (tight or constrained layout): a tight bounding box here would
    draw it twice."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    pyplot().close(fig)
    return buf.getvalue()


_OTHER_COLOURS = ("#6a3d9a", "#33a02c", "#b15928", "#e7298a", "#1f78b4", "#666666")


def colour(variant: str, order: int = 0) -> str:
    """A variant's colour: fixed for the built-in variants, from a palette by order otherwise."""
    return VARIANT_COLOURS.get(variant, _OTHER_COLOURS[order % len(_OTHER_COLOURS)])



def polyline_figure(curve_xy: np.ndarray, polyline_xy: np.ndarray) -> bytes:
    """The input curve and the polyline program's vertices, where a program without
    blending brings the arm to rest."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 5.6))
    ax.plot(curve_xy[:, 0], curve_xy[:, 1], color="#bbbbbb", lw=4, zorder=1, label="input curve")
    ax.plot(polyline_xy[:, 0], polyline_xy[:, 1], "-o", color=colour("polyline-stop"), lw=1.0, ms=2.5,
            zorder=2, label="polyline vertices")
    ax.set_title(f"polyline: {len(polyline_xy) - 1} straight moves")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return png_bytes(fig)

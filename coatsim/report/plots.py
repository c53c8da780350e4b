"""Report figures as PNG bytes: the polyline program and the speed profiles (the curve, its
polysegment and θ come from :mod:`coatsim.geometry.plots`; the thickness maps and
cross-sections from :mod:`coatsim.spray.outputs`).

Every function takes plain arrays, draws with matplotlib's Agg backend (imported here, inside
the functions, so importing coatsim stays light) and returns PNG bytes without a timestamp,
so equal inputs give equal bytes.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import Mapping

import numpy as np


VARIANT_COLOURS = {"polysegment": "#1b6ca8", "polyline-stop": "#c0392b", "polyline-blend": "#e08e0b"}


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported on first use)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def png_bytes(fig, dpi: int = 100) -> bytes:
    """The figure as PNG bytes without a timestamp (equal figures give equal bytes); closes it."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None}, bbox_inches="tight")
    pyplot().close(fig)
    return buf.getvalue()


_pyplot, _png = pyplot, png_bytes

_OTHER_COLOURS = ("#6a3d9a", "#33a02c", "#b15928", "#e7298a", "#1f78b4", "#666666")


def colour(variant: str, order: int = 0) -> str:
    """A variant's colour: fixed for the built-in variants, from a palette by order otherwise."""
    return VARIANT_COLOURS.get(variant, _OTHER_COLOURS[order % len(_OTHER_COLOURS)])


_colour = colour


def polyline_figure(curve_xy: np.ndarray, polyline_xy: np.ndarray) -> bytes:
    """The input curve and the polyline program's vertices, where a program without
    blending brings the arm to rest."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 5.6))
    ax.plot(curve_xy[:, 0], curve_xy[:, 1], color="#bbbbbb", lw=4, zorder=1, label="input curve")
    ax.plot(polyline_xy[:, 0], polyline_xy[:, 1], "-o", color=_colour("polyline-stop"), lw=1.0, ms=2.5,
            zorder=2, label="polyline vertices")
    ax.set_title(f"polyline: {len(polyline_xy) - 1} straight moves")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return _png(fig)


@dataclass(frozen=True, eq=False)
class SpeedProfile:
    """Tool speed (n,) against programmed path length (n,) for one variant."""

    progress_mm: np.ndarray
    speed_mm_s: np.ndarray


def speed_figure(profiles: Mapping[str, SpeedProfile], commanded_mm_s: float, curve_span_mm: tuple[float, float]) -> bytes:
    """Speed against path length for every variant on one plot; the curve proper between
    the shaded run-in and run-out."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(11, 4.6))
    lo, hi = curve_span_mm
    ax.axvspan(min(p.progress_mm.min() for p in profiles.values()), lo, color="#f0f0f0", lw=0)
    ax.axvspan(hi, max(p.progress_mm.max() for p in profiles.values()), color="#f0f0f0", lw=0)
    ax.axhline(commanded_mm_s, color="black", ls="--", lw=0.8, label=f"programmed {commanded_mm_s:g} mm/s")
    for name, p in profiles.items():
        ax.plot(p.progress_mm, p.speed_mm_s, color=_colour(name), lw=1.1, label=name)
    ax.set_xlabel("path length along the program (mm); grey: run-in / run-out")
    ax.set_ylabel("tool speed (mm/s)")
    ax.set_ylim(0, 1.15 * max(commanded_mm_s, max(float(np.nanmax(p.speed_mm_s)) for p in profiles.values())))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    return _png(fig)

"""Report figures as PNG bytes: segmentation, θ and speed profiles (the thickness maps and
cross-sections come from :mod:`coatsim.spray.outputs`).

Every function takes plain arrays, draws with matplotlib's Agg backend (imported here, inside
the functions, so importing coatsim stays light) and returns PNG bytes without a timestamp,
so equal inputs give equal bytes.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from coatsim.geometry.polysegment import Polysegment, wrap_angle
from coatsim.geometry.primitives import Arc

VARIANT_COLOURS = {"polysegment": "#1b6ca8", "polyline-stop": "#c0392b", "polyline-blend": "#e08e0b"}
SEGMENT_COLOURS = {"line": "#1b6ca8", "arc": "#d35400"}


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None}, bbox_inches="tight")
    _pyplot().close(fig)
    return buf.getvalue()


def _colour(variant: str) -> str:
    return VARIANT_COLOURS.get(variant, "#555555")


def segmentation_figure(curve_xy: np.ndarray, poly: Polysegment, polyline_xy: np.ndarray | None) -> bytes:
    """Left: the input curve and the polysegment, segments coloured by type, junctions as
    dots and true corners as crosses. Right (when given): the polyline program's vertices,
    where a program without blending stops."""
    plt = _pyplot()
    panels = 2 if polyline_xy is not None else 1
    fig, axes = plt.subplots(1, panels, figsize=(6.2 * panels, 5.2), squeeze=False)
    ax = axes[0, 0]
    ax.plot(curve_xy[:, 0], curve_xy[:, 1], color="#bbbbbb", lw=4, label="input curve", zorder=1)
    seen: set[str] = set()
    for seg in poly.segments:
        step = max(seg.length / 64, 1e-9)
        pts = seg.points(np.linspace(0.0, seg.length, max(2, int(math.ceil(seg.length / step)) + 1)))
        ax.plot(pts[:, 0], pts[:, 1], color=SEGMENT_COLOURS[seg.kind], lw=1.6, zorder=2,
                label=f"{seg.kind}s" if seg.kind not in seen else None)
        seen.add(seg.kind)
    ends = np.array([s.start for s in poly.segments] + [poly.end])
    ax.plot(ends[:, 0], ends[:, 1], ".", color="black", ms=4, zorder=3, label="junctions")
    if poly.corners:
        corner_pts = np.array([poly.segments[k].end for k in poly.corners])
        ax.plot(corner_pts[:, 0], corner_pts[:, 1], "x", color="#c0392b", ms=9, mew=2, zorder=4, label="true corners")
    ax.set_title(f"polysegment: {poly.n_lines} lines + {poly.n_arcs} arcs")
    if polyline_xy is not None:
        ax2 = axes[0, 1]
        ax2.plot(curve_xy[:, 0], curve_xy[:, 1], color="#bbbbbb", lw=4, zorder=1, label="input curve")
        ax2.plot(polyline_xy[:, 0], polyline_xy[:, 1], "-o", color=_colour("polyline-stop"), lw=1.0, ms=2.5,
                 zorder=2, label="polyline vertices")
        ax2.set_title(f"polyline: {len(polyline_xy) - 1} straight moves")
    for a in axes[0]:
        a.set_aspect("equal", adjustable="datalim")
        a.set_xlabel("x (mm)")
        a.set_ylabel("y (mm)")
        a.grid(alpha=0.3)
        a.legend(loc="best", fontsize=8)
    return _png(fig)


def polysegment_theta(poly: Polysegment, start_heading: float) -> tuple[np.ndarray, np.ndarray]:
    """Exact θ of a polysegment at its knots: (t (2n,), θ (2n,)) with t in [0, 1] and θ
    measured from ``start_heading``; arcs are the linear pieces, corners the jumps."""
    total = poly.length
    t, theta = [], []
    s, phi = 0.0, float(wrap_angle(poly.segments[0].start_heading - start_heading))
    previous = None
    for seg in poly.segments:
        if previous is not None:
            phi += float(wrap_angle(seg.start_heading - previous.end_heading))
        t.append(s / total)
        theta.append(phi)
        s += seg.length
        phi += seg.sweep if isinstance(seg, Arc) else 0.0
        t.append(s / total)
        theta.append(phi)
        previous = seg
    return np.array(t), np.array(theta)


def theta_figure(t_in: np.ndarray, theta_in: np.ndarray, t_fit: np.ndarray, theta_fit: np.ndarray) -> bytes:
    """θ(t) of the input curve and of its polysegment (top) and their difference (bottom)."""
    plt = _pyplot()
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10, 5.6), sharex=True, gridspec_kw={"height_ratios": [3, 1.2]})
    ax.plot(t_in, np.degrees(theta_in), color="#999999", lw=3, label="input curve")
    ax.plot(t_fit, np.degrees(theta_fit), color=_colour("polysegment"), lw=1.2, label="polysegment (piecewise linear)")
    ax.plot(t_fit[::2], np.degrees(theta_fit[::2]), "|", color="black", ms=8, label="segment starts")
    ax.set_ylabel("θ (deg)")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    diff = np.interp(t_in, t_fit, theta_fit) - theta_in
    ax2.plot(t_in, np.degrees(diff), color="#444444", lw=0.8)
    ax2.set_ylabel("Δθ (deg)")
    ax2.set_xlabel("normalised arc length t")
    ax2.grid(alpha=0.3)
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
    ax.set_ylabel("tool speed while spraying (mm/s)")
    ax.set_ylim(0, 1.15 * max(commanded_mm_s, max(float(np.nanmax(p.speed_mm_s)) for p in profiles.values())))
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    return _png(fig)

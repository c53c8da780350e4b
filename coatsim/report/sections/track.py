"""The thickness-along-track section, one figure: the centre-line thickness against arc length
per variant (small multiples on one scale) with the target band, the seam and the lead zones,
and beside them every variant's thickness histogram over the region of interest all variants
share."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.html import Figure, Section, figure_html
from coatsim.report.plots import colour, figure, grid, lean, png_bytes, title

BAND = (0.8, 1.2)  # the target band, x target: coverage below, thick spots above (the coating metrics' limits)


def _histogram(ax: Any, data: Any) -> None:
    """Area-weighted thickness histograms over the shared region of interest, on shared bins,
    one outline per variant."""
    target = data.spec.gun.target_thickness_um
    runs, area = data.runs, data.surface.areas
    roi = runs[0].coating.roi
    hi = max(max(float(r.coating.thickness_um[roi].max()) for r in runs if roi.any()), BAND[1] * target * 1.1)
    bins = np.linspace(0.0, hi, 61)
    ax.axvspan(BAND[0] * target, BAND[1] * target, color="#2e8b57", alpha=0.13, lw=0)
    ax.axvline(target, color="#2e8b57", lw=0.8, ls="--")
    for k, run in enumerate(runs):
        mask = run.coating.roi
        weights = 100.0 * area[mask] / max(float(area[mask].sum()), 1e-12)
        counts, _ = np.histogram(run.coating.thickness_um[mask], bins=bins, weights=weights)
        ax.stairs(counts, bins, color=colour(run.name, k), lw=1.3, label=run.name)
    title(ax, "distribution over the region of interest")
    ax.set_xlabel("thickness (µm)", fontsize=8)
    ax.set_ylabel("% of the region's area", fontsize=8)
    ax.legend(loc="upper right", fontsize=7, frameon=False)


def track_figure(data: Any) -> bytes:
    """Left, one panel per variant on the same axes: the centre-line thickness against arc
    length; right, the thickness histograms of every variant."""
    centre, surface = data.centre, data.surface
    target = data.spec.gun.target_thickness_um
    values = {r.name: centre.points.field(surface, r.coating.thickness_um) for r in data.runs}
    top = max(max(float(np.nanmax(v)) for v in values.values()), BAND[1] * target) * 1.08
    n = len(data.runs)
    fig = figure(13.5, 1.7 * n + 0.75)
    axes = grid(fig, n, 1, margins=(0.65, 4.3, 0.3, 0.5), gaps=(0.0, 0.4), sharex=True, sharey=True)[:, 0]
    s, length = centre.s_mm, centre.curve_length_mm
    for k, (ax, run) in enumerate(zip(axes, data.runs)):
        ax.axvspan(min(s[0], 0.0), 0.0, color="#ececec", lw=0)
        ax.axvspan(length, max(s[-1], length), color="#ececec", lw=0)
        ax.axhspan(BAND[0] * target, BAND[1] * target, color="#2e8b57", alpha=0.13, lw=0)
        ax.axhline(target, color="#2e8b57", lw=0.8, ls="--")
        if centre.closed:
            for x in (0.0, length):
                ax.axvline(x, color="#6a3d9a", lw=0.9, ls="-.")
        ax.plot(s, values[run.name], color=colour(run.name, k), lw=1.0)
        title(ax, run.name, loc="left", color=colour(run.name, k))
        ax.set_ylabel("µm", fontsize=8)
    axes[0].set_ylim(0.0, top)
    seam = "; dash-dot: the seam" if centre.closed else ""
    axes[-1].set_xlabel(f"along the track's centre line (mm); grey: run-in and run-out{seam}", fontsize=8)
    width, height = fig.get_size_inches()
    hist = fig.add_axes(((width - 3.55) / width, 0.5 / height, 3.4 / width, (height - 0.8) / height))
    lean(hist)
    _histogram(hist, data)
    return png_bytes(fig)


def section(data: Any) -> Section:
    target = data.spec.gun.target_thickness_um
    band = f"{BAND[0] * target:.3g} to {BAND[1] * target:.3g} µm"
    closed = "; dash-dot lines: the seam, where the lap starts and ends" if data.centre.closed else ""
    return Section("thickness-along-track", "Thickness along the track", figure_html(Figure(
        "Centre-line thickness along the track, and its distribution", track_figure(data),
        f"Left: coating thickness on the part along the track's centre line (the polysegment's aim point: tool centre "
        f"point plus the stand-off along the spray axis, projected onto the part), one panel per variant on the same "
        f"axes, against arc length from the start of the curve proper. Green band: the target {target:g} µm ± 20 % "
        f"({band}); below it a spot counts as not covered, above it as a thick spot. Grey: the run-in and run-out "
        f"zones{closed}. Right: per variant (one outline each, on shared bins), the share of the area of the region of "
        f"interest (the vertices inside every variant's band) at each thickness, with the target band; a narrow peak "
        f"inside the band is an even coat.")))

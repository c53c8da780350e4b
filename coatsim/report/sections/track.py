"""The thickness-along-track section: the centre-line thickness against arc length per variant
(small multiples on one scale) with the target band, the seam and the lead zones, and each
variant's thickness histogram over the region of interest all variants share."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.html import Figure, Section, figure_html
from coatsim.report.plots import colour, png_bytes, pyplot

BAND = (0.8, 1.2)  # the target band, x target: coverage below, thick spots above (the coating metrics' limits)


def track_figure(data: Any) -> bytes:
    centre, surface = data.centre, data.surface
    target = data.spec.gun.target_thickness_um
    values = {r.name: centre.points.field(surface, r.coating.thickness_um) for r in data.runs}
    top = max(max(float(np.nanmax(v)) for v in values.values()), BAND[1] * target) * 1.08
    plt = pyplot()
    n = len(data.runs)
    fig, axes = plt.subplots(n, 1, figsize=(11, 1.9 * n + 0.8), sharex=True, sharey=True, squeeze=False)
    s, length = centre.s_mm, centre.curve_length_mm
    for k, (ax, run) in enumerate(zip(axes[:, 0], data.runs)):
        ax.axvspan(min(s[0], 0.0), 0.0, color="#ececec", lw=0)
        ax.axvspan(length, max(s[-1], length), color="#ececec", lw=0)
        ax.axhspan(BAND[0] * target, BAND[1] * target, color="#2e8b57", alpha=0.13, lw=0)
        ax.axhline(target, color="#2e8b57", lw=0.8, ls="--")
        if centre.closed:
            for x in (0.0, length):
                ax.axvline(x, color="#6a3d9a", lw=0.9, ls="-.")
        ax.plot(s, values[run.name], color=colour(run.name, k), lw=1.0)
        ax.set_title(run.name, loc="left", fontsize=9, fontweight="bold", color=colour(run.name, k), pad=3)
        ax.set_ylabel("µm", fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=8)
    axes[0, 0].set_ylim(0.0, top)
    seam = "; dash-dot: the seam" if centre.closed else ""
    axes[-1, 0].set_xlabel(f"along the track's centre line (mm); grey: run-in and run-out{seam}")
    fig.tight_layout()
    return png_bytes(fig)


def histogram_figure(data: Any) -> bytes:
    """Area-weighted thickness histograms over the shared region of interest, shared bins."""
    target = data.spec.gun.target_thickness_um
    runs = data.runs
    roi = runs[0].coating.roi
    hi = max(max(float(r.coating.thickness_um[roi].max()) for r in runs if roi.any()), BAND[1] * target * 1.1)
    bins = np.linspace(0.0, hi, 61)
    plt = pyplot()
    fig, axes = plt.subplots(1, len(runs), figsize=(3.6 * len(runs) + 0.6, 2.6), sharex=True, sharey=True,
                             squeeze=False)
    area = data.surface.areas
    for k, (ax, run) in enumerate(zip(axes[0], runs)):
        mask = run.coating.roi
        weights = 100.0 * area[mask] / max(float(area[mask].sum()), 1e-12)
        counts, _ = np.histogram(run.coating.thickness_um[mask], bins=bins, weights=weights)
        ax.stairs(counts, bins, fill=True, color=colour(run.name, k))
        ax.axvspan(BAND[0] * target, BAND[1] * target, color="#2e8b57", alpha=0.13, lw=0)
        ax.axvline(target, color="#2e8b57", lw=0.8, ls="--")
        ax.set_title(run.name, fontsize=9)
        ax.set_xlabel("thickness (µm)", fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=8)
    axes[0, 0].set_ylabel("% of the region's area", fontsize=8)
    fig.tight_layout()
    return png_bytes(fig)


def section(data: Any) -> Section:
    target = data.spec.gun.target_thickness_um
    band = f"{BAND[0] * target:.3g} to {BAND[1] * target:.3g} µm"
    track = Figure(
        "Centre-line thickness along the track", track_figure(data),
        f"Coating thickness on the part along the track's centre line (the polysegment's aim point: tool centre point "
        f"plus the stand-off along the spray axis, projected onto the part), one panel per variant on the same axes, "
        f"against arc length from the start of the curve proper. Green band: the target {target:g} µm ± 20 % "
        f"({band}); below it a spot counts as not covered, above it as a thick spot. Grey: the run-in and run-out "
        f"zones{'; dash-dot lines: the seam, where the lap starts and ends' if data.centre.closed else ''}.")
    hist = Figure(
        "Thickness distribution", histogram_figure(data),
        "Per variant, the share of the area of the region of interest (the vertices inside every variant's band) at "
        "each thickness, with the target band. A narrow peak inside the band is an even coat.")
    return Section("thickness-along-track", "Thickness along the track", figure_html(track) + figure_html(hist))

"""The maps section, one figure: thickness heat maps of every variant on one colour scale with the
sprayed tool path drawn, and the difference map polysegment − best polyline (the other variant
with the lowest thickness CV) on a symmetric scale. Each map is an image of the part's 2-D view
on the report's pixel grid (:mod:`coatsim.report.raster`)."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.plots import bar_ticks, figure, lean, png_bytes, title
from coatsim.spray.outputs import COLOUR_MAP

DIFF_MAP = "RdBu_r"
PANEL_HEIGHT_IN = 2.8
GAP_IN, BAR_IN, BAR_GAP_IN = 0.15, 0.12, 0.95  # between panels; a colour bar and the room for its labels
LABELS_IN = 0.75  # left of a group of panels: its y tick labels and label


def _panels(data: Any, groups: Sequence[int]) -> tuple[Any, list, list]:
    """Map panels side by side, as wide as the view's aspect asks, in groups each followed by
    its colour bar, laid out by hand (a layout engine would measure every artist): the figure,
    the panels, one colour-bar axis per group."""
    x0, x1, y0, y1 = data.raster.extent
    width = float(np.clip(PANEL_HEIGHT_IN * (x1 - x0) / max(y1 - y0, 1e-9), 1.5, 6.0))
    total = sum(LABELS_IN + n * (width + GAP_IN) + BAR_IN + BAR_GAP_IN for n in groups)
    fig = figure(total, PANEL_HEIGHT_IN + 0.85)
    box = lambda left, w: (left / total, 0.55 / fig.get_figheight(), w / total, PANEL_HEIGHT_IN / fig.get_figheight())  # noqa: E731
    axes, bars, left = [], [], 0.0
    for n in groups:
        first, left = None, left + LABELS_IN
        for _ in range(n):
            ax = fig.add_axes(box(left, width), sharex=first, sharey=first)
            lean(ax)
            if first is not None:
                ax.yaxis.set_visible(False)  # the first panel's axis serves the group
            first = first or ax
            axes.append(ax)
            left += width + GAP_IN
        bar = fig.add_axes(box(left - GAP_IN + 0.1, BAR_IN))
        bar.tick_params(labelsize=8)
        bars.append(bar)
        left += BAR_IN + BAR_GAP_IN
    return fig, axes, bars


def _image(ax: Any, data: Any, values: np.ndarray, path: np.ndarray, line: str, **style: Any) -> Any:
    """A field on the pixel grid with a tool path over it, the view limited to the part."""
    raster = data.raster
    image = ax.imshow(raster.image(values), origin="lower", extent=raster.extent, interpolation="nearest",
                      aspect="auto", **style)
    ax.set_xlim(*raster.extent[:2])
    ax.set_ylim(*raster.extent[2:])
    ax.set_autoscale_on(False)  # the path leaves the view where it leaves the part
    ax.plot(path[:, 0], path[:, 1], color=line, lw=0.5, alpha=0.7)
    ax.set_xlabel(data.surface.view_labels[0], fontsize=8)
    return image


def maps_figure(data: Any, other: Optional[Any]) -> tuple[bytes, float]:
    """Every variant's thickness on the report's scale, then (when another variant ran) the
    difference reference − ``other`` on a symmetric scale; and that scale's limit (µm)."""
    vmin, vmax = data.scale_um
    fig, axes, bars = _panels(data, [len(data.runs)] + ([1] if other is not None else []))
    image = None
    for ax, run in zip(axes, data.runs):
        image = _image(ax, data, run.coating.thickness_um, data.track_view(run), "white", cmap=COLOUR_MAP, vmin=vmin,
                       vmax=vmax)
        title(ax, run.name)
    axes[0].set_ylabel(data.surface.view_labels[1], fontsize=8)
    fig.colorbar(image, cax=bars[0], ticks=bar_ticks()).set_label("thickness (µm)", fontsize=8)
    limit = 0.0
    if other is not None:
        diff = data.reference.coating.thickness_um - other.coating.thickness_um
        limit = float(np.percentile(np.abs(diff), 99.5)) or 1.0
        ax = axes[-1]
        image = _image(ax, data, diff, data.track_view(data.reference), "black", cmap=DIFF_MAP, vmin=-limit, vmax=limit)
        title(ax, f"{data.reference.name} − {other.name}")
        ax.set_ylabel(data.surface.view_labels[1], fontsize=8)
        fig.colorbar(image, cax=bars[1], ticks=bar_ticks()).set_label("thickness difference (µm)", fontsize=8)
    return png_bytes(fig), limit


def section(data: Any) -> Section:
    vmin, vmax = data.scale_um
    other = data.best_polyline
    png, limit = maps_figure(data, other)
    caption = (f"Per-vertex coating thickness of each variant on the same scale, {vmin:g} to {vmax:.3g} µm (the largest "
               f"99.5th percentile of the variants; thicker spots saturate), with the sprayed tool path (white: the aim "
               f"point while the gun is open). The PLY and GLB files of the run use the same colours.")
    if other is None:
        caption += " Only one variant ran: no difference map."
    else:
        cv = data.document["variants"][other.name]["coating"]["thickness_cv"]
        cv_text = "undefined" if cv is None else f"{100 * cv:.3g} %"
        caption += (f" Right: the thickness of the {data.reference.name} minus that of {other.name}, the other variant "
                    f"with the lowest thickness CV ({cv_text}), per vertex, on a symmetric scale of ±{limit:.3g} µm "
                    f"(99.5th percentile of the absolute difference). Red: the {data.reference.name} coats thicker "
                    f"there; blue: thinner.")
    body = figure_html(Figure("Thickness maps on one colour scale, and the difference", png, caption))
    return Section("maps", "Thickness maps", body + f'<p class="muted">Colour map {esc(COLOUR_MAP)}.</p>')

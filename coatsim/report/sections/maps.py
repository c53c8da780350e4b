"""The maps section: thickness heat maps of every variant on one colour scale with the sprayed
tool path drawn, and the difference map polysegment − best polyline (the other variant with the
lowest thickness CV) on a symmetric scale. Each map is an image of the part's 2-D view on the
report's pixel grid (:mod:`coatsim.report.raster`), drawn once."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.plots import figure, lean, png_bytes, title
from coatsim.spray.outputs import COLOUR_MAP

DIFF_MAP = "RdBu_r"
PANEL_HEIGHT_IN = 2.8


def _panels(data: Any, n: int) -> tuple[Any, list, Any]:
    """n map panels side by side, each as wide as the view's aspect asks, and a colour-bar
    axis on the right, laid out by hand (a layout engine would measure every artist)."""
    x0, x1, y0, y1 = data.raster.extent
    width = float(np.clip(PANEL_HEIGHT_IN * (x1 - x0) / max(y1 - y0, 1e-9), 1.5, 6.0))
    fig = figure(0.75 + n * (width + 0.15) + 1.0, PANEL_HEIGHT_IN + 0.85)
    w, h = fig.get_size_inches()
    axes = []
    for k in range(n):
        ax = fig.add_axes(((0.75 + k * (width + 0.15)) / w, 0.55 / h, width / w, PANEL_HEIGHT_IN / h),
                          sharex=axes[0] if axes else None, sharey=axes[0] if axes else None)
        lean(ax)
        if axes:
            ax.tick_params(labelleft=False)
        axes.append(ax)
    bar = fig.add_axes(((0.75 + n * (width + 0.15)) / w, 0.55 / h, 0.12 / w, PANEL_HEIGHT_IN / h))
    bar.tick_params(labelsize=8)
    return fig, axes, bar


def _image(ax: Any, data: Any, values: np.ndarray, **style: Any) -> Any:
    raster = data.raster
    image = ax.imshow(raster.image(values), origin="lower", extent=raster.extent, interpolation="nearest",
                      aspect="auto", **style)
    ax.set_xlim(*raster.extent[:2])
    ax.set_ylim(*raster.extent[2:])
    ax.set_autoscale_on(False)  # the tracks drawn next leave the view where they leave the part
    return image


def heat_figure(data: Any) -> bytes:
    vmin, vmax = data.scale_um
    fig, axes, bar = _panels(data, len(data.runs))
    image = None
    for ax, run in zip(axes, data.runs):
        image = _image(ax, data, run.coating.thickness_um, cmap=COLOUR_MAP, vmin=vmin, vmax=vmax)
        path = data.track_view(run)
        ax.plot(path[:, 0], path[:, 1], color="white", lw=0.5, alpha=0.8)
        title(ax, run.name)
        ax.set_xlabel(data.surface.view_labels[0], fontsize=8)
    axes[0].set_ylabel(data.surface.view_labels[1], fontsize=8)
    fig.colorbar(image, cax=bar).set_label("thickness (µm)", fontsize=8)
    return png_bytes(fig)


def difference_figure(data: Any, other: Any) -> tuple[bytes, float]:
    """The difference map and its scale (µm)."""
    diff = data.reference.coating.thickness_um - other.coating.thickness_um
    limit = float(np.percentile(np.abs(diff), 99.5)) or 1.0
    fig, (ax,), bar = _panels(data, 1)
    image = _image(ax, data, diff, cmap=DIFF_MAP, vmin=-limit, vmax=limit)
    path = data.track_view(data.reference)
    ax.plot(path[:, 0], path[:, 1], color="black", lw=0.4, alpha=0.6)
    title(ax, f"{data.reference.name} − {other.name}")
    ax.set_xlabel(data.surface.view_labels[0], fontsize=8)
    ax.set_ylabel(data.surface.view_labels[1], fontsize=8)
    fig.colorbar(image, cax=bar).set_label("thickness difference (µm)", fontsize=8)
    return png_bytes(fig), limit


def section(data: Any) -> Section:
    vmin, vmax = data.scale_um
    body = figure_html(Figure(
        "Thickness maps on one colour scale", heat_figure(data),
        f"Per-vertex coating thickness of each variant on the same scale, {vmin:g} to {vmax:.3g} µm (the largest "
        f"99.5th percentile of the variants; thicker spots saturate), with the sprayed tool path (white: the aim point "
        f"while the gun is open). The PLY and GLB files of the run use the same colours."))
    other = data.best_polyline
    if other is None:
        body += '<p class="muted">Only one variant ran: no difference map.</p>'
    else:
        png, limit = difference_figure(data, other)
        cv = data.document["variants"][other.name]["coating"]["thickness_cv"]
        cv_text = "undefined" if cv is None else f"{100 * cv:.3g} %"
        body += figure_html(Figure(
            f"Difference {data.reference.name} − {other.name}", png,
            f"Thickness of the {data.reference.name} minus that of {other.name}, the other variant with the lowest "
            f"thickness CV ({cv_text}), per vertex, on a symmetric scale of ±{limit:.3g} µm (99.5th percentile "
            f"of the absolute difference). Red: the {data.reference.name} coats thicker there; blue: thinner."))
    return Section("maps", "Thickness maps", body + f'<p class="muted">Colour map {esc(COLOUR_MAP)}.</p>')

"""The maps section: thickness heat maps of every variant on one colour scale with the sprayed
tool path drawn, and the difference map polysegment − best polyline (the other variant with the
lowest thickness CV) on a symmetric scale."""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.plots import png_bytes, pyplot
from coatsim.spray.outputs import COLOUR_MAP, view_faces

DIFF_MAP = "RdBu_r"


def _axes_grid(plt, n: int, width: float = 4.4):
    fig, axes = plt.subplots(1, n, figsize=(width * n + 1.3, 4.1), squeeze=False, layout="constrained",
                             sharex=True, sharey=True)
    return fig, axes[0]


def heat_figure(data: Any) -> bytes:
    surface = data.surface
    faces = view_faces(surface)
    vmin, vmax = data.scale_um
    plt = pyplot()
    fig, axes = _axes_grid(plt, len(data.runs))
    image = None
    for ax, run in zip(axes, data.runs):
        image = ax.tripcolor(surface.view[:, 0], surface.view[:, 1], faces, run.coating.thickness_um,
                             shading="gouraud", cmap=COLOUR_MAP, vmin=vmin, vmax=vmax)
        path = data.track_view(run)
        ax.plot(path[:, 0], path[:, 1], color="white", lw=0.5, alpha=0.8)
        ax.set_aspect("equal")
        ax.set_title(run.name, fontsize=10)
        ax.set_xlabel(surface.view_labels[0])
    axes[0].set_ylabel(surface.view_labels[1])
    fig.colorbar(image, ax=list(axes), label="thickness (µm)", shrink=0.9)
    return png_bytes(fig, dpi=110)


def difference_figure(data: Any, other: Any) -> tuple[bytes, float]:
    """The difference map and its scale (µm)."""
    surface = data.surface
    faces = view_faces(surface)
    diff = data.reference.coating.thickness_um - other.coating.thickness_um
    limit = float(np.percentile(np.abs(diff), 99.5)) or 1.0
    plt = pyplot()
    fig, axes = _axes_grid(plt, 1, 6.0)
    ax = axes[0]
    image = ax.tripcolor(surface.view[:, 0], surface.view[:, 1], faces, diff, shading="gouraud", cmap=DIFF_MAP,
                         vmin=-limit, vmax=limit)
    path = data.track_view(data.reference)
    ax.plot(path[:, 0], path[:, 1], color="black", lw=0.4, alpha=0.6)
    ax.set_aspect("equal")
    ax.set_title(f"{data.reference.name} − {other.name}", fontsize=10)
    ax.set_xlabel(surface.view_labels[0])
    ax.set_ylabel(surface.view_labels[1])
    fig.colorbar(image, ax=ax, label="thickness difference (µm)", shrink=0.9)
    return png_bytes(fig, dpi=110), limit


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

"""Report figure helpers: matplotlib figures drawn on Agg, PNG bytes, the variants' colours.

A report draws about ten figures per run, so every one is laid out by hand (a layout engine
measures every artist, which costs more than drawing them), titles sit at a fixed height (the
automatic placement measures every tick label), axes carry few ticks drawn as plain artists
(:mod:`coatsim.report.ticks`), many marks go in one collection, and rasters are drawn at screen
resolution. Figures are plain ``matplotlib.figure.Figure`` objects (no pyplot state);
matplotlib is imported on first use, so importing coatsim stays light. PNG bytes carry no
timestamp: equal figures give equal bytes.
"""

from __future__ import annotations

import io
from functools import cache
from typing import Any, Sequence

from coatsim.report.ticks import flatten

VARIANT_COLOURS = {"polysegment": "#1b6ca8", "polyline-stop": "#c0392b", "polyline-blend": "#e08e0b"}
_OTHER_COLOURS = ("#6a3d9a", "#33a02c", "#b15928", "#e7298a", "#1f78b4", "#666666")
DPI = 80    # the report's figures: about 900 pixels across for an 11-inch figure
TICKS = 3   # at most about this many ticks per axis (each tick is two lines and two labels to make)
COLOURS = 256  # PNGs are stored with a palette of at most this many colours (a third of the bytes)
HINTING = "no_hinting"  # glyphs drawn as designed: FreeType's auto-hinter, run on every glyph drawn, costs a fifth


def figure(width_in: float, height_in: float) -> Any:
    """An empty figure (inches)."""
    from matplotlib.figure import Figure

    return Figure(figsize=(width_in, height_in))


def grid(fig: Any, rows: int, cols: int, margins: Sequence[float] = (0.7, 0.25, 0.35, 0.55),
         gaps: Sequence[float] = (0.45, 0.55), **shared: Any) -> Any:
    """A rows x cols array of axes laid out by hand: ``margins`` (left, right, top, bottom) and
    ``gaps`` (horizontal, vertical) in inches; ``shared`` as ``Figure.subplots`` takes it."""
    width, height = fig.get_size_inches()
    left, right, top, bottom = margins
    fig.subplots_adjust(left=left / width, right=1 - right / width, top=1 - top / height, bottom=bottom / height,
                        wspace=gaps[0] * cols / max(width - left - right - gaps[0] * (cols - 1), 1e-3),
                        hspace=gaps[1] * rows / max(height - top - bottom - gaps[1] * (rows - 1), 1e-3))
    axes = fig.subplots(rows, cols, squeeze=False, **shared)
    for ax in axes.ravel():
        lean(ax)
    hide_inner_axes(axes, **shared)
    return axes


def hide_inner_axes(axes: Any, sharex: Any = False, sharey: Any = False) -> None:
    """Shared axes drawn once: the x axis of the bottom row only, the y axis of the left column
    only (the inner panels' ticks would repeat the outer ones' and cost as much to draw)."""
    for ax in axes[:-1, :].ravel() if sharex else ():
        ax.xaxis.set_visible(False)
    for ax in axes[:, 1:].ravel() if sharey else ():
        ax.yaxis.set_visible(False)


def lean(ax: Any, labelsize: float = 8) -> None:
    """Few ticks, small labels."""
    ax.xaxis.set_major_locator(bar_ticks())
    ax.yaxis.set_major_locator(bar_ticks())
    ax.tick_params(labelsize=labelsize)


def bar_ticks() -> Any:
    """The locator of an axis's or a colour bar's ticks: at most about TICKS, inside the view."""
    return _in_view_locator()(TICKS)


@cache
def _in_view_locator() -> type:
    """matplotlib's MaxNLocator without the ticks beyond the view it adds to round the range
    (each tick is five artists made, and none of these is drawn)."""
    from matplotlib.ticker import MaxNLocator

    class InViewLocator(MaxNLocator):
        def __call__(self) -> Any:
            locs = super().__call__()
            lo, hi = sorted(self.axis.get_view_interval())
            slack = 1e-9 * max(hi - lo, abs(hi), abs(lo), 1e-300)
            return locs[(locs >= lo - slack) & (locs <= hi + slack)]

    return InViewLocator


def title(ax: Any, text: str, **style: Any) -> None:
    """An axes title at a fixed height above the axes."""
    ax.set_title(text, y=1.0, pad=4, **{"fontsize": 9, **style})


def png_bytes(fig: Any, dpi: int = DPI) -> bytes:
    """The figure as an opaque palette PNG without a timestamp (equal figures give equal bytes)."""
    import numpy as np
    from matplotlib import rc_context
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    for ax in fig.axes:
        flatten(ax)
    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    with rc_context({"text.hinting": HINTING}):
        canvas.draw()
    rgb = np.asarray(canvas.buffer_rgba())[..., :3]
    image = Image.fromarray(np.ascontiguousarray(rgb)).quantize(COLOURS, method=Image.Quantize.FASTOCTREE)
    buf = io.BytesIO()
    image.save(buf, format="png")
    return buf.getvalue()


def colour(variant: str, order: int = 0) -> str:
    """A variant's colour: fixed for the built-in variants, from a palette by order otherwise."""
    return VARIANT_COLOURS.get(variant, _OTHER_COLOURS[order % len(_OTHER_COLOURS)])

"""An axes' ticks, tick labels and axis label drawn as a few plain artists instead of matplotlib's
tick machinery.

matplotlib makes each tick of an axis from five artists (two marks, two labels, a grid line)
and measures every label to place the axis label; across a report's axes that costs more than
the data drawn. Here the same ticks (the axis's locator and formatter, the view as drawn, the
side matplotlib would draw them on) become one line of marks and one artist for the labels
(:mod:`coatsim.report.labels`), the axis label sits at a distance estimated from the labels'
length, and the axis itself is hidden. Call :func:`flatten` once the axes are final, just
before drawing.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from coatsim.report.labels import labels

WIDTH_EM = {"−": 0.84, "-": 0.36, ".": 0.32, ",": 0.32, " ": 0.32}  # of the default font (DejaVu Sans), in ems
DIGIT_EM = 0.64   # a digit's width, and any other character's: the y labels' extent
LINE_EM = 1.2     # height of a line of text, in ems: the x labels' extent


def flatten(ax: Any) -> None:
    """Replace the visible x and y axes of ``ax`` by plain artists (see the module)."""
    ax.apply_aspect()  # the limits as drawn (an equal aspect moves them)
    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_visible() and ax.get_visible():
            _flatten_axis(ax, axis)
            axis.set_visible(False)


def _side(axis: Any) -> str:
    """The side of the axes the ticks are on: bottom, top, left or right."""
    side = axis.get_ticks_position()
    if side in ("bottom", "top", "left", "right"):
        return side
    return "bottom" if axis.axis_name == "x" else "left"


def _flatten_axis(ax: Any, axis: Any) -> None:
    """Draw ``axis``'s ticks, labels, offset text and axis label as plain artists on ``ax``."""
    import matplotlib as mpl
    from matplotlib import lines
    from matplotlib.font_manager import FontProperties
    from matplotlib.transforms import ScaledTranslation, blended_transform_factory

    name, side = axis.axis_name, _side(axis)
    kw, rc = axis.get_tick_params(which="major"), mpl.rcParams  # what tick_params set (sides, labelsize)
    lo, hi = sorted(axis.get_view_interval())
    slack = 1e-9 * max(hi - lo, 1e-300)
    locs = np.asarray(axis.get_major_locator()(), float)
    locs = locs[(locs >= lo - slack) & (locs <= hi + slack)]
    formatter = axis.get_major_formatter()
    formatter.set_locs(locs)
    near = side in ("bottom", "left")  # matplotlib's first side; its second is top or right
    texts = formatter.format_ticks(locs) if kw.get(f"label{side}", near) else []
    size = FontProperties(size=kw.get("labelsize", rc[f"{name}tick.labelsize"])).get_size_in_points()
    length, pad = rc[f"{name}tick.major.size"], rc[f"{name}tick.major.pad"]
    outward = -1.0 if near else 1.0
    edge = 0.0 if near else 1.0
    inches = ax.figure.dpi_scale_trans
    shift = (lambda pt: ScaledTranslation(0.0, outward * pt / 72, inches)) if name == "x" else \
        (lambda pt: ScaledTranslation(outward * pt / 72, 0.0, inches))
    if name == "x":
        along = blended_transform_factory(ax.transData, ax.transAxes)
        marker = {"bottom": lines.TICKDOWN, "top": lines.TICKUP}[side]
        xy = (locs, np.full(len(locs), edge))
        align = {"ha": "center", "va": "top" if outward < 0 else "bottom"}
        extent = LINE_EM * size if texts else 0.0
    else:
        along = blended_transform_factory(ax.transAxes, ax.transData)
        marker = {"left": lines.TICKLEFT, "right": lines.TICKRIGHT}[side]
        xy = (np.full(len(locs), edge), locs)
        align = {"ha": "right" if outward < 0 else "left", "va": "center_baseline"}
        extent = size * max((sum(WIDTH_EM.get(c, DIGIT_EM) for c in t) for t in texts), default=0.0)
    if kw.get(side, near) and len(locs):
        ax.add_line(lines.Line2D(*xy, transform=along, marker=marker, linestyle="none", markersize=length,
                                 markeredgewidth=rc[f"{name}tick.major.width"], color=rc[f"{name}tick.color"],
                                 clip_on=False))
    labels(ax, np.column_stack(xy), texts, along + shift(length + pad), fontsize=size, **align)
    offset = formatter.get_offset()  # a common offset or power of ten, at the axis's far end
    if offset and texts:
        at = (1.0, edge) if name == "x" else (edge, 1.0)
        ax.text(*at, offset, transform=ax.transAxes + shift(length + pad + extent), fontsize=size, **align)
    label = axis.label
    if label.get_text():
        away = shift(length + pad + extent + axis.labelpad)
        style = {"fontsize": label.get_fontsize(), "color": label.get_color()}
        if name == "x":
            ax.text(0.5, edge, label.get_text(), transform=ax.transAxes + away, ha="center",
                    va="top" if outward < 0 else "bottom", **style)
        else:
            ax.text(edge, 0.5, label.get_text(), transform=ax.transAxes + away, ha="center",
                    va="bottom" if outward < 0 else "top", rotation=90, rotation_mode="anchor", **style)

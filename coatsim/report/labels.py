"""Many short texts of one font and colour drawn by one artist, for the report's figures.

A matplotlib ``Text`` is a full artist: made with its own font properties and defaults, laid
out line by line, measured again for its descent; half of what a figure's tick labels and
event numbers cost is that bookkeeping. :func:`labels` draws the strings at their points (in
any transform, offset in points) straight with the renderer: each is measured once, aligned,
and drawn.
"""

from __future__ import annotations

from functools import cache
from typing import Any, Sequence

import numpy as np

H_SHIFT = {"left": 0.0, "center": 0.5, "right": 1.0}  # share of the width left of the point
TEXT_ZORDER = 3.0  # drawn in the order of matplotlib's texts


def labels(ax: Any, xy: np.ndarray, texts: Sequence[str], transform: Any, *, fontsize: float, color: Any = "black",
           ha: str = "center", va: str = "center_baseline") -> Any:
    """Add to ``ax`` the strings ``texts`` at the points ``xy`` (k, 2) of ``transform``, aligned
    as a Text's ``ha`` and ``va`` (top, bottom, center or center_baseline), unclipped as an
    axes' texts are; the artist."""
    artist = _labels_class()(np.asarray(xy, float).reshape(-1, 2), list(texts), fontsize, color, ha, va)
    artist.set_transform(transform)
    artist.set_zorder(TEXT_ZORDER)
    ax.add_artist(artist)
    artist.set_clip_on(False)
    return artist


@cache
def _labels_class() -> type:
    """The artist class (matplotlib is imported on first use)."""
    from matplotlib.artist import Artist
    from matplotlib.colors import to_rgba
    from matplotlib.font_manager import FontProperties

    class Labels(Artist):
        def __init__(self, xy: np.ndarray, texts: list[str], fontsize: float, color: Any, ha: str, va: str) -> None:
            super().__init__()
            self.xy, self.texts, self.ha, self.va = xy, texts, ha, va
            self.prop = FontProperties(size=fontsize)
            self.rgba = to_rgba(color)

        def draw(self, renderer: Any) -> None:
            if not self.get_visible() or not self.texts:
                return
            gc = renderer.new_gc()
            gc.set_foreground(self.rgba, isRGBA=True)
            self._set_gc_clip(gc)
            _, lp_height, lp_descent = renderer.get_text_width_height_descent("lp", self.prop, False)
            height = renderer.get_canvas_width_height()[1]
            for (x, y), text in zip(self.get_transform().transform(self.xy), self.texts):
                if not (text and np.isfinite(x) and np.isfinite(y)):
                    continue
                w, h, d = renderer.get_text_width_height_descent(text, self.prop, False)
                h, d = max(h, lp_height), max(d, lp_descent)  # as a Text: at least a line's height
                baseline = {"top": y - h + d, "bottom": y + d, "center": y - h / 2 + d,
                            "center_baseline": y - (h - d) / 2}[self.va]
                renderer.draw_text(gc, x - H_SHIFT[self.ha] * w, height - baseline, text, self.prop, 0.0)
            gc.restore()
            self.stale = False

    return Labels

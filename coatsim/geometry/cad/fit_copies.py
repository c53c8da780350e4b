"""Fits shared between copies: a free-form stretch that is a translated copy of one fitted
before (a repeated glyph, a pattern drawn twice) gets that fit moved into place instead of a
new one, with a certified deviation.

Exported drawings round their coordinates, so copies agree only to the rounding (1e-4 mm at 4
decimals). The moved chain then starts exactly on the copy's first point and ends within that
rounding of its last one; the end is closed without changing a single heading (the pinned end
tangents stay exact), by lengthening or shortening at most two of the chain's lines along
themselves (``_closed_gap``): every later segment moves by a translation. The deviation of the
result from the copy's polyline is at most the original's verified deviation, plus how far the
copy's points lie from the moved original's (the polylines are then that close everywhere),
plus how far the correction moves any point of the chain (triangle inequality of the
Hausdorff distance). A copy whose bound exceeds its tolerance, or whose gap no pair of lines
can close, is fitted afresh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from coatsim.geometry.primitives import Line, Segment, snap_end

HEADING_EXACT_RAD = 1e-9  # pinned headings equal to this share a fit
NEAR_MM = 1e-3            # copies whose points differ by more than this from the original are not tried
SHORTEN_AT_MOST = 0.5     # a line stretched to close the gap keeps at least this share of its length
CANDIDATES = 64           # originals of one size compared with a stretch, at most


@dataclass(frozen=True, eq=False)
class Fitted:
    """A stretch fitted once: its points (n, 2), its pinned end headings, its chain and verified deviation."""

    points: np.ndarray
    start_heading: Optional[float]
    end_heading: Optional[float]
    segments: tuple[Segment, ...]
    deviation_mm: float


def _same_heading(a: Optional[float], b: Optional[float]) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return abs(math.remainder(a - b, 2 * math.pi)) <= HEADING_EXACT_RAD


def bucket(points: np.ndarray, closed_loop: bool, speed_kappa: Optional[float]) -> tuple:
    """The key under which the originals a stretch may copy are kept."""
    return len(points), closed_loop, speed_kappa


def reuse(originals: Sequence[Fitted], points: np.ndarray, tolerance: float, start_heading: Optional[float],
          end_heading: Optional[float]) -> Optional[tuple[tuple[Segment, ...], float]]:
    """The chain of an original that ``points`` copies, moved onto them, and its certified
    deviation bound (mm); None when no original serves (see the module docstring)."""
    rel = points - points[0]
    for original in originals[:CANDIDATES]:
        if not (_same_heading(original.start_heading, start_heading) and _same_heading(original.end_heading,
                                                                                         end_heading)):
            continue
        apart = float(np.linalg.norm(rel - (original.points - original.points[0]), axis=1).max(initial=0.0))
        if apart > NEAR_MM or original.deviation_mm + apart > tolerance:
            continue
        shift = points[0] - original.points[0]
        moved = tuple(s.transformed(np.eye(2), shift, 1.0) for s in original.segments)
        closed = _closed_gap(moved, points[-1])
        if closed is None:
            continue
        segments, displaced = closed
        bound = original.deviation_mm + apart + displaced
        if bound <= tolerance:
            return segments, bound
    return None


def _closed_gap(segments: tuple[Segment, ...], end: np.ndarray) -> Optional[tuple[tuple[Segment, ...], float]]:
    """The chain ending exactly at ``end``, each heading kept: the gap closed along one line (if
    parallel to it) or two, the later segments translated; and how far any point moved (mm).
    None when no line or pair of lines can close it."""
    gap = np.asarray(end, float) - np.asarray(segments[-1].end, float)
    size = float(np.linalg.norm(gap))
    if size <= 1e-12 * max(1.0, float(np.abs(end).max())):
        return snap_end(segments, (float(end[0]), float(end[1]))), size
    lines = [k for k, s in enumerate(segments) if isinstance(s, Line)]
    best: Optional[tuple[float, dict[int, float]]] = None
    for i, a in enumerate(lines):
        da = np.array([math.cos(segments[a].start_heading), math.sin(segments[a].start_heading)])
        if abs(da[0] * gap[1] - da[1] * gap[0]) <= 1e-12 * size:  # the gap along this line: one is enough
            options = [{a: float(da @ gap)}]
        else:
            options = []
        for b in lines[i + 1:]:
            db = np.array([math.cos(segments[b].start_heading), math.sin(segments[b].start_heading)])
            det = da[0] * db[1] - da[1] * db[0]
            if abs(det) > 1e-3:
                options.append({a: (gap[0] * db[1] - gap[1] * db[0]) / det, b: (da[0] * gap[1] - da[1] * gap[0]) / det})
        for stretch in options:
            cost = sum(abs(c) for c in stretch.values())
            if all(abs(c) <= (1 - SHORTEN_AT_MOST) * segments[k].length for k, c in stretch.items()) and (
                    best is None or cost < best[0]):
                best = (cost, stretch)
    if best is None:
        return None
    return snap_end(_stretched(segments, best[1]), (float(end[0]), float(end[1]))), best[0]


def _stretched(segments: tuple[Segment, ...], stretch: dict[int, float]) -> tuple[Segment, ...]:
    """Each line ``k`` of ``stretch`` longer by ``stretch[k]`` mm along itself, every segment
    after it translated by as much."""
    out: list[Segment] = []
    offset = np.zeros(2)
    for k, s in enumerate(segments):
        moved = s.transformed(np.eye(2), offset, 1.0) if offset.any() else s
        if k in stretch:
            d = stretch[k] * np.array([math.cos(s.start_heading), math.sin(s.start_heading)])
            offset = offset + d
            moved = Line(moved.start, (moved.end[0] + d[0], moved.end[1] + d[1]))
        out.append(moved)
    return tuple(out)

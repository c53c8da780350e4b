"""The polysegment: a chain of lines and arcs, tangent-continuous except at listed corners."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from coatsim.geometry.primitives import Arc, Line, Point, Segment, make_segment


def wrap_angle(angle: np.ndarray | float) -> np.ndarray | float:
    """Angle(s) wrapped into [-pi, pi)."""
    return np.remainder(np.asarray(angle) + np.pi, 2 * np.pi) - np.pi


@dataclass(frozen=True)
class Polysegment:
    """Chain of segments; ``corners`` are junction indices k (end of k, start of k+1,
    with ``n - 1`` the seam of a closed chain) where tangency is intentionally broken;
    ``speed_limited`` the stretches (s0 mm, s1 mm, v_max mm/s) along the chain where the
    speed it was fitted for cannot be kept (coatsim.geometry.dynamics), if one was given."""

    segments: tuple[Segment, ...]
    closed: bool = False
    corners: tuple[int, ...] = ()
    speed_limited: tuple[tuple[float, float, float], ...] = ()

    def __post_init__(self) -> None:
        if not self.segments:
            raise ValueError("a polysegment needs at least one segment")

    @property
    def n_segments(self) -> int:
        return len(self.segments)

    @property
    def n_arcs(self) -> int:
        return sum(isinstance(s, Arc) for s in self.segments)

    @property
    def n_lines(self) -> int:
        return sum(isinstance(s, Line) for s in self.segments)

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    @property
    def start(self) -> Point:
        return self.segments[0].start

    @property
    def end(self) -> Point:
        return self.segments[-1].end

    def junction_breaks(self) -> np.ndarray:
        """Absolute heading change (rad) at every junction, seam last for a closed chain."""
        segs = self.segments
        pairs = list(zip(segs[:-1], segs[1:]))
        if self.closed:
            pairs.append((segs[-1], segs[0]))
        return np.array([abs(wrap_angle(b.start_heading - a.end_heading)) for a, b in pairs])

    def max_tangent_break(self, include_corners: bool = False) -> float:
        """Largest heading change (rad) over junctions that are not listed corners."""
        breaks = self.junction_breaks()
        if not include_corners and len(breaks):
            mask = np.ones(len(breaks), dtype=bool)
            mask[[k for k in self.corners if k < len(breaks)]] = False
            breaks = breaks[mask]
        return float(breaks.max()) if len(breaks) else 0.0

    def sample(self, step: float) -> tuple[np.ndarray, np.ndarray]:
        """Points every ``step`` mm or closer, every segment's end included.

        Returns (points (n, 2), arc length (n,)).
        """
        pts, ss = [np.asarray([self.start], dtype=float)], [np.zeros(1)]
        offset = 0.0
        for seg in self.segments:
            n = max(1, int(math.ceil(seg.length / step)))
            s = np.linspace(0.0, seg.length, n + 1)[1:]
            p = seg.points(s)
            p[-1] = seg.end
            pts.append(p)
            ss.append(offset + s)
            offset += seg.length
        return np.vstack(pts), np.concatenate(ss)

    def transformed(self, matrix: np.ndarray, offset: Sequence[float], scale: float = 1.0) -> Polysegment:
        """Image under p -> scale * matrix @ p + offset (matrix orthogonal); speed limits
        scale with the radii (s by ``scale``, v_max by its square root)."""
        off = np.asarray(offset, dtype=float)
        segs = tuple(s.transformed(np.asarray(matrix, float), off, scale) for s in self.segments)
        limited = tuple((a * scale, b * scale, v * math.sqrt(scale)) for a, b, v in self.speed_limited)
        return replace(self, segments=segs, speed_limited=limited)


def chain(
    start: Point,
    heading: float,
    curvatures: Sequence[float],
    lengths: Sequence[float],
) -> tuple[Segment, ...]:
    """Tangent-continuous chain from a start pose and (curvature, length) per segment.

    Each segment starts exactly where the previous one ends, at the previous end heading,
    so the chain is G1 by construction.
    """
    segs: list[Segment] = []
    p, h = start, heading
    for kappa, length in zip(curvatures, lengths):
        seg = make_segment(p, h, float(kappa), float(length))
        segs.append(seg)
        p, h = seg.end, h + float(kappa) * float(length)
    return tuple(segs)

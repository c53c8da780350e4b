"""The 3-D polysegment: a chain of Line3/Arc3, tangent-continuous except at listed corners."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3

Axis = tuple[float, float, float]


@dataclass(frozen=True, eq=False)
class SpaceChain:
    """Chain of 3-D segments; consecutive segments share end points exactly.

    ``corners``: junction indices k (end of k, start of k + 1; ``n - 1`` the seam of a
    closed chain) where tangency is intentionally broken; ``speed_limited``: stretches
    (s0 mm, s1 mm, v_max mm/s) where the speed it was fitted for cannot be kept;
    ``axes``: optionally, per segment, the unit tool axis at its start, via point and end
    (an orientation-aware fit, coatsim.geometry.space.orient), else empty.
    """

    segments: tuple[Segment3, ...]
    closed: bool = False
    corners: tuple[int, ...] = ()
    speed_limited: tuple[tuple[float, float, float], ...] = ()
    axes: tuple[tuple[Axis, Axis, Axis], ...] = ()

    def __post_init__(self) -> None:
        if not self.segments:
            raise ValueError("a chain needs at least one segment")
        if self.axes and len(self.axes) != len(self.segments):
            raise ValueError("a chain's axes are given for every segment or for none")

    @property
    def n_segments(self) -> int:
        return len(self.segments)

    @property
    def n_arcs(self) -> int:
        return sum(isinstance(s, Arc3) for s in self.segments)

    @property
    def n_lines(self) -> int:
        return sum(isinstance(s, Line3) for s in self.segments)

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    def junction_breaks(self) -> np.ndarray:
        """Angle (rad) between the tangents meeting at every junction, seam last when closed."""
        segs = self.segments
        pairs = list(zip(segs[:-1], segs[1:])) + ([(segs[-1], segs[0])] if self.closed else [])
        return np.array([_angle(a.end_tangent, b.start_tangent) for a, b in pairs])

    def max_tangent_break(self, include_corners: bool = False) -> float:
        """Largest tangent break (rad) over junctions that are not listed corners."""
        breaks = self.junction_breaks()
        if not include_corners and len(breaks):
            keep = np.ones(len(breaks), dtype=bool)
            keep[[k for k in self.corners if k < len(breaks)]] = False
            breaks = breaks[keep]
        return float(breaks.max()) if len(breaks) else 0.0

    def max_curvature_jump(self) -> float:
        """Largest |Δ curvature vector| (1/mm) at a junction that is not a listed corner: the
        step of sideways acceleration per v² the tool feels there."""
        segs = self.segments
        pairs = [(k, k + 1) for k in range(len(segs) - 1)] + ([(len(segs) - 1, 0)] if self.closed and len(segs) > 1 else [])
        return max((float(np.linalg.norm(_kappa_vector(segs[b], True) - _kappa_vector(segs[a], False)))
                    for k, (a, b) in enumerate(pairs) if k not in self.corners), default=0.0)

    def sample(self, step: float) -> tuple[np.ndarray, np.ndarray]:
        """Points every ``step`` mm or closer, every segment end included: (points (n, 3),
        arc length (n,))."""
        pts, ss = [self.segments[0].start[None]], [np.zeros(1)]
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

    def transformed(self, pose: Pose) -> SpaceChain:
        axes = tuple(tuple(tuple(float(v) for v in pose.apply_vectors(np.array(a))) for a in trio) for trio in self.axes)
        return replace(self, segments=tuple(s.transformed(pose) for s in self.segments), axes=axes)  # type: ignore[arg-type]


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    return math.atan2(float(np.linalg.norm(np.cross(a, b))), float(a @ b))


def _kappa_vector(seg: Segment3, at_start: bool) -> np.ndarray:
    """Curvature vector (towards the centre, 1/mm) at a segment's start or end."""
    if isinstance(seg, Line3):
        return np.zeros(3)
    point = seg.start if at_start else seg.end
    return (seg.center - point) / seg.radius**2

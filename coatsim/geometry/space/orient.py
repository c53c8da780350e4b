"""Orientation-aware fit of a surface pass: the G1 chain of the TCP points with the tool axis
given at every segment end and arc via point, so that the axis a controller interpolates
between those poses stays within ``angle_tol_deg`` of the wanted axis along the whole path.

The wanted axis at a point of the chain is the given spray axis (unit, from the gun toward the
surface: minus the smoothed surface normal) interpolated at the place along the input that matches
the point's place along the chain (coatsim.geometry.space.along: not at its nearest input point,
which on a path coming back close to itself may lie on another stretch). The controller model:
between two given poses the axis turns at a constant rate along the great circle joining them
(slerp, linear in the fraction of the move's length); an arc is two such stretches, start -> via and
via -> end. Where the interpolated axis strays further than the tolerance, the segment is split at
its middle (a line into two lines, an arc into two arcs of its circle: the path and its tangents do
not change), which gives the controller one more pose there. The roll about the axis is not chosen
here (the language writer fixes it or follows the travel direction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.space.along import AlongPass
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.primitives import Line3, Segment3
from coatsim.geometry.space.segment import SpaceSegmentation, segment_space_curve

ANGLE_TOL_DEG = defaults.ANGLE_TOL_DEG  # the interpolated axis stays this close to the wanted one
MAX_TURN_DEG = 90.0  # consecutive input axes turning more than this are a flip, not a surface
SAMPLES_PER_MM = 2.0  # the axis error is measured this densely (and at least 16 times a segment)
MIN_SPLIT_MM = 1e-3  # no segment is split shorter than this


@dataclass(frozen=True, eq=False)
class OrientedFit:
    """The fitted pass (its chain carries the axes) and the largest angle (rad) between the
    interpolated and the wanted axis measured along it."""

    segmentation: SpaceSegmentation
    max_axis_error_rad: float
    angle_tol_rad: float

    @property
    def chain(self) -> SpaceChain:
        return self.segmentation.chain


def slerp_axes(a: np.ndarray, b: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Unit vectors (n, 3) at fractions ``u`` along the great circle from unit ``a`` to ``b``."""
    angle = math.atan2(float(np.linalg.norm(np.cross(a, b))), float(a @ b))
    u = np.asarray(u, dtype=float)
    if angle < 1e-12:
        v = (1 - u)[:, None] * a + u[:, None] * b
    else:
        v = (np.sin((1 - u) * angle)[:, None] * a + np.sin(u * angle)[:, None] * b) / math.sin(angle)
    return v / np.linalg.norm(v, axis=1)[:, None]


def _interpolated(seg: Segment3, ends: tuple[np.ndarray, np.ndarray, np.ndarray], s: np.ndarray) -> np.ndarray:
    """The controller's axis at arc lengths ``s`` of a segment given its start, via and end axes."""
    start, via, end = ends
    if isinstance(seg, Line3):
        return slerp_axes(start, end, s / seg.length)
    half = seg.length / 2
    first = s <= half
    out = np.empty((len(s), 3))
    out[first] = slerp_axes(start, via, s[first] / half)
    out[~first] = slerp_axes(via, end, (s[~first] - half) / half)
    return out


def _segment_error(seg: Segment3, wanted: AlongPass) -> tuple[float, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """(largest axis error along the segment, its (start, via, end) axes)."""
    ends = tuple(wanted(np.array([p]))[0] for p in (seg.start, seg.via, seg.end))
    s = np.linspace(0.0, seg.length, max(16, int(math.ceil(seg.length * SAMPLES_PER_MM)) + 1))
    got, want = _interpolated(seg, ends, s), wanted(seg.points(s))  # type: ignore[arg-type]
    err = np.arctan2(np.linalg.norm(np.cross(got, want), axis=1), np.einsum("ij,ij->i", got, want))
    return float(err.max()), ends  # type: ignore[return-value]


def _check_axes(points: np.ndarray, axes: np.ndarray, name: str) -> np.ndarray:
    a = np.asarray(axes, dtype=float)
    if a.shape != points.shape:
        raise InputError(f"{name}: spray axes: expected one (x, y, z) per point, {points.shape}, got {a.shape}")
    norm = np.linalg.norm(a, axis=1)
    bad = ~(np.isfinite(norm) & (norm > 0))
    if bad.any():
        raise InputError(f"{name}: spray axis {int(np.argmax(bad)) + 1} is zero or not finite")
    a = a / norm[:, None]
    turn = np.degrees(np.arctan2(np.linalg.norm(np.cross(a[:-1], a[1:]), axis=1), np.einsum("ij,ij->i", a[:-1], a[1:])))
    if (turn > MAX_TURN_DEG).any():
        k = int(np.argmax(turn > MAX_TURN_DEG))
        raise InputError(f"{name}: the spray axis turns {turn[k]:.1f} degrees between points {k + 1} and {k + 2}; "
                         "smooth the surface normals (a flip is not a surface)")
    return a


def fit_surface_pass(points: np.ndarray, spray_axes: np.ndarray, tolerance_mm: float,
                     angle_tol_deg: float = ANGLE_TOL_DEG, corner_deg: float = 20.0,
                     min_segment_mm: float | None = None, speed_mm_s: float | None = None,
                     tool_accel_mm_s2: float | None = None, name: str = "surface pass") -> OrientedFit:
    """The G1 chain of TCP ``points`` (n, 3) within ``tolerance_mm`` with the tool axis at
    every segment end and via point, the interpolated axis within ``angle_tol_deg`` of
    ``spray_axes`` (n, 3) along the whole path (see the module text)."""
    if not (isinstance(angle_tol_deg, (int, float)) and math.isfinite(angle_tol_deg) and 0 < angle_tol_deg < 90):
        raise InputError(f"angle_tol_deg: must be between 0 and 90 degrees, got {angle_tol_deg}")
    curve = make_space_curve(points, name, "no")
    axes = _check_axes(np.asarray(points, dtype=float), spray_axes, name)
    keep = np.ones(len(points), dtype=bool)  # make_space_curve dropped repeated points: so do the axes
    keep[1:] = np.any(np.diff(np.asarray(points, dtype=float), axis=0) != 0.0, axis=1)
    try:
        seg = segment_space_curve(curve, tolerance_mm, corner_deg, min_segment_mm, speed_mm_s, tool_accel_mm_s2)
    except InputError as exc:  # said of the pass it is about, with its size (a loop of a millimetre misfits)
        if str(exc).startswith(name):
            raise
        length = float(np.linalg.norm(np.diff(curve.points, axis=0), axis=1).sum())
        raise type(exc)(f"{name} (its tool path {length:.3g} mm long): {exc}", parameters=exc.parameters) from None
    wanted = AlongPass(seg.chain.segments, curve.points, axes[keep], tolerance_mm)
    limit = math.radians(angle_tol_deg)
    pieces: list[list[Segment3]] = [[s] for s in seg.chain.segments]
    out_axes: list[list[tuple]] = [[] for _ in pieces]
    worst = 0.0
    for k, group in enumerate(pieces):
        todo, done = list(group), []
        while todo:
            s = todo.pop(0)
            err, ends = _segment_error(s, wanted)
            if err > limit and s.length / 2 >= MIN_SPLIT_MM:
                todo[:0] = list(s.halves())
                continue
            worst = max(worst, err)
            done.append(s)
            out_axes[k].append(tuple(tuple(float(v) for v in e) for e in ends))
        pieces[k] = done
    counts = np.cumsum([len(p) for p in pieces])
    chain = SpaceChain(tuple(s for p in pieces for s in p), seg.chain.closed,
                       tuple(int(counts[k]) - 1 for k in seg.chain.corners), seg.chain.speed_limited,
                       tuple(a for group in out_axes for a in group))
    return OrientedFit(replace(seg, chain=chain), worst, limit)

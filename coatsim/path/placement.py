"""Placement: a planar polysegment becomes a 3-D tool path in the robot base frame.

The curve lies in the XY plane of the workpiece frame, whose pose in the base frame is given as
x, y, z (mm) and O-A-T (deg). The surface normal is the workpiece +z axis; the tool centre point
runs ``standoff_mm`` above the surface along it, with the spray axis (tool z) pointing at the
surface. Tangent extensions before and after the curve (lead-in, lead-out) let the gun reach
its speed before it reaches the curve; the spray is on along them and along the curve.

Tool orientation is ``R_frame . Ry(180 deg) . Rz(gamma)``. With a fixed roll gamma is the roll
angle, so an unrotated frame and zero roll give O-A-T = (0, 180, 0). With ``follow_tangent``
gamma = 180 deg - heading + roll, so at zero roll the tool x axis points along the direction
of travel and turns with the path on arcs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line
from coatsim.geometry.space.primitives import Arc3, DegenerateArc, Line3, Segment3, arc_through
from coatsim.path.frames import DEFAULT_FRAME
from coatsim.geometry.space.rotations import rot_y, rot_z
from coatsim.geometry.space.pose import Pose, exp_rotation, slerp


# An arc that bulges less than this from its chord is placed as the chord (far below the
# 1e-7 mm a written coordinate carries).
_MIN_SAGITTA_MM = 1e-8


@dataclass(frozen=True)
class Placement:
    """Where and how the curve is sprayed; ``offset_xy`` is added to the curve before placing
    (see :func:`centering_offset` to centre it on the frame origin)."""

    frame: Pose = DEFAULT_FRAME
    standoff_mm: float = defaults.STANDOFF_MM
    roll_deg: float = 0.0
    follow_tangent: bool = False
    lead_in_mm: float = defaults.LEAD_IN_MM
    lead_out_mm: float = defaults.LEAD_OUT_MM
    offset_xy: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        checks = (
            ("standoff_mm", self.standoff_mm, self.standoff_mm > 0.0),
            ("lead_in_mm", self.lead_in_mm, self.lead_in_mm >= 0.0),
            ("lead_out_mm", self.lead_out_mm, self.lead_out_mm >= 0.0),
        )
        if not math.isfinite(self.roll_deg):
            raise InputError(f"roll_deg = {self.roll_deg}: must be a finite number of degrees")
        if not all(math.isfinite(v) for v in self.offset_xy):
            raise InputError(f"offset_xy = {self.offset_xy}: must be finite (mm)")
        for name, value, ok in checks:
            if not (ok and math.isfinite(value)):
                raise InputError(f"{name} = {value}: must be a finite number {'> 0' if name == 'standoff_mm' else '>= 0'}")


@dataclass(frozen=True, eq=False)
class PlacedMove:
    """One TCP move of a placed path: its geometry (a Line3 or an Arc3, base frame, mm), the tool
    pose at its start and at its end, and the part of the path it belongs to ("lead_in",
    "curve" or "lead_out"); on an arc with ``follow_tangent`` the tool turns with the path.

    A move of a 3-D pass gives its arc's middle pose explicitly (``via_pose``: the controller
    turns the tool from the start pose to it and on to the end pose) and may have its own
    programmed speed (``speed_mm_s``; None: the plan's). A writer writes both.
    """

    geometry: Segment3
    start: Pose
    end: Pose
    part: str = "curve"
    follow_tangent: bool = False
    via_pose: Pose | None = None
    speed_mm_s: float | None = None

    @property
    def length(self) -> float:
        return self.geometry.length

    @property
    def is_arc(self) -> bool:
        return self.geometry.kind == "arc"

    def pose_at(self, u: float) -> Pose:
        """Pose at fraction ``u`` of an arc's sweep (u = 1 gives ``end`` exactly)."""
        if u == 1.0:
            return self.end
        arc = self.geometry
        point = arc.at_angles(np.array([u * arc.sweep]))[0]
        if self.via_pose is not None:
            if u == 0.5:
                return self.via_pose
            a, b, f = (self.start, self.via_pose, 2 * u) if u < 0.5 else (self.via_pose, self.end, 2 * u - 1)
            return Pose(slerp(a.rotation, b.rotation, f)[0], point)
        rotation = self.start.rotation
        if self.follow_tangent:
            rotation = exp_rotation(arc.normal * (u * arc.sweep)) @ rotation
        return Pose(rotation, point)

    @property
    def via(self) -> Pose:
        """An arc's middle, a three-point circular move's via point."""
        return self.pose_at(0.5)

    def point_tangent(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points (n, 3) and unit tangents (n, 3) at fractions ``u`` of the move."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        if self.is_arc:
            angles = u * self.geometry.sweep
            return self.geometry.at_angles(angles), self.geometry.tangents_at_angles(angles)
        line = self.geometry
        return line.start + np.outer(u, line.end - line.start), np.tile(line.direction, (len(u), 1))

    def split(self, max_sweep: float) -> tuple[PlacedMove, ...]:
        """An arc as equal pieces of at most ``max_sweep`` rad each."""
        arc = self.geometry
        n = max(1, math.ceil(arc.sweep / max_sweep - 1e-12))
        if n == 1:
            return (self,)
        poses = [self.pose_at(k / n) for k in range(n)] + [self.end]
        vias = [self.pose_at((k + 0.5) / n) if self.via_pose is not None else None for k in range(n)]
        return tuple(PlacedMove(placed_arc(poses[k], poses[k + 1], arc.center, arc.normal, arc.sweep / n),
                                poses[k], poses[k + 1], self.part, self.follow_tangent, vias[k], self.speed_mm_s)
                     for k in range(n))


def placed_line(start: Pose, end: Pose, part: str = "curve") -> PlacedMove:
    """A straight TCP move between two poses."""
    return PlacedMove(Line3(start.translation_mm, end.translation_mm), start, end, part)


def placed_arc(start: Pose, end: Pose, center: np.ndarray, normal: np.ndarray, sweep: float) -> Arc3:
    """The arc from ``start`` turning ``sweep`` (> 0) rad about the unit ``normal`` around ``center``."""
    radius = float(np.linalg.norm(start.translation_mm - center))
    return Arc3(start.translation_mm, end.translation_mm, center, normal, radius, sweep)


@dataclass(frozen=True, eq=False)
class PlacedPath:
    """The sprayed tool path in the base frame: lead-in, curve, lead-out, end to end.

    ``approach_clearance_mm`` and ``depart_clearance_mm`` are how far back along its axis the
    tool comes in to this path's start and leaves after its end (None: the plan's
    ``approach_mm``): the straight gun-off travel between two passes of a 3-D part may need more
    room than on a flat one."""

    segments: tuple[PlacedMove, ...]
    normal: np.ndarray
    standoff_mm: float
    lead_in_mm: float
    lead_out_mm: float
    curve_length_mm: float
    approach_clearance_mm: float | None = None
    depart_clearance_mm: float | None = None

    @property
    def start(self) -> Pose:
        return self.segments[0].start

    @property
    def end(self) -> Pose:
        return self.segments[-1].end

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))


def centering_offset(poly: Polysegment) -> tuple[float, float]:
    """The shift that moves the centre of the exact bounding box of ``poly`` (arcs included)
    to the origin."""
    pts = [np.asarray(s.start, dtype=float) for s in poly.segments] + [np.asarray(poly.end, dtype=float)]
    for seg in poly.segments:
        if isinstance(seg, Arc):
            lo = min(seg.start_angle, seg.start_angle + seg.sweep)
            hi = max(seg.start_angle, seg.start_angle + seg.sweep)
            for k in range(math.ceil(lo / (math.pi / 2)), math.floor(hi / (math.pi / 2)) + 1):
                phi = k * math.pi / 2
                pts.append(np.asarray(seg.center) + seg.radius * np.array([math.cos(phi), math.sin(phi)]))
    arr = np.array(pts)
    mid = (arr.min(axis=0) + arr.max(axis=0)) / 2.0
    return (float(-mid[0]) + 0.0, float(-mid[1]) + 0.0)


class _Mapper:
    """Maps workpiece-plane points and headings to base-frame TCP poses."""

    def __init__(self, placement: Placement) -> None:
        self.rotation = placement.frame.rotation
        self.normal = self.rotation[:, 2].copy()
        self.lift = placement.frame.translation_mm + placement.standoff_mm * self.normal
        self.offset = np.asarray(placement.offset_xy, dtype=float)
        self.roll = math.radians(placement.roll_deg)
        self.follow = placement.follow_tangent
        self.tool_down = self.rotation @ rot_y(math.pi)

    def point(self, xy: tuple[float, float] | np.ndarray) -> np.ndarray:
        p = np.asarray(xy, dtype=float) + self.offset
        return self.lift + self.rotation @ np.array([p[0], p[1], 0.0])

    def pose(self, xy: tuple[float, float] | np.ndarray, heading: float) -> Pose:
        gamma = (math.pi - heading + self.roll) if self.follow else self.roll
        return Pose(self.tool_down @ rot_z(gamma), self.point(xy))


def _extension(m: _Mapper, anchor: np.ndarray, heading: float, length: float, part: str) -> PlacedMove:
    """Tangent line of ``length`` ending (lead-in) or starting (lead-out) at ``anchor``."""
    direction = np.array([math.cos(heading), math.sin(heading)])
    far = anchor + (-length if part == "lead_in" else length) * direction
    a, b = (far, anchor) if part == "lead_in" else (anchor, far)
    return placed_line(m.pose(a, heading), m.pose(b, heading), part)


def _placed_arc(m: _Mapper, arc: Arc, follow_tangent: bool) -> PlacedMove:
    """An arc up to a half turn becomes the circle through its start, middle and end, which
    is exactly what a program can say even if the arc's end is off its circle by rounding;
    a longer arc (up to full turns) keeps its centre and sweep; an arc too flat to define a
    circle becomes its chord."""
    start, end = m.pose(arc.start, arc.start_heading), m.pose(arc.end, arc.end_heading)
    if abs(arc.sweep) > math.pi:
        normal = m.normal if arc.sweep > 0 else -m.normal
        return PlacedMove(placed_arc(start, end, m.point(arc.center), normal, abs(arc.sweep)), start, end, "curve",
                          follow_tangent)
    a, b = np.asarray(arc.start, dtype=float), np.asarray(arc.end, dtype=float)
    chord = b - a
    sagitta = 2.0 * arc.radius * math.sin(arc.sweep / 4.0) ** 2
    if sagitta < _MIN_SAGITTA_MM:
        return placed_line(start, end)
    # The arc bulges away from its centre: to the right of the chord when turning left.
    left = np.array([-chord[1], chord[0]]) / float(np.linalg.norm(chord))
    middle = m.point((a + b) / 2.0 - math.copysign(sagitta, arc.sweep) * left)
    try:
        circle = arc_through(start.translation_mm, middle, end.translation_mm)
    except DegenerateArc:
        return placed_line(start, end)
    return PlacedMove(placed_arc(start, end, circle.center, circle.normal, circle.sweep), start, end, "curve",
                      follow_tangent)


def place(poly: Polysegment, placement: Placement) -> PlacedPath:
    """The 3-D sprayed path of ``poly``: lead-in line, one placed segment per segment, lead-out."""
    m = _Mapper(placement)
    segments: list[PlacedMove] = []
    first, last = poly.segments[0], poly.segments[-1]
    if placement.lead_in_mm > 0.0:
        segments.append(_extension(m, np.asarray(first.start, float), first.start_heading, placement.lead_in_mm, "lead_in"))
    for seg in poly.segments:
        if isinstance(seg, Line):
            if seg.length > 0.0:
                h = seg.start_heading
                segments.append(placed_line(m.pose(seg.start, h), m.pose(seg.end, h)))
            continue
        segments.append(_placed_arc(m, seg, placement.follow_tangent))
    if placement.lead_out_mm > 0.0:
        segments.append(_extension(m, np.asarray(last.end, float), last.end_heading, placement.lead_out_mm, "lead_out"))
    return PlacedPath(
        segments=tuple(segments),
        normal=m.normal,
        standoff_mm=placement.standoff_mm,
        lead_in_mm=placement.lead_in_mm,
        lead_out_mm=placement.lead_out_mm,
        curve_length_mm=poly.length,
    )


def polyline_polysegment(points: np.ndarray, closed: bool) -> Polysegment:
    """The polysegment of straight lines through ``points`` (n, 2), zero-length steps dropped;
    for a closed polyline the last point is joined back to the first if it is not already."""
    pts = np.asarray(points, dtype=float)
    if closed and len(pts) > 2 and not np.array_equal(pts[0], pts[-1]):
        pts = np.vstack((pts, pts[:1]))
    lines = tuple(
        Line((float(a[0]), float(a[1])), (float(b[0]), float(b[1])))
        for a, b in zip(pts[:-1], pts[1:])
        if not np.array_equal(a, b)
    )
    if not lines:
        raise InputError("the polyline has no segment of non-zero length")
    return Polysegment(lines, closed=closed)

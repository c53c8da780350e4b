"""The lead-in before a pass and the lead-out after it: the pass's first or last line or arc
continued, the tool turning on at the rate it turns at that end, so that neither the path's
tangent nor the tool's turning rate changes where the gun's pass begins or ends.
"""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from coatsim.geometry.space.pose import Pose, exp_rotation, log_rotation
from coatsim.geometry.space.primitives import Arc3, Line3, rotate_about
from coatsim.path.placement import PlacedMove
from coatsim.path.roll import Oriented

MAX_LEAD_TURN_RAD = math.radians(120.0)  # a lead continuing a tighter circle is a tangent line
# What lies beyond a pass is not known: a lead turns the tool by no more than this. At the end of a
# pass inside a trough the tool centre point moves a few % of the spot's way while the axis turns
# with the surface: a 0.16 mm end piece turning 1.1° made a 15 mm lead-in turn the tool by 102°.
MAX_TOOL_TURN_RAD = math.radians(10.0)


def lead_move(o: Oriented, length: float, part: str, speed_mm_s: Optional[float]) -> PlacedMove:
    """A lead-in before the first piece or a lead-out after the last: the piece's own line or
    circle continued by ``length`` (a line along its tangent where the circle would turn more
    than ``MAX_LEAD_TURN_RAD``), the tool turning on at the rate it turns at that end, so that
    neither the path's tangent nor the tool's turning rate changes where the pass begins or ends,
    by ``MAX_TOOL_TURN_RAD`` at most (slower where that rate would turn it more)."""
    seg = o.geometry
    before = part == "lead_in"
    anchor = Pose(o.start, seg.start) if before else Pose(o.end, seg.end)
    if o.via is None:
        rate = log_rotation(o.start.T @ o.end) / seg.length
    else:
        rate = log_rotation(o.start.T @ o.via if before else o.via.T @ o.end) / (seg.length / 2)
    turn = float(np.linalg.norm(rate)) * length
    if turn > MAX_TOOL_TURN_RAD:
        rate = rate * (MAX_TOOL_TURN_RAD / turn)
    def turned(ds: float) -> np.ndarray:  # the rotation ds mm along the lead from the anchor, outward
        return anchor.rotation @ exp_rotation((-ds if before else ds) * rate)
    far = turned(length)
    circle = seg if isinstance(seg, Arc3) and length / seg.radius <= MAX_LEAD_TURN_RAD else None
    if circle is not None:
        sweep = length / circle.radius
        normal = circle.normal
        if before:  # the circle run backwards from the start: the arc from its far end to the start
            tip = circle.start + rotate_about(circle.start - circle.center, normal, np.array([-sweep]))[0]
            arc = Arc3(tip, circle.start, circle.center, normal, circle.radius, sweep)
        else:
            arc = Arc3(circle.end, circle.at_angles(np.array([circle.sweep + sweep]))[0], circle.center, normal,
                       circle.radius, sweep)
        mid = Pose(turned(length / 2), arc.via)
        ends = (Pose(far, arc.start), anchor) if before else (anchor, Pose(far, arc.end))
        return PlacedMove(arc, *ends, part, False, mid, speed_mm_s)
    t = seg.start_tangent if before else seg.end_tangent
    tip = anchor.translation_mm + (-length if before else length) * t
    ends = (Pose(far, tip), anchor) if before else (anchor, Pose(far, tip))
    return PlacedMove(Line3(ends[0].translation_mm, ends[1].translation_mm), *ends, part, speed_mm_s=speed_mm_s)

"""URScript writer: a ProgramPlan becomes a ``.script`` file, one function the controller runs.

Layout: header comments (the process record as ``# coatsim: …`` lines), ``def name():``, the
spray gun's TCP (``set_tcp``), the workpiece frame as a pose variable ``frame`` (each target is
``pose_trans(frame, p[…])``, as Polyscope writes waypoints relative to a feature), the gun closed,
and per path: ``movej`` above its start, ``movel`` down to the stand-off with ``r=0`` (at rest),
one ``movel`` per line and one ``movec`` (via, end; ``mode=0``) per arc piece of at most
``MAX_ARC_SWEEP_DEG``, ``movel`` back up; ``end``. Poses are metres (11 decimals: 1e-8 mm) and
rotation vectors (radians, 12 decimals); ``v`` the plan's speed in m/s (the joint move's ``v``
in rad/s the same number), ``a`` the controller's default accelerations. The blend radius ``r``
is the plan's accuracy, cut to ``BLEND_SHARE`` of each neighbouring move (RoboDK's UR post keeps
a blend within 40 % of the move, so that two blends never overlap: the controller skips a move
whose blends overlap), 0 at the end of a path and everywhere for an exact stop.

Gun timing (instructions run in order): ``set_standard_digital_out(gun, True)`` written before a
motion opens the gun as that motion starts: at rest before the first sprayed motion of a path, or
on the fly as the curve of a closed contour starts after its lead-in; it closes on the fly as the
lead-out starts, or at rest after the path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.languages.urscript.names import check_name, clean_comment
from coatsim.languages.urscript.values import PoseValue
from coatsim.path.placement import PlacedPath
from coatsim.path.plan import ProgramPlan
from coatsim.path.process_record import comment_lines

M_DECIMALS, RAD_DECIMALS = 11, 12
LINEAR_ACCEL_M_S2, JOINT_ACCEL_RAD_S2 = 1.2, 1.4  # the controller's defaults
BLEND_SHARE = 0.4
MAX_ARC_SWEEP_DEG = 170.0
MAX_COORDINATE_MM = 1e6
MAX_OUTPUT = 7  # standard digital outputs 0 to 7
INDENT = "  "


@dataclass(frozen=True)
class _Motion:
    """One motion of a path: ``via`` for an arc, ``end``, its length, the gun from its start."""

    via: Optional[Pose]
    end: Pose
    length: float
    sprayed: bool
    label: str


def _literal(pose: Pose) -> str:
    """``p[x, y, z, rx, ry, rz]`` of a pose (m, rad)."""
    v = PoseValue.of(pose)
    return "p[" + ", ".join([fmt_short(x, M_DECIMALS) for x in v[:3]] + [fmt_short(x, RAD_DECIMALS) for x in v[3:]]) \
        + "]"


def _pose_text(frame_inv: Pose, pose: Pose) -> str:
    return f"pose_trans(frame, {_literal(frame_inv @ pose)})"


def _motions(path: PlacedPath, spray_leads: bool) -> list[_Motion]:
    counters = {"lead_in": 0, "curve": 0, "lead_out": 0}
    out = []
    for seg in path.segments:
        counters[seg.part] += 1
        label = seg.part.replace("_", "-") if seg.part != "curve" else f"segment {counters['curve']}"
        sprayed = spray_leads or seg.part == "curve"
        pieces = seg.split(math.radians(MAX_ARC_SWEEP_DEG)) if seg.is_arc else (seg,)
        for k, piece in enumerate(pieces):
            via = piece.via if piece.is_arc else None
            if via is not None:
                try:
                    arc_through(piece.start.translation_mm, via.translation_mm, piece.end.translation_mm)
                except DegenerateArc:
                    via = None  # too flat to define a circle: a line
            out.append(_Motion(via, piece.end, piece.length, sprayed, label if k == 0 else ""))
    return out


def _path_lines(path: PlacedPath, spray_leads: bool, plan: ProgramPlan, frame_inv: Pose, speed: str) -> list[str]:
    motions = _motions(path, spray_leads)
    out, gun_on = [], False
    accel = fmt_short(LINEAR_ACCEL_M_S2)
    for k, motion in enumerate(motions):
        if motion.sprayed != gun_on:
            state = "True" if motion.sprayed else "False"
            out.append(f"set_standard_digital_out({plan.gun_signal}, {state})  # gun {'on' if motion.sprayed else 'off'}")
            gun_on = motion.sprayed
        last = k == len(motions) - 1
        r = 0.0 if plan.exact_stop or last else min(plan.accuracy_mm, BLEND_SHARE * motion.length,
                                                    BLEND_SHARE * motions[k + 1].length)
        tail = f"a={accel}, v={speed}, r={fmt_short(r / 1000.0, M_DECIMALS)}"
        comment = f"  # {motion.label}" if motion.label else ""
        if motion.via is not None:
            out.append(f"movec({_pose_text(frame_inv, motion.via)}, {_pose_text(frame_inv, motion.end)}, {tail}, "
                       f"mode=0){comment}")
        else:
            out.append(f"movel({_pose_text(frame_inv, motion.end)}, {tail}){comment}")
    if gun_on:
        out.append(f"set_standard_digital_out({plan.gun_signal}, False)  # gun off")
    return out


def write_urscript(plan: ProgramPlan) -> str:
    """The complete script of ``plan`` (ASCII, '\\n' line ends); InputError for an invalid name or a
    gun output the controller does not have."""
    check_name(plan.name)
    if not 0 <= plan.gun_signal <= MAX_OUTPUT:
        raise InputError(f"gun_signal {plan.gun_signal}: a UR controller has standard digital outputs 0 to "
                         f"{MAX_OUTPUT}", parameters=("gun_signal",))
    frame = plan.user_frame
    frame_inv = frame.inverse()
    speed = fmt_short(plan.speed_mm_s / 1000.0, M_DECIMALS)
    head = [f"# {clean_comment(text)}" for text in plan.comments]
    head += [f"# {clean_comment(text)}" for text in comment_lines(plan.process)]
    body = [f"set_tcp({_literal(plan.tool)})  # spray gun TCP on the flange (m, rad)",
            f"frame = {_literal(frame)}  # workpiece frame in the base",
            f"set_standard_digital_out({plan.gun_signal}, False)  # gun off"]
    for index, (path, spray_leads) in enumerate(plan.legs):
        above = [Pose(p.rotation, p.translation_mm - mm * p.rotation[:, 2])
                 for p, mm in ((path.start, plan.approach_of(path)), (path.end, plan.depart_of(path)))]
        which = f" of contour {index + 1}" if len(plan.paths) > 1 else ""
        if index == 0:
            body.append(f"movej({_pose_text(frame_inv, above[0])}, a={fmt_short(JOINT_ACCEL_RAD_S2)}, v={speed})"
                        f"  # above the start{which}")
        else:
            body.append(f"movel({_pose_text(frame_inv, above[0])}, a={fmt_short(LINEAR_ACCEL_M_S2)}, v={speed}, r=0)"
                        f"  # gun off: travel above the start{which}")
        body.append(f"movel({_pose_text(frame_inv, path.start)}, a={fmt_short(LINEAR_ACCEL_M_S2)}, v={speed}, r=0)"
                    "  # down to the stand-off")
        body += _path_lines(path, spray_leads, plan, frame_inv, speed)
        body.append(f"movel({_pose_text(frame_inv, above[1])}, a={fmt_short(LINEAR_ACCEL_M_S2)}, v={speed}, r=0)"
                    "  # back along the tool axis")
    lines = head + [f"def {plan.name}():"] + [INDENT + line for line in body] + ["end"]
    return "\n".join(lines) + "\n"


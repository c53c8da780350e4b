"""RAPID writer: a ProgramPlan becomes one module (``.mod``) a RobotStudio user would load.

Layout: ``MODULE name``; header comments and the process record (``! coatsim: key=value``);
the gun as ``PERS tooldata``, the workpiece frame as ``PERS wobjdata`` (poses are written in it:
the coordinates a person reads on the part), ``CONST speeddata`` and, when blending, a
``CONST zonedata`` whose ``pzone_tcp`` is the plan's accuracy; every pose a ``CONST robtarget``
(quaternion with q1 >= 0, configuration 0 with ``ConfL \\Off``, external axes unused 9E+09);
then ``PROC main()``: a joint approach above the start (``RelTool`` back along the tool axis),
down to the stand-off (a stop point), per path ``MoveL`` per line and ``MoveC`` (circle point at
the arc's middle) per arc piece of at most ``max_arc_sweep_deg``, a linear depart. The gun:
``SetDO doN, 1`` before the first sprayed move — after a stop point at rest, after a fly-by point
in its corner zone, as that move starts — and ``SetDO doN, 0`` likewise; polyline-stop moves
end at ``fine`` points throughout.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.numbers import MM_DECIMALS, fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.geometry.space.rotations import matrix_to_quaternion
from coatsim.languages.abb_rapid.names import check_name
from coatsim.languages.script.header import header_comments
from coatsim.languages.script.names import sanitize_comment
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.plan import ProgramPlan

MAX_ARC_SWEEP_DEG = 170.0  # one MoveC: the circle point well inside the arc
MAX_COORDINATE_MM = 1e6  # RAPID num is a 32-bit float: exact to ~1e-4 mm up to a metre
QUATERNION_DECIMALS = 10
INDENT = "  "
TOOL, WOBJ, SPEED, ZONE = "tCoatGun", "wCoatPart", "vCoat", "zCoat"


def _num(value: float) -> str:
    return fmt_short(value, MM_DECIMALS)


def pose_text(pose: Pose) -> str:
    """``[[x,y,z],[q1,q2,q3,q4]]`` of a pose."""
    q = matrix_to_quaternion(pose.rotation)
    return (f"[[{','.join(_num(v) for v in pose.translation_mm)}],"
            f"[{','.join(fmt_short(v, QUATERNION_DECIMALS) for v in q)}]]")


def robtarget_text(pose: Pose) -> str:
    return f"[{pose_text(pose)[1:-1]},[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]]"


class _Body:
    """The statements of PROC main with their trailing comments; the poses they name."""

    def __init__(self, frame: Pose, blend: str) -> None:
        self.lines: list[str] = []
        self.poses: list[Pose] = []
        self.inverse = frame.inverse()
        self.blend = blend

    def name(self, pose: Pose) -> str:
        self.poses.append(self.inverse @ pose)
        return f"p{len(self.poses) - 1:04d}"

    def add(self, statement: str, comment: str = "") -> None:
        text = 2 * INDENT + statement
        self.lines.append(f"{text.ljust(60)} ! {sanitize_comment(comment)}" if comment else text)

    def move(self, kind: str, target: str, stop: bool, comment: str = "") -> None:
        zone = "fine" if stop else self.blend
        self.add(f"{kind} {target}, {SPEED}, {zone}, {TOOL}\\WObj:={WOBJ};", comment)


def _writable(start: Pose, via: Pose, end: Pose) -> bool:
    points = [np.array([float(_num(v)) for v in p.translation_mm]) for p in (start, via, end)]
    try:
        arc_through(*points)
    except DegenerateArc:
        return False
    return True


def _labels(segments) -> list[str]:
    count = 0
    out = []
    for seg in segments:
        count += seg.part == "curve"
        out.append(f"segment {count}" if seg.part == "curve" else seg.part.replace("_", "-"))
    return out


def _segment(body: _Body, seg: PlacedMove, label: str, stop: bool, max_sweep: float) -> list[Callable[[bool], None]]:
    """The moves of one segment as callables taking whether the move ends at a stop point."""
    if not seg.is_arc:
        return [lambda last, e=seg.end: body.move("MoveL", body.name(e), last or stop, label)]
    pieces = seg.split(math.radians(max_sweep))
    out = []
    for k, piece in enumerate(pieces):
        tag = label if len(pieces) == 1 else f"{label} ({k + 1}/{len(pieces)})"
        if _writable(piece.start, piece.via, piece.end):
            out.append(lambda last, p=piece, t=tag: body.move("MoveC", f"{body.name(p.via)}, {body.name(p.end)}",
                                                              last or stop, t))
        else:
            out.append(lambda last, p=piece, t=tag: body.move("MoveL", body.name(p.end), last or stop,
                                                              f"{t}, arc flatter than the pose resolution"))
    return out


def _path(body: _Body, path: PlacedPath, spray_leads: bool, gun: str, stop: bool, max_sweep: float) -> None:
    """The moves of one sprayed path and the gun's switches along it."""
    moves: list[tuple[bool, Callable[[bool], None]]] = []
    for seg, label in zip(path.segments, _labels(path.segments)):
        sprayed = spray_leads or seg.part == "curve"
        moves += [(sprayed, m) for m in _segment(body, seg, label, stop, max_sweep)]
    gun_on = False
    for k, (sprayed, move) in enumerate(moves):
        if sprayed != gun_on:
            at_rest = k == 0
            body.add(f"SetDO {gun}, {1 if sprayed else 0};",
                     f"gun {'on' if sprayed else 'off'}" + ("" if at_rest else " as the next move starts (on the fly)"))
            gun_on = sprayed
        move(k == len(moves) - 1)
    if gun_on:
        body.add(f"SetDO {gun}, 0;", "gun off, at rest")


def write_rapid(plan: ProgramPlan, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> str:
    """The complete module text of ``plan`` (ASCII, '\\n' line ends); InputError if the program
    name is not a valid RAPID name."""
    check_name(plan.name)
    frame = plan.user_frame
    blend = ZONE if plan.accuracy_mm > 0 else "z0"
    body = _Body(frame, "fine" if plan.exact_stop else blend)
    gun = f"do{plan.gun_signal}"
    body.add("ConfL\\Off;", "no configuration check on the linear moves")
    for index, (path, spray_leads) in enumerate(plan.legs):
        which = f" of contour {index + 1}" if len(plan.paths) > 1 else ""
        start = body.name(path.start)
        kind = "MoveJ" if index == 0 else "MoveL"
        body.move(kind, f"RelTool({start},0,0,{_num(-plan.approach_of(path))})", False, f"above the start{which}" +
                  ("" if index == 0 else ", gun off"))
        body.move("MoveL", start, True, "down to the stand-off")
        _path(body, path, spray_leads, gun, plan.exact_stop, max_arc_sweep_deg)
        body.move("MoveL", f"RelTool({body.name(path.segments[-1].end)},0,0,{_num(-plan.depart_of(path))})",
                  index == len(plan.paths) - 1,
                  "back along the tool axis")
    lines = [f"MODULE {plan.name}"]
    lines += header_comments(plan, f"{INDENT}! ")
    tool = plan.tool
    lines.append(f"{INDENT}PERS tooldata {TOOL} := [TRUE,{pose_text(tool)},[1,[0,0,1],[1,0,0,0],0,0,0]];")
    lines.append(f'{INDENT}PERS wobjdata {WOBJ} := [FALSE,TRUE,"",{pose_text(frame)},[[0,0,0],[1,0,0,0]]];')
    lines.append(f"{INDENT}CONST speeddata {SPEED} := [{_num(plan.speed_mm_s)},500,5000,1000];")
    a = plan.accuracy_mm
    if a > 0:
        lines.append(f"{INDENT}CONST zonedata {ZONE} := [FALSE,{_num(a)},{_num(1.5 * a)},{_num(1.5 * a)},"
                     f"{_num(0.15 * a)},{_num(1.5 * a)},{_num(0.15 * a)}];")
    lines += [f"{INDENT}CONST robtarget p{k:04d} := {robtarget_text(p)};" for k, p in enumerate(body.poses)]
    lines += ["", f"{INDENT}PROC main()", *body.lines, f"{INDENT}ENDPROC", "ENDMODULE"]
    return "\n".join(lines) + "\n"

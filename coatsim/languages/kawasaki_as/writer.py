"""Kawasaki AS writer: a ProgramPlan becomes a complete, loadable .as file.

Layout: ``.PROGRAM name()`` with header comments, BASE/TOOL/SPEED/ACCURACY/CP set explicitly,
then per path of the plan in turn: a joint approach above the
start, a linear move down to the stand-off and ``BREAK`` (at rest at the start of the lead-in),
one LMOVE per line and one C1MOVE (arc middle) + C2MOVE (arc end) pair per arc, ``BREAK``, a
linear depart; ``.END``, then every pose in a ``.TRANS`` section. Only straight-line code
between the first and last sprayed move: loops and calls there make a Kawasaki controller slow
down.

Gun timing (AS forward processing, as the interpreter models it): a ``SIGNAL`` written after a
motion, with no ``BREAK`` in between, switches as that motion starts. So:
- the gun opens with the first sprayed move: ``BREAK`` + ``SIGNAL gun`` before it when it is
  the first move of the path (at rest), otherwise ``SIGNAL gun`` right after it (on the fly:
  at the seam of a closed contour, at full speed after the lead-in);
- it closes with the first move after the sprayed ones: ``SIGNAL -gun`` right after that move
  (on the fly: as the lead-out starts, after exactly one lap), or ``BREAK`` + ``SIGNAL -gun``
  at rest after the last move when the path is sprayed to its end.
"""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.numbers import MM_DECIMALS, fmt, fmt_short
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.path.process_record import encode as encode_header
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH, check_name, sanitize_comment
from coatsim.path.plan import ProgramPlan
from coatsim.geometry.space.rotations import matrix_to_oat
from coatsim.geometry.space.xyzoat import xyzoat
from coatsim.path.placement import PlacedMove
from coatsim.geometry.space.pose import Pose

# 6 decimals in degrees round an angle by <= 5e-7 deg (9e-9 rad).
DEG_DECIMALS = 6
# Longest arc one C1MOVE/C2MOVE pair may sweep; a pair cannot describe 180 deg or more reliably.
MAX_ARC_SWEEP_DEG = 170.0
# Largest coordinate a written program holds (1e9 mm is beyond any cell).
MAX_COORDINATE_MM = 1e9
INDENT = "  "
_COMMENT_COLUMN = 30


def pose_values(pose: Pose) -> tuple[str, ...]:
    """x y z (mm) o a t (deg) as the writer formats them."""
    o, a, t = matrix_to_oat(pose.rotation)
    return tuple(fmt(v, MM_DECIMALS) for v in pose.translation_mm) + tuple(fmt(v, DEG_DECIMALS) for v in (o, a, t))


def _trans_literal(frame: Pose) -> str:
    x, y, z, o, a, t = xyzoat(frame)
    mm = ",".join(fmt(v, MM_DECIMALS) for v in (x, y, z))
    deg = ",".join(fmt(v, DEG_DECIMALS) for v in (o, a, t))
    return f"TRANS({mm},{deg})"


class _Lines:
    """Program lines with aligned trailing comments."""

    def __init__(self) -> None:
        self.lines: list[str] = []

    def add(self, statement: str, comment: str = "") -> None:
        text = INDENT + statement
        if comment:
            text = f"{text.ljust(_COMMENT_COLUMN)} ; {comment}"
        self.lines.append(text)


def _arc_is_writable(start: Pose, via: Pose, end: Pose) -> bool:
    """Whether the circle through the poses as written (rounded) is defined."""
    rounded = [np.array([float(v) for v in pose_values(p)[:3]]) for p in (start, via, end)]
    try:
        arc_through(*rounded)
    except DegenerateArc:
        return False
    return True


def _segment_moves(seg: PlacedMove, label: str, name: Callable[[Pose], str],
                   max_arc_sweep_deg: float) -> list[tuple[str, str]]:
    """(statement, comment) of the motions of one segment: one LMOVE for a line; one C1MOVE +
    C2MOVE pair per arc piece of at most ``max_arc_sweep_deg`` (an LMOVE for a piece too flat to
    define a circle once written)."""
    if not seg.is_arc:
        return [(f"LMOVE {name(seg.end)}", label)]
    out: list[tuple[str, str]] = []
    pieces = seg.split(math.radians(max_arc_sweep_deg))
    for k, piece in enumerate(pieces):
        part_label = label if len(pieces) == 1 else f"{label} ({k + 1}/{len(pieces)})"
        if _arc_is_writable(piece.start, piece.via, piece.end):
            out.append((f"C1MOVE {name(piece.via)}", f"{part_label}, arc via"))
            out.append((f"C2MOVE {name(piece.end)}", "arc end"))
        else:
            out.append((f"LMOVE {name(piece.end)}", f"{part_label}, arc flatter than the pose resolution"))
    return out


def _labels(segments: Sequence[PlacedMove]) -> list[str]:
    """The comment naming each segment: lead-in, segment k, lead-out."""
    counters = {"lead_in": 0, "curve": 0, "lead_out": 0}
    labels = []
    for seg in segments:
        counters[seg.part] += 1
        labels.append(seg.part.replace("_", "-") if seg.part != "curve" else f"segment {counters['curve']}")
    return labels


def path_moves(segments: Sequence[PlacedMove], name: Callable[[Pose], str],
               max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> list[tuple[str, str]]:
    """(statement, comment) of each motion along ``segments``; ``name`` gives the text a pose is
    written as."""
    return [move for seg, label in zip(segments, _labels(segments))
            for move in _segment_moves(seg, label, name, max_arc_sweep_deg)]


def _path_lines(out: "_Lines", path, spray_leads: bool, gun: int, name, max_arc_sweep_deg: float,
               speed: list[float]) -> None:
    """The moves of one sprayed path and the gun signals along it: open along the whole path
    with ``spray_leads``, otherwise exactly along its curve part (switched on the fly). A move
    with its own speed gets a ``SPEED ... ALWAYS`` before it where the speed changes (``speed``
    holds the speed in force, one item)."""
    gun_on = False
    for index, (seg, label) in enumerate(zip(path.segments, _labels(path.segments))):
        if seg.speed_mm_s is not None and seg.speed_mm_s != speed[0]:
            speed[0] = seg.speed_mm_s
            out.add(f"SPEED {fmt_short(speed[0])} MM/S ALWAYS", "the speed of the moves below")
        sprayed = spray_leads or seg.part == "curve"
        if index == 0:
            out.add("BREAK", "at rest before the gun opens" if sprayed else "at rest at the start of the lead-in")
            if sprayed:
                out.add(f"SIGNAL {gun}", "gun on")
                gun_on = True
        moves = _segment_moves(seg, label, name, max_arc_sweep_deg)
        first = 1 if moves[0][0].startswith("LMOVE") else 2  # the segment's first motion (C1MOVE + C2MOVE)
        for move in moves[:first]:
            out.add(*move)
        if sprayed != gun_on:
            out.add(f"SIGNAL {gun if sprayed else -gun}", f"gun {'on' if sprayed else 'off'} as the move above starts (on the fly)")
            gun_on = sprayed
        for move in moves[first:]:
            out.add(*move)
    if gun_on:
        out.add("BREAK", "at rest before the gun closes")
        out.add(f"SIGNAL {-gun}", "gun off")
    else:
        out.add("BREAK", "at rest at the end of the path")


def write_as(plan: ProgramPlan, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> str:
    """The complete AS program text of ``plan`` (ASCII, '\\n' line ends); InputError if the
    program name is not a valid AS name."""
    check_name(plan.name)
    poses: list[Pose] = []

    def name(pose: Pose) -> str:
        poses.append(pose)
        return f"p{len(poses) - 1:0{width}d}"

    n_points = sum(1 + sum(2 * math.ceil(s.geometry.sweep / math.radians(max_arc_sweep_deg)) if s.is_arc else 1
                           for s in path.segments) for path in plan.paths)
    width = max(4, len(str(n_points)))
    if 1 + width > MAX_NAME_LENGTH:
        raise InputError(f"{n_points} poses do not fit {MAX_NAME_LENGTH}-character names; split the path")

    out = _Lines()
    for text in plan.comments:
        out.add(f"; {sanitize_comment(text)}")
    for key, value in encode_header(plan.process):
        out.add(f"; coatsim: {sanitize_comment(key)}={sanitize_comment(value, None)}")  # read back whole
    out.add("BASE NULL", "poses are in the robot base frame")
    out.add(f"TOOL {_trans_literal(plan.tool)}", "spray gun TCP")
    out.add(f"SPEED {fmt_short(plan.speed_mm_s)} MM/S ALWAYS")
    out.add(f"ACCURACY {fmt_short(plan.accuracy_mm)} ALWAYS")
    out.add("CP OFF" if plan.exact_stop else "CP ON", "stop at every point" if plan.exact_stop else "blend")
    speed = [plan.speed_mm_s]
    for index, (path, spray_leads) in enumerate(plan.legs):
        which = f" of contour {index + 1}" if len(plan.paths) > 1 else ""
        start = name(path.start)
        clearance = fmt_short(plan.approach_of(path))
        if speed[0] != plan.speed_mm_s:  # approach and travel at the plan's speed
            speed[0] = plan.speed_mm_s
            out.add(f"SPEED {fmt_short(speed[0])} MM/S ALWAYS")
        if index == 0:
            out.add(f"JAPPRO {start}, {clearance}", f"above the start{which}")
        else:  # the next contour of a part: straight travel at the clearance, gun off
            out.add(f"LAPPRO {start}, {clearance}", f"gun off: travel above the start{which}")
        out.add(f"LMOVE {start}", "down to the stand-off")
        _path_lines(out, path, spray_leads, plan.gun_signal, name, max_arc_sweep_deg, speed)
        out.add(f"LDEPART {fmt_short(plan.depart_of(path))}", "back along the tool axis")

    lines = [f".PROGRAM {plan.name}()", *out.lines, ".END", ".TRANS"]
    for k, pose in enumerate(poses):
        lines.append(" ".join((f"p{k:0{width}d}", *pose_values(pose))))
    lines.append(".END")
    return "\n".join(lines) + "\n"

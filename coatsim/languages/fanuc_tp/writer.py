"""Fanuc TP writer: a ProgramPlan becomes an .LS file (MakeTP's ASCII form of a TP program).

Layout: ``/PROG``, ``/ATTR`` (fixed dates: the output is deterministic), ``/MN``, ``/POS``, ``/END``.
``/MN`` holds the header remarks (the process record as ``!coatsim: …`` remarks of at most
32 characters, continued where longer), then sets the spray gun's TCP as tool frame
``TOOL_NUMBER`` and the workpiece frame as user frame ``FRAME_NUMBER`` through the spare position
register ``SPARE_PR`` (``PR[i,j]=value``, ``UTOOL[i]=PR[i]``: RoboDK's Fanuc post does the same,
with the same numbers), selects them, closes the gun, and per path: a joint motion above its
start (``%`` of ``FULL_SPEED_MM_S``), a linear motion down to the stand-off ending ``FINE`` (at
rest), one ``L`` per line and one ``C`` (via, end) per arc piece of at most ``MAX_ARC_SWEEP_DEG``
(an arc too flat for the 3 decimals written is an ``L``), ``CNT n`` for the plan's accuracy at its
speed (:mod:`.blend`) or ``FINE`` for an exact stop, ``FINE`` at the end of the path, a linear
motion back up. Positions (``/POS``) are in that user frame and tool, X-Y-Z-W-P-R with 3
decimals, configuration ``'N U T, 0, 0, 0'`` (the twin does not read it; a controller picks the
nearest solution of that configuration).

Gun timing (instructions run in order, :mod:`.interpreter`): ``DO[gun]=ON`` written before a
motion opens the gun as that motion starts. So it opens at rest before the first sprayed motion of
a path, or on the fly as the curve of a closed contour starts after the lead-in; it closes on the
fly as the lead-out starts, or at rest after the path.
"""

from __future__ import annotations

import math
import textwrap
from typing import Callable

import numpy as np

from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.languages.fanuc_tp.blend import DECEL_MM_S2, cnt_for
from coatsim.languages.fanuc_tp.motion import FULL_SPEED_MM_S
from coatsim.languages.fanuc_tp.names import REMARK_WIDTH, check_name, clean_remark
from coatsim.languages.fanuc_tp.positions import DECIMALS, format_position, values_of
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.plan import ProgramPlan
from coatsim.path.process_record import comment_lines

TOOL_NUMBER, FRAME_NUMBER, SPARE_PR = 9, 9, 9
MAX_ARC_SWEEP_DEG = 170.0
MAX_COORDINATE_MM = 99999.999  # the largest value the position data's format holds
_FLAT_SAGITTA_MM = 10 * 10.0 ** -DECIMALS  # an arc bulging less than ten resolutions is written as an L


class _Program:
    """The ``/MN`` instructions and the ``/POS`` positions of the program being written."""

    def __init__(self, frame: Pose) -> None:
        self.frame_inv = frame.inverse()
        self.lines: list[str] = []
        self.count = 0  # instructions (a circular motion takes two lines)
        self.positions: list[Pose] = []

    def add(self, text: str, motion: str = " ") -> None:
        self.count += 1
        self.lines.append(f"{self.count:4d}:{motion} {text} ;")

    def remark(self, text: str) -> None:
        self.add(f"!{clean_remark(text)}")

    def point(self, pose: Pose) -> str:
        """``P[i]`` of a new position at ``pose`` (base frame)."""
        self.positions.append(self.frame_inv @ pose)
        return f"P[{len(self.positions)}]"

    def circular(self, via: Pose, end: Pose, tail: str) -> None:
        self.count += 1
        self.lines.append(f"{self.count:4d}:C {self.point(via)} ")
        self.lines.append(f"    :  {self.point(end)} {tail} ;")

    def set_frame(self, kind: str, number: int, pose: Pose) -> None:
        for j, value in enumerate(values_of(pose), start=1):
            self.add(f"PR[{SPARE_PR},{j}]={fmt_short(value, DECIMALS)}")
        self.add(f"{kind}[{number}]=PR[{SPARE_PR}]")


def _rounded(pose: Pose) -> np.ndarray:
    return np.round(pose.translation_mm, DECIMALS)


def _writable_arc(piece: PlacedMove) -> bool:
    arc = piece.geometry
    if arc.radius * (1.0 - math.cos(min(arc.sweep, math.pi) / 2.0)) < _FLAT_SAGITTA_MM:
        return False
    try:
        arc_through(_rounded(piece.start), _rounded(piece.via), _rounded(piece.end))
    except DegenerateArc:
        return False
    return True


def _labels(path: PlacedPath) -> list[str]:
    counters = {"lead_in": 0, "curve": 0, "lead_out": 0}
    out = []
    for seg in path.segments:
        counters[seg.part] += 1
        out.append(seg.part.replace("_", "-") if seg.part != "curve" else f"segment {counters['curve']}")
    return out


def _segment(out: _Program, seg: PlacedMove, label: str, tail: Callable[[bool], str]) -> None:
    """The motions of one placed move; ``tail(last)`` the speed and termination of a motion."""
    if seg.is_arc:
        pieces = seg.split(math.radians(MAX_ARC_SWEEP_DEG))
        for k, piece in enumerate(pieces):
            last = k == len(pieces) - 1
            if _writable_arc(piece):
                out.circular(piece.via, piece.end, tail(last))
            else:
                out.add(f"{out.point(piece.end)} {tail(last)}", "L")
        return
    out.add(f"{out.point(seg.end)} {tail(True)}", "L")


def _path(out: _Program, path: PlacedPath, spray_leads: bool, gun: int, speed: str, term: str) -> None:
    gun_on = False
    segments = list(zip(path.segments, _labels(path)))
    for index, (seg, label) in enumerate(segments):
        sprayed = spray_leads or seg.part == "curve"
        if sprayed != gun_on:
            out.add(f"DO[{gun}]={'ON' if sprayed else 'OFF'}")
            gun_on = sprayed
        out.remark(label)
        end_of_path = index == len(segments) - 1
        _segment(out, seg, label, lambda last: f"{speed} {'FINE' if end_of_path and last else term}")
    if gun_on:
        out.add(f"DO[{gun}]=OFF")


def write_ls(plan: ProgramPlan, decel_mm_s2: float = DECEL_MM_S2) -> str:
    """The complete .LS text of ``plan`` (ASCII, '\\n' line ends); InputError for an invalid name."""
    check_name(plan.name)
    frame = plan.user_frame
    out = _Program(frame)
    for text in plan.comments:
        for piece in textwrap.wrap(clean_remark(text), REMARK_WIDTH):
            out.remark(piece)
    for text in comment_lines(plan.process, REMARK_WIDTH, clean_remark):
        out.remark(text)
    out.remark("spray gun TCP, workpiece frame")
    out.set_frame("UTOOL", TOOL_NUMBER, plan.tool)
    out.set_frame("UFRAME", FRAME_NUMBER, frame)
    out.add(f"UFRAME_NUM={FRAME_NUMBER}")
    out.add(f"UTOOL_NUM={TOOL_NUMBER}")
    out.add(f"DO[{plan.gun_signal}]=OFF")
    speed = f"{max(1, round(plan.speed_mm_s))}mm/sec"
    percent = min(100, max(1, round(100.0 * plan.speed_mm_s / FULL_SPEED_MM_S)))
    term = "FINE" if plan.exact_stop else f"CNT{cnt_for(plan.accuracy_mm, plan.speed_mm_s, decel_mm_s2)}"
    for index, (path, spray_leads) in enumerate(plan.legs):
        above = [Pose(p.rotation, p.translation_mm - mm * p.rotation[:, 2])
                 for p, mm in ((path.start, plan.approach_of(path)), (path.end, plan.depart_of(path)))]
        out.remark(f"contour {index + 1}" if len(plan.paths) > 1 else "approach")
        if index == 0:
            out.add(f"{out.point(above[0])} {percent}% FINE", "J")
        else:
            out.add(f"{out.point(above[0])} {speed} FINE", "L")
        out.add(f"{out.point(path.start)} {speed} FINE", "L")
        _path(out, path, spray_leads, plan.gun_signal, speed, term)
        out.add(f"{out.point(above[1])} {speed} FINE", "L")
    head = [f"/PROG  {plan.name}", "/ATTR", "OWNER\t\t= MNEDITOR;", 'COMMENT\t\t= "coatsim";', "PROG_SIZE\t= 0;",
            "CREATE\t\t= DATE 00-01-01  TIME 00:00:00;", "MODIFIED\t= DATE 00-01-01  TIME 00:00:00;",
            "FILE_NAME\t= ;", "VERSION\t\t= 0;", f"LINE_COUNT\t= {out.count};",
            "MEMORY_SIZE\t= 0;", "PROTECT\t\t= READ_WRITE;", "TCD:  STACK_SIZE\t= 0,", "      TASK_PRIORITY\t= 50,",
            "      TIME_SLICE\t= 0,", "      BUSY_LAMP_OFF\t= 0,", "      ABORT_REQUEST\t= 0,",
            "      PAUSE_REQUEST\t= 0;", "DEFAULT_GROUP\t= 1,*,*,*,*;", "CONTROL_CODE\t= 00000000 00000000;", "/MN"]
    pos = [line for k, pose in enumerate(out.positions, start=1)
           for line in format_position(k, pose, FRAME_NUMBER, TOOL_NUMBER)]
    return "\n".join(head + out.lines + ["/POS"] + pos + ["/END"]) + "\n"

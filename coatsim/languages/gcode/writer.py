"""G-code writer: a ProgramPlan becomes a program for a control that reads RS274/NGC.

Layout: ``%``, the program name and header comments (the process record as ``(coatsim: ...)``
lines, units, tool axis, gun codes), ``G21 G90 G94 G17 G40 G49 G80``, the work frame as the G54
work offset (``G10 L2 P1 X Y Z [R]``, then ``G54``), the path control (``G61`` exact stop for a
plan that stops at every point, else ``G64 P`` the plan's accuracy), the gun closed; per path: a
rapid ``G0`` above its start, a ``G1`` down to the stand-off, ``G4 P0`` (at rest), its moves, a
``G1`` back up; ``M2``, ``%``.

Coordinates are the work frame's (the plan's workpiece frame when its normal is the base's +Z,
else the base frame), mm with 4 decimals (a Fanuc-style control's least increment of 0.0001 mm,
at most 8 digits a word: |x| < 10 000 mm). The gun must point along −Z of that frame: G-code has
no tool orientation, so a tilted gun is refused; the gun's turn about its own axis (a roll or a
tool that follows the path) is not written, the reader gives it the work frame's. An arc in
G17/G18/G19 is one ``G2``/``G3`` with ``I J K`` per half turn at most; an arc in any other plane
becomes lines within ``CHORD_TOL_MM`` (a comment says so, and that a curve segmented with
``arc_planes="principal"`` has no such arc); an arc too flat for the resolution
becomes its chord.

Gun timing (the blocks run in order, :mod:`.interpreter`): a gun code written between two moves
switches as the second starts. So the gun opens at rest before the first sprayed move of a path
(``G4 P0`` then the on code) or, on a closed contour, on the fly as the curve starts after the
lead-in; it closes on the fly as the lead-out starts, or at rest after the path.
"""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import rot_z
from coatsim.languages.gcode.arcs import arc_words
from coatsim.languages.gcode.gun import GunCodes
from coatsim.languages.gcode.names import check_name, clean_comment
from coatsim.path.language import UNTILTED_TOL_RAD
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.plan import ProgramPlan
from coatsim.path.process_record import comment_lines

DECIMALS = 4
MAX_COORDINATE_MM = 9999.9999
MAX_ARC_SWEEP_DEG = 180.0
CHORD_TOL_MM = 0.01
COMMENT_WIDTH = 72
_FLAT_SAGITTA_MM = 10 * 10.0 ** -DECIMALS  # an arc bulging less than ten resolutions is written as its chord
_AXIS_TOL_RAD = 1e-6  # the gun's axis this far from −Z of the work frame is a tilt G-code cannot write


def num(value: float) -> str:
    return fmt_short(value, DECIMALS)


def program_frame(plan: ProgramPlan) -> Pose:
    """The work frame of the program: the plan's workpiece frame turned about the base's Z only
    (its normal the base's +Z), else the base frame."""
    frame = plan.user_frame
    if abs(float(frame.rotation[2, 2]) - 1.0) > 1e-12:
        return Pose.identity()
    heading = math.atan2(float(frame.rotation[1, 0]), float(frame.rotation[0, 0]))
    return Pose(rot_z(heading), frame.translation_mm)


def _check_axis(plan: ProgramPlan, frame: Pose) -> None:
    down = frame.rotation @ np.array([0.0, 0.0, -1.0])
    for p_index, path in enumerate(plan.paths):
        for s_index, seg in enumerate(path.segments):
            for pose in (seg.start, seg.end):
                tilt = math.acos(float(np.clip(pose.rotation[:, 2] @ down, -1.0, 1.0)))
                if tilt > UNTILTED_TOL_RAD:
                    raise InputError(
                        f"{plan.name}: G-code has no tool orientation, the gun points along -Z of the work frame; "
                        f"path {p_index + 1}, segment {s_index + 1} tilts it by {math.degrees(tilt):.3g} deg: write "
                        "this plan in a language with tool orientation (any other language)")


class _Program:
    """Blocks with the modal state they leave: position, plane, feed written."""

    def __init__(self, frame: Pose, feed: str) -> None:
        self.frame_inv, self.feed = frame.inverse(), feed
        self.lines: list[str] = []
        self.at: list[Optional[str]] = [None, None, None]
        self.plane = 17
        self.feed_written = False

    def add(self, text: str, comment: str = "") -> None:
        self.lines.append(f"{text} ({clean_comment(comment)})" if comment else text)

    def local(self, point: np.ndarray) -> np.ndarray:
        return self.frame_inv.apply(point)

    def axes(self, point: np.ndarray) -> str:
        """The axis words of a move to ``point`` (base frame), those that change."""
        words = []
        for k, axis in enumerate("XYZ"):
            text = num(float(self.local(point)[k]))
            if text != self.at[k]:
                words.append(f"{axis}{text}")
                self.at[k] = text
        return " ".join(words)

    def move(self, code: str, point: np.ndarray, extra: str = "", comment: str = "") -> None:
        words = " ".join(w for w in (code, self.axes(point), extra) if w)
        if code != "G0" and not self.feed_written:
            words += f" F{self.feed}"
            self.feed_written = True
        self.add(words, comment)

    def segment(self, seg: PlacedMove, label: str) -> None:
        """The blocks of one placed move."""
        if not seg.is_arc:
            self.move("G1", seg.geometry.end, comment=label)
            return
        pieces = seg.split(math.radians(MAX_ARC_SWEEP_DEG))
        for k, piece in enumerate(pieces):
            arc = piece.geometry
            local = arc.transformed(self.frame_inv)
            words = arc_words(local)
            note = label if k == 0 else ""
            if words is None:
                self.chords(piece, note)
            elif arc.radius * (1 - math.cos(min(arc.sweep, math.pi) / 2)) < _FLAT_SAGITTA_MM or \
                    float(np.abs(words.offsets).max()) > MAX_COORDINATE_MM:
                self.move("G1", arc.end, comment=f"{note}, arc flatter than the resolution".lstrip(", "))
            else:
                letters = [("IJK"[i], words.offsets[i]) for i in range(3) if i != {17: 2, 18: 1, 19: 0}[words.plane]]
                plane = f"G{words.plane} " if words.plane != self.plane else ""
                self.plane = words.plane
                code = f"{plane}G{2 if words.clockwise else 3}"
                self.move(code, arc.end, " ".join(f"{a}{num(float(v))}" for a, v in letters), note)

    def chords(self, piece: PlacedMove, label: str) -> None:
        arc = piece.geometry
        step = 2.0 * math.acos(max(1.0 - CHORD_TOL_MM / arc.radius, -1.0))
        n = max(1, math.ceil(arc.sweep / step))
        points = arc.at_angles(np.arange(1, n + 1) * (arc.sweep / n))
        points[-1] = arc.end
        for k, point in enumerate(points):
            self.move("G1", point, comment=f"{label}: arc outside G17/G18/G19 as {n} lines within "
                      f"{CHORD_TOL_MM:g} mm; a 3-D curve segmented with arc_planes principal has none"
                      if k == 0 else "")


def _labels(path: PlacedPath) -> list[str]:
    counters = {"lead_in": 0, "curve": 0, "lead_out": 0}
    out = []
    for seg in path.segments:
        counters[seg.part] += 1
        out.append(seg.part.replace("_", "-") if seg.part != "curve" else f"segment {counters['curve']}")
    return out


def _path(out: _Program, path: PlacedPath, spray_leads: bool, gun: GunCodes, depart: np.ndarray) -> None:
    """The moves of one sprayed path and the gun codes along it, then up to ``depart``."""
    out.move("G1", path.start.translation_mm, comment="down to the stand-off")
    gun_on = False
    for index, (seg, label) in enumerate(zip(path.segments, _labels(path))):
        sprayed = spray_leads or seg.part == "curve"
        if index == 0:
            out.add("G4 P0", "at rest before the gun opens" if sprayed else "at rest at the start of the lead-in")
            if sprayed:
                out.add(f"M{gun.on}", "gun on")
                gun_on = True
        elif sprayed != gun_on:
            out.add(f"M{gun.on if sprayed else gun.off}", f"gun {'on' if sprayed else 'off'} as the next move starts")
            gun_on = sprayed
        out.segment(seg, label)
    out.add("G4 P0", "at rest before the gun closes" if gun_on else "at rest at the end of the path")
    if gun_on:
        out.add(f"M{gun.off}", "gun off")
    out.move("G1", depart, comment="back along the tool axis")


def write_gcode(plan: ProgramPlan, gun: GunCodes) -> str:
    """The complete G-code program of ``plan`` (ASCII, '\\n' line ends); InputError if the name is
    not a valid program name, the gun tilts, or a coordinate is out of range."""
    check_name(plan.name)
    frame = program_frame(plan)
    _check_axis(plan, frame)
    up = frame.rotation @ np.array([0.0, 0.0, 1.0])
    above = lambda pose, mm: pose.translation_mm + mm * up  # noqa: E731
    out = _Program(frame, fmt_short(plan.speed_mm_s * 60.0, 3))
    out.add("%")
    out.add(f"({plan.name})")
    for text in plan.comments:
        out.add(f"({clean_comment(text)})")
    for text in comment_lines(plan.process, COMMENT_WIDTH, clean_comment):
        out.add(f"({text})")
    out.add(f"(units mm, feed mm/min; the gun points along -Z of the work frame; gun on M{gun.on}, off M{gun.off})")
    out.add("G21 G90 G94 G17 G40 G49 G80")
    x, y, z = (num(float(v)) for v in frame.translation_mm)
    turn = math.degrees(math.atan2(float(frame.rotation[1, 0]), float(frame.rotation[0, 0])))
    rotation = f" R{fmt_short(turn, 6)}" if fmt_short(turn, 6) != "0" else ""
    out.add(f"G10 L2 P1 X{x} Y{y} Z{z}{rotation}", "work offset G54: the workpiece frame")
    out.add("G54")
    out.add("G61" if plan.exact_stop else f"G64 P{num(plan.accuracy_mm)}",
            "exact stop at every point" if plan.exact_stop else "blend within the accuracy")
    out.add(f"M{gun.off}", "gun off")
    for index, (path, spray_leads) in enumerate(plan.legs):
        which = f" of contour {index + 1}" if len(plan.paths) > 1 else ""
        out.move("G0", above(path.start, plan.approach_of(path)), comment=f"above the start{which}")
        _path(out, path, spray_leads, gun, above(path.end, plan.depart_of(path)))
    out.add("M2")
    out.add("%")
    _check_range(out.lines, plan.name)
    return "\n".join(out.lines) + "\n"


def _check_range(lines: list[str], name: str) -> None:
    for line in lines:
        for word in line.split("(")[0].split():
            if word[0] in "XYZIJK" and abs(float(word[1:])) > MAX_COORDINATE_MM:
                raise InputError(f"{name}: {word} is beyond the {num(MAX_COORDINATE_MM)} mm a G-code word holds; "
                                 "place the part nearer the work frame's origin")

"""G-code -> ToolPath: the modal state of a CNC control, run on the twin's arm.

What the twin assumes (a G-code program says nothing of a robot):

- The machine's coordinates are the robot base frame, mm. A work offset (G54 … G59.3: a
  translation and LinuxCNC's rotation about Z, see :mod:`.parameters`) places the program's
  coordinates; G92 shifts them further.
- G-code has no tool orientation: the gun's spray axis is the machine's tool axis, −Z of the work
  frame (its tool x axis along −X: the pose Ry(180°) in the work frame). A rotary axis word
  (A, B, C) or a secondary linear axis (U, V, W) that moves is refused: the gun would tilt.
- G0 is a joint move at ``RAPID_MM_S`` (a robot's rapid path is its own, not the control's
  straight line); G1/G2/G3 are linear and circular moves at the feed F (mm/min, G94; in/min under
  G20). G28/G30 go to the cell's home 1/2 (through the given point first).
- Path control as :mod:`.blend` describes. Dwell ``G4 P`` in seconds (RS274/NGC; a Fanuc-style
  control reads ``P`` in milliseconds, ``X`` in seconds: ``X`` is read as seconds too).
- The gun: the M-code pair the language is set with (``M3``/``M5`` by default, a plasma table's
  torch), or ``M62``-``M65 P n`` with n the gun output. A switch takes effect as the next motion
  starts (the blocks run in order); a control may stop to switch a spindle or coolant code, which
  the twin does not (write ``G4 P0`` before the code for a stop).
- Program flow (O-words, a Fanuc macro's WHILE/IF/GOTO, M98/M99 subprograms) as :mod:`.flow`
  says. Cutter compensation, inverse-time feed, canned cycles and other codes whose motion the
  twin cannot follow are refused (ExecutionError) at their line; codes without motion (S, T,
  tool length offsets) pass.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Optional

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import rot_y, rot_z
from coatsim.languages.gcode.arcs import PLANES, ArcError, arc_pieces, centre_from_radius
from coatsim.languages.gcode.blend import BLEND, EXACT_PATH, EXACT_STOP, PathControl, settle
from coatsim.languages.gcode.blocks import Block
from coatsim.languages.gcode.flow import Runner
from coatsim.languages.gcode.gun import GunCodes
from coatsim.languages.gcode.parameters import (G92_BASE, WORK_OFFSET_BASE, WORK_OFFSET_STEP, WORK_ROTATION,
                                                Parameters)
from coatsim.languages.script.unknowns import DependsOn
from coatsim.path.language import ReadOptions
from coatsim.path.process_record import read_comment_lines
from coatsim.path.toolpath import MotionSettings, ToolPath
from coatsim.path.toolpath_builder import ToolPathBuilder

RAPID_MM_S = 1000.0
MM_PER_INCH = 25.4
_AXES = "XYZ"
_SAME_POINT_MM = 1e-9  # a move this short goes nowhere (a control skips it)
_TILT_AXES = "ABCUVW"
_PASS_WORDS = set("FSTNPQRLHDE") | set("IJK") | set(_AXES)
_TARGET_WORDS = set(_AXES) | set("IJKR")  # a motion's target: unknown in them skips the motion alone
_WORDS_OF_AXES = {4.0, 10.0, 28.0, 30.0, 92.0}  # codes whose axis words are not a motion's target
_SYSTEMS = {54.0: 1, 55.0: 2, 56.0: 3, 57.0: 4, 58.0: 5, 59.0: 6, 59.1: 7, 59.2: 8, 59.3: 9}
_REFUSED_G = {41.0: "cutter radius compensation", 42.0: "cutter radius compensation", 93.0: "inverse-time feed",
              95.0: "feed per revolution", 5.0: "splines", 5.1: "splines", 5.2: "splines", 33.0: "threading",
              33.1: "tapping", 38.2: "probing", 38.3: "probing", 38.4: "probing", 38.5: "probing",
              68.0: "coordinate rotation", 76.0: "a threading cycle", 7.0: "lathe diameter mode",
              15.0: "polar coordinates", 16.0: "polar coordinates", 73.0: "a canned cycle",
              **{float(g): "a canned cycle" for g in range(81, 90)}}
_PASSED_G = {40.0, 43.0, 43.1, 49.0, 80.0, 94.0, 8.0, 96.0, 97.0, 98.0, 99.0, 69.0, 50.0, 21.1}


def _code(value: float) -> float:
    return round(value, 1)


class Interpreter:
    """Runs the blocks of one program file."""

    def __init__(self, blocks: tuple[Block, ...], source: str, options: ReadOptions, gun: GunCodes,
                 name: str) -> None:
        self.blocks, self.source, self.options, self.gun, self.name = blocks, source, options, gun, name
        self.line = 0
        start = None
        if options.kinematics is not None:
            kin = options.kinematics
            start = lambda: (kin.forward(kin.home(1)), kin.home(1))  # noqa: E731
        self.builder = ToolPathBuilder(lambda line: f"{source}:{line}", start, lambda: (source, name, self.work()))
        self.params = Parameters(options.variables, lambda message: self.builder.error(self.line, message),
                                 lambda: f"{source}:{self.line}")
        self.controls: list[Optional[PathControl]] = []
        self.switched: list[str] = []
        self.motion: Optional[float] = None
        self.plane, self.absolute, self.arc_absolute = 17, True, False
        self.inch: Optional[bool] = None
        self.feed_mm_min: Optional[float] = None
        self.control = PathControl()
        self.system = 1
        self.unknown_target: tuple[str, ...] = ()  # the unknowns of the running block's motion target

    # --- messages -----------------------------------------------------------------------
    def error(self, message: str) -> InputError:
        return self.builder.error(self.line, message)

    def refuse(self, what: str) -> ExecutionError:
        return ExecutionError(f"{self.source}:{self.line}: {what} is not simulated; the twin cannot run this program")

    # --- frames -------------------------------------------------------------------------
    def mm(self, value: float) -> float:
        return value * MM_PER_INCH if self.inch else value

    def work(self) -> Pose:
        """The work frame in force (work offset, then G92) in the machine frame."""
        return self.offset(self.system) @ Pose.from_translation(
            np.array([self.params.get(G92_BASE + k) for k in range(3)]))

    def offset(self, number: int) -> Pose:
        """Work offset ``number`` (1: G54 … 9: G59.3) in the machine frame."""
        base = WORK_OFFSET_BASE + WORK_OFFSET_STEP * (number - 1)
        get = self.params.get
        return Pose(rot_z(math.radians(get(base + WORK_ROTATION))), np.array([get(base + k) for k in range(3)]))

    def tool_pose(self, point: np.ndarray) -> Pose:
        """The TCP pose at machine ``point``: the spray axis −Z of the work frame in force."""
        return Pose(self.work().rotation @ rot_y(math.pi), point)

    def program_position(self, frame: Pose, what: str) -> np.ndarray:
        return frame.inverse().apply(self.builder.here(what, self.line).translation_mm)

    # --- running ------------------------------------------------------------------------
    def run(self) -> ToolPath:
        """Run the blocks; ``ended`` then says how the program ended."""
        self.ended = f"it ends at line {self.blocks[-1].line if self.blocks else 1}"
        if self.options.program is not None:
            self.builder.warn("program", f"{self.source}: a G-code file holds one program; the name "
                              f"{self.options.program!r} is not used")
        runner = Runner(self.blocks, self)
        last = runner.execute()
        if last is not None:
            self.ended = f"{self.source}:{last}: {runner.how} ends it"
        if self.inch is None:
            self.builder.warn("units", f"{self.source}: no G20/G21 in the program; millimetres assumed (G21)")
        settle(self.builder, self.controls + [None] * (len(self.builder.moves) - len(self.controls)))
        process = read_comment_lines((c for b in self.blocks for c in b.comments), self.source)
        return self.builder.toolpath(self.name, process)

    def step(self, block: Block) -> None:
        """The block about to run."""
        self.line = block.line
        self.builder.step(block.line)

    def words(self, block: Block) -> tuple[list[float], list[float], dict[str, float]]:
        """G codes, M codes and the other words of a block, evaluated; DependsOn when an unknown
        is in a word the block needs before its motion (the unknowns of a motion's target are
        in ``self.unknown_target``)."""
        gs, ms, other = [], [], {}
        target: dict[str, None] = {}
        for letter, expr in block.words:
            try:
                value = self.params.evaluate(expr)
            except DependsOn as unknown:
                if letter not in _TARGET_WORDS:
                    raise
                target.update(dict.fromkeys(unknown.names))
                other[letter] = math.nan
                continue
            if letter == "G":
                gs.append(_code(value))
            elif letter == "M":
                ms.append(_code(value))
            elif letter in other:
                raise self.error(f"word {letter} twice in one block")
            else:
                other[letter] = value
        for letter in other:
            if letter not in _PASS_WORDS and letter not in _TILT_AXES:
                raise self.error(f"word {letter} is not a G-code word this reader knows")
        if target and _WORDS_OF_AXES & set(gs):
            raise DependsOn(tuple(target))
        self.unknown_target = tuple(target)
        return gs, ms, other

    def run_block(self, block: Block) -> bool:
        """Run one block, or skip it when its words need an unknown (its parameter settings are made
        all the same); True at the end of the program (M2, M30)."""
        self.unknown_target: tuple[str, ...] = ()
        try:
            return self.execute(block)
        except DependsOn as unknown:
            if not self.unknown_target:  # the words before the motion: the block is not run
                for target, expr in block.settings:
                    self.params.assign(target, expr)
            what = "the motion" if self.unknown_target else "the block"
            self.params.unknown.skip(f"{self.source}:{block.line}", what, unknown.names)
            return False

    def execute(self, block: Block) -> bool:
        """Run one block; True at the end of the program (M2, M30)."""
        gs, ms, w = self.words(block)
        for target, expr in block.settings:  # after the line's words are read (RS274/NGC)
            self.params.assign(target, expr)
        for letter in _TILT_AXES:
            if w.get(letter, 0.0) != 0.0:
                raise self.refuse(f"axis {letter} (a gun tilted away from −Z or a second linear axis)")
        if "E" in w:
            self.builder.warn("E", f"{self.source}:{self.line}: E words (an extruder axis) are not simulated")
        for g in gs:
            if g in _REFUSED_G:
                raise self.refuse(f"G{g:g} ({_REFUSED_G[g]})")
        if "F" in w:
            if not w["F"] > 0.0:
                raise self.error(f"feed F{w['F']:g} must be > 0")
            self.feed_mm_min = self.mm(w["F"])
        self.m_codes(ms, w)
        self.modes(gs, w)
        if self.unknown_target:
            raise DependsOn(self.unknown_target)
        self.motion_block(gs, w)
        return bool({2.0, 30.0} & set(ms))

    def m_codes(self, ms: list[float], w: dict[str, float]) -> None:
        for m in ms:
            if m in (self.gun.on, self.gun.off):
                self.builder.switch_gun(m == self.gun.on)
                self.builder.switched(self.line, f"M{m:g}", None, m == self.gun.on)
                self.switched.append(f"M{m:g}")
            elif m in (62.0, 63.0, 64.0, 65.0):
                if "P" not in w:
                    raise self.error(f"M{m:g} needs P, the output number")
                number = int(w["P"])
                self.switched.append(f"M{m:g} P{number}")
                gun = number == self.options.gun_signal
                self.builder.switched(self.line, f"M{m:g} P{number}", number, m in (62.0, 64.0) if gun else None)
                if gun:
                    self.builder.switch_gun(m in (62.0, 64.0))
            elif m in (0.0, 1.0, 60.0):
                self.builder.stop()
                self.builder.warn(f"M{m:g}", f"{self.source}:{self.line}: M{m:g} (a pause for the operator) is "
                                  "simulated as a stop without waiting")
            elif m in (2.0, 30.0):
                self.builder.switch_gun(False)
            elif m not in (6.0, 48.0, 49.0):
                self.switched.append(f"M{m:g}")
                self.builder.switched(self.line, f"M{m:g}")
                self.builder.warn(f"M{m:g}", f"{self.source}:{self.line}: M{m:g} is not the gun "
                                  f"({self.gun.describe()}); not simulated")

    def modes(self, gs: list[float], w: dict[str, float]) -> None:
        """Modal settings and the non-motion codes of a block, in RS274/NGC's order."""
        for g in gs:
            if g == 4.0:
                self.builder.dwell(w.get("P", w.get("X", 0.0)), self.line)
            elif g in (17.0, 18.0, 19.0):
                self.plane = int(g)
            elif g in (20.0, 21.0):
                self.inch = g == 20.0
            elif g in _SYSTEMS:
                self.system = _SYSTEMS[g]
            elif g in (61.0, 61.1):
                self.control = PathControl(EXACT_PATH if g == 61.0 else EXACT_STOP)
            elif g == 64.0:
                self.control = PathControl(BLEND, self.mm(w["P"]) if "P" in w else None)
            elif g in (90.0, 91.0):
                self.absolute = g == 90.0
            elif g in (90.1, 91.1):
                self.arc_absolute = g == 90.1
            elif g == 10.0:
                self.set_offset(w)
            elif g in (92.0, 92.1, 92.2):
                self.g92(g, w)
            elif g in (0.0, 1.0, 2.0, 3.0):
                self.motion = g
            elif g not in _PASSED_G | {9.0, 28.0, 30.0, 53.0, 28.1, 30.1}:
                raise self.error(f"G{g:g} is not a G-code this reader knows")
            if g == 80.0:
                self.motion = None

    def set_offset(self, w: dict[str, float]) -> None:
        """G10 L2 (offset values) or L20 (the current position reads as the values)."""
        level, number = int(w.get("L", 0)), int(w.get("P", 0)) or self.system
        if level not in (2, 20) or not 1 <= number <= 9:
            raise self.refuse(f"G10 L{level:g} P{number}" if level not in (2, 20) else f"G10 P{number}")
        base = WORK_OFFSET_BASE + WORK_OFFSET_STEP * (number - 1)
        if "R" in w:
            self.params.set(base + WORK_ROTATION, w["R"])
        if level == 2:
            for k, axis in enumerate(_AXES):
                if axis in w:
                    self.params.set(base + k, self.mm(w[axis]))
            return
        here = self.builder.here("G10 L20", self.line).translation_mm
        turn = rot_z(math.radians(self.params.get(base + WORK_ROTATION)))
        for k, axis in enumerate(_AXES):
            if axis in w:
                wanted = np.zeros(3)
                wanted[k] = self.mm(w[axis])
                self.params.set(base + k, float(here[k] - (turn @ wanted)[k]))

    def g92(self, g: float, w: dict[str, float]) -> None:
        if g != 92.0:
            for k in range(3):
                self.params.set(G92_BASE + k, 0.0)
            return
        here = self.offset(self.system).inverse().apply(self.builder.here("G92", self.line).translation_mm)
        for k, axis in enumerate(_AXES):
            if axis in w:
                self.params.set(G92_BASE + k, float(here[k] - self.mm(w[axis])))

    # --- motion -------------------------------------------------------------------------
    def target(self, frame: Pose, w: dict[str, float], what: str) -> np.ndarray:
        """The programmed point (program coordinates) of a move's axis words."""
        given = {axis: self.mm(w[axis]) for axis in _AXES if axis in w}
        if len(given) == 3 and self.absolute:
            return np.array([given[a] for a in _AXES])
        point = self.program_position(frame, what).copy()
        for k, axis in enumerate(_AXES):
            if axis in given:
                point[k] = given[axis] if self.absolute else point[k] + given[axis]
        return point

    def motion_block(self, gs: list[float], w: dict[str, float]) -> None:
        if {4.0, 10.0, 92.0} & set(gs):
            return  # their axis words set offsets, or G4 X's dwell (a Fanuc control's seconds)
        home = next((g for g in gs if g in (28.0, 30.0)), None)
        moves = any(axis in w for axis in _AXES)
        machine = 53.0 in gs
        frame = Pose.identity() if machine else self.work()
        if home is not None:
            if moves:
                self.rapid(frame, w)
            self.go_home(1 if home == 28.0 else 2)
            return
        if not moves and not (self.motion in (2.0, 3.0) and any(k in w for k in "IJK")):
            return
        if self.motion is None:
            raise self.error("axis words without a motion mode (G0, G1, G2 or G3)")
        if self.motion == 0.0:
            self.rapid(frame, w)
            return
        if self.feed_mm_min is None:
            raise self.error(f"G{self.motion:g} without a feed rate: give F (mm/min, or in/min under G20)")
        settings = self.control.settings(self.feed_mm_min / 60.0, 9.0 in gs)
        end = self.target(frame, w, f"G{self.motion:g}")
        if self.motion == 1.0:
            start = self.program_position(frame, "G1")
            if float(np.linalg.norm(end - start)) > _SAME_POINT_MM:
                self.feed_line(frame, end, settings)
            return
        self.feed_arc(frame, end, w, settings)

    def rapid(self, frame: Pose, w: dict[str, float]) -> None:
        end = self.target(frame, w, "G0")
        here = self.builder.current
        if here is not None and float(np.linalg.norm(here.translation_mm - frame.apply(end))) <= _SAME_POINT_MM:
            return  # a rapid to where the tool is (a G43 Z line, say) does not move
        settings = MotionSettings(RAPID_MM_S, 0.0, False, True)
        self.builder.joint(self.tool_pose(frame.apply(end)), settings, self.line)
        self.controls.append(None)

    def go_home(self, number: int) -> None:
        kin = self.options.kinematics
        if kin is None:
            raise self.error(f"G{28 if number == 1 else 30} goes home; reading it needs the cell (its home pose)")
        joints = kin.home(number)
        if joints is None:
            raise self.error(f"G30 goes to the second reference point: the cell model has no keyframe 'home{number}'")
        self.builder.joint(kin.forward(joints), MotionSettings(RAPID_MM_S, 0.0, False, True), self.line, joints)
        self.controls.append(None)

    def feed_line(self, frame: Pose, end: np.ndarray, settings: MotionSettings) -> None:
        self.builder.linear(self.tool_pose(frame.apply(end)), settings, self.line)
        self.controls.append(self.control)

    def feed_arc(self, frame: Pose, end: np.ndarray, w: dict[str, float], settings: MotionSettings) -> None:
        start = self.program_position(frame, f"G{self.motion:g}")
        a, b, normal = PLANES[self.plane]
        clockwise = self.motion == 2.0
        try:
            if "R" in w:
                centre = centre_from_radius(start, end, self.mm(w["R"]), self.plane, clockwise)
            else:
                letters = "IJK"
                if not any(letters[k] in w for k in (a, b)):
                    raise ArcError(f"a G{self.motion:g} arc in G{self.plane} needs {letters[a]} and {letters[b]} "
                                   "(the centre) or R")
                centre = start.copy() if not self.arc_absolute else np.zeros(3)
                for k in (a, b):
                    value = self.mm(w.get(letters[k], 0.0))
                    centre[k] = value if self.arc_absolute else start[k] + value
            if abs(end[normal] - start[normal]) > 1e-9:
                raise self.refuse(f"a helical arc (G{self.motion:g} moving along {_AXES[normal]})")
            pieces = arc_pieces(start, end, centre, self.plane, clockwise, int(w.get("P", 1)))
        except ArcError as exc:
            raise self.error(str(exc)) from None
        for k, (via, stop) in enumerate(pieces):
            last = k == len(pieces) - 1
            self.builder.circular(self.tool_pose(frame.apply(via)), self.tool_pose(frame.apply(stop)),
                                  settings if last else replace(settings, stop_at_end=False), self.line)
            self.controls.append(self.control)

"""Interpreter: a parsed AS program -> the ToolPath the robot executes.

What it implements (Kawasaki AS semantics as far as public sources go, see the robot-language
reference; the parts marked there as unconfirmed are modelled as stated here):

- Poses: ``.TRANS`` names, ``POINT`` assignments, ``TRANS(...)``, ``SHIFT(p BY dx, dy, dz)``
  (translation along the BASE axes), ``a + b`` (b in a's frame) and ``NULL``. Every pose is
  relative to the current ``BASE``; the ToolPath is in the robot base frame.
- Motions: JMOVE, JAPPRO (joint moves), LMOVE, LAPPRO, LDEPART, JDEPART, DRAW (BASE axes), TDRAW
  (tool axes), and C1MOVE via + C2MOVE end (the arc through start, via and end). HOME and joint
  poses need the controller's kinematics and are rejected.
- ``SPEED``, ``ACCURACY`` without ALWAYS apply to the next motion only; with ALWAYS they become
  the default. Speed units: MM/S, MM/MIN, S (time for the motion), % of ``full_speed_mm_s``.
  Before any SPEED the speed is 10 %, before any ACCURACY the accuracy 1 mm, CP is ON.
- ``stop_at_end`` is true when the motion ran with CP OFF or ACCURACY ... FINE, when a BREAK or
  DELAY follows it before the next motion, and for the last motion of the program.
- Gun signal (forward processing): the program runs ahead while a motion executes, so a
  ``SIGNAL`` written after motion k with no BREAK in between switches the gun as motion k
  starts; after a BREAK it switches when motion k has ended, i.e. as motion k+1 starts. The
  rule is the same under CP ON and CP OFF, for lines and arcs (C2MOVE), and a SIGNAL never
  makes the robot stop. Under CP ON, "motion k starts" where the tool enters the accuracy zone
  of the point before it (the robot stage switches at the start of the corner blend). A move's
  ``spray`` is the gun state from its start to its end; several SIGNALs between two motions
  act as the last one. Switching delays of a real gun, TWAIT before a SIGNAL, other outputs,
  ACCEL and DECEL do not change the path and are not represented. The writer relies on this
  to spray a closed contour exactly once around, switching on the fly at the seam.
- ``TOOL`` (at any point) sets the controller's TCP in the flange frame for the motions after
  it (``MotionSettings.tool``; the robot stage puts the flange where that TCP reaches the
  programmed poses, wherever the physical gun is). A TOOL after motion ends that motion at rest
  (like BREAK) and re-expresses the current pose with the new TCP, the flange staying put
  (when the previous TOOL is known). The last TOOL is also metadata ``tool`` = "x,y,z,o,a,t".
  ``; coatsim: key=value`` comments become ToolPath metadata.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.errors import InputError
from coatsim.program import as_ast as ast
from coatsim.program.arcs import DegenerateArc, circle_through
from coatsim.program.oat import matrix_to_oat, oat_to_matrix
from coatsim.program.toolpath import (CircularMove, JointMove, LinearMove, MotionSettings, Move, Pose, ToolFrame,
                                      ToolPath)

# What SPEED 100 (percent) means in mm/s; the controller's true maximum is robot-specific.
FULL_SPEED_MM_S = 1000.0
DEFAULT_SPEED = (10.0, "%")
DEFAULT_ACCURACY_MM = 1.0


@dataclass(frozen=True, eq=False)
class _Frame:
    """Rigid transformation: rotation (3, 3), translation (3,)."""

    r: np.ndarray
    p: np.ndarray

    def __mul__(self, other: _Frame) -> _Frame:
        return _Frame(self.r @ other.r, self.p + self.r @ other.p)

    def pose(self) -> Pose:
        return Pose(self.p.copy(), self.r.copy())


_IDENTITY = _Frame(np.eye(3), np.zeros(3))


def _inverse(f: _Frame) -> _Frame:
    return _Frame(f.r.T, -(f.r.T @ f.p))


@dataclass
class _Pending:
    """A motion issued but not yet final (its stop and spray may still change)."""

    kind: str
    start: Optional[Pose]
    end: Pose
    via: Optional[Pose]
    speed: tuple[float, str]
    accuracy: float
    cp: bool
    stop: bool
    spray: bool
    line: int
    tool: Optional[ToolFrame]


class _Machine:
    """Executes statements one by one, as the controller's program pointer would."""

    def __init__(self, file: ast.AsFile, program: ast.AsProgram, gun: int, full_speed: float) -> None:
        self.file, self.program, self.gun, self.full_speed = file, program, gun, full_speed
        self.base = _IDENTITY
        self.points: dict[str, _Frame] = {}
        self.tool: Optional[ToolFrame] = None
        self.speed_always, self.speed_once = DEFAULT_SPEED, None
        self.acc_always, self.acc_once = DEFAULT_ACCURACY_MM, None
        self.fine_always, self.fine_once = False, False
        self.cp = True
        self.current: Optional[Pose] = None
        self.gun_on = False
        self.moves: list[_Pending] = []
        self.break_since_move = False
        self.c1: Optional[tuple[Pose, int]] = None

    def error(self, line: int, message: str) -> InputError:
        return InputError(f"{self.file.source}:{line}: {message}")

    # --- values -------------------------------------------------------------------------
    def num(self, value: ast.Num, line: int) -> float:
        if isinstance(value, ast.RealRef):
            real = self.file.reals.get(value.name)
            if real is None:
                raise self.error(line, f"real variable '{value.name}' is not defined; add it to .REALS")
            return -real.value if value.negate else real.value
        return float(value)

    def frame(self, expr: ast.PoseExpr, line: int) -> _Frame:
        if isinstance(expr, ast.PoseName):
            if expr.name in self.points:
                return self.points[expr.name]
            trans = self.file.trans.get(expr.name)
            if trans is None:
                raise self.error(line, f"pose '{expr.name}' is not defined; add it to .TRANS or assign it with POINT")
            x, y, z, o, a, t = trans.values
            return _Frame(oat_to_matrix(o, a, t), np.array([x, y, z]))
        if isinstance(expr, ast.TransLiteral):
            x, y, z, o, a, t = (self.num(v, line) for v in expr.values)
            return _Frame(oat_to_matrix(o, a, t), np.array([x, y, z]))
        if isinstance(expr, ast.NullPose):
            return _IDENTITY
        if isinstance(expr, ast.Shift):
            base = self.frame(expr.base, line)
            return _Frame(base.r, base.p + np.array([self.num(v, line) for v in expr.delta]))
        if isinstance(expr, ast.Compose):
            return self.frame(expr.left, line) * self.frame(expr.right, line)
        name = expr.name if isinstance(expr, ast.JointName) else "#[...]"
        raise self.error(line, f"joint pose {name} needs the robot's kinematics; coatsim programs move to Cartesian poses (.TRANS)")

    def target(self, expr: ast.PoseExpr, line: int) -> Pose:
        return (self.base * self.frame(expr, line)).pose()

    def need_current(self, op: str, line: int) -> Pose:
        if self.current is None:
            raise self.error(line, f"{op} needs a known start pose; begin the program with JMOVE or JAPPRO")
        return self.current

    # --- motions ------------------------------------------------------------------------
    def issue(self, kind: str, end: Pose, line: int, via: Optional[Pose] = None) -> None:
        fine = self.fine_once or self.fine_always
        self.moves.append(_Pending(
            kind, self.current, end, via, self.speed_once or self.speed_always,
            self.acc_always if self.acc_once is None else self.acc_once,
            self.cp, (not self.cp) or fine, False, line, self.tool,
        ))
        self.moves[-1].spray = self.gun_on
        self.speed_once, self.acc_once, self.fine_once = None, None, False
        self.current = end
        self.break_since_move = False

    def stop_previous(self) -> None:
        if self.moves:
            self.moves[-1].stop = True
        self.break_since_move = True

    def run(self) -> None:
        for st in self.program.statements:
            if self.c1 is not None and not (isinstance(st, ast.Move) and st.op == "C2MOVE"):
                raise self.error(self.c1[1], f"C1MOVE must be followed directly by C2MOVE (line {st.line} is not one)")
            self.step(st)
        if self.c1 is not None:
            raise self.error(self.c1[1], "C1MOVE at the end of the program; expected C2MOVE with the arc end")

    def step(self, st: ast.Statement) -> None:  # noqa: C901 - one branch per statement kind
        if isinstance(st, ast.Move):
            self.move(st)
        elif isinstance(st, ast.Appro):
            distance = self.num(st.distance, st.line)
            goal = self.target(st.target, st.line)
            back = Pose(goal.position - distance * goal.rotation[:, 2], goal.rotation)
            if st.op == "LAPPRO":
                self.need_current(st.op, st.line)
            self.issue("joint" if st.op == "JAPPRO" else "line", back, st.line)
        elif isinstance(st, ast.Depart):
            here = self.need_current(st.op, st.line)
            distance = self.num(st.distance, st.line)
            self.issue("joint" if st.op == "JDEPART" else "line",
                       Pose(here.position - distance * here.rotation[:, 2], here.rotation), st.line)
        elif isinstance(st, ast.Draw):
            here = self.need_current(st.op, st.line)
            d = [self.num(v, st.line) for v in st.deltas]
            if any(v != 0.0 for v in d[3:]):
                raise self.error(st.line, f"{st.op} with a rotation is not supported; use LMOVE to a pose")
            axes = here.rotation if st.op == "TDRAW" else self.base.r
            self.issue("line", Pose(here.position + axes @ np.array(d[:3]), here.rotation), st.line)
        elif isinstance(st, ast.Home):
            raise self.error(st.line, "HOME moves to the controller's stored home pose, which a program file does not define; use JMOVE to a .TRANS pose")
        elif isinstance(st, (ast.Delay, ast.Twait)):
            if self.num(st.seconds, st.line) < 0.0:
                raise self.error(st.line, "a time must be >= 0 s")
            if isinstance(st, ast.Delay):
                self.stop_previous()
        elif isinstance(st, ast.Break):
            self.stop_previous()
        else:
            self.setting(st)

    def move(self, st: ast.Move) -> None:
        if st.op == "JMOVE":
            self.issue("joint", self.target(st.target, st.line), st.line)
        elif st.op == "LMOVE":
            self.need_current(st.op, st.line)
            self.issue("line", self.target(st.target, st.line), st.line)
        elif st.op == "C1MOVE":
            self.need_current(st.op, st.line)
            self.c1 = (self.target(st.target, st.line), st.line)
        else:
            if self.c1 is None:
                raise self.error(st.line, "C2MOVE without a C1MOVE before it; an arc is C1MOVE via then C2MOVE end")
            via, via_line = self.c1
            self.c1 = None
            end = self.target(st.target, st.line)
            try:
                circle_through(self.current.position, via.position, end.position)
            except DegenerateArc as exc:
                raise self.error(st.line, f"arc from the current pose through the C1MOVE pose (line {via_line}) to here is undefined: {exc}") from None
            self.issue("arc", end, st.line, via=via)

    def setting(self, st: ast.Statement) -> None:
        if isinstance(st, ast.Speed):
            value = self.num(st.value, st.line)
            if not value > 0.0:
                raise self.error(st.line, "SPEED must be > 0")
            if st.always:
                self.speed_always = (value, st.unit)
            else:
                self.speed_once = (value, st.unit)
        elif isinstance(st, ast.Accuracy):
            value = self.num(st.value, st.line)
            if value < 0.0:
                raise self.error(st.line, "ACCURACY must be >= 0 mm")
            if st.always:
                self.acc_always, self.fine_always = value, st.fine
            else:
                self.acc_once, self.fine_once = value, st.fine
        elif isinstance(st, ast.Cp):
            self.cp = st.on
        elif isinstance(st, ast.Signal):
            for output in st.outputs:
                if abs(output) == self.gun:
                    self.gun_on = output > 0
                    if self.moves and not self.break_since_move:
                        self.moves[-1].spray = self.gun_on
        elif isinstance(st, ast.Tool):
            f = self.frame(st.pose, st.line)
            if self.moves:
                self.stop_previous()
            if self.current is not None and self.tool is not None:
                # the flange stays where it is; the pose now names the new TCP
                old = _Frame(self.tool.rotation, self.tool.offset_mm)
                flange = _Frame(self.current.rotation, self.current.position) * _inverse(old)
                self.current = (flange * f).pose()
            self.tool = ToolFrame(f.r.copy(), f.p.copy(), st.line)
        elif isinstance(st, ast.Base):
            self.base = self.frame(st.pose, st.line)
        elif isinstance(st, ast.Point):
            self.points[st.name] = self.frame(st.pose, st.line)
        # ACCEL / DECEL: the robot stage applies its own acceleration limits.

    # --- result -------------------------------------------------------------------------
    def speed_mm_s(self, m: _Pending) -> float:
        value, unit = m.speed
        if unit == "MM/S":
            return value
        if unit == "MM/MIN":
            return value / 60.0
        if unit == "%":
            return value / 100.0 * self.full_speed
        start = m.start.position if m.start is not None else m.end.position
        if m.kind == "arc":
            c = circle_through(start, m.via.position, m.end.position)
            length = c.radius * c.sweep
        else:
            length = float(np.linalg.norm(m.end.position - start))
        return length / value

    def toolpath(self) -> ToolPath:
        if self.moves:
            self.moves[-1].stop = True
        moves: list[Move] = []
        for m in self.moves:
            settings = MotionSettings(self.speed_mm_s(m), m.accuracy, m.cp, m.stop, m.tool)
            if m.kind == "joint":
                moves.append(JointMove(m.start, m.end, settings, m.spray, m.line))
            elif m.kind == "line":
                moves.append(LinearMove(m.start, m.end, settings, m.spray, m.line))
            else:
                moves.append(CircularMove(m.start, m.via, m.end, settings, m.spray, m.line))
        metadata = dict(self.program.metadata)
        if self.tool is not None:
            metadata["tool"] = ",".join(f"{v:.6g}" for v in (*self.tool.offset_mm, *matrix_to_oat(self.tool.rotation)))
        return ToolPath(self.program.name, tuple(moves), metadata)


def interpret(file: ast.AsFile, gun_signal: int = 1, program: Optional[str] = None,
              full_speed_mm_s: float = FULL_SPEED_MM_S) -> ToolPath:
    """The ToolPath of ``program`` (default: the file's first program); InputError naming the
    file and line on anything the program cannot mean."""
    if not file.programs:
        raise InputError(f"{file.source}: no .PROGRAM section; expected '.PROGRAM name()' ... '.END'")
    chosen = file.programs[0]
    if program is not None:
        matches = [p for p in file.programs if p.name.lower() == program.lower()]
        if not matches:
            names = ", ".join(p.name for p in file.programs)
            raise InputError(f"{file.source}: no program named '{program}' (the file has: {names})")
        chosen = matches[0]
    if gun_signal < 1:
        raise InputError(f"gun signal {gun_signal}: must be an output number >= 1")
    machine = _Machine(file, chosen, gun_signal, full_speed_mm_s)
    machine.run()
    return machine.toolpath()

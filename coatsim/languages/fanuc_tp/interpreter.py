"""Fanuc TP -> ToolPath: runs the main program (and the programs it CALLs) as the controller would.

What the twin models (see :mod:`.blend` for FINE/CNT/CR, :mod:`.registers` for the data):

- A motion goes to ``P[i]`` in the user frame and with the tool it was taught in (its ``UF``/``UT``;
  once the program selects ``UFRAME_NUM``/``UTOOL_NUM`` they must agree, as the controller refuses
  a mismatch), or to ``PR[i]`` in the selected ones. Speeds: mm/sec, cm/min, inch/min; ``sec`` (the
  time the motion takes); % and ``max_speed`` of ``FULL_SPEED_MM_S``; scaled by ``OVERRIDE``.
  ``INC``, ``Offset[,PR[i]]`` (the target moved by the offset in the user frame) and
  ``Tool_Offset[,PR[i]]`` (in the tool frame) apply; ``ACC`` and options of the joint motion pass;
  other options are noted. A motion to joint values needs the cell's kinematics.
- Outputs switch in program order: ``DO[gun]=ON`` between two motions opens the gun as the second
  starts (under CNT where the tool enters the corner). ``WAIT t(sec)`` stops the robot and rests;
  a ``WAIT`` on a condition already met does not stop it; one on a signal nobody gives is taken as
  met (a warning); one that can never be met ends at its ``TIMEOUT,LBL[]`` or is an ExecutionError.
- Control flow: labels and ``JMP``, ``IF``, ``SELECT``, ``FOR``, ``CALL`` (the program from another
  file read together; ``AR[i]`` its arguments), ``END`` (returns), ``ABORT`` (ends), ``PAUSE`` (noted).
- The ``A`` motion (an arc through consecutive points) and application instructions are not
  simulated: an ``A`` motion is an ExecutionError, the others one warning each.
"""

from __future__ import annotations

from typing import Optional, Union

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.languages.fanuc_tp.motion import FULL_SPEED_MM_S, Motions
from coatsim.languages.fanuc_tp.program import LsProgram
from coatsim.languages.fanuc_tp.positions import values_of
from coatsim.languages.fanuc_tp.registers import PositionValue, Registers
from coatsim.languages.fanuc_tp.statements import (Assign, Block, Call, If, Jump, Label, Motion, Note, Pulse, Remark,
                                                   Select, Statement, Stop, Wait)
from coatsim.languages.script.unknowns import DependsOn
from coatsim.path.language import ReadOptions
from coatsim.path.process_record import read_comment_lines
from coatsim.path.toolpath import ToolPath
from coatsim.path.toolpath_builder import ToolPathBuilder

MAX_CALL_DEPTH = 32
_END, _ABORT = "end", "abort"


class _Structure:
    """Labels and the matching IF/ELSE/ENDIF and FOR/ENDFOR of one program."""

    def __init__(self, program: LsProgram) -> None:
        self.labels: dict[int, int] = {}
        self.pairs: dict[int, int] = {}
        stack: list[tuple[str, int]] = []
        for k, st in enumerate(program.statements):
            where = f"{program.source}:{st.line}"
            if isinstance(st, Label):
                if st.index[0] != "num":
                    raise InputError(f"{where}: a label's number is a constant, LBL[n]")
                self.labels.setdefault(int(st.index[1]), k)
            elif isinstance(st, Block) and st.kind in ("IF", "FOR"):
                stack.append((st.kind, k))
            elif isinstance(st, Block):
                opener = "FOR" if st.kind == "ENDFOR" else "IF"
                if not stack or stack[-1][0] != opener:
                    raise InputError(f"{where}: {st.kind} without its {opener}")
                kind, start = stack[-1]
                if st.kind == "ELSE":
                    self.pairs[start] = k
                    stack[-1] = ("IF", k)
                else:
                    stack.pop()
                    self.pairs[start], self.pairs[k] = k, start
        if stack:
            raise InputError(f"{program.source}:{program.statements[stack[-1][1]].line}: {stack[-1][0]} is not closed")


class FanucRun(Motions):
    """One run of a main program over the programs read together."""

    def __init__(self, programs: dict[str, LsProgram], options: ReadOptions, decel_mm_s2: float) -> None:
        self.programs, self.options, self.decel = programs, options, decel_mm_s2
        self.program: Optional[LsProgram] = None
        self.source, self.line = next(iter(programs.values())).source, 0
        start = None
        if options.kinematics is not None:
            kin = options.kinematics
            start = lambda: (kin.forward(kin.home(1)), kin.home(1))  # noqa: E731
        self.user_frame = Pose.identity()  # the user frame of the target last computed
        self.builder = ToolPathBuilder(lambda line: f"{self.source}:{line}", start,
                                       lambda: (self.source, self.program.name, self.user_frame))
        self.data = Registers(options.variables, options.inputs, self.error, self.warn,
                              lambda: f"{self.source}:{self.line}")
        self.uf: Optional[int] = None
        self.ut: Optional[int] = None
        self.tool_number: Optional[int] = None
        self.override = 100.0
        self.offsets: dict[str, Optional[tuple]] = {"OFFSET": None, "TOOL_OFFSET": None}  # OFFSET CONDITION PR[i]
        self.structures: dict[str, _Structure] = {}
        self.unsimulated: list[str] = []  # statements read but not simulated (running refuses them)

    # --- messages -----------------------------------------------------------------------
    def error(self, message: str) -> InputError:
        return self.builder.error(self.line, message)

    def warn(self, key: str, message: str) -> None:
        self.builder.warn(key, f"{self.source}:{self.line}: {message}")

    def unsimulated_speed(self, what: str) -> float:
        """A speed the twin cannot simulate: listed as an unsimulated statement (reading goes on at
        full speed; running refuses it, see :meth:`Reading.require_complete`)."""
        self.unsimulated.append(f"{self.source}:{self.line}: {what} is not simulated")
        self.warn(f"speed:{what}", f"{what} is not simulated; read at {FULL_SPEED_MM_S:g} mm/sec")
        return FULL_SPEED_MM_S

    def refuse(self, what: str) -> ExecutionError:
        return ExecutionError(f"{self.source}:{self.line}: {what} is not simulated; the twin cannot run this program")

    # --- running ------------------------------------------------------------------------
    def run(self, main: str) -> ToolPath:
        """Run program ``main``; ``ended`` then says how it ended."""
        outcome = self.call(main, (), 0)
        program = self.programs[main]
        self.ended = f"{self.source}:{self.line}: ABORT ends it" if outcome == _ABORT else \
            f"it ends at line {program.statements[-1].line if program.statements else program.line}"
        process = read_comment_lines((st.text for st in program.statements if isinstance(st, Remark)), program.source)
        return self.builder.toolpath(program.name, process)

    def call(self, name: str, args: tuple, depth: int) -> str:
        """Run program ``name``; _ABORT when the run ends there."""
        if name not in self.programs:
            raise self.error(f"CALL {name}: no program {name} among the files read; give its .LS file too")
        if depth > MAX_CALL_DEPTH:
            raise ExecutionError(f"{self.source}:{self.line}: CALLs nest deeper than {MAX_CALL_DEPTH}")
        program = self.programs[name]
        caller = self.program
        self.program, self.source = program, program.source
        if name not in self.structures:
            self.structures[name] = _Structure(program)
        structure = self.structures[name]
        pc, statements = 0, program.statements
        while pc < len(statements):
            st = statements[pc]
            self.line = st.line
            self.builder.step(st.line)
            try:
                outcome = self.execute(st, args, depth, structure, pc)
            except DependsOn as unknown:
                self.data.unknown.skip(f"{self.source}:{st.line}", _what(st), unknown.names)
                outcome = None
            if outcome in (_END, _ABORT):
                if outcome == _ABORT:
                    return _ABORT
                break
            pc = pc + 1 if outcome is None else outcome
        self.program = caller
        if caller is not None:
            self.source = caller.source
        return _END

    def _label(self, index_expr, args, structure: _Structure) -> int:
        number = self.data.index(index_expr, args)
        if number not in structure.labels:
            raise self.error(f"JMP LBL[{number}]: the program has no LBL[{number}]")
        return structure.labels[number]

    def execute(self, st: Statement, args: tuple, depth: int, structure: _Structure, pc: int) -> Union[None, int, str]:
        """Run one statement; the index of the next one, None for the one after, or _END/_ABORT."""
        if isinstance(st, Motion):
            self.motion(st, args)
        elif isinstance(st, Assign):
            self.assign(st, args)
        elif isinstance(st, Pulse):
            self.pulse(st, args)
        elif isinstance(st, Jump):
            return self._label(st.index, args, structure)
        elif isinstance(st, If):
            if self.data.evaluate(st.condition, args):
                return self.execute(st.action, args, depth, structure, pc)
        elif isinstance(st, Select):
            subject = self.data.evaluate(st.subject, args)
            for value, action in st.cases:
                if value is None or self.data.evaluate(value, args) == subject:
                    return self.execute(action, args, depth, structure, pc)
        elif isinstance(st, Block):
            return self.block(st, args, structure, pc)
        elif isinstance(st, Call):
            values = tuple(a if isinstance(a, str) else self.data.evaluate(a, args) for a in st.args)
            if self.call(st.name, values, depth + 1) == _ABORT:
                return _ABORT
        elif isinstance(st, Wait):
            return self.wait(st, args, structure)
        elif isinstance(st, Stop):
            if st.kind == "PAUSE":
                self.builder.stop()
                self.warn("PAUSE", "PAUSE (the operator resumes) is simulated as a stop without waiting")
                return None
            return _ABORT if st.kind == "ABORT" else _END
        elif isinstance(st, Note) and not st.ignored:
            self.warn(f"note:{st.text.split()[0]}", f"{st.text[:60]} is not simulated")
        return None

    def block(self, st: Block, args: tuple, structure: _Structure, pc: int) -> Optional[int]:
        pairs = structure.pairs
        if st.kind == "IF":
            return None if self.data.evaluate(st.condition, args) else pairs[pc] + 1
        if st.kind == "ELSE":
            return pairs[pc] + 1
        if st.kind == "FOR":
            number = self.data.index(st.register, args)
            first, last = self.data.evaluate(st.start, args), self.data.evaluate(st.stop, args)
            self.data.r[number] = first
            self.data.unset.pop(f"R[{number}]", None)
            return pairs[pc] + 1 if (first < last if st.down else first > last) else None
        if st.kind == "ENDFOR":
            head = self.program.statements[pairs[pc]]
            number = self.data.index(head.register, args)
            step = -1.0 if head.down else 1.0
            self.data.r[number] = self.data.r.get(number, 0.0) + step
            last = self.data.evaluate(head.stop, args)
            within = self.data.r[number] >= last if head.down else self.data.r[number] <= last
            return pairs[pc] + 1 if within else None
        return None

    def wait(self, st: Wait, args: tuple, structure: _Structure) -> Optional[int]:
        if st.seconds is not None:
            self.builder.dwell(self.data.evaluate(st.seconds, args), st.line)
            return None
        unknown_before = self.data.unknown_reads
        if self.data.evaluate(st.condition, args):
            return None
        if self.data.unknown_reads > unknown_before:
            self.warn(f"wait:{st.line}", "WAIT on a signal nobody gives is taken as met")
            return None
        if st.timeout_label is not None:
            self.builder.stop()
            self.warn(f"timeout:{st.line}", "WAIT can never be met; it ends at its TIMEOUT label")
            return self._label(st.timeout_label, args, structure)
        raise ExecutionError(f"{self.source}:{st.line}: WAIT can never be met (the signals and registers it reads "
                             "do not change while it waits); give the inputs the cell sets")

    # --- data ---------------------------------------------------------------------------
    def assign(self, st: Assign, args: tuple) -> None:
        target, value = st.target, st.value
        if target[0] == "name":
            name = target[1]
            if name in self.offsets:  # the register is read as each motion uses it, not now
                self.offsets[name] = (value, args)
                return
            number = self.data.evaluate(value, args)
            if name == "UFRAME_NUM":
                self.uf = self._frame_number(number, "UFRAME_NUM")
            elif name == "UTOOL_NUM":
                self.ut = self._frame_number(number, "UTOOL_NUM")
            elif name == "OVERRIDE":
                if not 0.0 < number <= 100.0:
                    raise self.error(f"OVERRIDE={number:g}%: from 1 to 100")
                self.override = number
            else:
                self.warn(f"set:{name}", f"{name}= is not simulated")
            return
        kind, number = target[1], self.data.index(target[2], args)
        try:
            self.set_register(kind, number, target, value, args)
        except DependsOn as unknown:
            if kind not in ("R", "PR", "UFRAME", "UTOOL"):
                raise
            self.data.unset[f"{kind}[{number}]"] = unknown.names  # set from an unknown: unknown too

    def set_register(self, kind: str, number: int, target, value, args: tuple) -> None:
        """``R[i]=``, ``PR[i]=``, ``PR[i,j]=``, ``UFRAME[i]=``, ``UTOOL[i]=`` or a signal's ``=``."""
        if kind in ("R", "UFRAME", "UTOOL") or (kind == "PR" and len(target) != 4):
            self.data.unset.pop(f"{kind}[{number}]", None)
        if kind == "R":
            self.data.r[number] = self.data.evaluate(value, args)
        elif kind == "PR" and len(target) == 4:
            self.data.set_element(number, self.data.index(target[3], args), self.data.evaluate(value, args))
        elif kind == "PR":
            self.data.pr[number] = self.position_value(value, args)
        elif kind in ("UFRAME", "UTOOL"):
            frame = self.position_value(value, args)
            if frame.joints:
                raise self.error(f"{kind}[{number}] needs a Cartesian position, not joint values")
            self.data.frames[kind][number] = frame.pose()
            if kind == "UTOOL" and number == self.tool_number:
                self.tool_number = None  # the tool in use changed: set again at the next motion
        elif kind == "AR":
            raise self.error("AR[] are a CALL's arguments; a program cannot set them")
        else:
            self.set_signal(kind, number, self.data.evaluate(value, args))

    def position_value(self, value, args: tuple) -> PositionValue:
        if value[0] != "pos":
            raise self.error("a position register takes a position (PR[i], P[i], LPOS, JPOS, UFRAME[i], UTOOL[i])")
        return self.data.combine(value[1], args, self.lpos, self.jpos, self.point)

    def point(self, number: int) -> PositionValue:
        """``P[i]`` of the program's /POS as a register's value (``PR[i] = P[i]``: its numbers as taught)."""
        position = self.program.positions.get(number)
        if position is None:
            raise self.error(f"P[{number}] is not in the program's /POS section")
        if position.pose is None:
            return PositionValue(tuple(float(v) for v in position.joints_deg[:6]), True)
        return PositionValue(values_of(position.pose))

    def lpos(self) -> Pose:
        frame = self.data.frame("UFRAME", self.uf or 0)
        return frame.inverse() @ self.builder.here("LPOS", self.line)

    def jpos(self) -> np.ndarray:
        joints = self.builder.current_joints
        if joints is None:
            raise self.error("JPOS needs the arm's joint values, which the twin knows only after a joint motion "
                             "to joint values")
        return joints

    def _frame_number(self, value: float, what: str) -> int:
        if value != round(value) or not 0 <= value <= 99:
            raise self.error(f"{what}={value:g}: a frame number from 0")
        return int(value)

    def set_signal(self, kind: str, number: int, value: float) -> None:
        self.data.outputs[(kind, number)] = value
        gun = kind == "DO" and number == self.options.gun_signal
        shown = ("ON" if value else "OFF") if kind in ("DO", "RO") else f"{value:g}"
        self.builder.switched(self.line, f"{kind}[{number}]={shown}", number if kind == "DO" else None,
                              value != 0.0 if gun else None)
        if gun:
            self.builder.switch_gun(value != 0.0)

    def pulse(self, st: Pulse, args: tuple) -> None:
        kind, number = st.target[1], self.data.index(st.target[2], args)
        self.builder.switched(self.line, f"{kind}[{number}]=PULSE", number if kind == "DO" else None)
        self.warn(f"pulse:{kind}{number}", f"{kind}[{number}]=PULSE is not simulated (the output is left as it was)")


def _what(st: Statement) -> str:
    """A statement as a skipped one is named."""
    if isinstance(st, Block):
        return st.kind
    if isinstance(st, Call):
        return f"CALL {st.name}"
    return {Motion: "the motion", Assign: "the assignment", Pulse: "PULSE", Jump: "JMP", If: "IF", Select: "SELECT",
            Wait: "WAIT"}.get(type(st), "the statement")

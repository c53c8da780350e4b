"""Interpreter: parsed AS files -> the ToolPath the robot executes.

Runs the main program (the one named, else one no other program CALLs:
:mod:`~coatsim.languages.kawasaki_as.main_program`) with the programs it CALLs, their control
flow, variables and expressions.
Poses are relative to the current BASE (``BASE``); the ToolPath is in the robot base frame.
Motions, settings, the gun and the rests follow :mod:`~coatsim.languages.kawasaki_as.motion`; signals
and unknown inputs :mod:`~coatsim.languages.kawasaki_as.io_model`; variables
:mod:`~coatsim.languages.kawasaki_as.memory`. Joint values and HOME use the cell's kinematics
(``kinematics``); without it they are an error. What a program reads that no file gives is an
unknown (:mod:`~coatsim.languages.kawasaki_as.unknowns`): its default is taken, a condition that
depends on one is reported, a statement that cannot run without it (a motion to a pose no file
gives, a motion the twin does not simulate, a CALL of a program not loaded) is skipped with a
note in ``Run.skipped``. What the twin does not simulate either stops the run (exit 3: the gun
pulsed, a BRAKE during a motion) or is one warning line in ``ToolPath.warnings`` (tasks,
network, grippers, displays, unknown inputs). Backward jumps follow
:mod:`~coatsim.languages.kawasaki_as.loops` (a cycle the cell repeats runs once; a loop that
changes nothing waits for the cell or never ends; a step budget stops any other loop that never
ends, naming it); CALLs nested too deep name their cycle.
"""

from __future__ import annotations

import random as _random
from collections import Counter
from dataclasses import dataclass, field
from typing import Mapping, Optional, Sequence, Union


from coatsim.geometry.space.pose import InvalidPose, Pose
from coatsim.core.errors import CoatsimError, ExecutionError, InputError
from coatsim.path.process_record import decode as decode_header
from coatsim.path.reading import require_every_statement
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.compile import EXEC, FOR_INIT, FOR_NEXT, FOR_TEST, JUMP, JUMP_IF_FALSE, JUMP_IF_TRUE, \
    Code, compile_program
from coatsim.languages.kawasaki_as.evaluate import Evaluator
from coatsim.languages.kawasaki_as.instructions import UNSIMULATED_MOTION
from coatsim.languages.kawasaki_as.main_program import choose_main
from coatsim.languages.kawasaki_as.io_model import SignalIO, Signals, Warnings
from coatsim.languages.kawasaki_as.loops import LoopControl
from coatsim.languages.kawasaki_as.memory import Memory
from coatsim.languages.kawasaki_as.motion import FULL_SPEED_MM_S, Controller
from coatsim.languages.kawasaki_as.parser import key as norm
from coatsim.languages.kawasaki_as.robot_queries import RobotQueries
from coatsim.languages.kawasaki_as.scope import KINDS, Scope
from coatsim.languages.kawasaki_as.statements_exec import ReturnFromProgram, StopProgram, execute_statement, \
    statement_name
from coatsim.languages.kawasaki_as.unknowns import ABSENT, Absent, NotSimulated, UnknownRead, Unknowns
from coatsim.languages.kawasaki_as.values import IDENTITY
from coatsim.path.toolpath import Kinematics, ToolPath

MAX_STEPS = 1_000_000
MAX_CALL_DEPTH = 50
# Statements that place the arm or a pose: an unknown number in them skips them (no made-up place).
_MOTIONS = (ast.Move, ast.Appro, ast.Depart, ast.Draw, ast.Home, ast.PointAssign)  # (the motions, then POINT)


@dataclass(frozen=True, eq=False)
class Run:
    """An interpreted program: its ToolPath, where each move comes from ((program, first line,
    line): an arc's first line is its C1MOVE) and the BASE it was given in, how often each
    (program, line) ran, the programs loaded, whether the gun output is still on when the
    program ends (a switch after the last motion counts), the STOP / HALT that ended it
    ("file:line: HALT"; empty when it ran to its end), the variables it read that no file gives,
    the statements it skipped for want of a value, the outputs (below the inputs) it switches,
    what a reader must know of the run (which program was taken as the main one), and where
    motions were skipped while the gun was on (the sprayed path lacks them: ``dry``)."""

    toolpath: ToolPath
    move_origins: tuple[tuple[str, int, int], ...]
    move_bases: tuple[Pose, ...]
    executions: Mapping[tuple[str, int], int]
    programs: Mapping[str, ast.Program]
    gun_on_at_end: bool = False
    stopped: str = ""
    unknowns: tuple[UnknownRead, ...] = ()
    skipped: tuple[str, ...] = ()
    outputs: tuple[int, ...] = ()
    unsimulated: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    dry: tuple[str, ...] = ()

    def require_complete(self) -> None:
        """What simulates or rewrites the path needs every statement: InputError naming the first
        one skipped for want of a value, ExecutionError when it is one the twin does not simulate."""
        require_every_statement(self.skipped, self.unsimulated)


@dataclass
class _Frame:
    """One program invocation: its locals, its FOR loops' bounds (by slot), per backward jump
    the run's state when it was last taken (Interpreter.jump) and, per conditional jump, what
    unknown its condition last turned on ("" when none: LoopControl.blind)."""

    program: ast.Program
    scope: Scope
    loops: dict = field(default_factory=dict)
    visits: dict = field(default_factory=dict)
    blind: dict = field(default_factory=dict)


class Interpreter(Memory, SignalIO, RobotQueries, LoopControl):
    """State of one run: variables, signals, the controller, the call stack, the budget."""

    def __init__(self, files: Sequence[ast.AsFile], gun: int, inputs: Mapping[int, bool],
                 kinematics: Optional[Kinematics], full_speed_mm_s: float, max_steps: int) -> None:
        self.files, self.gun, self.kinematics, self.max_steps = files, gun, kinematics, max_steps
        self.warnings = Warnings()
        self.programs: dict[str, ast.Program] = {}
        for f in files:
            for p in f.programs:
                other = self.programs.get(p.name.lower())
                if other is not None:
                    raise InputError(f"{p.source}:{p.line}: program '{p.name}' is also defined in "
                                     f"{other.source}:{other.line}")
                self.programs[p.name.lower()] = p
        self.globals = Scope()
        self.globals.load(files, self.warnings.add)
        self.signals = Signals(inputs)
        self.switches: dict[str, bool] = {}
        self.base = IDENTITY
        self.eval = Evaluator(self)
        self.stack: list[_Frame] = []
        self.code: dict[str, Code] = {}
        self.steps, self.line, self.last_loop = 0, 0, None
        self.changes = 0  # values and signals changed so far (a loop that changes nothing: see jump)
        self.served: set[tuple[str, int]] = set()  # loops taken as ended that waited for an input or a message
        self.stopped = ""  # "file:line: HALT" of the STOP / HALT that ended the run
        self.rng: Optional[_random.Random] = None
        self.origins: list[tuple[str, int, int]] = []
        self.bases: list[Pose] = []
        self.executions: Counter = Counter()
        self.unknowns = Unknowns()
        self.skipped_via: Optional[int] = None  # line of a C1MOVE skipped: its C2MOVE goes too
        self.placing = False  # a motion statement runs: an unknown number is Absent, not 0 (no move to a made-up place)
        self.outputs: set[int] = set()  # outputs the program switches (SIGNAL, PULSE, DLYSIG, BITS)
        self.dry: list[str] = []  # "file:line" of the motions skipped while the gun is on
        self.controller = Controller(full_speed_mm_s, self.where, self.home_pose if kinematics is not None else None)

    # --- messages ------------------------------------------------------------------------
    @property
    def source(self) -> str:
        return self.stack[-1].program.source if self.stack else self.files[0].source

    def where(self, line: Optional[int] = None) -> str:
        return f"{self.source}:{self.line if line is None else line}"

    def error(self, message: str) -> InputError:
        return InputError(f"{self.where()}: {message}")

    def failure(self, message: str) -> ExecutionError:
        return ExecutionError(f"{self.where()}: {message}")

    def warn(self, key: str, message: str) -> None:
        self.warnings.add(key, f"{self.where()}: {message}")

    def not_simulated(self, key: str, message: str) -> None:
        """A value the run does not compute: noted once, and counted as a read of an unknown
        (a condition that depends on it is reported as taken with its default)."""
        self.unknowns.reads += 1
        self.unknowns.last = key.split(":", 1)[-1]
        self.warn(key, message)

    def skip(self, st: ast.Statement, reason: str, unsimulated: bool = False) -> None:
        """A statement that cannot run for want of a value (or that the twin does not simulate):
        noted, the run goes on."""
        text = f"{self.where()}: {statement_name(st)} skipped: {reason}"
        self.unknowns.skipped.append(text)
        if unsimulated:
            self.unknowns.unsimulated.append(text)
        self.warnings.add(f"skip:{self.where()}", text)

    def switch_state(self, name: str) -> bool:
        return self.controller.cp if name == "CP" else self.switches.get(name, False)

    def random(self) -> float:
        if self.rng is None:
            self.rng = _random.Random(0)
            self.warn("random", "RANDOM gives a fixed pseudo-random sequence (seed 0), the same on every run")
        self.changes += 1
        return self.rng.random()

    # --- running -------------------------------------------------------------------------
    def call(self, program: ast.Program, args: tuple[ast.Expr, ...]) -> None:
        if len(self.stack) >= MAX_CALL_DEPTH:
            raise self.failure(self.cycle())
        if len(args) > len(program.params):
            raise self.error(f"program '{program.name}' takes {len(program.params)} argument(s), {len(args)} given")
        scope, copy_back = Scope(), []
        for param, arg in zip(program.params, args):
            formal = ast.Name(param.name)
            by_ref = param.by_ref or isinstance(arg, ast.Ref)
            actual = arg.target if isinstance(arg, ast.Ref) else arg
            if by_ref and not isinstance(actual, ast.Name):
                raise self.error(f"argument for {param.name} of '{program.name}' is passed by reference; give a variable")
            if isinstance(actual, ast.Name) and actual.whole:  # an entire array: every element
                for kind, suffix, value in self.scope_of(actual).array(norm(actual.name)):
                    scope.set(kind, norm(formal.name) + suffix, value)
            elif isinstance(actual, ast.Name):  # its values as they are (none: the parameter is unknown)
                k, source = self.key(actual), self.scope_of(actual)
                for kind in KINDS:
                    if source.has(kind, k):
                        scope.set(kind, norm(formal.name), source.get(kind, k))
            else:
                kind = self.eval.kind(actual)
                value = {"real": self.eval.real, "string": self.eval.string, "pose": self.eval.pose,
                         "joint": self.eval.joint_value}[kind](actual)
                scope.set(kind, norm(formal.name), value)
            if by_ref:
                copy_back.append((formal, actual))
        caller_line = self.line
        self.stack.append(_Frame(program, scope))
        try:
            self.execute(self.compiled(program))
        except ReturnFromProgram:
            pass
        finally:
            frame = self.stack.pop()
            self.line = caller_line
        for formal, actual in copy_back:
            if actual.whole:
                for kind, suffix, value in frame.scope.array(norm(formal.name)):
                    self.scope_of(actual).set(kind, norm(actual.name) + suffix, value)
                self.changes += 1
                continue
            for kind in KINDS:
                value = frame.scope.get(kind, norm(formal.name))
                if value is not None:
                    self.set(kind, actual, value)

    def cycle(self) -> str:
        """The message for CALLs nested too deep, naming the first cycle of programs that repeats."""
        names = [f.program.name for f in self.stack]
        for i, name in enumerate(names):
            if name in names[i + 1:]:
                j = names.index(name, i + 1)
                return (f"CALLs nested more than {MAX_CALL_DEPTH} deep: the CALL cycle {' -> '.join(names[i:j + 1])} "
                        "never ends (a program calling itself, directly or through others)")
        return f"CALLs nested more than {MAX_CALL_DEPTH} deep ({' -> '.join(names[:3])} -> ...)"

    def compiled(self, program: ast.Program) -> Code:
        code = self.code.get(program.name.lower())
        if code is None:
            code = self.code[program.name.lower()] = compile_program(program)
        return code

    def execute(self, code: Code) -> None:
        ops, n, pc = code.ops, len(code.ops), 0
        frame = self.stack[-1]
        name = frame.program.name
        test = self.test
        while pc < n:
            op = ops[pc]
            self.steps += 1
            if self.steps > self.max_steps:
                self.line = op[1]
                raise self.budget_error()
            kind, self.line = op[0], op[1]
            if kind == EXEC:
                self.executions[(name, self.line)] += 1
                self.statement(op[2])
                moves = self.controller.moves
                if len(moves) > len(self.origins):  # (moves of a CALL were recorded inside it)
                    for m in moves[len(self.origins):]:
                        self.origins.append((name, m.first_line, m.line))
                        self.bases.append(self.base)
                pc += 1
            elif kind == JUMP:
                pc = self.jump(code, pc, op[3])
            elif kind == JUMP_IF_FALSE:
                pc = pc + 1 if test(op[2], pc) else self.jump(code, pc, op[3])
            elif kind == JUMP_IF_TRUE:
                pc = self.jump(code, pc, op[3]) if test(op[2], pc) else pc + 1
            elif kind == FOR_INIT:
                st = op[2]
                step = 1.0 if st.step is None else self.guarded(self.eval.real, st.step, 1.0)
                start, stop = self.guarded(self.eval.real, st.start, 0.0), self.guarded(self.eval.real, st.stop, 0.0)
                self.set("real", st.var, start)
                frame.loops[op[3]] = (stop, step)
                pc += 1
            elif kind == FOR_TEST:
                stop, step = frame.loops[op[3]]
                value = self.eval.real(op[2].var)
                pc = op[4] if (value > stop if step >= 0 else value < stop) else pc + 1
            elif kind == FOR_NEXT:
                if op[3] not in frame.loops:
                    raise self.failure(f"NEXT step of the FOR loop of line {op[2].line} reached without its FOR "
                                       "(a GOTO into the loop?)")
                self.set("real", op[2].var, self.eval.real(op[2].var) + frame.loops[op[3]][1])
                pc = self.jump(code, pc, op[4])
            else:  # CASE
                pc = self.case(op)

    def statement(self, st: ast.Statement) -> None:
        """Run one statement; one that cannot run for want of a value is skipped with a note."""
        before = self.unknowns.reads
        self.placing = isinstance(st, _MOTIONS)
        try:
            execute_statement(self, st)
        except InvalidPose as exc:
            raise self.failure(f"the pose is not a finite rigid transformation ({exc})") from None
        except Absent as exc:
            self.absent(st, exc.reason, isinstance(exc, NotSimulated))
        except CoatsimError as exc:
            if getattr(exc, "judged", False) or self.unknowns.reads == before:
                exc.judged = True  # (a CALL's callee judged it: the caller does not take it for its own)
                raise
            self.absent(st, f"it reads {self.unknowns.last}, which has no value here, and then "
                            f"{str(exc).split(': ', 1)[-1]}")
        finally:
            self.placing = False

    def absent(self, st: ast.Statement, reason: str, unsimulated: bool = False) -> None:
        """Skip ``st``: its POINT / HERE target (the reals of a DECOMPOSE) has no value after it,
        an arc whose C1MOVE is skipped loses its C2MOVE too."""
        try:
            if isinstance(st, (ast.PointAssign, ast.Here)) and st.target.kind != "string":
                self.set("joint" if st.target.kind == "joint" else "pose", st.target, ABSENT)
            elif isinstance(st, ast.Decompose) and len(st.target.index) == 1:  # the six reals it would have set
                first = self.eval.integer(st.target.index[0], "the DECOMPOSE index")
                for i in range(6):
                    self.set("real", ast.Name(st.target.name, (ast.Num(float(first + i)),)), ABSENT)
        except (CoatsimError, Absent):
            pass  # (an index that cannot be computed: nothing to mark)
        if isinstance(st, ast.Move) and st.op in ("C1MOVE", "C2MOVE"):
            self.controller.c1 = None
            self.skipped_via = st.line if st.op == "C1MOVE" else None
        moves = isinstance(st, _MOTIONS[:-1]) or (isinstance(st, ast.Command) and st.name in UNSIMULATED_MOTION)
        if moves and self.controller.gun_on:
            self.dry.append(self.where())
        self.skip(st, reason, unsimulated)

    def test(self, e: ast.Expr, at: Optional[int] = None) -> bool:
        """The truth of condition ``e``; that of the conditional jump at op ``at`` notes what
        unknown it turned on (for a loop ended only by those)."""
        if at is None:
            return self.guarded(self.eval.truth, e, False)
        before = (self.unknowns.reads, self.signals.unknown_reads)
        value = self.guarded(self.eval.truth, e, False)
        self.stack[-1].blind[at] = self.blind(e, self.signals.unknown_reads > before[1]) \
            if (self.unknowns.reads, self.signals.unknown_reads) != before else ""
        return value

    def case(self, op: tuple) -> int:
        st: ast.Case = op[2]
        value = self.eval.string if st.string else self.eval.real
        subject = self.guarded(value, st.subject, "" if st.string else 0.0)
        for (values, _, _), target in zip(st.branches, op[3]):
            if any(value(v) == subject for v in values):
                return target
        return op[4]

    def run(self, main: ast.Program) -> ToolPath:
        if main.params:
            self.warn("main-params", f"program '{main.name}' takes parameters; run as the main program they are unset")
        try:
            self.call(main, ())
        except StopProgram:
            pass
        self.line = main.end_line
        self.stack.append(_Frame(main, Scope(), {}))
        self.controller.finish(main.end_line)
        self.stack.pop()
        return self.controller.toolpath(main.name, decode_header(main.metadata, f"{main.source}:{main.line}"), tuple(self.warnings.lines))


def interpret_run(files: Union[ast.AsFile, Sequence[ast.AsFile]], gun_signal: int = 1, program: Optional[str] = None,
                  *, inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                  full_speed_mm_s: float = FULL_SPEED_MM_S, max_steps: int = MAX_STEPS,
                  variables: Optional[Mapping[str, Union[str, float]]] = None) -> Run:
    """Run the main program of ``files`` (``program``, else the one
    :func:`~coatsim.languages.kawasaki_as.main_program.choose_main` takes) and report where each move comes from. ``variables`` gives
    global variables values from outside the files (``{"direction": 8, "pick": "TRANS(...)"}``)."""
    files = (files,) if isinstance(files, ast.AsFile) else tuple(files)
    if gun_signal < 1:
        raise InputError(f"gun signal {gun_signal}: must be an output number >= 1")
    all_programs = [p for f in files for p in f.programs]
    if not all_programs:
        names = ", ".join(f.source for f in files)
        raise InputError(f"{names}: no .PROGRAM section; expected '.PROGRAM name()' ... '.END'")
    run = Interpreter(files, gun_signal, inputs or {}, kinematics, full_speed_mm_s, max_steps)
    run.give(variables or {})
    notes: tuple[str, ...] = ()
    if program is None:
        main, note = choose_main(all_programs)
        notes = (note,) if note else ()
    else:
        main = run.programs.get(program.lower())
        if main is None:
            names = ", ".join(p.name for p in all_programs)
            raise InputError(f"{files[0].source}: no program named '{program}' (loaded: {names})")
    toolpath = run.run(main)
    return Run(toolpath, tuple(run.origins), tuple(run.bases), dict(run.executions), dict(run.programs),
               run.controller.gun_on, run.stopped, tuple(run.unknowns.first.values()), tuple(run.unknowns.skipped),
               tuple(sorted(run.outputs)), tuple(run.unknowns.unsimulated), notes, tuple(run.dry))


def interpret(files: Union[ast.AsFile, Sequence[ast.AsFile]], gun_signal: int = 1, program: Optional[str] = None,
              **options) -> ToolPath:
    """The ToolPath of the main program; InputError naming file and line on anything the
    program cannot mean, ExecutionError on what the twin cannot run."""
    return interpret_run(files, gun_signal, program, **options).toolpath

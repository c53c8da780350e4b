"""Interpreter: parsed AS files -> the ToolPath the robot executes.

Runs the main program (the one named, else the first one loaded that is not a background PC
program ``*.pc``) with the programs it CALLs, their control flow, variables and expressions.
Poses are relative to the current BASE (``BASE``); the ToolPath is in the robot base frame.
Motions, settings, the gun and the rests follow :mod:`~coatsim.languages.kawasaki_as.motion`; signals
and unknown inputs :mod:`~coatsim.languages.kawasaki_as.io_model`. Joint values and HOME use the
cell's kinematics (``kinematics``); without it they are an error. What the twin does not
simulate either stops the run (exit 3: motions it cannot follow, teach-pendant block steps, the
gun pulsed) or is one warning line in ``ToolPath.warnings`` (tasks, network, grippers, displays,
unknown inputs). A step budget stops a program that never ends, naming its loop.
"""

from __future__ import annotations

import math
import random as _random
from collections import Counter
from dataclasses import dataclass
from typing import Mapping, Optional, Sequence, Union


from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as.header import decode as decode_header
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.compile import EXEC, FOR_INIT, FOR_NEXT, FOR_TEST, JUMP, JUMP_IF_FALSE, JUMP_IF_TRUE, \
    Code, compile_program
from coatsim.languages.kawasaki_as.evaluate import Evaluator
from coatsim.languages.kawasaki_as.io_model import Signals, Warnings, is_input
from coatsim.languages.kawasaki_as.motion import FULL_SPEED_MM_S, Controller
from coatsim.languages.kawasaki_as.parser import key as norm
from coatsim.languages.kawasaki_as.robot_queries import RobotQueries
from coatsim.languages.kawasaki_as.scope import Scope
from coatsim.languages.kawasaki_as.statements_exec import ReturnFromProgram, StopProgram, execute_statement
from coatsim.languages.kawasaki_as.values import IDENTITY, Frame
from coatsim.path.toolpath import Kinematics, ToolPath

MAX_STEPS = 1_000_000
MAX_CALL_DEPTH = 50


@dataclass(frozen=True, eq=False)
class Run:
    """An interpreted program: its ToolPath, where each move comes from ((program, first line,
    line): an arc's first line is its C1MOVE) and the BASE it was given in, how often each
    (program, line) ran, the programs loaded, whether the gun output is still on when the
    program ends (a switch after the last motion counts), and the STOP / HALT that ended it
    ("file:line: HALT"; empty when it ran to its end)."""

    toolpath: ToolPath
    move_origins: tuple[tuple[str, int, int], ...]
    move_bases: tuple[Frame, ...]
    executions: Mapping[tuple[str, int], int]
    programs: Mapping[str, ast.Program]
    gun_on_at_end: bool = False
    stopped: str = ""


@dataclass
class _Frame:
    program: ast.Program
    scope: Scope
    loops: dict


class Interpreter(RobotQueries):
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
        self.stopped = ""  # "file:line: HALT" of the STOP / HALT that ended the run
        self.rng: Optional[_random.Random] = None
        self.origins: list[tuple[str, int, int]] = []
        self.bases: list[Frame] = []
        self.executions: Counter = Counter()
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

    def unknown(self, key: str, message: str) -> None:
        self.signals.unknown_read = True
        self.warn(key, message)

    # --- variables -----------------------------------------------------------------------
    def scope_of(self, name: ast.Name) -> Scope:
        return self.stack[-1].scope if name.is_local else self.globals

    def key(self, name: ast.Name) -> str:
        if not name.index:
            return norm(name.name)
        parts = []
        for e in name.index:
            value = self.eval.real(e)
            if value != math.floor(value) or value < 0:
                raise self.error(f"array index of {name.name} must be a whole number >= 0, got {value:g}")
            parts.append(str(int(value)))
        return f"{norm(name.name)}[{','.join(parts)}]"

    def _get(self, kind: str, name: ast.Name, what: str, hint: str):
        k = self.key(name)
        value = self.scope_of(name).get(kind, k)
        if value is None:
            shown = name.name + (k[k.index("["):] if "[" in k else "")
            other = [o for o in ("real", "pose") if o != kind and kind in ("real", "pose")
                     and self.scope_of(name).has(o, k)]
            if other:
                raise self.error(f"'{shown}' is a {other[0]} variable, not a {kind}")
            raise self.error(f"{what} '{shown}' is not defined; {hint}")
        return value

    def get_real(self, name: ast.Name) -> float:
        if name.kind != "value":
            raise self.error(f"expected a number, found the {'string' if name.kind == 'string' else 'joint value'} "
                             f"{name.name}")
        return self._get("real", name, "real variable", "assign it first or add it to .REALS")

    def get_string(self, name: ast.Name) -> str:
        return self._get("string", name, "string variable", "assign it first or add it to .STRINGS")

    def get_pose(self, name: ast.Name) -> Frame:
        return self._get("pose", name, "pose", "add it to .TRANS or assign it with POINT")

    def get_joints(self, name: ast.Name) -> tuple[float, ...]:
        return self._get("joint", name, "joint pose", "add it to .JOINTS or assign it with POINT")

    def has_real(self, name: ast.Name) -> bool:
        return self.scope_of(name).has("real", self.key(name))

    def has_pose(self, name: ast.Name) -> bool:
        return self.scope_of(name).has("pose", self.key(name))

    def set(self, kind: str, name: ast.Name, value) -> None:
        self.scope_of(name).set(kind, self.key(name), value)

    def set_string(self, name: ast.Name, value: str) -> None:
        self.set("string", name, value)

    def exists(self, function: str, text: str) -> bool:
        kind = {"EXISTREAL": "real", "EXISTTRANS": "pose", "EXISTJOINT": "joint", "EXISTCHAR": "string"}.get(function)
        if kind is None:
            return text.lower() in self.programs
        name = ast.Name(text)
        return self.scope_of(name).has(kind, norm(text)) if text else False

    def sig(self, numbers: list[int]) -> float:
        result = True
        for n in numbers:
            if n == 0:
                raise self.error("signal number 0 does not exist")
            on, known = self.signals.state(abs(n))
            if not known:
                self.warn(f"input:{abs(n)}", f"input {abs(n)} is not given; taken as OFF (set it with --inputs or "
                          "the scenario's inputs)")
            result = result and (on == (n > 0))
        return -1.0 if result else 0.0

    def read_bits(self, start: int, count: int) -> int:
        if not 1 <= count <= 32:
            raise self.error(f"BITS count must be 1 to 32, got {count}")
        value = 0
        for i in range(count):
            on, known = self.signals.state(start + i)
            if not known:
                self.warn(f"input:{start + i}", f"input {start + i} is not given; taken as OFF")
            value |= int(on) << i
        return value

    def set_signal(self, number: int, on: bool) -> None:
        if number == self.gun:
            self.controller.switch_gun(on)
        elif is_input(number):
            self.warn(f"set-input:{number}", f"signal {number} is an input; the program sets it here")
        self.signals.set(number, on)

    def switch_state(self, name: str) -> bool:
        return self.controller.cp if name == "CP" else self.switches.get(name, False)

    def random(self) -> float:
        if self.rng is None:
            self.rng = _random.Random(0)
            self.warn("random", "RANDOM gives a fixed pseudo-random sequence (seed 0), the same on every run")
        return self.rng.random()

    # --- running -------------------------------------------------------------------------
    def program(self, name: str) -> ast.Program:
        found = self.programs.get(name.lower())
        if found is None:
            raise self.error(f"no program named '{name}' (loaded: {', '.join(p.name for p in self.programs.values())})")
        return found

    def call(self, program: ast.Program, args: tuple[ast.Expr, ...]) -> None:
        if len(self.stack) >= MAX_CALL_DEPTH:
            raise self.failure(f"CALLs nested more than {MAX_CALL_DEPTH} deep (a program calling itself?)")
        if len(args) > len(program.params):
            raise self.error(f"program '{program.name}' takes {len(program.params)} argument(s), {len(args)} given")
        scope, copy_back = Scope(), []
        for param, arg in zip(program.params, args):
            formal = ast.Name(param.name)
            by_ref = param.by_ref or isinstance(arg, ast.Ref)
            actual = arg.target if isinstance(arg, ast.Ref) else arg
            if by_ref and not isinstance(actual, ast.Name):
                raise self.error(f"argument for {param.name} of '{program.name}' is passed by reference; give a variable")
            kinds = [k for k in ("real", "string", "pose", "joint") if isinstance(actual, ast.Name)
                     and self.scope_of(actual).has(k, self.key(actual))] if by_ref else [self.eval.kind(actual)]
            for kind in kinds:
                value = {"real": self.eval.real, "string": self.eval.string, "pose": self.eval.pose,
                         "joint": self.eval.joints}[kind](actual)
                scope.set(kind, norm(formal.name), value)
            if by_ref:
                copy_back.append((formal, actual))
        caller_line = self.line
        self.stack.append(_Frame(program, scope, {}))
        try:
            self.execute(self.compiled(program))
        except ReturnFromProgram:
            pass
        finally:
            frame = self.stack.pop()
            self.line = caller_line
        for formal, actual in copy_back:
            for kind in ("real", "string", "pose", "joint"):
                value = frame.scope.get(kind, norm(formal.name))
                if value is not None:
                    self.set(kind, actual, value)

    def compiled(self, program: ast.Program) -> Code:
        code = self.code.get(program.name.lower())
        if code is None:
            code = self.code[program.name.lower()] = compile_program(program)
        return code

    def execute(self, code: Code) -> None:
        ops, n, pc = code.ops, len(code.ops), 0
        frame = self.stack[-1]
        name = frame.program.name
        truth = self.eval.truth
        while pc < n:
            op = ops[pc]
            self.steps += 1
            if self.steps > self.max_steps:
                self.line = op[1]
                raise self.budget_error()
            kind, self.line = op[0], op[1]
            if kind == EXEC:
                self.executions[(name, self.line)] += 1
                execute_statement(self, op[2])
                moves = self.controller.moves
                if len(moves) > len(self.origins):  # (moves of a CALL were recorded inside it)
                    for m in moves[len(self.origins):]:
                        self.origins.append((name, m.first_line, m.line))
                        self.bases.append(self.base)
                pc += 1
            elif kind == JUMP:
                pc = self.jump(code, pc, op[3])
            elif kind == JUMP_IF_FALSE:
                pc = pc + 1 if truth(op[2]) else self.jump(code, pc, op[3])
            elif kind == JUMP_IF_TRUE:
                pc = self.jump(code, pc, op[3]) if truth(op[2]) else pc + 1
            elif kind == FOR_INIT:
                st = op[2]
                step = 1.0 if st.step is None else self.eval.real(st.step)
                start, stop = self.eval.real(st.start), self.eval.real(st.stop)
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

    def jump(self, code: Code, pc: int, target: int) -> int:
        if target <= pc:
            self.last_loop = (self.source, *code.loops.get(pc, (self.line, "loop")))
        return target

    def case(self, op: tuple) -> int:
        st: ast.Case = op[2]
        value = self.eval.string if st.string else self.eval.real
        subject = value(st.subject)
        for (values, _, _), target in zip(st.branches, op[3]):
            if any(value(v) == subject for v in values):
                return target
        return op[4]

    def budget_error(self) -> ExecutionError:
        if self.last_loop is not None:
            source, line, what = self.last_loop
            return ExecutionError(f"{source}:{line}: the program ran {self.max_steps} steps without ending, in the "
                                  f"{what} of line {line}; an endless cycle? (end it with STOP or HALT)")
        return self.failure(f"the program ran {self.max_steps} steps without ending")

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
        return self.controller.toolpath(main.name, decode_header(main.metadata, main.name), tuple(self.warnings.lines))


def interpret_run(files: Union[ast.AsFile, Sequence[ast.AsFile]], gun_signal: int = 1, program: Optional[str] = None,
                  *, inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                  full_speed_mm_s: float = FULL_SPEED_MM_S, max_steps: int = MAX_STEPS) -> Run:
    """Run the main program of ``files`` (``program``, else the first one loaded that is not a
    background PC program ``*.pc``) and report where each move comes from."""
    files = (files,) if isinstance(files, ast.AsFile) else tuple(files)
    if gun_signal < 1:
        raise InputError(f"gun signal {gun_signal}: must be an output number >= 1")
    all_programs = [p for f in files for p in f.programs]
    if not all_programs:
        names = ", ".join(f.source for f in files)
        raise InputError(f"{names}: no .PROGRAM section; expected '.PROGRAM name()' ... '.END'")
    run = Interpreter(files, gun_signal, inputs or {}, kinematics, full_speed_mm_s, max_steps)
    if program is None:  # PC programs (autostart.pc, ...) are background tasks, never the robot's main program
        main = next((p for p in all_programs if not p.name.lower().endswith(".pc")), all_programs[0])
    else:
        main = run.programs.get(program.lower())
        if main is None:
            names = ", ".join(p.name for p in all_programs)
            raise InputError(f"{files[0].source}: no program named '{program}' (loaded: {names})")
    toolpath = run.run(main)
    return Run(toolpath, tuple(run.origins), tuple(run.bases), dict(run.executions), dict(run.programs),
               run.controller.gun_on, run.stopped)


def interpret(files: Union[ast.AsFile, Sequence[ast.AsFile]], gun_signal: int = 1, program: Optional[str] = None,
              **options) -> ToolPath:
    """The ToolPath of the main program; InputError naming file and line on anything the
    program cannot mean, ExecutionError on what the twin cannot run."""
    return interpret_run(files, gun_signal, program, **options).toolpath

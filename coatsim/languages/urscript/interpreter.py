"""URScript -> ToolPath: runs a script's statements, expressions and functions.

Which code runs: the script's top-level statements, in order; when they call none of the
functions the script defines (a file holding ``def prog(): … end`` alone, as Polyscope exports
and as the controller runs a script sent to it), the main function then runs too: the one the
reading names, else the function without parameters no other function calls (the last such).
Functions may be defined inside others (Polyscope defines a program's functions inside it). Variables: top-level assignments and ``global`` ones
are global; inside a function an assignment is local unless the name is global already or
declared ``global`` (as Polyscope programs rely on). A variable the script reads but never sets
(an installation variable, a feature) is an unknown unless the reading gives it
(:mod:`coatsim.languages.script.unknowns`): what needs its value is skipped and listed.
``pose_trans(feature, p)`` with ``feature`` a pose variable gives ``p`` in that frame, the user
frame the reading reports for the move. Threads (``thread``/``run``) are noted, not run. The robot's functions (motions, the TCP, outputs, waits) are in :mod:`.robot_calls`.
"""

from __future__ import annotations

import math
from typing import Optional, Sequence

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.urscript.blend import note_overlaps
from coatsim.languages.urscript.evaluate import Expressions
from coatsim.languages.urscript.parser import Expr, Statement
from coatsim.languages.urscript.robot_calls import RobotCalls
from coatsim.languages.urscript.values import PURE, FramedPose, PoseValue
from coatsim.languages.script.unknowns import DependsOn, Unset, UnknownLog, require_known, unset_names
from coatsim.path.language import ReadOptions
from coatsim.path.process_record import read_comment_lines
from coatsim.path.toolpath import ToolPath

MAX_CALL_DEPTH = 64


class _Return(Exception):
    def __init__(self, value) -> None:
        self.value = value


class _Halt(Exception):
    pass


_BREAK, _CONTINUE = "break", "continue"


class UrRun(Expressions):
    """One run of a script."""

    def __init__(self, statements: tuple[Statement, ...], comments: Sequence[str], source: str,
                 options: ReadOptions, name: str) -> None:
        self.statements, self.comments, self.source, self.options, self.name = statements, comments, source, options, name
        self.line = 0
        self.running: list[str] = [name]  # the function running, innermost last
        self.robot = RobotCalls(source, options, lambda: self.line, lambda: self.running[-1])
        self.globals: dict[str, object] = {}
        self.functions: dict[str, Statement] = {}
        self.depth = 0
        self.unknown = UnknownLog("an installation variable or a feature the controller keeps")

    # --- messages -----------------------------------------------------------------------
    def error(self, message: str) -> InputError:
        return InputError(f"{self.source}:{self.line}: {message}")

    # --- running ------------------------------------------------------------------------
    def run(self) -> ToolPath:
        """Run the script; ``main`` is then the main function (None: the top level), ``ended`` how
        the run ended."""
        for st in self.statements:
            if st.kind == "def":
                self.functions.setdefault(st.name, st)
        self.main = main = self.main_function()
        self.ended = f"it ends at line {self.statements[-1].line if self.statements else 1}"
        try:
            self.block(self.statements, None)
            if main is not None:
                self.line = main.line
                self.invoke(main, (), (), main.line)
        except _Halt:
            self.ended = f"{self.source}:{self.line}: halt ends it"
        note_overlaps(self.robot.builder, self.source)
        process = read_comment_lines(self.comments, self.source)
        return self.robot.builder.toolpath(main.name if main is not None else self.name, process)

    def main_function(self) -> Optional[Statement]:
        """The function to run after the top level, None when the top level calls one itself."""
        wanted = self.options.program
        if wanted is not None:
            if wanted not in self.functions or self.functions[wanted].scope != "def":
                raise InputError(f"{self.source}: the script defines no function {wanted!r}", parameters=("program",))
            return self.functions[wanted]
        if self._callees(tuple(st for st in self.statements if st.kind != "def")) & set(self.functions):
            return None
        called = {name for st in self.statements if st.kind == "def" for name in self._callees(st.body)}
        roots = [st for st in self.statements if st.kind == "def" and st.scope == "def" and not st.params
                 and st.name not in called]
        return roots[-1] if roots else None

    def _callees(self, body: tuple[Statement, ...]) -> set[str]:
        """Names of the functions a body calls."""
        found: set[str] = set()

        def walk(expr) -> None:
            if isinstance(expr, tuple) and expr:
                if expr[0] == "call":
                    found.add(expr[1])
                for item in expr[1:]:
                    walk(item)

        for st in body:
            for expr in (st.value, st.target, *(c for c, _ in st.branches), *st.args):
                walk(expr)
            found |= self._callees(st.body) | {n for _, b in st.branches for n in self._callees(b)}
        return found

    def block(self, statements: tuple[Statement, ...], scope: Optional[dict]) -> Optional[str]:
        for st in statements:
            self.line = st.line
            self.robot.builder.step(st.line)
            try:
                signal = self.statement(st, scope)
            except DependsOn as unknown:
                self.unknown.skip(f"{self.source}:{st.line}", _what(st), unknown.names)
                continue
            if signal is not None:
                return signal
        return None

    def statement(self, st: Statement, scope: Optional[dict]) -> Optional[str]:
        kind = st.kind
        if kind == "def":
            self.functions[st.name] = st  # Polyscope defines a program's functions inside it
            return None
        if kind == "assign":
            self.assign(st, scope)
        elif kind == "expr":
            self.evaluate(st.value, scope)
        elif kind == "if":
            for condition, body in st.branches:
                if self.truth(self.evaluate(condition, scope)):
                    return self.block(body, scope)
        elif kind == "while":
            return self.repeat(st, scope)
        elif kind == "for":
            return self.loop(st, scope)
        elif kind == "return":
            raise _Return(None if st.value is None else self.evaluate(st.value, scope))
        elif kind in (_BREAK, _CONTINUE):
            return kind
        elif kind == "halt":
            raise _Halt()
        elif kind == "note":
            self.robot.builder.warn(f"note:{st.name}", f"{self.source}:{st.line}: {st.name} (a thread) is not simulated")
        return None

    def repeat(self, st: Statement, scope: Optional[dict]) -> Optional[str]:
        """A while loop; one that repeats forever (``while True``) with motions in it is a cycle the
        robot repeats: the twin runs it once."""
        condition, body = st.branches[0]
        endless = condition == ("bool", True)
        waiting = all(s.kind == "expr" and s.value[0] == "call" and s.value[1] in ("sync", "sleep") for s in body)
        unknown = self.robot.unknown_reads
        while self.truth(self.evaluate(condition, scope)):
            if waiting and self.robot.unknown_reads > unknown:
                self.robot.builder.warn(f"wait:{st.line}", f"{self.source}:{st.line}: the loop waits for an input "
                                        "nobody gives; taken as met")
                break
            motions = len(self.robot.builder.moves)
            signal = self.block(body, scope)
            self.line = st.line
            self.robot.builder.step(st.line)
            if signal == _BREAK:
                break
            if signal not in (None, _CONTINUE):
                return signal
            if endless and len(self.robot.builder.moves) > motions:
                self.robot.builder.warn(f"cycle:{st.line}", f"{self.source}:{st.line}: the loop repeats forever (a "
                                        "cycle); the twin runs it once")
                break
        return None

    def loop(self, st: Statement, scope: Optional[dict]) -> Optional[str]:
        bounds = [self.number(self.evaluate(a, scope)) for a in st.args]
        if not 1 <= len(bounds) <= 3 or any(b != int(b) for b in bounds):
            raise self.error("range() takes 1 to 3 whole numbers")
        for value in range(*(int(b) for b in bounds)):
            self.store(st.name, value, scope, "")
            signal = self.block(st.body, scope)
            if signal == _BREAK:
                break
            if signal not in (None, _CONTINUE):
                return signal
        return None

    # --- variables ----------------------------------------------------------------------
    def store(self, name: str, value, scope: Optional[dict], declared: str) -> None:
        if scope is None or declared == "global" or (declared != "local" and name in self.globals and
                                                     name not in scope):
            self.globals[name] = value
        else:
            scope[name] = value

    def assign(self, st: Statement, scope: Optional[dict]) -> None:
        value = self.evaluate(st.value, scope)
        if st.target[0] == "name":
            self.store(st.target[1], self.copy(value), scope, st.scope)
            return
        container = self.evaluate(st.target[1], scope)
        position = self.evaluate(st.target[2], scope)
        names = unset_names((container, position, value))
        if names and (isinstance(container, (PoseValue, Unset)) or isinstance(position, Unset)):
            self.store(st.target[1][1], Unset(names), scope, "")  # an element unknown: the whole value is
            return
        index = self.index(position, container)
        if isinstance(container, PoseValue):
            items = list(container)
            items[index] = self.number(value)
            self.store(st.target[1][1], PoseValue(items), scope, "")
        else:
            container[index] = value

    @staticmethod
    def copy(value):
        return list(value) if isinstance(value, list) else value

    def call(self, expr: Expr, scope: Optional[dict]):
        _, name, arg_exprs, kwarg_exprs, line = expr
        args = tuple(self.evaluate(a, scope) for a in arg_exprs)
        kwargs = tuple((k, self.evaluate(v, scope)) for k, v in kwarg_exprs)
        self.line = line
        if name in self.functions:
            return self.invoke(self.functions[name], args, kwargs, line)
        if name in PURE and unset_names(args + tuple(v for _, v in kwargs)):
            return Unset(unset_names(args + tuple(v for _, v in kwargs)))
        if name in PURE:
            if kwargs:
                raise self.error(f"{name}() takes no keyword arguments")
            try:
                result = PURE[name](*args)
            except (TypeError, ValueError, OverflowError, ZeroDivisionError) as exc:
                raise self.error(f"{name}(): {exc}") from None
            if isinstance(result, float) and not math.isfinite(result):
                raise self.error(f"{name}() has no finite value here")
            return _framed(name, arg_exprs, args, result)
        if self.robot.harmless(name):
            return None  # a message or a set-up value: an unknown in it changes no motion
        require_known(args + tuple(v for _, v in kwargs))
        return self.robot.call(name, args, kwargs)

    def invoke(self, function: Statement, args: tuple, kwargs: tuple, line: int):
        if function.scope != "def":
            self.robot.builder.warn(f"thread:{function.name}", f"{self.source}:{line}: {function.name} is a "
                                    f"{function.scope}; it is not run")
            return None
        if self.depth >= MAX_CALL_DEPTH:
            raise ExecutionError(f"{self.source}:{line}: calls nest deeper than {MAX_CALL_DEPTH}")
        local: dict[str, object] = {}
        given = dict(kwargs)
        if len(args) > len(function.params) or set(given) - set(function.params):
            raise self.error(f"{function.name}() takes the parameters {', '.join(function.params) or 'none'}")
        for k, param in enumerate(function.params):
            if k < len(args):
                local[param] = self.copy(args[k])
            elif param in given:
                local[param] = self.copy(given[param])
            elif function.defaults[k] is not None:
                local[param] = self.evaluate(function.defaults[k], None)
            else:
                raise self.error(f"{function.name}() needs its parameter {param}")
        self.depth += 1
        self.running.append(function.name)
        try:
            self.block(function.body, local)
        except _Return as result:
            return result.value
        finally:
            self.running.pop()
            self.depth -= 1
            self.line = line
        return None


def _what(st: Statement) -> str:
    """A statement as a skipped one is named: the function it calls, the variable it sets, its keyword."""
    if st.kind == "expr" and st.value[0] == "call":
        return f"{st.value[1]}()"
    if st.kind == "assign":
        target = st.target[1] if st.target[0] == "name" else st.target[1][1]
        return f"the assignment to {target}"
    return st.kind


def _framed(name: str, arg_exprs: tuple, args: tuple, result):
    """``pose_trans(feature, p)`` with ``feature`` a pose variable: the pose given in that frame
    (a pose already given in one keeps its frame: ``pose_trans(target, tool_offset)``)."""
    if name != "pose_trans" or not isinstance(result, PoseValue):
        return result
    first = args[0]
    if isinstance(first, FramedPose):
        return FramedPose(result, first.feature)
    if arg_exprs[0][0] == "name":
        return FramedPose(result, first)
    return result

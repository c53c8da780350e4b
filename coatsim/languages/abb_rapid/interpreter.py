"""RAPID modules run: the moves, rests and output switches of the entry routine's run.

Runs the entry routine (``main``, or the one named) with the routines it calls, its data
(``CONST``, ``PERS``, ``VAR``; routine data local to each call), ``IF``/``FOR``/``WHILE``/``TEST``,
labels and ``GOTO``, user ``FUNC``s. Motions follow :mod:`.motion`; ``SetDO``/``Set``/``Reset``
switch outputs, each numbered by the digits its name ends with (``do1``, ``DO_12``) or by a
``variables`` entry ``NAME=number``. ``WaitTime`` is a rest at the last point, ``WaitDI``/
``WaitUntil`` wait for the inputs given (assumed met otherwise, with a warning). Interrupts
(``CONNECT``, ``ISignalDI``) and ``TRAP`` routines are noted, not run; error handlers are not run.
What a statement reads that no file gives (data of another module, a routine not loaded) skips
the statement and is listed; a step budget stops a program that never ends.
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.languages.abb_rapid import data as d
from coatsim.languages.abb_rapid import syntax as s
from coatsim.languages.abb_rapid.evaluate import Expressions, Unknown
from coatsim.languages.abb_rapid.instructions import Instructions
from coatsim.languages.abb_rapid.motion import Motions
from coatsim.languages.script import nodes as n
from coatsim.languages.script.flow import Halt, Jump, Return
from coatsim.languages.script.unknowns import UnknownLog
from coatsim.path.language import ReadOptions
from coatsim.path.reading import MoveSource, OutputSwitch
from coatsim.path.toolpath import Dwell

MAX_STEPS = 1_000_000
MAX_CALL_DEPTH = 50
_POSITIONS = ("robtarget", "pose", "orient")  # the types whose declaration without a value is no value


class Interpreter(Instructions, Expressions, Motions):
    """One run of a RAPID program."""

    def __init__(self, modules: Sequence[s.Module], options: ReadOptions) -> None:
        self.modules, self.options = modules, options
        self.routines: dict[str, s.Routine] = {}
        self.globals: dict[str, tuple[str, Any]] = {}
        self.frames: list[dict[str, tuple[str, Any]]] = []
        self.moves: list = []
        self.sources: list[MoveSource] = []
        self.move_frames: list[Pose] = []
        self.dwells: list[Dwell] = []
        self.warnings: dict[str, str] = {}
        self.switches: list[OutputSwitch] = []
        self.outputs: set[int] = set()
        self.unnumbered: dict[str, str] = {}  # signal name -> where it is first switched
        self.skipped: list[str] = []
        self.unsimulated: list[str] = []
        self.unknowns: dict[str, str] = {}  # the inputs read that nobody gives
        self.valueless: set[int] = set()  # ids of the positions declared without a value, not set since
        self.unknown = UnknownLog("a variable of a module the files loaded do not include")
        self.spraying = False
        self.steps = 0
        self.line, self.source, self.routine = 0, modules[0].source, ""
        self.init_motion()
        for m in modules:
            for r in m.routines:
                key = r.name.lower()
                if key in self.routines:
                    other = self.routines[key]
                    raise InputError(f"{r.source}:{r.line}: routine {r.name} is also defined in {other.source}:"
                                     f"{other.line}")
                self.routines[key] = r
        for m in modules:
            self.source = m.source
            for decl in m.data:
                self.globals[decl.name.lower()] = self._declare(decl)

    # --- messages -------------------------------------------------------------------------
    def where(self, line: Optional[int] = None) -> str:
        return f"{self.source}:{self.line if line is None else line}"

    def error(self, message: str) -> InputError:
        return InputError(f"{self.where()}: {message}")

    def failure(self, message: str) -> ExecutionError:
        return ExecutionError(f"{self.where()}: {message}")

    def warn(self, key: str, message: str) -> None:
        self.warnings.setdefault(key, f"{self.where()}: {message}")

    # --- data -----------------------------------------------------------------------------
    def _declare(self, decl: s.DataDecl) -> tuple[str, Any]:
        self.line = decl.line
        if decl.dims:
            sizes = [int(self._num(self.eval(e))) for e in decl.dims]
            value: Any = self.eval(decl.value) if decl.value is not None else None
            return decl.type, self._array(decl.type, sizes, value)
        value = d.default(decl.type) if decl.value is None else d.coerce(decl.type, self.eval(decl.value), self.error)
        if decl.value is None and decl.type in _POSITIONS:
            self.valueless.add(id(value))  # its zero quaternion is no orientation: reading it is an unknown
        return decl.type, value

    def _array(self, type_: str, sizes: list[int], value: Any) -> list:
        if value is None:
            return [self._array(type_, sizes[1:], None) if len(sizes) > 1 else d.default(type_) for _ in range(sizes[0])]
        if not isinstance(value, list) or len(value) != sizes[0]:
            raise self.error(f"an array of {sizes[0]} where {d._shown(value)} is given")
        return [self._array(type_, sizes[1:], v) if len(sizes) > 1 else d.coerce(type_, v, self.error) for v in value]

    def lookup(self, name: str, line: int) -> Any:
        key = name.lower()
        declared = False
        for scope in (self.frames[-1] if self.frames else {}, self.globals):
            if key in scope:
                declared = id(scope[key][1]) in self.valueless
                if not declared:
                    return scope[key][1]
                break
        if key in d.PREDEFINED and not declared:
            return d.PREDEFINED[key][1]
        for given, text in self.options.variables.items():
            if given.lower() == key:
                return self._given(given, text)
        raise Unknown(name, line, declared)

    def _given(self, name: str, text: Any) -> Any:
        if isinstance(text, (int, float)):
            return float(text)
        from coatsim.languages.script.parse import Stream
        from coatsim.languages.script.tokens import NEWLINE, tokenize
        from coatsim.languages.abb_rapid.parser import _aggregate, _argument

        tokens = [t for t in tokenize(str(text), s.SYNTAX, f"{name}=") if t.kind != NEWLINE]
        return self.eval(Stream(tokens, f"value of {name}", s.GRAMMAR, _aggregate, _argument).expression())

    def _assign(self, target: n.Expr, value: Any) -> None:
        path: list = []
        e = target
        while isinstance(e, (n.Field, n.Index)):
            path.append(e)
            e = e.base
        if not isinstance(e, n.Name):
            raise self.error("the left of := must be data")
        key = e.name.lower()
        scope = self.frames[-1] if self.frames and key in self.frames[-1] else self.globals
        if key not in scope:
            raise Unknown(e.name, target.line)
        type_, current = scope[key]
        self.valueless.discard(id(current))  # set, whole or in part: it has a value
        if not path:
            scope[key] = (type_, d.coerce(type_, value, self.error) if not isinstance(current, list) else value)
            return
        holder = current
        for step in reversed(path[1:]):
            holder = self._child(holder, step)
        last = path[0]
        if isinstance(last, n.Field):
            if not isinstance(holder, d.Record) or last.field.lower() not in holder.fields:
                raise self.error(f"no component {last.field}")
            field_type = dict(d.RECORDS[holder.type])[last.field.lower()]
            holder.fields[last.field.lower()] = d.coerce(field_type, value, self.error)
        else:
            k = int(self._num(self.eval(last.index[-1])))
            if not isinstance(holder, list) or not 1 <= k <= len(holder):
                raise self.error(f"index {k} out of the array")
            holder[k - 1] = d.coerce(type_, value, self.error)

    def _child(self, holder: Any, step: n.Expr) -> Any:
        if isinstance(step, n.Field):
            return holder.fields[step.field.lower()]
        for i in step.index:
            holder = holder[int(self._num(self.eval(i))) - 1]
        return holder

    # --- running --------------------------------------------------------------------------
    def run(self, entry: str) -> None:
        routine = self.routines.get(entry.lower())
        if routine is None:
            procs = [r.name for r in self.routines.values() if r.kind == "PROC"]
            raise InputError(f"{self.modules[0].source}: no PROC {entry} in the files loaded"
                             + (f" (routines: {', '.join(procs)})" if procs else ""))
        self.main = routine
        try:
            self.call(routine, ())
        except Halt as stop:
            self.stopped = stop.how

    def call(self, routine: s.Routine, args: tuple[n.Arg, ...]) -> Any:
        if len(self.frames) >= MAX_CALL_DEPTH:
            raise self.failure(f"calls nested deeper than {MAX_CALL_DEPTH} (a routine calling itself?): {routine.name}")
        frame = self._bind(routine, args)
        saved = (self.source, self.routine)
        self.frames.append(frame)
        self.source, self.routine = routine.source, routine.name
        returned, value = False, None
        try:
            for decl in routine.data:
                frame[decl.name.lower()] = self._declare(decl)
            self.block(routine.body)
        except Return as ret:
            returned, value = True, ret.value
        finally:
            self.frames.pop()
            self.source, self.routine = saved
        self._pass_back(routine, args, frame)
        if routine.kind == "FUNC" and not returned:
            raise self.failure(f"FUNC {routine.name} ends without RETURN")
        return value

    def _pass_back(self, routine: s.Routine, args: tuple[n.Arg, ...], frame: dict) -> None:
        """A VAR, PERS or INOUT parameter is the caller's data itself: what the routine made of it
        is the caller's."""
        required = [p for p in routine.params if not p.optional]
        positional = [a for a in args if a.name is None]
        for p, a in zip(required, positional):
            if p.mode != "IN" and isinstance(a.value, (n.Name, n.Field, n.Index)):
                self._assign(a.value, frame[p.name.lower()][1])

    def _bind(self, routine: s.Routine, args: tuple[n.Arg, ...]) -> dict:
        required = [p for p in routine.params if not p.optional]
        positional = [a for a in args if a.name is None]
        if len(positional) != len(required):
            raise self.error(f"{routine.name} takes {len(required)} argument{'s' if len(required) != 1 else ''} "
                             f"({', '.join(p.name for p in required)}), got {len(positional)}")
        frame: dict[str, tuple[str, Any]] = {}
        for p, a in zip(required, positional):
            frame[p.name.lower()] = (p.type, d.coerce(p.type, self.eval(a.value), self.error))
        optional = {p.name.lower(): p for p in routine.params if p.optional}
        self._present = getattr(self, "_present", [])
        for a in args:
            if a.name is None:
                continue
            p = optional.get(a.name.lower())
            if p is None:
                raise self.error(f"{routine.name} has no optional argument \\{a.name}")
            value = True if a.value is None else d.coerce(p.type, self.eval(a.value), self.error)
            frame[p.name.lower()] = (p.type, value)
        return frame

    def present(self, e: n.Expr) -> bool:
        return isinstance(e, n.Name) and bool(self.frames) and e.name.lower() in self.frames[-1]

    def block(self, body: tuple) -> None:
        labels = {st.name.lower(): k for k, st in enumerate(body) if isinstance(st, s.Label)}
        k = 0
        while k < len(body):
            try:
                self.statement(body[k])
                k += 1
            except Jump as jump:
                if jump.label.lower() not in labels:
                    raise
                k = labels[jump.label.lower()]

    def statement(self, st) -> None:
        self.steps += 1
        if self.steps > MAX_STEPS:
            raise self.failure(f"more than {MAX_STEPS} statements run: a loop that never ends?")
        self.line = st.line
        try:
            self._execute(st)
        except Unknown as unknown:
            self.unknown.read(unknown.name, self.where(unknown.line), unknown.name.lower())
            which = "which has no value (declared without one)" if unknown.declared else "which no file declares"
            self.skipped.append(f"{self.where()}: statement skipped: it reads {unknown.name}, {which}")

    def _execute(self, st) -> None:
        if isinstance(st, s.Assign):
            self._assign(st.target, self.eval(st.value))
        elif isinstance(st, s.ProcCall):
            self.instruction(st)
        elif isinstance(st, s.If):
            for cond, body in st.branches:
                if self._bool(self.eval(cond)):
                    self.block(body)
                    return
            self.block(st.orelse)
        elif isinstance(st, s.For):
            self._for(st)
        elif isinstance(st, s.While):
            while self._bool(self.eval(st.cond)):
                self.block(st.body)
                self.line = st.line
        elif isinstance(st, s.Test):
            value = self.eval(st.value)
            for values, body in st.cases:
                if any(self.eval(v) == value for v in values):
                    self.block(body)
                    return
            if st.default is not None:
                self.block(st.default)
        elif isinstance(st, s.Goto):
            raise Jump(st.label)
        elif isinstance(st, s.Return):
            raise Return(None if st.value is None else self.eval(st.value))
        elif isinstance(st, s.Connect):
            self.warn("interrupt", f"interrupts (CONNECT ... WITH {st.trap}) are noted, not run: TRAP routines do not "
                                   "run in the twin")

    def _for(self, st: s.For) -> None:
        start, stop = self._num(self.eval(st.start)), self._num(self.eval(st.stop))
        step = self._num(self.eval(st.step)) if st.step is not None else (1.0 if stop >= start else -1.0)
        if step == 0:
            raise self.error("FOR ... STEP 0 never ends")
        frame = self.frames[-1]
        key = st.var.lower()
        saved = frame.get(key)
        value = start
        while (value <= stop) if step > 0 else (value >= stop):
            frame[key] = ("num", value)
            self.block(st.body)
            self.line = st.line
            value += step
        if saved is not None:
            frame[key] = saved
        else:
            frame.pop(key, None)

    def call_function(self, call: n.Call) -> Any:
        value = self.builtin_function(call)
        if value is not None:
            return value
        routine = self.routines.get(call.name.lower())
        if routine is None or routine.kind != "FUNC":
            raise Unknown(call.name, call.line)
        saved = self.line
        result = self.call(routine, call.args)
        self.line = saved
        return d.coerce(routine.type, result, self.error)

    def add_move(self, move, call: s.ProcCall, frame: Pose) -> None:
        self.moves.append(move)
        self.sources.append(MoveSource(self.source, self.routine, call.line, call.end_line))
        self.move_frames.append(frame)

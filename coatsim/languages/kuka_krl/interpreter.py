"""KRL routines -> the ToolPath the robot executes, with the Reading check-program needs: the
statements and data here, expressions in :mod:`.evaluate`, motions in :mod:`.motion`.

Runs the main routine (the first ``DEF`` of the first file, or the one named) with the routines
it calls, the ``.dat`` data (``DECL E6POS``/``FRAME``/``POS`` ...), declarations, assignments,
``IF``/``FOR``/``WHILE``/``LOOP``/``REPEAT``/``SWITCH``/``GOTO``. Motions: ``PTP``, ``LIN``,
``CIRC aux, end`` (``CA`` not simulated), ``LIN_REL``/``PTP_REL``; a target's missing components
are the current position's; poses are in ``$BASE`` (``BASE_DATA[n]``, ``BAS(#BASE, n)``) with
``$TOOL`` (``TOOL_DATA[n]``, ``BAS(#TOOL, n)``); ``A : B`` composes frames. Speed ``$VEL.CP`` in
m/s (``BAS(#VEL_CP, v)``); a point is an exact stop unless the motion carries ``C_DIS`` (blended
within ``$APO.CDIS`` mm, cut to half the neighbouring moves; ``C_VEL``, ``C_ORI`` and ``C_PTP``
are modelled as ``C_DIS``, a warning says so).

Outputs (KUKA System Software 8, "Advance run"): ``$OUT[n] = ...`` stops the advance run, so the
motion before it ends at rest and the output switches there (approximation is not possible);
after ``CONTINUE`` it is set in the advance run — the twin switches it as the next motion starts
and warns that the controller may set it up to ``$ADVANCE`` motions earlier; ``$OUT_C[n]`` and
``TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[n]=...`` switch as the next motion starts (``DISTANCE=1``:
as the one after starts, at its start point's approximation), without a stop. ``WAIT SEC`` and
``WAIT FOR`` stop the advance run (a rest); interrupts and ``TRIGGER WHEN PATH`` are noted.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, Optional, Sequence

from coatsim.core.errors import ExecutionError, InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.geometry.space.pose import Pose
from coatsim.languages.kuka_krl import values as v
from coatsim.languages.kuka_krl.blocks import Block, build
from coatsim.languages.kuka_krl.evaluate import Expressions, Unknown
from coatsim.languages.kuka_krl.motion import DEFAULT_VEL_CP_M_S, MOTION_DATA, Motions
from coatsim.languages.kuka_krl.names import MAX_NAME_LENGTH
from coatsim.languages.kuka_krl.parser import Line, Routine, parse_krl, split_commas
from coatsim.languages.kuka_krl.statements import MAX_STEPS, Statements
from coatsim.languages.script import nodes as n
from coatsim.languages.script.flow import Halt, Jump, Return
from coatsim.languages.script.tokens import NAME, OP
from coatsim.languages.script.unknowns import UnknownLog
from coatsim.path.language import ReadOptions
from coatsim.path.process_record import decode as decode_record
from coatsim.path.reading import MoveSource, OutputSwitch, Reading
from coatsim.path.toolpath import Dwell, ToolFrame, ToolPath

MAX_CALL_DEPTH = 50
RECORD = re.compile(r"^\s*;\s*coatsim:\s*([^=]+?)\s*=(.*)$", re.MULTILINE)


class Interpreter(Statements, Expressions, Motions):
    """One run of a KRL program."""

    def __init__(self, routines: Sequence[Routine], datas, options: ReadOptions) -> None:
        self.options = options
        self.routines = {r.name.lower(): r for r in routines}
        self.globals: dict[str, Any] = {}
        self.system: dict[str, Any] = {"$VEL": v.Struct("VEL", {"CP": DEFAULT_VEL_CP_M_S}),
                                       "$APO": v.Struct("APO", {"CDIS": 0.0, "CVEL": 0.0, "CORI": 0.0, "CPTP": 0.0}),
                                       "$BASE": v.default("FRAME"), "$NULLFRAME": v.default("FRAME"),
                                       "$ADVANCE": 3.0, "$ACC": v.Struct("ACC", {"CP": 0.0, "ORI1": 0.0, "ORI2": 0.0})}
        self.tool: Optional[ToolFrame] = None
        self.int_names: set[str] = set()  # the names declared INT (any scope)
        self.frames_unknown = ""  # the inline form's frame data no file gives, until one that is given
        self.frames_given: set[str] = set()  # $TOOL, $BASE set by the program since (both: the frames are known)
        self.frames: list[dict[str, Any]] = []
        self.moves: list = []
        self.sources: list[MoveSource] = []
        self.move_frames: list[Pose] = []
        self.dwells: list[Dwell] = []
        self.warnings: dict[str, str] = {}
        self.switches: list[OutputSwitch] = []
        self.outputs: set[int] = set()
        self.skipped: list[str] = []
        self.unsimulated: list[str] = []
        self.unknowns: dict[str, str] = {}  # the inputs read that nobody gives
        self.valueless: set[int] = set()  # ids of the positions declared without a value, not set since
        self.unknown = UnknownLog("a variable of $CONFIG.DAT or of a module the files loaded do not include")
        self.spraying = False
        self.pending: list[tuple[int, bool]] = []  # (motions still to start, gun on) of triggered switches
        self.tcp: Optional[Pose] = None
        self.position: Optional[v.Struct] = None  # the last target, in its $BASE
        self.steps, self.line, self.source, self.routine = 0, 0, "", ""
        self.continue_next = False
        self.cache: dict[int, Any] = {}
        for data in datas:
            self.source = data.source
            for ln in data.body:
                self.line = ln.line
                self.declaration(ln, self.globals)

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
    def declaration(self, ln: Line, scope: dict) -> bool:
        """``[DECL] [GLOBAL] type name[dims] [= value], ...``: True if the line is one."""
        toks = list(ln.tokens)
        words = [t.text.upper() for t in toks if t.kind == NAME]
        i = 0
        while i < len(toks) and toks[i].kind == NAME and toks[i].text.upper() in ("DECL", "GLOBAL", "CONST"):
            i += 1
        if i >= len(toks) - 1 or toks[i].kind != NAME or toks[i + 1].kind != NAME:
            return False
        if i == 0 and not (toks[0].text.upper() in v.BASIC or toks[0].text.upper() in v.TYPES):
            return False
        if words[:1] in (["SIGNAL"], ["ENUM"], ["STRUC"], ["EXT"], ["EXTFCT"]):
            return False
        type_ = toks[i].text.upper()
        items = split_commas(toks[i + 1:])
        for item in items:
            name = item[0].text.upper()
            if type_ == "INT":
                self.int_names.add(name)
            if len(name) > MAX_NAME_LENGTH:
                self.warn(f"long{name}", f"name {item[0].text} is longer than {MAX_NAME_LENGTH} characters")
            rest = item[1:]
            if rest and rest[0].kind == OP and rest[0].text == "[":
                close = next(k for k, t in enumerate(rest) if t.text == "]")
                dims = [int(float(t.text)) for t in rest[1:close] if t.kind == "num"]
                scope[name] = [v.declared(type_) for _ in range(dims[0] if dims else 0)]
                continue
            value = v.declared(type_)
            if type_ in v.TYPES and not (rest and rest[0].kind == OP and rest[0].text == "="):
                self.valueless.add(id(value))  # a position declared without one: reading it is an unknown
            if rest and rest[0].kind == OP and rest[0].text == "=":
                value = self.eval(self.expr(rest[1:]))
                if isinstance(value, v.Struct) and not value.type:
                    value.type = type_
            scope[name] = value
        return True

    def assign(self, target: n.Expr, value: Any) -> None:
        if isinstance(target, n.Name):
            key = target.name.upper()
            scope = self.frames[-1] if self.frames and key in self.frames[-1] else \
                self.globals if key in self.globals else \
                self.system if key.startswith("$") or key in MOTION_DATA else None
            if scope is None:
                raise Unknown(target.name)
            old = scope.get(key)
            if key in self.int_names and isinstance(value, float) and math.isfinite(value):
                value = float(math.copysign(math.floor(abs(value) + 0.5), value))  # a REAL set to an INT: rounded
            if isinstance(old, v.Struct) and isinstance(value, v.Struct):
                merged = old.copy()
                merged.fields.update(value.fields)
                value = merged
            scope[key] = value
            if key == "$TOOL":
                pose = v.pose_of(value)
                self.tool = ToolFrame(pose.rotation, pose.translation_mm, self.line)
            if key in ("$TOOL", "$BASE") and self.frames_unknown:  # the program gives the frames itself
                self.frames_given.add(key)
                if len(self.frames_given) == 2:
                    self.frames_unknown = ""
            return
        if isinstance(target, n.Field):
            holder = self._stored(target.base) if isinstance(target.base, n.Name) else self.eval(target.base)
            self.valueless.discard(id(holder))  # a component set: the position has a value
            if not isinstance(holder, v.Struct):
                raise self.error(f"no component {target.field}")
            holder.fields[target.field.upper()] = value
            if isinstance(target.base, n.Name) and target.base.name.upper() == "$TOOL":
                self.assign(target.base, holder)
            return
        if isinstance(target, n.Index):
            base = target.base
            if isinstance(base, n.Name) and base.name.upper() in ("$OUT", "$OUT_C"):
                return  # handled by the caller
            if isinstance(base, n.Name) and base.name.upper() in ("TOOL_DATA", "BASE_DATA"):
                key = f"{base.name.upper()}[{int(self._num(self.eval(target.index[0])))}]"
                self.globals[key] = value
                return
            holder = self.eval(base)
            k = int(self._num(self.eval(target.index[-1])))
            if not isinstance(holder, list) or not 1 <= k <= len(holder):
                raise self.error(f"index {k} out of the array")
            holder[k - 1] = value
            return
        raise self.error("the left of '=' must be a variable")

    # --- signals --------------------------------------------------------------------------
    def signal(self, which: str, number: int) -> bool:
        if which == "$IN":
            if number in self.options.inputs:
                return bool(self.options.inputs[number])
            self.unknowns.setdefault(f"$in[{number}]", f"{self.where()}: $IN[{number}] (taken as off)")
            return False
        return self.spraying if number == self.options.gun_signal else False

    def switch(self, number: int, on: bool, text: str, when: str) -> None:
        """Output ``number`` to ``on``: ``when`` "now" (at rest after an advance run stop), "next"
        (as the next motion starts), "after" (as the motion after the next starts)."""
        self.outputs.add(number)
        gun = number == self.options.gun_signal
        self.switches.append(OutputSwitch(self.source, self.line, text + (f" (gun {'on' if on else 'off'})" if gun
                                                                          else "")))
        if not gun:
            return
        if when == "now":
            self.spraying = on
        else:
            self.pending.append((1 if when == "after" else 0, on))
            if when == "next":
                self.spraying = on
                self.pending.pop()

    # --- running --------------------------------------------------------------------------
    def run(self, routine: Routine) -> None:
        self.main = routine
        try:
            self.call(routine, ())
        except Halt as halt:
            self.stopped = halt.how

    def call(self, routine: Routine, args) -> Any:
        if len(self.frames) >= MAX_CALL_DEPTH:
            raise self.failure(f"calls nested deeper than {MAX_CALL_DEPTH}: {routine.name}")
        values = [self.eval(a.value) for a in args]
        if len(values) > len(routine.params):
            raise self.error(f"{routine.name} takes {len(routine.params)} arguments, got {len(values)}")
        frame = {p.upper(): val for p, val in zip(routine.params, values)}
        saved = (self.source, self.routine, self.line)
        self.frames.append(frame)
        self.source, self.routine = routine.source, routine.name
        try:
            self.block(self._body(routine))
        except Return as ret:
            return ret.value
        except Jump as jump:
            raise InputError(f"{routine.source}:{jump.line}: GOTO {jump.label}: no such label in {routine.name} (a "
                             "GOTO may leave a block, not enter one)") from None
        finally:
            self.frames.pop()
            self.source, self.routine, self.line = saved
        return None

    def _body(self, routine: Routine) -> tuple:
        key = id(routine)
        if key not in self.cache:
            self.cache[key] = build(routine.body, routine.source)
        return self.cache[key]

    def block(self, body: tuple) -> None:
        labels = {ln.tokens[0].text.upper(): k for k, ln in enumerate(body) if isinstance(ln, Line)
                  and len(ln.tokens) == 2 and ln.tokens[1].text == ":"}
        k = 0
        while k < len(body):
            item = body[k]
            k += 1
            if isinstance(item, Block):
                try:
                    self.structure(item)
                except Jump as jump:  # out of a block to a label of this one
                    if jump.label not in labels:
                        raise
                    k = labels[jump.label]
                continue
            self.steps += 1
            if self.steps > MAX_STEPS:
                raise self.failure(f"more than {MAX_STEPS} statements run: a loop that never ends?")
            self.line = item.line
            if item.word == "GOTO":
                label = item.tokens[1].text.upper() if len(item.tokens) > 1 else ""
                if label not in labels:
                    raise Jump(label, item.line)
                k = labels[label]
                continue
            try:
                self.simple(item)
            except Unknown as unknown:
                self.unknown.read(unknown.name, self.where(), unknown.name.lower())
                which = "which has no value in the files (declared without one)" if unknown.declared else \
                    "which no file declares"
                self.skipped.append(f"{self.where()}: statement skipped: it reads {unknown.name}, {which}")


def _files(paths: Sequence[Path]) -> list[Path]:
    """The files given, with the ``.dat`` beside each ``.src`` that comes without it."""
    items = [Path(p) for p in paths]
    given = {p.resolve() for p in items if p.exists()}
    out = list(items)
    for p in items:
        if p.suffix.lower() == ".src":
            for dat in (p.with_suffix(".dat"), p.with_suffix(".DAT")):
                if dat.exists() and dat.resolve() not in given:
                    out.append(dat)
                    given.add(dat.resolve())
                    break
    return out


def read_krl(paths: Sequence[Path], options: ReadOptions) -> Reading:
    """Parse and run KRL files loaded together (a ``.src`` with its ``.dat``)."""
    if not paths:
        raise InputError("no program file given")
    routines, datas, texts = [], [], {}
    for p in _files(paths):
        text = decode_text(read_program_file(p))
        texts[str(p)] = text
        r, d = parse_krl(text, str(p))
        routines += r
        datas += d
    if not routines:
        raise InputError(f"{paths[0]}: no DEF in the files loaded")
    run = Interpreter(routines, datas, options)
    main = next((r for r in routines if r.name.lower() == options.program.lower()), None) if options.program \
        else routines[0]
    if main is None:
        raise InputError(f"{paths[0]}: no DEF {options.program} in the files loaded (routines: "
                         f"{', '.join(r.name for r in routines)})")
    run.stopped = ""
    run.run(main)
    record = decode_record([(k.strip(), x.strip()) for k, x in RECORD.findall(texts[main.source])], main.source)
    toolpath = ToolPath(main.name, tuple(run.moves), record, tuple(run.dwells), tuple(run.warnings.values()), run.tool)
    problems = []
    stem = Path(main.source).stem
    if routines[0] is main and stem.lower() != main.name.lower() and Path(main.source).suffix.lower() == ".src":
        problems.append(f"{main.source}:{main.line}: DEF {main.name} in a file named {Path(main.source).name}: the "
                        "controller loads a program by its file's name")
    problems += [f"{r.source}:{r.line}: routine name '{r.name}' is longer than {MAX_NAME_LENGTH} characters"
                 for r in routines if len(r.name) > MAX_NAME_LENGTH]
    return Reading(
        toolpath=toolpath, sources=tuple(str(p) for p in paths), program=main.name, program_source=main.source,
        program_line=main.line, programs=tuple(r.name for r in routines),
        ended=f"{run.stopped} ends it" if run.stopped else f"it ends at line {main.end_line}",
        move_sources=tuple(run.sources), move_frames=tuple(run.move_frames), n_steps=len(main.body),
        n_poses=sum(1 for val in run.globals.values() if isinstance(val, v.Struct) and val.type in v.TYPES),
        switches=tuple(run.switches), outputs=tuple(sorted(run.outputs)), problems=tuple(problems),
        unknowns=tuple(run.unknowns.values()) + run.unknown.unknowns(), skipped=tuple(run.skipped), unsimulated=tuple(run.unsimulated),
        gun_on_at_end=run.spraying,
        external_axes=any(isinstance(val, v.Struct) and any(abs(float(val.fields.get(a, 0.0))) > 1e-9
                                                             for a in v.AXES if isinstance(val.fields.get(a, 0.0), float))
                          for val in run.globals.values()),
    )

"""AS files read for check-program and convert: the Reading of an interpreted run, with what
only AS can tell (its statement count, its poses, its SIGNAL/PULSE/BITS lines, SPEED in %,
15-character names, poses never used, controller sections, arc pairs beyond 180 deg, motions
skipped while the gun is on)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Iterator, Mapping, Optional, Sequence

from coatsim.geometry.space.primitives import arc_through
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.files import parse_files
from coatsim.languages.kawasaki_as.interpreter import Run, interpret_run
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH
from coatsim.languages.kawasaki_as.printer import expr_text
from coatsim.languages.kawasaki_as.statements_exec import gun_pulse_problem
from coatsim.path.language import ReadOptions
from coatsim.path.reading import MoveSource, OutputSwitch, Reading
from coatsim.path.toolpath import CircularMove

_LISTED = 5  # unused poses named before "and N more"
_HALF_CIRCLE_ROUNDING = math.radians(0.05)  # a half circle of radius 1 mm or more, its poses rounded to 0.001 mm


def walk(body: tuple[ast.Statement, ...]) -> Iterator[ast.Statement]:
    """Every statement of a body, blocks entered, in source order."""
    for st in body:
        yield st
        if isinstance(st, ast.If):
            for _, inner in st.branches:
                yield from walk(inner)
            yield from walk(st.orelse)
        elif isinstance(st, (ast.While, ast.DoUntil, ast.For)):
            yield from walk(st.body)
        elif isinstance(st, ast.Case):
            for _, inner, _ in st.branches:
                yield from walk(inner)
            yield from walk(st.default or ())


def used_names(e) -> Iterator[str]:
    """Base names (lower case, no index) of the variables an expression or statement uses."""
    if isinstance(e, ast.Name):
        yield e.name.lower()
        for i in e.index:
            yield from used_names(i)
    elif isinstance(e, tuple):
        for item in e:
            yield from used_names(item)
    elif e is not None and hasattr(e, "__dataclass_fields__") and not isinstance(e, (ast.Num, ast.Str)):
        for name in e.__dataclass_fields__:
            value = getattr(e, name)
            if isinstance(value, (tuple, ast.Name)) or hasattr(value, "__dataclass_fields__"):
                yield from used_names(value)


def _constant(e, reals: Mapping[str, float]) -> Optional[float]:
    """The value of a signal number written as a number or a .REALS variable (with a sign)."""
    if isinstance(e, ast.Num):
        return e.value
    if isinstance(e, ast.Name) and not e.index and not e.is_local:
        return reals.get(e.name.lower())
    if isinstance(e, ast.Unary) and e.op == "-":
        inner = _constant(e.operand, reals)
        return None if inner is None else -inner
    return None


def _switch(st: ast.Statement, gun: int, source: str, reals: Mapping[str, float]) -> Optional[OutputSwitch]:
    if isinstance(st, ast.Signal):
        text = "SIGNAL " + ", ".join(expr_text(e) for e in st.outputs)
        values = [_constant(e, reals) for e in st.outputs]
        gun_parts = ["gun on" if v > 0 else "gun off" for v in values if v is not None and abs(v) == gun]
        return OutputSwitch(source, st.line, text + (f" ({', '.join(gun_parts)})" if gun_parts else ""))
    if isinstance(st, ast.Pulse):
        value = _constant(st.signal, reals)
        gun_part = "" if value is None or abs(value) != gun else " (gun pulsed)" if st.op == "PULSE" else \
            " (gun on)" if value > 0 else " (gun off)"
        return OutputSwitch(source, st.line, f"{st.op} {expr_text(st.signal)}"
                            + (f", {expr_text(st.seconds)}" if st.seconds is not None else "") + gun_part)
    if isinstance(st, ast.Bits):
        return OutputSwitch(source, st.line, f"BITS {expr_text(st.start)}, {expr_text(st.count)} = {expr_text(st.value)}")
    return None


def _problems(files, run: Run, used: set[str]) -> list[str]:
    """Long names, poses never used, external axes that move, sections not read, arc pairs of
    beyond 180 deg (a half circle is one pair's limit, within the rounding of its poses)."""
    problems: list[str] = []
    unused = []
    for f in files:
        for name, trans in f.trans.items():
            if len(trans.name) > MAX_NAME_LENGTH:
                problems.append(f"{f.source}:{trans.line}: pose name '{trans.name}' is longer than {MAX_NAME_LENGTH} "
                                "characters")
            if name.split("[")[0] not in used:
                unused.append(f"{f.source}:{trans.line}: pose '{trans.name}' is defined but never used")
    problems += unused[:_LISTED]
    if len(unused) > _LISTED:
        problems.append(f"... and {len(unused) - _LISTED} more poses defined but never used")
    extra = {}  # the external axis values (rails, positioners) of the poses the program names
    for f in files:
        for name, trans in f.trans.items():
            if trans.extra and name.split("[")[0] in used:
                extra.setdefault(tuple(trans.extra), f"{f.source}:{trans.line}: {trans.name}")
    if len(extra) > 1:
        shown = "; ".join(f"{where} {', '.join(f'{v:g}' for v in values)}"
                          for (values, where) in list(extra.items())[:2])
        problems.append(f"the poses hold different external axis values ({shown}): an external axis (a rail, a "
                        "positioner) moves during the program; coatsim does not move external axes, so the path read "
                        "is the arm's alone, not the tool's over the part")
    sections = [f".{s.name} (line {s.line})" for f in files for s in f.sections]
    if sections:
        problems.append(f"sections not read (controller data): {', '.join(sections)}")
    for move, (name, _, _) in zip(run.toolpath.moves, run.move_origins):
        if isinstance(move, CircularMove):
            sweep = arc_through(move.start.translation_mm, move.via.translation_mm, move.end.translation_mm).sweep
            if sweep > math.pi + _HALF_CIRCLE_ROUNDING:
                problems.append(f"{run.programs[name.lower()].source}:{move.line}: arc sweeps {math.degrees(sweep):.1f} "
                                "deg; keep one C1MOVE/C2MOVE pair within 180 deg")
    return problems


def _dry(dry: tuple[str, ...], gun: int, sprays: bool) -> str:
    """The problem of motions skipped while the gun is on (``dry``: where); ``sprays`` whether
    any motion read sprays (else nothing sprayed is read at all)."""
    shown = ", ".join(dry[:_LISTED]) + (f" and {len(dry) - _LISTED} more" if len(dry) > _LISTED else "")
    if not sprays:
        return (f"every motion while the gun (output {gun}) is on is skipped ({shown}): the program's sprayed path "
                "is not read")
    many = len(dry) > 1
    return (f"{len(dry)} motion{'s' if many else ''} while the gun (output {gun}) is on {'are' if many else 'is'} "
            f"skipped ({shown}): the sprayed path read lacks {'them' if many else 'it'}")


def read_as(paths: Sequence[Path], options: ReadOptions) -> Reading:
    """Parse and interpret AS files loaded together (statements that cannot run are skipped
    and listed) and describe the run."""
    files = parse_files(paths)
    run = interpret_run(files, options.gun_signal, options.program, inputs=options.inputs,
                        kinematics=options.kinematics, variables=options.variables)
    toolpath = run.toolpath
    main = run.programs[toolpath.name.lower()]
    problems: list[str] = []
    used: set[str] = set()
    switches: list[OutputSwitch] = []
    reals = {k: d.value for f in files for k, d in f.reals.items()}
    gun = options.gun_signal
    for p in run.programs.values():
        for st in walk(p.body):
            used.update(used_names(st))
            switch = _switch(st, options.gun_signal, p.source, reals)
            if switch is not None:
                switches.append(switch)
            if isinstance(st, ast.Pulse) and st.op == "PULSE" and _constant(st.signal, reals) in (gun, -gun):
                seconds = None if st.seconds is None else _constant(st.seconds, reals)
                problems.append(f"{p.source}:{st.line}: {gun_pulse_problem(gun, seconds)}")
            if isinstance(st, ast.Speed) and st.unit == "%":
                problems.append(f"{p.source}:{st.line}: SPEED in % depends on the robot's maximum speed; coatsim "
                                "assumes 100 % = 1000 mm/s")
        if len(p.name) > MAX_NAME_LENGTH:
            problems.append(f"{p.source}:{p.line}: program name '{p.name}' is longer than {MAX_NAME_LENGTH} characters")
    problems += _problems(files, run, used)
    if run.dry:
        problems.append(_dry(run.dry, options.gun_signal, bool(toolpath.spray_moves)))
    return Reading(
        toolpath=toolpath,
        sources=tuple(f.source for f in files),
        program=main.name,
        program_source=main.source,
        program_line=main.line,
        programs=tuple(p.name for p in run.programs.values()),
        ended=f"{run.stopped} ends it" if run.stopped else f"it ends at line {main.end_line}",
        move_sources=tuple(MoveSource(run.programs[name.lower()].source, name, first, last)
                           for name, first, last in run.move_origins),
        move_frames=run.move_bases,
        n_steps=sum(1 for st in walk(main.body) if not isinstance(st, ast.Label)),
        n_poses=sum(len(f.trans) for f in files),
        switches=tuple(switches),
        outputs=run.outputs,
        problems=tuple(problems),
        notes=run.notes,
        unknowns=tuple(u.note() for u in run.unknowns),
        skipped=run.skipped,
        unsimulated=run.unsimulated,
        gun_on_at_end=run.gun_on_at_end,
        external_axes=any(d.extra for f in files for d in f.trans.values()),
    )

"""RAPID files -> the Reading check-program needs: the files parsed, the entry routine run
(:mod:`.interpreter`), the ToolPath the robot executes with where each move comes from, and what
the files hold that RAPID or the twin does not allow (names too long, TRAP routines)."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import decode_text, read_program_file
from coatsim.languages.abb_rapid import data as d
from coatsim.languages.abb_rapid import syntax as s
from coatsim.languages.abb_rapid.interpreter import Interpreter
from coatsim.languages.abb_rapid.names import MAX_NAME_LENGTH
from coatsim.languages.abb_rapid.parser import parse_rapid
from coatsim.path.language import ReadOptions
from coatsim.path.process_record import decode as decode_record
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

RECORD = re.compile(r"^\s*!\s*coatsim:\s*([^=]+?)\s*=(.*)$", re.MULTILINE)


def parse_files(paths: Sequence[Path]) -> tuple[tuple[s.Module, ...], dict[str, str]]:
    """The modules of every file and each file's text."""
    if not paths:
        raise InputError("no program file given")
    modules, texts = [], {}
    for p in paths:
        text = decode_text(read_program_file(p))
        texts[str(p)] = text
        modules += parse_rapid(text, str(p))
    return tuple(modules), texts


def read_rapid(paths: Sequence[Path], options: ReadOptions) -> Reading:
    """Parse and run RAPID files loaded together; the Reading of the entry routine's run."""
    modules, texts = parse_files(paths)
    run = Interpreter(modules, options)
    run.stopped = ""
    run.run(options.program or "main")
    main = run.main
    record = decode_record([(k.strip(), v.strip()) for k, v in RECORD.findall(texts[main.source])], main.source)
    toolpath = ToolPath(main.name, tuple(run.moves), record, tuple(run.dwells), tuple(run.warnings.values()),
                        run.moves[-1].settings.tool if run.moves else None)
    return Reading(
        toolpath=toolpath, sources=tuple(str(p) for p in paths), program=main.name, program_source=main.source,
        program_line=main.line, programs=tuple(r.name for r in run.routines.values()),
        ended=f"{run.stopped} ends it" if run.stopped else f"it ends at line {main.end_line}",
        move_sources=tuple(run.sources), move_frames=tuple(run.move_frames),
        n_steps=_count(main.body), n_poses=sum(1 for m in modules for x in m.data if x.type in ("robtarget", "jointtarget")),
        switches=tuple(run.switches), outputs=tuple(sorted(run.outputs)), unnumbered=tuple(run.unnumbered.values()), problems=tuple(_problems(modules)),
        unknowns=tuple(run.unknowns.values()) + run.unknown.unknowns(), skipped=tuple(run.skipped), unsimulated=tuple(run.unsimulated),
        gun_on_at_end=run.spraying,
        external_axes=any(_has_axes(v) for v in run.globals.values()),
    )


def _count(body: tuple) -> int:
    total = 0
    for st in body:
        if isinstance(st, s.Label):
            continue
        total += 1
        if isinstance(st, s.If):
            total += sum(_count(b) for _, b in st.branches) + _count(st.orelse)
        elif isinstance(st, (s.For, s.While)):
            total += _count(st.body)
        elif isinstance(st, s.Test):
            total += sum(_count(b) for _, b in st.cases) + _count(st.default or ())
    return total


def _has_axes(entry: tuple[str, Any]) -> bool:
    type_, value = entry
    if type_ != "robtarget" or not isinstance(value, d.Record):
        return False
    return any(abs(v) < d.UNSET_AXIS * 0.999 for v in value.fields["extax"].fields.values())


def _problems(modules: Sequence[s.Module]) -> list[str]:
    """Names longer than RAPID allows; TRAP routines (noted, not run)."""
    out = []
    for m in modules:
        named = [(m.name, m.line, "module")] + [(x.name, x.line, "data") for x in m.data] + \
            [(r.name, r.line, r.kind) for r in m.routines]
        out += [f"{m.source}:{line}: {what} name '{name}' is longer than {MAX_NAME_LENGTH} characters"
                for name, line, what in named if len(name) > MAX_NAME_LENGTH]
        out += [f"{m.source}:{r.line}: TRAP {r.name} runs on an interrupt; the twin does not run it"
                for r in m.routines if r.kind == "TRAP"]
    return out

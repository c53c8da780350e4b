"""Replace the statements that make a process path with its arc moves, in the program's own file.

The statements replaced are the smallest run of consecutive statements of one program (blocks
whole) that make exactly the path's moves. They may hold linear and arc motions (LMOVE, C1MOVE,
C2MOVE, LAPPRO, LDEPART, DRAW, TDRAW), assignments, loops (a label and the GOTO back to it too),
labels no other GOTO names and the gun's own switch (forward processing: it is written again after the first
new move); anything else there (other signals, waits, calls, setting changes) would change
meaning and is refused with its line, as are moves given in different BASEs or settings.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.core.fileio import read_input
from coatsim.geometry.space.pose import Pose
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.edit import edit_lines, indentation
from coatsim.languages.kawasaki_as.files import parse_files
from coatsim.languages.kawasaki_as.interpreter import Run, interpret_run
from coatsim.languages.kawasaki_as.names import sanitize_comment
from coatsim.languages.kawasaki_as.reading import used_names, walk
from coatsim.languages.kawasaki_as.writer import fmt, fmt_short, path_moves, pose_values
from coatsim.path.edit import FittedPath, InPlaceEdit
from coatsim.path.language import ReadOptions

_HINT = "; use --standalone"


def _span(st: ast.Statement) -> tuple[int, int]:
    return st.line, getattr(st, "end_line", st.line)


def _gun_on(st: ast.Signal, gun: int) -> bool:
    return all(isinstance(e, ast.Num) and e.value == gun for e in st.outputs)


def _goto_loops(body: Sequence[ast.Statement], lo: int, hi: int) -> tuple[int, int]:
    """``lo``..``hi`` (indices into ``body``) widened to every loop made of a label and a GOTO
    back to it (``loop:`` ... ``IF .i < n GOTO loop``) that overlaps it: such a loop is replaced
    whole, like a FOR loop."""
    labels = {st.name: i for i, st in enumerate(body) if isinstance(st, ast.Label)}
    jumps = [(labels[g.label], j) for j, st in enumerate(body) for g in walk((st,))
             if isinstance(g, ast.Goto) and labels.get(g.label, j + 1) <= j]
    changed = True
    while changed:
        changed = False
        for i, j in jumps:
            if i <= hi and j >= lo and (i < lo or j > hi):
                lo, hi, changed = min(lo, i), max(hi, j), True
    return lo, hi


def _keyword(st: ast.Statement) -> str:
    """The statement as a user wrote it, by its AS keyword: ``a CALL statement``."""
    if isinstance(st, ast.Switch):
        word = f"{st.name} {'ON' if st.on else 'OFF'}"
    elif isinstance(st, ast.Case):
        word = "SCASE" if st.string else "CASE"
    else:
        word = (getattr(st, "op", None) or (st.name if isinstance(st, ast.Command) else None)
                or (st.kind if isinstance(st, ast.BlockStep) else None)
                or ("CALL" if isinstance(st, ast.CallProgram) else type(st).__name__.upper()))
    return f"a{'n' if word[0] in 'AEIOU' else ''} {word} statement"


def _check_statements(body: Sequence[ast.Statement], program: ast.Program, gun: int) -> bool:
    """Whether the replaced statements hold the gun's switch; InputError on one that cannot go
    (a GOTO in or out of them among them)."""
    inside = list(walk(tuple(body)))
    ids = {id(st) for st in inside}
    labels = {st.name for st in inside if isinstance(st, ast.Label)}
    gotos = {st.label for st in walk(program.body) if isinstance(st, ast.Goto) and id(st) not in ids}
    switch = False
    for st in inside:
        where = f"{program.source}:{st.line}"
        if isinstance(st, ast.Label):
            if st.name in gotos:
                raise InputError(f"{where}: label {st.name} inside the process path is a GOTO target{_HINT}")
        elif isinstance(st, ast.Goto):
            if st.label not in labels:
                raise InputError(f"{where}: GOTO {st.label} leaves the process path{_HINT}")
        elif isinstance(st, (ast.Move, ast.Appro, ast.Depart, ast.Draw)):
            if st.op not in ("LMOVE", "C1MOVE", "C2MOVE", "LAPPRO", "LDEPART", "DRAW", "TDRAW"):
                raise InputError(f"{where}: {st.op} inside the process path{_HINT}")
        elif isinstance(st, ast.Signal) and _gun_on(st, gun) and not switch:
            switch = True
        elif not isinstance(st, (ast.Assign, ast.PointAssign, ast.For, ast.While, ast.DoUntil, ast.If)):
            raise InputError(f"{where}: the process path holds {_keyword(st)} that an arc program "
                             f"cannot keep in place{_HINT}")
    return switch


def _external_axes(files, body: Sequence[ast.Statement], where: str) -> tuple[str, ...]:
    """The external axis values (rail, positioner) of the ``.TRANS`` poses the replaced
    statements name, written after each new pose: they must be one set along the path."""
    used = {name for st in walk(tuple(body)) for name in used_names(st)}
    found = {d.extra for f in files for k, d in f.trans.items() if k.split("[")[0] in used}
    if len(found) > 1:
        raise InputError(f"{where}: the poses of the process path hold different external axis values; coatsim "
                         "does not move external axes along an arc path")
    return tuple(fmt(v, 3) for v in (found.pop() if found else ()))


def _names_taken(files) -> set[str]:
    return {k.split("[")[0] for f in files for table in (f.trans, f.reals, f.joints) for k in table}


def edit_in_place(items: Sequence[Path], options: ReadOptions, fitted: Sequence[FittedPath],
                  tolerance_mm: float) -> InPlaceEdit:
    """The file holding the process paths ``fitted`` (of the run of ``items`` read with
    ``options``) with each path's statements replaced by its moves."""
    files = parse_files(items)
    run = interpret_run(files, options.gun_signal, options.program, inputs=options.inputs,
                        kinematics=options.kinematics, variables=options.variables)
    programs = {run.move_origins[i][0] for f in fitted for i in f.path.moves}
    program_objs = [run.programs[name.lower()] for name in programs]
    sources = {p.source for p in program_objs}
    if len(sources) != 1:
        raise InputError(f"the process paths lie in several files ({', '.join(sorted(sources))}){_HINT}")
    source = sources.pop()
    path = next(p for p in items if str(p) == source)
    data = read_input(path, "program")
    taken = _names_taken(files)
    prefix = next(p for p in ("cv", "cva", "cvb", "cvc", "cvz") if not any(t.startswith(p) for t in taken))
    replacements, trans, counts, ranges = [], [], [], []
    for k, f in enumerate(fitted, start=1):
        program, lo, hi, first_line, last_line = _replaced_lines(run, f, source)
        body = program.body
        switch = _check_statements(body[lo:hi + 1], program, options.gun_signal)
        extra = _external_axes(files, body[lo:hi + 1], f"{source}:{first_line}")
        moves = [run.toolpath.moves[i] for i in f.path.moves]
        base = _one_setting(run, f, moves, f"{source}:{first_line}")
        inverse = base.inverse()

        def name(pose: Pose, _k=k) -> str:
            user = inverse @ pose
            label = f"{prefix}{_k}_{len(trans):04d}"
            if len(label) > 15:
                raise InputError(f"too many new poses for 15-character names{_HINT}")
            trans.append(" ".join((label, *pose_values(user), *extra)))
            return label

        statements = path_moves(f.segments, name)
        indent = indentation(data, first_line)
        block = [f"{indent}; coatsim convert: lines {first_line}-{last_line}, {len(moves)} moves -> "
                 f"{f.n_lines} lines + {f.n_arcs} arcs within {fmt_short(tolerance_mm)} mm"]
        for statement, comment in statements:
            block.append(f"{indent}{statement}".ljust(30) + f" ; {sanitize_comment(comment)}")
            if switch and not statement.startswith("C1MOVE"):  # after the first complete move, as before
                block.append(f"{indent}SIGNAL {options.gun_signal}".ljust(30) + " ; gun on (as in the original)")
                switch = False
        replacements.append((first_line, last_line, block))
        ranges.append((first_line, last_line))
        counts.append(sum(1 for s, _ in statements if not s.startswith("C1MOVE")))
    new = edit_lines(data, replacements, [".TRANS", *trans, ".END"])
    return InPlaceEdit(source, new, tuple(counts), tuple(ranges))


def _replaced_lines(run: Run, f: FittedPath, source: str) -> tuple[ast.Program, int, int, int, int]:
    """The program and the statements (``lo``..``hi``, lines ``first``..``last``) that make
    exactly the moves of the process path ``f``, or an InputError saying why none do."""
    origins = [run.move_origins[i] for i in f.path.moves]
    names = {o[0] for o in origins}
    if len(names) != 1:
        raise InputError(f"the process path of lines {f.lines[0]}-{f.lines[1]} comes from programs "
                         f"{', '.join(sorted(names))}{_HINT}")
    program = run.programs[names.pop().lower()]
    body = program.body
    touched = [i for i, st in enumerate(body)
               if any(_span(st)[0] <= a <= _span(st)[1] or _span(st)[0] <= b <= _span(st)[1] for _, a, b in origins)]
    lo, hi = _goto_loops(body, touched[0], touched[-1])
    first_line, last_line = _span(body[lo])[0], _span(body[hi])[1]
    made = [i for i, (name, a, b) in enumerate(run.move_origins)
            if name.lower() == program.name.lower() and first_line <= a and b <= last_line]
    if made != list(f.path.moves):
        raise InputError(f"{source}:{first_line}: lines {first_line}-{last_line} make other moves than the process "
                         f"path (they run more than once, or hold other motions){_HINT}")
    return program, lo, hi, first_line, last_line


def _one_setting(run: Run, f: FittedPath, moves: list, where: str) -> Pose:
    """The BASE of the process path ``f``, whose moves must share speed, accuracy and BASE
    (one set of replacement moves carries one of each)."""
    settings = {(m.settings.speed_mm_s, m.settings.accuracy_mm, m.settings.cp) for m in moves}
    if len(settings) != 1:
        raise InputError(f"{where}: the speed or accuracy changes along the process path{_HINT}")
    base = run.move_bases[f.path.moves[0]]
    if any(run.move_bases[i] is not base for i in f.path.moves):
        raise InputError(f"{where}: BASE changes along the process path{_HINT}")
    return base

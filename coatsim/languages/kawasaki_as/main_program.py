"""Which loaded program is the main one when none is named.

A controller backup saves its programs in alphabetical order, so the first one is often a
helper (``a.home``, ``gun.off``) that the real main program CALLs. The main program is one that
no other loaded program CALLs (a root): the first program loaded (background PC programs
``*.pc`` aside) when it is a root with a motion, else the first root with a motion (in itself or
in what it CALLs), else the first root.
"""

from __future__ import annotations

from typing import Iterator, Sequence

from coatsim.languages.kawasaki_as import ast

_MOTIONS = (ast.Move, ast.Appro, ast.Depart, ast.Draw, ast.Home)


def nodes(e) -> Iterator:
    """Every node of an expression or statement (blocks and indices entered), itself first."""
    if isinstance(e, tuple):
        for item in e:
            yield from nodes(item)
    elif hasattr(e, "__dataclass_fields__"):
        yield e
        for f in e.__dataclass_fields__:
            yield from nodes(getattr(e, f))


def _callees(program: ast.Program) -> set[str]:
    """The programs ``program`` CALLs by name (lower case)."""
    return {n.program.lower() for n in nodes(program.body) if isinstance(n, ast.CallProgram)
            and isinstance(n.program, str)}


def _moves(name: str, programs: dict[str, ast.Program], seen: set[str]) -> bool:
    """Whether the program ``name`` or one it CALLs holds a motion."""
    program = programs.get(name)
    if program is None or name in seen:
        return False
    seen.add(name)
    return any(isinstance(n, _MOTIONS) for n in nodes(program.body)) or \
        any(_moves(c, programs, seen) for c in sorted(_callees(program)))


def choose_main(programs: Sequence[ast.Program]) -> tuple[ast.Program, str]:
    """The main program of those loaded (in order), and a note when the choice is not plain (it
    is not the first program, or other programs no one CALLs move too); "" otherwise."""
    candidates = [p for p in programs if not p.name.lower().endswith(".pc")] or list(programs)
    by_name = {p.name.lower(): p for p in programs}
    called = set().union(*(_callees(p) for p in programs))
    roots = [p for p in candidates if p.name.lower() not in called] or candidates
    moving = [p for p in roots if _moves(p.name.lower(), by_name, set())]
    first = candidates[0]
    main = first if first in moving else (moving or roots)[0]
    others = [p.name for p in moving if p is not main]
    if main is first and not others:
        return main, ""
    note = f"program {main.name} is taken as the main program: no other loaded program CALLs it"
    if main is not first:
        note += f" (the first, {first.name}, is " + (
            "CALLed by another)" if first.name.lower() in called else "without motion)")
    if others:
        note += f"; other programs no one CALLs that move: {', '.join(others)}; name one to run it instead"
    return main, note

"""G-code program flow: LinuxCNC's O-words and a Fanuc control's custom macro and subprograms.

LinuxCNC (RS274/NGC, "O Codes"): ``oN sub`` … ``oN endsub`` (skipped where it stands, run by
``oN call [a] [b] …`` with ``#1``, ``#2`` … the arguments and ``#1``-``#30`` local to the call,
``oN return`` leaving early), ``oN while [c]`` … ``oN endwhile``, ``oN do`` … ``oN while [c]``,
``oN if [c]`` / ``elseif [c]`` / ``else`` / ``endif``, ``oN repeat [n]`` … ``oN endrepeat``,
``oN break`` and ``oN continue`` (the loop of the same label). A Fanuc control (Fanuc Series 0i,
"Custom macro"): ``WHILE [c] DOm`` … ``ENDm``, ``IF [c] GOTO n`` and ``GOTO n`` (to the block
numbered ``Nn``), ``IF [c] THEN`` a statement, ``M98 P<program> [L<times>]`` calling the
program ``O<program>`` of the same file and ``M99`` returning from it (in the main program
``M99`` ends it: the twin runs a cycle once).

A condition or count that needs a parameter no file gives skips its construct (listed, as a
block's unknowns are); a step budget stops a program that never ends.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Optional

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.script.unknowns import DependsOn

Expr = tuple  # an expression of .blocks

MAX_STEPS = 200_000  # blocks run: a program that never ends stops in a few seconds
LOCAL_PARAMETERS = 30  # #1-#30 are local to an O-word call
_OWORD = re.compile(r"O(<[^>]*>|[0-9]+)(SUB|ENDSUB|CALL|RETURN|WHILE|ENDWHILE|DO|IF|ELSEIF|ELSE|ENDIF|REPEAT|ENDREPEAT|"
                    r"BREAK|CONTINUE)(.*)\Z")
_FANUC = re.compile(r"(?:N[0-9]+)?(WHILE|IF|GOTO|END)(.*)\Z")


@dataclass(frozen=True)
class Flow:
    """A block's flow statement: ``kind`` (an O-word keyword in lower case; or ``fwhile``,
    ``fend``, ``goto``, ``ifgoto``, ``then``), the O-word's label or the Fanuc loop number, the
    condition or count, the call's arguments or the jump's target."""

    kind: str
    label: str
    value: Optional[Expr] = None
    args: tuple = ()


def parse_flow(code: str, reader) -> tuple[Optional[Flow], str]:
    """The flow statement at the start of ``code`` (spaces removed, upper case; ``reader`` reads
    it) and the code left after it (an ``IF … THEN`` statement's); (None, code) for a block
    without one."""
    m = _OWORD.match(code)
    if m:
        label, kind = m.group(1).lower(), m.group(2).lower()
        reader.i = m.start(3)
        values = []
        while reader.i < len(code):
            if not reader.peek("["):
                raise reader.error(f"o{label} {kind}: expected a bracketed value at column {reader.i + 1}")
            values.append(reader.value())
        if kind in ("while", "if", "elseif", "repeat") and len(values) != 1:
            raise reader.error(f"o{label} {kind} takes one bracketed expression")
        single = values[0] if values and kind != "call" else None
        return Flow(kind, label, single, tuple(values) if kind == "call" else ()), ""
    m = _FANUC.match(code)
    if not m:
        return None, code
    word = m.group(1)
    reader.i = m.start(2)
    if word == "GOTO":
        return Flow("goto", "", reader.value()), _rest(reader, code)
    if word == "END":
        return Flow("fend", _loop_number(reader)), _rest(reader, code)
    cond = reader.value()
    if word == "WHILE":
        reader.expect("DO")
        return Flow("fwhile", _loop_number(reader), cond), _rest(reader, code)
    if reader.take("GOTO"):
        return Flow("ifgoto", "", cond, (reader.value(),)), _rest(reader, code)
    reader.expect("THEN")
    return Flow("then", "", cond), code[reader.i:]


def _loop_number(reader) -> str:
    value = reader.value()
    if value[0] != "num":
        raise reader.error("a WHILE ... DO / END loop is numbered by a constant (DO1, END1)")
    return str(int(value[1]))


def _rest(reader, code: str) -> str:
    if reader.i < len(code):
        raise reader.error(f"unexpected {code[reader.i:]!r} after the flow statement")
    return ""


class Runner:
    """Runs a file's blocks in the order their flow gives. ``interpreter`` provides ``params``,
    ``run_block(block)`` (True at M2/M30), ``step(block)``, ``source`` and ``error``."""

    def __init__(self, blocks: tuple, interpreter) -> None:
        self.blocks, self.run = blocks, interpreter
        self.pairs = _pairs(blocks, interpreter.source)
        self.numbers = {_n_word(b): k for k, b in reversed(list(enumerate(blocks))) if _n_word(b) is not None}
        self.programs = {b.program_number: k for k, b in enumerate(blocks) if b.program_number is not None}
        self.subs = {b.flow.label: k for k, b in enumerate(blocks) if b.flow is not None and b.flow.kind == "sub"}
        self.may_call = {k for k, b in enumerate(blocks)  # the blocks whose M words may be M98/M99
                         if any(letter == "M" and (e[0] != "num" or e[1] in (98.0, 99.0)) for letter, e in b.words)}
        self.calls: list[tuple] = []  # (return index, saved locals or None, times left, program index)
        self.counts: dict[int, int] = {}  # repeat index -> repetitions left
        self.how = "M2/M30"  # what ended the program

    def execute(self) -> Optional[int]:
        """Run from the first block; the line of the block that ends the program (None: the end)."""
        pc, steps = 0, 0
        while pc < len(self.blocks):
            steps += 1
            if steps > MAX_STEPS:
                raise ExecutionError(f"{self.run.source}:{self.blocks[pc].line}: more than {MAX_STEPS} blocks run: "
                                     "a loop that never ends?")
            block = self.blocks[pc]
            self.run.step(block)
            try:
                if block.flow is not None:
                    nxt = self.flow(pc, block)
                elif pc in self.may_call:
                    nxt = self.calls_of(pc, block)
                else:
                    nxt = None if self.run.run_block(block) else pc + 1
            except DependsOn as unknown:  # a condition or count no file gives: the construct is skipped
                self.run.params.unknown.skip(f"{self.run.source}:{block.line}", "the block", unknown.names)
                nxt = self.past(pc)
            if nxt is None:
                return block.line
            pc = nxt
        return None

    def past(self, pc: int) -> int:
        """The block after the construct ``pc`` opens (after ``pc`` itself for any other block)."""
        block, ends = self.blocks[pc], self.pairs.get(pc, ())
        opens = block.flow is not None and block.flow.kind in _OPENERS and ends and ends[-1] > pc
        return ends[-1] + 1 if opens else pc + 1

    def value(self, expr) -> float:
        return self.run.params.evaluate(expr)

    def calls_of(self, pc: int, block) -> Optional[int]:
        """A block of words: M98 calls a subprogram, M99 returns; other blocks run."""
        m = {round(self.value(e), 1) for letter, e in block.words if letter == "M"}
        if 98.0 in m:
            words = {letter: e for letter, e in block.words}
            if "P" not in words:
                raise self.run.error("M98 needs P, the number of the program it calls")
            number, times = int(self.value(words["P"])), int(self.value(words["L"])) if "L" in words else 1
            if number not in self.programs:
                raise ExecutionError(f"{self.run.source}:{block.line}: M98 P{number}: program O{number} is not in the "
                                     "file; a program the control holds is not simulated")
            if times > 0:
                self.calls.append((pc + 1, None, times, self.programs[number]))
                return self.programs[number] + 1
            return pc + 1
        if 99.0 in m:
            return self.leave(block)
        return None if self.run.run_block(block) else pc + 1

    def leave(self, block) -> Optional[int]:
        """M99, endsub, return: back to the caller (again while an L count is left)."""
        if not self.calls:
            if block.flow is None:
                self.run.builder.warn("M99", f"{self.run.source}:{block.line}: M99 in the main program repeats it; "
                                      "the twin runs it once")
                self.how = "M99"
                return None
            raise self.run.error(f"o{block.flow.label} {block.flow.kind} outside a call")
        back, saved, times, start = self.calls.pop()
        if times > 1:
            self.calls.append((back, saved, times - 1, start))
            return start + 1
        if saved is not None:
            for k, v in saved.items():
                self.run.params.numbered.pop(k, None) if v is None else self.run.params.set(k, v)
        return back

    def flow(self, pc: int, block) -> Optional[int]:
        f = block.flow
        kind = f.kind
        if kind == "then":
            return None if self.value(f.value) and self.run.run_block(block) else pc + 1
        if kind in ("goto", "ifgoto"):
            if kind == "ifgoto" and not self.value(f.value):
                return pc + 1
            target = int(self.value(f.value if kind == "goto" else f.args[0]))
            if target not in self.numbers:
                raise self.run.error(f"GOTO {target}: no block N{target} in the file")
            return self.numbers[target]
        if kind == "call":
            return self.call(pc, f)
        if kind in ("endsub", "return"):
            return self.leave(block)
        return self.structure(pc, f)

    def call(self, pc: int, f: Flow) -> int:
        if f.label not in self.subs:
            raise self.run.error(f"o{f.label} call: no o{f.label} sub in the file")
        args = [self.value(a) for a in f.args]
        numbered = self.run.params.numbered
        saved = {k: numbered.get(k) for k in range(1, LOCAL_PARAMETERS + 1)}
        for k in range(1, LOCAL_PARAMETERS + 1):
            numbered.pop(k, None)
        for k, a in enumerate(args, start=1):
            self.run.params.set(k, a)
        self.calls.append((pc + 1, saved, 1, self.subs[f.label]))
        return self.subs[f.label] + 1

    def structure(self, pc: int, f: Flow) -> int:
        """Loops and branches: each jumps by the indices ``_pairs`` found."""
        kind, ends = f.kind, self.pairs.get(pc, ())
        if kind == "sub":
            return ends[-1] + 1  # a definition: skipped where it stands
        if kind in ("while", "fwhile") and f.value is not None and (kind == "fwhile" or ends):
            if ends and self.blocks[ends[0]].flow.kind == "do":  # the tail of a do ... while
                return ends[0] + 1 if self.value(f.value) else pc + 1
            return pc + 1 if self.value(f.value) else ends[-1] + 1
        if kind in ("endwhile", "fend"):
            return ends[0]
        if kind == "repeat":
            self.counts[pc] = int(self.value(f.value))
            return pc + 1 if self.counts[pc] > 0 else ends[-1] + 1
        if kind == "endrepeat":
            start = ends[0]
            self.counts[start] -= 1
            return start + 1 if self.counts[start] > 0 else pc + 1
        if kind == "if":
            return self.branch(pc, ends)
        if kind in ("elseif", "else"):
            return ends[-1] + 1  # a branch that ran ends here
        if kind in ("break", "continue"):
            loop = ends
            return loop[-1] + 1 if kind == "break" else loop[-1]
        return pc + 1  # do, endif

    def branch(self, pc: int, ends: tuple) -> int:
        """``if`` … ``elseif`` … ``else`` … ``endif``: the first branch whose condition holds."""
        for k in (pc,) + ends[:-1]:
            f = self.blocks[k].flow
            if f.kind == "else" or self.value(f.value):
                return k + 1
        return ends[-1] + 1


_OPENERS = {"sub": "endsub", "while": "endwhile", "if": "endif", "repeat": "endrepeat", "do": "while", "fwhile": "fend"}


def _pairs(blocks: tuple, source: str) -> dict[int, tuple]:
    """For each opening flow block the indices of its other parts, its closing one last (an
    ``if``: its ``elseif``/``else`` and ``endif``); for a closing block its opening one; for
    ``break``/``continue`` the enclosing loop's (opening, closing). InputError for a block that
    closes nothing or an opening never closed."""
    pairs: dict[int, tuple] = {}
    open_: list[tuple[int, Flow, list[int]]] = []
    for k, b in enumerate(blocks):
        f = b.flow
        if f is None:
            continue
        if f.kind == "while" and open_ and open_[-1][1].kind == "do" and open_[-1][1].label == f.label:
            start = open_.pop()[0]
            pairs[start], pairs[k] = (k,), (start,)  # do ... while: the tail
            continue
        if f.kind in _OPENERS:
            open_.append((k, f, []))
        elif f.kind in ("elseif", "else"):
            if not open_ or open_[-1][1].kind != "if" or open_[-1][1].label != f.label:
                raise InputError(f"{source}:{b.line}: o{f.label} {f.kind} without its o{f.label} if")
            open_[-1][2].append(k)
        elif f.kind in ("break", "continue"):
            loop = next(((s, g) for s, g, _ in reversed(open_) if g.label == f.label and g.kind in
                         ("while", "do", "repeat", "fwhile")), None)
            if loop is None:
                raise InputError(f"{source}:{b.line}: o{f.label} {f.kind} outside a loop o{f.label}")
            pairs[k] = (loop[0],)  # completed below, once the loop's end is known
        elif f.kind in ("endsub", "endwhile", "endif", "endrepeat", "fend"):
            if not open_ or _OPENERS[open_[-1][1].kind] != f.kind or open_[-1][1].label != f.label:
                raise InputError(f"{source}:{b.line}: {_shown(f)} closes no open block")
            start, _, parts = open_.pop()
            pairs[start], pairs[k] = tuple(parts) + (k,), (start,)
            for p in parts:
                pairs[p] = (k,)
    if open_:
        start, f, _ = open_[-1]
        raise InputError(f"{source}:{blocks[start].line}: {_shown(f)} is never closed")
    for k, b in enumerate(blocks):  # break: past the loop's end; continue: to its end (which loops)
        if b.flow is not None and b.flow.kind in ("break", "continue"):
            start = pairs[k][0]
            pairs[k] = (start, pairs[start][-1])
    return pairs


def _shown(f: Flow) -> str:
    if f.kind == "fwhile":
        return f"WHILE ... DO{f.label}"
    if f.kind == "fend":
        return f"END{f.label}"
    return f"o{f.label} {f.kind}"


def _n_word(block) -> Optional[int]:
    return next((int(e[1]) for letter, e in block.words if letter == "N" and e[0] == "num"), None)

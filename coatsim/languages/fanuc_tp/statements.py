"""Fanuc TP instructions as values: what each line of ``/MN`` says.

Motion: ``J|L|C|A target [target] speed termination [options]`` with targets ``P[i]``/``PR[i]``,
speed ``n%``, ``n mm/sec``, ``cm/min``, ``inch/min``, ``deg/sec``, ``sec``, ``msec`` or
``max_speed`` (the value may be a register), termination ``FINE``, ``CNT n`` or ``CR n``, options
``ACC n``, ``Offset[,PR[i]]``, ``Tool_Offset[,PR[i]]``, ``INC`` and others (noted). Control:
labels and jumps, ``IF … ,action``, ``IF (…) THEN``/``ELSE``/``ENDIF``, ``SELECT`` with its case
lines, ``FOR``/``ENDFOR``, ``CALL``, ``WAIT``, ``END``/``ABORT``/``PAUSE``. Data: assignments to
registers, position registers (whole, an element, from ``LPOS``/``JPOS``/frames, sums), frames
(``UFRAME[i]=PR[j]``, ``UTOOL_NUM=i``), signals (``DO[i]=ON``, ``PULSE``), ``OVERRIDE``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Optional, Union

from coatsim.languages.fanuc_tp.expressions import SIGNALS, Expr, Tokens, tokenize

SPEED_UNITS = {("%",): "%", ("MM", "/", "SEC"): "mm/sec", ("CM", "/", "MIN"): "cm/min",
               ("INCH", "/", "MIN"): "inch/min", ("DEG", "/", "SEC"): "deg/sec", ("SEC",): "sec",
               ("MSEC",): "msec"}
#: Motion options the twin runs as if absent (they change how the arm moves its joints, not the path).
PASSIVE_OPTIONS = ("WJNT", "PTH", "RT_LD", "AP_LD", "LD", "CTV", "BREAK", "MROT", "PSPD")
_TERM = re.compile(r"(CNT|CR)(\d+(?:\.\d*)?)\Z")
#: Instructions without motion the twin passes silently, and those it notes (one warning each).
_SILENT = ("MESSAGE", "TIMER", "PAYLOAD", "COL", "LOCK", "UNLOCK", "JOINT_MAX_SPEED", "LINEAR_MAX_SPEED")
_NOTED = ("RSR", "TIME_SEGMENT", "UALM", "SKIP", "STOP_TRACKING", "CLEAR_RESUME_PROG", "DIAG_REC")


@dataclass(frozen=True)
class Motion:
    line: int
    kind: str  # J, L, C, A
    targets: tuple[tuple[str, Expr], ...]  # ("P" | "PR", index)
    speed: Optional[Expr]
    unit: str  # one of SPEED_UNITS' values, "max", or an application's speed name
    term: str  # FINE, CNT, CR
    term_value: Optional[Expr]
    options: tuple[tuple[str, Optional[Expr]], ...]  # ACC n, OFFSET (PR index or None), TOOL_OFFSET, INC
    other_options: str = ""
    end_line: int = 0  # the last file line of a motion written over several (a C motion's end point)


@dataclass(frozen=True)
class Assign:
    """``target = value``: target ("reg", kind, index[, element]) or ("name", NAME); value an
    expression, or for a position ("pos", ((sign, atom), …)) with atoms ("LPOS",), ("JPOS",),
    ("PR" | "UFRAME" | "UTOOL", index)."""

    line: int
    target: Expr
    value: Expr


@dataclass(frozen=True)
class Pulse:
    line: int
    target: Expr
    seconds: Optional[Expr]


@dataclass(frozen=True)
class Label:
    line: int
    index: Expr


@dataclass(frozen=True)
class Jump:
    line: int
    index: Expr


@dataclass(frozen=True)
class If:
    line: int
    condition: Expr
    action: "Statement"


@dataclass(frozen=True)
class Block:
    """``IF (cond) THEN`` (kind IF), ``ELSE``, ``ENDIF``, ``FOR`` … ``ENDFOR``."""

    line: int
    kind: str
    condition: Optional[Expr] = None
    register: Optional[Expr] = None
    start: Optional[Expr] = None
    stop: Optional[Expr] = None
    down: bool = False


@dataclass(frozen=True)
class Select:
    """``SELECT R[i]=value,action`` and its case lines (a case line alone has no ``subject``)."""

    line: int
    subject: Optional[Expr]
    cases: tuple[tuple[Optional[Expr], "Statement"], ...]  # (value, action); value None: ELSE


@dataclass(frozen=True)
class Call:
    line: int
    name: str
    args: tuple[Union[Expr, str], ...]


@dataclass(frozen=True)
class Wait:
    line: int
    seconds: Optional[Expr]
    condition: Optional[Expr]
    timeout_label: Optional[Expr]


@dataclass(frozen=True)
class Stop:
    line: int
    kind: str  # END, ABORT, PAUSE


@dataclass(frozen=True)
class Remark:
    line: int
    text: str


@dataclass(frozen=True)
class Note:
    """An instruction the twin does not simulate (one warning), or ``ignored`` silently."""

    line: int
    text: str
    ignored: bool = False


Statement = Union[Motion, Assign, Pulse, Label, Jump, If, Block, Select, Call, Wait, Stop, Remark, Note]


def _target(t: Tokens) -> tuple[str, Expr]:
    kind = t.name()
    if kind not in ("P", "PR"):
        raise t.error(f"a motion goes to P[i] or PR[i], not {kind!r}")
    return kind, t.index()


def _speed(t: Tokens) -> tuple[Optional[Expr], str]:
    if t.take("MAX_SPEED"):
        return None, "max"
    tok = t.peek()
    if tok is not None and tok.kind == "name" and tok.text not in ("R", "AR"):
        t.i += 1
        return None, tok.text  # an application's speed (WELD_SPEED, …)
    value = t._atom()
    for words, unit in SPEED_UNITS.items():
        if all(t.peek(k) is not None and t.peek(k).text == w for k, w in enumerate(words)):
            t.i += len(words)
            return value, unit
    raise t.error("a motion's speed needs a unit: %, mm/sec, cm/min, inch/min, deg/sec, sec or msec")


def _termination(t: Tokens) -> tuple[str, Optional[Expr]]:
    if t.done():
        raise t.error("a motion ends FINE, CNT n or CR n")
    word = t.name()
    if word == "FINE":
        return "FINE", None
    joined = _TERM.match(word)
    if joined:
        return joined.group(1), ("num", float(joined.group(2)))
    if word in ("CNT", "CR"):
        return word, t._atom()
    raise t.error(f"a motion ends FINE, CNT n or CR n, not {word!r}")


def _options(t: Tokens) -> tuple[tuple[tuple[str, Optional[Expr]], ...], str]:
    options: list[tuple[str, Optional[Expr]]] = []
    while not t.done():
        word = t.peek().text
        if word.startswith("ACC") and word != "ACC" and word[3:].isdigit():
            t.i += 1
            options.append(("ACC", ("num", float(word[3:]))))
        elif t.take("ACC"):
            options.append(("ACC", t._atom()))
        elif word in ("OFFSET", "TOOL_OFFSET"):
            t.i += 1
            register = None
            if t.take(","):
                t.expect("PR")
                register = t.index()
            options.append((word, register))
        elif t.take("INC"):
            options.append(("INC", None))
        elif word in PASSIVE_OPTIONS:
            t.i += 1
            if t.peek() is not None and t.peek().kind == "num":
                t.i += 1
        else:
            rest = t.rest()
            t.i = len(t.t)
            return tuple(options), rest
    return tuple(options), ""


def _motion(t: Tokens, line: int) -> Motion:
    kind = t.name()
    targets = [_target(t)]
    if kind == "C":
        t.take(":")
        targets.append(_target(t))
    speed, unit = _speed(t)
    term, value = _termination(t)
    options, other = _options(t)
    return Motion(line, kind, tuple(targets), speed, unit, term, value, options, other)


def _position_value(t: Tokens) -> Expr:
    """The right side of a position register assignment."""
    items = []
    sign = "+"
    while True:
        word = t.name()
        if word in ("LPOS", "JPOS"):
            items.append((sign, (word,)))
        elif word in ("PR", "UFRAME", "UTOOL", "P"):
            items.append((sign, (word, t.index())))
        else:
            raise t.error(f"a position register takes LPOS, JPOS, PR[i], UFRAME[i] or UTOOL[i], not {word!r}")
        op = t.take("+", "-")
        if op is None:
            return ("pos", tuple(items))
        sign = op.text


def _assignment(t: Tokens, line: int) -> Statement:
    word = t.name()
    if word in ("R", "AR", "PR", "SR", *SIGNALS) or (word in ("UFRAME", "UTOOL") and t.at("[")):
        target = t.register(word)
    else:
        target = ("name", word)
    t.expect("=")
    if word in SIGNALS and t.take("PULSE"):
        seconds = None
        if t.take(","):
            seconds = t._atom()
            t.take("SEC")
        return Pulse(line, target, seconds)
    whole_position = word == "PR" and len(target) == 3
    if whole_position or (word in ("UFRAME", "UTOOL") and target[0] == "reg"):
        value = _position_value(t)
    elif word == "SR":
        return Note(line, "string registers", ignored=True)
    else:
        value = t.expression()
        t.take("%")  # OVERRIDE=50%
    if not t.done():
        raise t.error(f"unexpected {t.rest()!r} after the value")
    return Assign(line, target, value)


def _wait(t: Tokens, line: int) -> Wait:
    value = t.expression()
    if t.take("("):
        t.expect("SEC")
        t.expect(")")
        return Wait(line, value, None, None)
    if t.done() and value[0] in ("num", "reg") and (value[0] == "num" or value[1] == "R"):
        return Wait(line, value, None, None)  # WAIT R[1]: seconds in a register
    timeout = None
    if t.take("TIMEOUT"):
        t.expect(",")
        t.expect("LBL")
        timeout = t.index()
    return Wait(line, None, value, timeout)


def _call(t: Tokens, line: int) -> Call:
    name = t.name()
    args: list[Union[Expr, str]] = []
    if t.take("("):
        while not t.take(")"):
            tok = t.peek()
            if tok is not None and tok.kind == "str":
                t.i += 1
                args.append(tok.text[1:-1])
            else:
                args.append(t.expression())
            t.take(",")
            if t.done():
                raise t.error("a CALL's arguments are not closed")
    return Call(line, name, tuple(args))


def _statement(t: Tokens, line: int) -> Statement:
    """One instruction from the cursor (also the action of an IF or a SELECT case)."""
    first, second = t.peek(), t.peek(1)
    word = first.text
    if word in ("J", "L", "C", "A") and second is not None and second.text in ("P", "PR"):
        return _motion(t, line)
    t.i += 1
    if word == "LBL":
        return Label(line, t.index())
    if word == "JMP":
        t.expect("LBL")
        return Jump(line, t.index())
    if word == "CALL":
        return _call(t, line)
    if word == "RUN":
        return Note(line, f"RUN {t.rest()} (a task started beside this one)")
    if word == "WAIT":
        return _wait(t, line)
    if word in ("END", "ABORT", "PAUSE"):
        return Stop(line, word)
    if word == "IF":
        condition = t.expression()
        if t.take("THEN"):
            return Block(line, "IF", condition=condition)
        t.expect(",")
        return If(line, condition, _statement(t, line))
    if word in ("ELSE", "ENDIF", "ENDFOR") and t.done():
        return Block(line, word)
    if word == "FOR":
        t.expect("R")
        register = t.index()
        t.expect("=")
        start = t.expression()
        down = t.take("TO", "DOWNTO")
        if down is None:
            raise t.error("FOR R[i]=start TO|DOWNTO end")
        return Block(line, "FOR", register=register, start=start, stop=t.expression(), down=down.text == "DOWNTO")
    if word == "SELECT":
        t.expect("R")
        subject = ("reg", "R", t.index())
        t.expect("=")
        value = t.expression()
        t.expect(",")
        return Select(line, subject, ((value, _statement(t, line)),))
    if word in ("OFFSET", "TOOL_OFFSET") and t.take("CONDITION"):
        t.expect("PR")
        return Assign(line, ("name", word), ("pos", (("+", ("PR", t.index())),)))
    if word in _SILENT + _NOTED or word.startswith("$"):
        return Note(line, " ".join([word, t.rest()]).strip(), ignored=word in _SILENT)
    t.i -= 1
    if second is not None and second.text in ("=", "["):
        return _assignment(t, line)
    return Note(line, t.rest().strip())


def parse_instruction(text: str, line: int, where: str) -> Optional[Statement]:
    """The statement of one instruction (``text`` without its ``;``); None for an empty one or a
    line commented out with ``//``."""
    stripped = text.strip()
    if not stripped or stripped.startswith("//"):
        return None
    if stripped.startswith("!"):
        return Remark(line, stripped[1:].strip())
    if stripped.startswith("--"):
        return Remark(line, stripped.lstrip("-").strip())
    t = Tokens(tokenize(stripped, where), where)
    if t.at("=") or (t.at("ELSE") and t.peek(1) is not None and t.peek(1).text == ","):
        return _select_case(t, line)
    statement = _statement(t, line)
    if not t.done() and not isinstance(statement, Note):
        raise t.error(f"unexpected {t.rest()!r} at the end of the instruction")
    return statement


def _select_case(t: Tokens, line: int) -> Select:
    """A SELECT case line (``=value,action`` or ``ELSE,action``), joined to its SELECT by the parser."""
    value = None
    if t.take("="):
        value = t.expression()
    else:
        t.expect("ELSE")
    t.expect(",")
    return Select(line, None, ((value, _statement(t, line)),))

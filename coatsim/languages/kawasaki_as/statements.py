"""One AS program line -> its label and statement (or block marker).

Every instruction word is parsed into its typed statement; block statements come back as
markers (:mod:`~coatsim.languages.kawasaki_as.statements_flow`) that
:mod:`~coatsim.languages.kawasaki_as.blocks` nests into blocks.
"""

from __future__ import annotations

from typing import Callable, Union

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.instructions import (
    BLOCK_STEPS,
    COMMANDS,
    RAW_TEXT,
    SWITCHES,
)
from coatsim.languages.kawasaki_as.keywords import Keywords
from coatsim.languages.kawasaki_as.lexer import Token
from coatsim.languages.kawasaki_as.source import AsSyntaxError
from coatsim.languages.kawasaki_as.statement_parser import StatementParser
from coatsim.languages.kawasaki_as.statements_flow import FLOW_PARSERS, Item

_UNITS = {"MM": ("S", "MIN"), "CM": ("S", "MIN"), "DEG": ("S", "MIN")}
_POINT_PARTS = ("X", "Y", "Z", "O", "A", "T", "OAT")


Parser = Callable[[StatementParser, str, int], Item]


def _move(c: StatementParser, op: str, line: int) -> Item:
    target = c.expr("a pose")
    if op == "XMOVE":
        c.expect_word("TILL", "in XMOVE pose TILL signal")
        return ast.Move(line, op, target, till=c.expr("a signal"))
    clamp = None
    if c.is_op(","):
        c.take()
        clamp = c.expr("a clamp number")
    return ast.Move(line, op, target, clamp)


def _appro(c: StatementParser, op: str, line: int) -> Item:
    target = c.expr("a pose")
    c.op(",", f"between the pose and the distance of {op}")
    return ast.Appro(line, op, target, c.expr("a distance in mm"))


def _speed(c: StatementParser, op: str, line: int) -> Item:
    value = c.expr("a speed value")
    unit = "%"
    if c.is_op("%"):
        c.take()
    elif c.is_word(*_UNITS):
        base = c.take().upper
        c.op("/", f"in the speed unit {base}/S or {base}/MIN")
        word = c.word(*_UNITS[base])
        if word is None:
            raise c.error(f"expected 'S' or 'MIN' after '{base}/', found {c.found(c.peek())}", c.peek())
        unit = f"{base}/{word}"
    elif c.word("S"):
        unit = "S"
    if c.is_op(","):  # (no AS reference at hand shows a second, rotation speed: refused, not guessed)
        raise c.error("SPEED with a second speed after ',' (a rotation speed?) is not read: the AS references "
                      "coatsim follows show one speed; write SPEED v [unit] [ALWAYS]", c.peek())
    always = c.qualifier("ALWAYS") is not None
    if not c.at_end():
        raise c.error(f"unexpected {c.peek().show()} in SPEED; expected a unit (%, MM/S, MM/MIN, S), ALWAYS or "
                      "end of line", c.peek())
    return ast.Speed(line, value, unit, always)


def _accuracy(c: StatementParser, op: str, line: int) -> Item:
    value = c.expr("an accuracy in mm")
    flags: set[str] = set()
    while not c.at_end():
        word = c.qualifier("ALWAYS", "FINE")
        if word is None:
            raise c.error(f"unexpected {c.peek().show()} in ACCURACY; expected ALWAYS, FINE or end of line", c.peek())
        if word in flags:
            raise c.error(f"{word} given twice in ACCURACY", c.tokens[c.pos - 1])
        flags.add(word)
    return ast.Accuracy(line, value, "ALWAYS" in flags, "FINE" in flags)


def _on_off(c: StatementParser, name: str) -> bool:
    if c.is_op("="):
        c.take()
    word = c.word("ON", "OFF")
    if word is None:
        raise c.error(f"expected ON or OFF after {name}, found {c.found(c.peek())}", c.peek())
    return word == "ON"


def _switch(c: StatementParser, op: str, line: int) -> Item:
    name = op
    if op == "SWITCH":
        tok = c.take()
        if tok is None or tok.kind != "name":
            raise c.error(f"expected a switch name after SWITCH, found {c.found(tok)}", tok)
        name = tok.upper
    return ast.Switch(line, name, _on_off(c, name))


def _point(c: StatementParser, op: str, line: int) -> Item:
    component = None
    if c.is_op("/"):
        c.take()
        tok = c.peek()
        if tok is not None and tok.kind == "num" and tok.text.isdigit() and 7 <= int(tok.text) <= ast.MAX_AXES:
            component = str(int(c.take().text))  # an external axis: POINT/7 p = TRANS(,,,,,,1200)
        else:
            component = c.word(*_POINT_PARTS)
        if component is None:
            raise c.error(f"expected one of {', '.join(_POINT_PARTS)} or an external axis 7..{ast.MAX_AXES} after "
                          f"'POINT/', found {c.found(c.peek())}", c.peek())
    target = c.target_name("a pose or joint variable")
    if target.kind == "string":
        raise c.error(f"POINT assigns poses and joint values; assign the string {target.name} with '='")
    c.op("=", f"after POINT {target.name}")
    value = c.expr("a pose")
    reference = None
    if c.is_op(","):
        c.take()
        reference = c.expr("a joint value (the configuration)")
        if target.kind != "joint":
            raise c.error(f"POINT {target.name} = pose, #ref: the reference joint value picks the configuration of "
                          "a joint value; assign it to a #name")
    return ast.PointAssign(line, target, value, component, reference)


def _decompose(c: StatementParser, op: str, line: int) -> Item:
    target = c.target_name("an array element such as a[1]")
    c.op("=", "in DECOMPOSE array[i] = pose")
    return ast.Decompose(line, target, c.expr("a pose"))


def _pulse(c: StatementParser, op: str, line: int) -> Item:
    signal = c.expr("a signal number")
    seconds = None
    if op == "DLYSIG" or not c.at_end():
        c.op(",", f"in {op} signal, time")
        seconds = c.expr("a time in s")
    return ast.Pulse(line, op, signal, seconds)


def _bits(c: StatementParser, op: str, line: int) -> Item:
    start = c.expr("the first signal number")
    c.op(",", f"in {op} start, count = value")
    count = c.expr("a signal count")
    c.op("=", f"in {op} start, count = value")
    return ast.Bits(line, start, count, c.expr("a value"))


def _output(c: StatementParser, op: str, line: int) -> Item:
    if c.peek() is not None and c.peek().kind == "num" and c.peek(1) is not None and c.peek(1).text == ":":
        c.pos += 2  # a device number: PRINT 2: ...
    items = list(c.format_items(None))
    target = None
    if op == "PROMPT":
        if not items or not isinstance(items[-1], ast.Name):
            raise c.error("PROMPT needs a variable to receive the answer as its last item")
        target = items.pop()
    return ast.Output(line, op, tuple(items), target)


def _call(c: StatementParser, op: str, line: int) -> Item:
    if op == "SCALL":
        tok = c.take()
        if tok is None or not (tok.kind == "str" or (tok.kind == "name" and tok.text.lstrip(".")[:1] == "$")):
            raise c.error(f"expected a string (the program name) after SCALL, found {c.found(tok)}", tok)
        program: Union[str, ast.Expr] = ast.Str(str(tok.value)) if tok.kind == "str" else c.variable(tok)
    else:
        tok = c.take()
        if tok is None or tok.kind != "name" or not tok.text[:1].isalpha():
            raise c.error(f"expected a program name after CALL, found {c.found(tok)}", tok)
        program = tok.text
    args: tuple = ()
    if c.is_op("("):
        c.take()
        args = c.arguments(")", "an argument", allow_ref=True)
        if any(a is None for a in args):
            raise c.error("an argument of CALL is empty")
    return ast.CallProgram(line, program, args)


def _command(c: StatementParser, op: str, line: int) -> Item:
    text = c.rest_text()
    args: tuple[ast.Expr, ...] = ()
    if op not in RAW_TEXT and not c.at_end():
        start = c.pos
        try:
            parsed = c.arguments_until_end()
        except AsSyntaxError:  # not expression syntax: kept as text only
            c.pos, parsed = start, ()
        args = parsed
    c.pos = len(c.tokens)
    return ast.Command(line, op, args, text)


def _simple(factory: Callable[[int], Item]) -> Parser:
    def parse(c: StatementParser, op: str, line: int) -> Item:
        c.end(op)
        return factory(line)
    return parse


def _accel(c: StatementParser, op: str, line: int) -> ast.Accel:
    """ACCEL / DECEL percent [ALWAYS]; a second percentage, which RoboDK's post writes (``ACCEL 50
    50``), is read and left, as the first is (the cell's limits apply)."""
    value = c.expr("a percentage")
    always = c.qualifier("ALWAYS") is not None
    if not always and not c.at_end():
        c.expr("a percentage")
        always = c.qualifier("ALWAYS") is not None
    return ast.Accel(line, op, value, always)


def _one(factory: Callable[[int, ast.Expr], Item], what: str) -> Parser:
    return lambda c, op, line: factory(line, c.expr(what))


PARSERS: dict[str, Parser] = {
    **dict.fromkeys(("JMOVE", "LMOVE", "C1MOVE", "C2MOVE", "XMOVE", "HMOVE"), _move),
    **dict.fromkeys(("JAPPRO", "LAPPRO"), _appro),
    **dict.fromkeys(("JDEPART", "LDEPART"), lambda c, op, line: ast.Depart(line, op, c.expr("a distance in mm"))),
    **dict.fromkeys(("DRAW", "TDRAW"), lambda c, op, line: ast.Draw(line, op, c.optional_list(f"{op} value", 7))),
    "HOME": lambda c, op, line: ast.Home(line, None if c.at_end() else c.expr("a home number")),
    "HOME2": _simple(lambda line: ast.Home(line, ast.Num(2.0))),
    **dict.fromkeys(("DELAY", "STABLE"), lambda c, op, line: ast.Delay(line, op, c.expr("a time in s"))),
    "SPEED": _speed,
    "ACCURACY": _accuracy,
    **dict.fromkeys(("ACCEL", "DECEL"), _accel),
    **dict.fromkeys((*SWITCHES, "SWITCH"), _switch),
    "BREAK": _simple(ast.Break),
    "BRAKE": _simple(ast.Brake),
    "TOOL": _one(ast.Tool, "a pose"),
    "BASE": _one(ast.Base, "a pose"),
    "POINT": _point,
    "DECOMPOSE": _decompose,
    "HERE": lambda c, op, line: ast.Here(line, c.target_name("a pose or joint variable")),
    "SIGNAL": lambda c, op, line: ast.Signal(line, c.expr_list("a signal number")),
    **dict.fromkeys(("PULSE", "DLYSIG"), _pulse),
    **dict.fromkeys(("BITS", "BITS32"), _bits),
    "SWAIT": lambda c, op, line: ast.Swait(line, c.expr_list("a signal number")),
    "WAIT": lambda c, op, line: ast.Wait(line, c.condition()),
    "TWAIT": _one(ast.Twait, "a time in s"),
    **dict.fromkeys(("TYPE", "PRINT", "PROMPT"), _output),
    **dict.fromkeys(("CALL", "SCALL"), _call),
    "GOTO": lambda c, op, line: ast.Goto(line, c.label()),
    **dict.fromkeys(("RETURN", "RETURNE"), _simple(ast.Return)),  # RETURNE: from an error program
    **dict.fromkeys(("STOP", "HALT", "PAUSE"), lambda c, op, line: ast.Stop(line, op)),
    "EXIT": _simple(ast.Exit),
    **FLOW_PARSERS,
    **dict.fromkeys(COMMANDS, _command),
}
_NOT_LABELS = {"VALUE", "SVALUE", "ANY"}
KEYWORDS = Keywords((*PARSERS, *BLOCK_STEPS))


def parse_line(tokens: list[Token], source: str, line: int, text: str) -> list[Item]:
    """The label (as an :class:`ast.Label`) and the statement of one program line."""
    c = StatementParser(tokens, source, line, len(text), text)
    items: list[Item] = []
    first, second = c.peek(), c.peek(1)
    if first is not None and first.kind == "num" and first.text.isdigit():
        c.take()
        items.append(ast.Label(line, str(int(first.text))))
    elif (first is not None and first.kind == "name" and second is not None and second.text == ":"
          and first.upper not in _NOT_LABELS and first.text[:1].isalpha()):
        c.pos = 2
        items.append(ast.Label(line, first.text.lower()))
    keyword = c.peek()
    if keyword is None:
        return items
    if keyword.kind != "name":
        raise c.error(f"expected a statement keyword, found {keyword.show()}", keyword)
    if _is_assignment(c):
        items.append(_assignment(c, line))
        return items
    word = _instruction(c, keyword)
    if word in BLOCK_STEPS:
        items.append(ast.BlockStep(line, word, c.rest_text()))
        return items
    c.take()
    statement = PARSERS.get(word, _switch)(c, word, line)
    c.end(f"{word} statement")
    items.append(statement)
    return items


def _is_assignment(c: StatementParser) -> bool:
    """``name = ...`` or ``name[...] = ...``: an assignment, whatever the name (``value[i] = 1``
    assigns an array called value)."""
    nxt = c.peek(1)
    if nxt is None or nxt.kind != "op":
        return False
    if nxt.text == "=":
        return True
    if nxt.text != "[":
        return False
    depth, i = 0, c.pos + 1
    while i < len(c.tokens):
        tok = c.tokens[i]
        if tok.kind == "op" and tok.text == "[":
            depth += 1
        elif tok.kind == "op" and tok.text == "]":
            depth -= 1
            if depth == 0:
                after = c.tokens[i + 1] if i + 1 < len(c.tokens) else None
                return after is not None and after.kind == "op" and after.text == "="
        i += 1
    return False


def _instruction(c: StatementParser, keyword: Token) -> str:
    """The instruction a statement's first word names: the word itself, a system switch set by
    name (``DISP.EXESTEP ON``), or the instruction it abbreviates."""
    word = keyword.upper
    if word in PARSERS or word in BLOCK_STEPS:
        return word
    if _is_switch_line(c):
        return word  # (parsed as a switch: no instruction has this name)
    full, matches = KEYWORDS.expand(word)
    if full is not None:
        return full
    fits = [m for m in matches if _reads_as(c, m)]
    if len(fits) == 1:
        return fits[0]  # (SW 1001: SWAIT; a SWITCH needs a switch name)
    if matches:
        raise c.error(f"{keyword.show()} abbreviates several AS instructions ({', '.join(matches[:6])}"
                      f"{', ...' if len(matches) > 6 else ''}); write the one meant in full", keyword)
    raise c.error(f"{keyword.show()} is not an AS instruction coatsim knows", keyword)


def _reads_as(c: StatementParser, word: str) -> bool:
    """Whether the rest of the line reads as the instruction ``word`` (the cursor is left where it was)."""
    if word in BLOCK_STEPS:
        return False
    pos, depth = c.pos, c.depth
    try:
        c.take()
        PARSERS.get(word, _switch)(c, word, 0)
        c.end(f"{word} statement")
        return True
    except AsSyntaxError:
        return False
    finally:
        c.pos, c.depth = pos, depth


def _is_switch_line(c: StatementParser) -> bool:
    """``NAME ON`` / ``NAME OFF`` and nothing else: a system switch set by the program."""
    rest = c.tokens[c.pos + 1:]
    return len(rest) == 1 and rest[0].kind == "name" and rest[0].upper in ("ON", "OFF") \
        and c.tokens[c.pos].text[:1].isalpha()


def _assignment(c: StatementParser, line: int) -> ast.Assign:
    target = c.target_name("a variable")
    if target.kind == "joint":
        raise c.error(f"assign the joint value {target.name} with POINT {target.name} = ...")
    c.op("=", f"after {target.name}")
    value = c.expr("a value")
    c.end("assignment")
    return ast.Assign(line, target, value)

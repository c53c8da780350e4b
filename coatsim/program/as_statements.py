"""Parser of one AS statement line (after its label) into an :mod:`as_ast` statement."""

from __future__ import annotations

from typing import Callable, Optional

from coatsim.program import as_ast as ast
from coatsim.program.as_lexer import Cursor, Token

_MAX_NESTING = 16
_RESERVED = {"ALWAYS", "FINE", "BY", "ON", "OFF", "MM", "S", "MIN", "TRANS", "SHIFT", "NULL"}
_KNOWN_OTHER = {
    "CALL", "RETURN", "GOTO", "IF", "ELSE", "END", "WHILE", "DO", "UNTIL", "FOR", "CASE", "VALUE",
    "ANY", "PRINT", "TYPE", "PAUSE", "HALT", "STOP", "WAIT", "SWAIT", "MVWAIT", "PULSE", "DLYSIG",
    "BITS", "DRIVE", "XMOVE", "ALIGN", "STABLE", "HERE", "DECOMPOSE", "QTOOL", "SETHOME", "SWITCH",
}
SUBSET = ("JMOVE, LMOVE, C1MOVE, C2MOVE, JAPPRO, LAPPRO, JDEPART, LDEPART, DRAW, TDRAW, HOME, DELAY, "
          "SPEED, ACCURACY, ACCEL, DECEL, CP, BREAK, SIGNAL, TWAIT, TOOL, BASE, POINT")


class _StatementCursor(Cursor):
    """Cursor with the expression grammar of statements."""

    depth = 0

    def found(self, tok: Optional[Token]) -> str:
        return tok.show() if tok is not None else "end of line"

    def punct(self, text: str, context: str) -> None:
        tok = self.take()
        if tok is None or tok.text != text:
            raise self.error(f"expected '{text}' {context}, found {self.found(tok)}", tok)

    def word(self, *words: str) -> Optional[str]:
        """Take the next token if it is one of the keywords ``words``."""
        tok = self.peek()
        if tok is not None and tok.kind == "name" and tok.upper in words:
            self.take()
            return tok.upper
        return None

    def num(self, what: str) -> ast.Num:
        tok = self.peek()
        negate = tok is not None and tok.text == "-"
        if tok is not None and tok.text in ("+", "-"):
            self.take()
            tok = self.peek()
        if tok is not None and tok.kind == "name" and tok.upper not in _RESERVED and not tok.text.startswith("."):
            return ast.RealRef(self.name(what), negate)
        if tok is None or tok.kind != "num":
            raise self.error(f"expected {what}, found {self.found(tok)}", tok)
        self.take()
        return -float(tok.text) if negate else float(tok.text)

    def integer(self, what: str) -> int:
        tok = self.peek()
        sign = 1
        if tok is not None and tok.text == "-":
            sign, _ = -1, self.take()
            tok = self.peek()
        if tok is None or tok.kind != "num" or not tok.text.isdigit():
            raise self.error(f"expected {what} (a whole number), found {self.found(tok)}", tok)
        self.take()
        return sign * int(tok.text)

    def nums(self, count: int, what: str) -> tuple[ast.Num, ...]:
        values = [self.num(what)]
        for _ in range(count - 1):
            self.punct(",", f"between the {what}s")
            values.append(self.num(what))
        return tuple(values)

    def pose(self) -> ast.PoseExpr:
        """pose := primary ('+' primary)*"""
        expr = self.primary()
        while self.peek() is not None and self.peek().text == "+":
            self.take()
            expr = ast.Compose(expr, self.primary())
        return expr

    def primary(self) -> ast.PoseExpr:
        tok = self.peek()
        if tok is not None and tok.text == "#":
            nxt = self.tokens[self.pos + 1] if self.pos + 1 < len(self.tokens) else None
            if nxt is not None and nxt.text == "[":
                self.pos += 2
                values = [self.num("a joint value")]
                while self.peek() is not None and self.peek().text == ",":
                    self.take()
                    values.append(self.num("a joint value"))
                self.punct("]", "after the joint values")
                return ast.JointLiteral(tuple(values))
            return ast.JointName(self.name("a joint pose name", joint=True))
        if tok is None or tok.kind != "name":
            raise self.error(f"expected a pose (a name, TRANS(...) or SHIFT(...)), found {self.found(tok)}", tok)
        if tok.upper == "NULL":
            self.take()
            return ast.NullPose()
        if tok.upper in ("TRANS", "SHIFT"):
            self.take()
            self.punct("(", f"after {tok.upper}")
            if tok.upper == "TRANS":
                values = self.nums(6, "TRANS value")
                self.punct(")", "after the 6 TRANS values x, y, z, o, a, t")
                return ast.TransLiteral(values)
            self.depth += 1
            if self.depth > _MAX_NESTING:
                raise self.error(f"SHIFT nested more than {_MAX_NESTING} deep", tok)
            base = self.pose()
            if self.word("BY") is None:
                raise self.error(f"expected 'BY' in SHIFT(pose BY dx, dy, dz), found {self.found(self.peek())}", self.peek())
            delta = self.nums(3, "SHIFT offset")
            self.punct(")", "after SHIFT(pose BY dx, dy, dz")
            self.depth -= 1
            return ast.Shift(base, (delta[0], delta[1], delta[2]))
        return ast.PoseName(self.name("a pose name"))

    def end(self, keyword: str) -> None:
        tok = self.peek()
        if tok is not None:
            raise self.error(f"unexpected {tok.show()} after the {keyword} statement; expected end of line", tok)


def _move(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    target = c.pose()
    clamp = None
    if c.peek() is not None and c.peek().text == ",":
        c.take()
        clamp = c.num("a clamp number")
    return ast.Move(line, op, target, clamp)


def _appro(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    target = c.pose()
    c.punct(",", f"between the pose and the distance of {op}")
    return ast.Appro(line, op, target, c.num("a distance in mm"))


def _draw(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    values = list(c.nums(3, f"{op} offset"))
    if c.peek() is not None and c.peek().text == ",":
        c.take()
        values.extend(c.nums(3, f"{op} rotation"))
    return ast.Draw(line, op, tuple(values))


def _speed(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    value = c.num("a speed value")
    unit = "%"
    if c.peek() is not None and c.peek().text == "%":
        c.take()
    elif c.word("MM"):
        c.punct("/", "in the speed unit MM/S or MM/MIN")
        word = c.word("S", "MIN")
        if word is None:
            raise c.error(f"expected 'S' or 'MIN' after 'MM/', found {c.found(c.peek())}", c.peek())
        unit = "MM/" + word
    elif c.word("S"):
        unit = "S"
    always = c.word("ALWAYS") is not None
    if c.peek() is not None:
        raise c.error(f"unexpected {c.peek().show()} in SPEED; expected a unit (%, MM/S, MM/MIN, S), ALWAYS or end of line", c.peek())
    return ast.Speed(line, value, unit, always)


def _accuracy(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    value = c.num("an accuracy in mm")
    flags: set[str] = set()
    while c.peek() is not None:
        word = c.word("ALWAYS", "FINE")
        if word is None:
            raise c.error(f"unexpected {c.peek().show()} in ACCURACY; expected ALWAYS, FINE or end of line", c.peek())
        if word in flags:
            raise c.error(f"{word} given twice in ACCURACY", c.tokens[c.pos - 1])
        flags.add(word)
    return ast.Accuracy(line, value, "ALWAYS" in flags, "FINE" in flags)


def _accel(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    value = c.num("a percentage")
    return ast.Accel(line, op, value, c.word("ALWAYS") is not None)


def _cp(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    word = c.word("ON", "OFF")
    if word is None:
        raise c.error(f"expected ON or OFF after CP, found {c.found(c.peek())}", c.peek())
    return ast.Cp(line, word == "ON")


def _signal(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    outputs = [c.integer("a signal number")]
    while c.peek() is not None and c.peek().text == ",":
        c.take()
        outputs.append(c.integer("a signal number"))
    for number in outputs:
        if number == 0:
            raise c.error("signal number 0 does not exist; expected n (on) or -n (off) with n >= 1", c.tokens[1])
    return ast.Signal(line, tuple(outputs))


def _home(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    return ast.Home(line, c.integer("a home number") if c.peek() is not None else None)


def _point(c: _StatementCursor, op: str, line: int) -> ast.Statement:
    tok = c.peek()
    if tok is not None and tok.text == "#":
        raise c.error("POINT to a joint variable needs the robot's kinematics; coatsim reads Cartesian POINT only", tok)
    name = c.name("a pose name")
    c.punct("=", f"after POINT {name}")
    return ast.Point(line, name, c.pose())


_PARSERS: dict[str, Callable[[_StatementCursor, str, int], ast.Statement]] = {
    **dict.fromkeys(("JMOVE", "LMOVE", "C1MOVE", "C2MOVE"), _move),
    **dict.fromkeys(("JAPPRO", "LAPPRO"), _appro),
    **dict.fromkeys(("JDEPART", "LDEPART"), lambda c, op, line: ast.Depart(line, op, c.num("a distance in mm"))),
    **dict.fromkeys(("DRAW", "TDRAW"), _draw),
    **dict.fromkeys(("ACCEL", "DECEL"), _accel),
    "HOME": _home,
    "DELAY": lambda c, op, line: ast.Delay(line, c.num("a time in s")),
    "TWAIT": lambda c, op, line: ast.Twait(line, c.num("a time in s")),
    "SPEED": _speed,
    "ACCURACY": _accuracy,
    "CP": _cp,
    "BREAK": lambda c, op, line: ast.Break(line),
    "SIGNAL": _signal,
    "TOOL": lambda c, op, line: ast.Tool(line, c.pose()),
    "BASE": lambda c, op, line: ast.Base(line, c.pose()),
    "POINT": _point,
}


def parse_statement(tokens: list[Token], source: str, line: int, width: int) -> Optional[ast.Statement]:
    """The statement on a line (None for a label alone); raises AsSyntaxError."""
    c = _StatementCursor(tokens, source, line, width)
    first = c.peek()
    if first is not None and first.kind == "num" and first.text.isdigit():
        c.take()
    elif first is not None and first.kind == "name" and len(tokens) > 1 and tokens[1].text == ":":
        c.pos = 2
    keyword = c.take()
    if keyword is None:
        return None
    if keyword.kind != "name":
        raise c.error(f"expected a statement keyword, found {keyword.show()}", keyword)
    parser = _PARSERS.get(keyword.upper)
    if parser is None:
        nxt = c.peek()
        if nxt is not None and nxt.text in ("=", "["):
            raise c.error("variable assignment is not in the AS subset coatsim runs; use POINT name = pose for poses", keyword)
        known = "is not in the AS subset coatsim runs" if keyword.upper in _KNOWN_OTHER else "is not an AS statement"
        raise c.error(f"{keyword.show()} {known}; expected one of {SUBSET}", keyword)
    statement = parser(c, keyword.upper, line)
    c.end(keyword.upper)
    return statement

"""Block statements of an AS line: IF/THEN (and IF ... GOTO), ELSEIF, ELSE, END, WHILE/DO,
DO/UNTIL, FOR, CASE/SCASE, VALUE/SVALUE and ANY come back as markers (:class:`Open`,
:class:`Marker`) that :mod:`~coatsim.languages.kawasaki_as.blocks` nests into blocks."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.statement_parser import StatementParser


@dataclass(frozen=True)
class Open:
    """Opens a block: kind IF, WHILE, DO, FOR or CASE; ``data`` what the block needs."""

    kind: str
    line: int
    data: tuple


@dataclass(frozen=True)
class Marker:
    """Inside or at the end of a block: ELSE, ELSEIF (cond), END, UNTIL (cond), VALUE (values), ANY."""

    kind: str
    line: int
    data: tuple = ()


Item = Union[ast.Statement, Open, Marker]


def _if(c: StatementParser, op: str, line: int) -> Item:
    condition = c.condition()
    if c.word("GOTO"):
        label = c.label()
        c.end("IF ... GOTO statement")
        return ast.Goto(line, label, condition)
    if not c.at_end():  # THEN may be left out, as controllers save some blocks
        c.expect_word("THEN", "after the IF condition (or GOTO label)")
    if not c.at_end():  # (AS has no one-line IF ... THEN statement: its only one-line IF is IF ... GOTO)
        raise c.error(f"unexpected {c.peek().show()} after the IF ... THEN: an AS IF ... THEN opens a block; "
                      "write its statements on the lines after it and close it with END, or use "
                      "IF condition GOTO label", c.peek())
    return Open("IF", line, (condition,))


def _elseif(c: StatementParser, op: str, line: int) -> Item:
    condition = c.condition()
    if not c.at_end():
        c.expect_word("THEN", "after the ELSEIF condition")
    c.end("ELSEIF ... THEN")
    return Marker("ELSEIF", line, (condition,))


def _while(c: StatementParser, op: str, line: int) -> Item:
    condition = c.condition()
    c.expect_word("DO", "after the WHILE condition")
    c.end("WHILE ... DO")
    return Open("WHILE", line, (condition,))


def _for(c: StatementParser, op: str, line: int) -> Item:
    var = c.target_name("a loop variable")
    if var.kind != "value":
        raise c.error(f"the FOR variable must be a real, not {var.name}")
    c.op("=", "after the FOR variable")
    start = c.expr("a start value")
    c.expect_word("TO", "in FOR v = start TO end")
    stop = c.expr("an end value")
    step = c.expr("a step") if c.word("STEP") else None
    c.end("FOR statement")
    return Open("FOR", line, (var, start, stop, step))


def _case(c: StatementParser, op: str, line: int) -> Item:
    subject = c.expr("a value")
    c.expect_word("OF", f"after the {op} value")
    c.end(f"{op} ... OF")
    return Open("CASE", line, (subject, op == "SCASE"))


def _value(c: StatementParser, op: str, line: int) -> Item:
    values = c.expr_list("a value")
    if c.is_op(":"):
        c.take()
    c.end(f"{op} list")
    return Marker("VALUE", line, (values, op == "SVALUE"))


def _any(c: StatementParser, op: str, line: int) -> Item:
    if c.is_op(":"):
        c.take()
    c.end("ANY")
    return Marker("ANY", line)


def _marker(kind: str):
    def parse(c: StatementParser, op: str, line: int) -> Item:
        c.end(op)
        return Marker(kind, line) if kind != "DO" else Open("DO", line, ())
    return parse


FLOW_PARSERS = {
    "IF": _if,
    "ELSEIF": _elseif,
    "ELSE": _marker("ELSE"),
    "END": _marker("END"),
    "WHILE": _while,
    "DO": _marker("DO"),
    "UNTIL": lambda c, op, line: Marker("UNTIL", line, (c.condition(),)),
    "FOR": _for,
    **dict.fromkeys(("CASE", "SCASE"), _case),
    **dict.fromkeys(("VALUE", "SVALUE"), _value),
    "ANY": _any,
}

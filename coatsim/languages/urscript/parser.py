"""URScript text -> statements and expressions.

URScript reads like Python with ``end`` closing blocks: ``def name(params):`` … ``end``, ``thread``
and ``sec`` the same way, ``if c:`` / ``elif c:`` / ``else:`` … ``end``, ``while c:`` … ``end``,
``for i in range(a, b):`` … ``end``, ``return``, ``break``, ``continue``, ``halt``, assignments with
``global``/``local`` (``x = …``, ``x[i] = …``), calls with keyword arguments (``movel(p, a=1.2,
v=0.25, r=0.001)``), lists ``[…]``, pose literals ``p[x, y, z, rx, ry, rz]``, numbers, strings,
``True``/``False``, operators ``+ - * / %``, comparisons, ``and or not xor``. ``#`` starts a comment;
indentation is free; Polyscope's ``$ n "…"`` step markers are skipped. Keywords are case-sensitive
as on the controller.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Optional

from coatsim.core.errors import InputError

_TOKEN = re.compile(r"""[ \t]*(?:
    (?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)
  | (?P<str>"[^"\n]*"|'[^'\n]*')
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>==|!=|<=|>=|[-+*/%<>()\[\],:=.])
  | (?P<comment>\#[^\n]*)
  | (?P<nl>\n)
  )""", re.X)
KEYWORDS = {"def", "end", "if", "elif", "else", "while", "for", "in", "return", "global", "local", "and", "or",
            "not", "xor", "True", "False", "thread", "run", "join", "kill", "halt", "break", "continue", "pass",
            "sec", "enter_critical", "exit_critical"}
_BINARY = (("or",), ("xor",), ("and",), ("==", "!=", "<", ">", "<=", ">="), ("+", "-"), ("*", "/", "%"))
_RANK = {op: rank for rank, ops in enumerate(_BINARY) for op in ops}  # loosest 0

Expr = tuple  # ("num", v) | ("str", s) | ("bool", b) | ("name", n) | ("list", items) | ("pose", items)
# | ("index", e, i) | ("call", name, args, kwargs, line) | ("un", op, e) | ("bin", op, a, b)


@dataclass(frozen=True)
class Token:
    kind: str
    text: str
    line: int


@dataclass(frozen=True)
class Statement:
    """``kind`` one of def, assign, expr, if, while, for, return, break, continue, halt, note;
    the fields a kind uses (see the parser)."""

    kind: str
    line: int
    name: str = ""
    params: tuple[str, ...] = ()
    defaults: tuple[Optional[Expr], ...] = ()
    body: tuple["Statement", ...] = ()
    branches: tuple[tuple[Expr, tuple["Statement", ...]], ...] = ()
    target: Optional[Expr] = None
    value: Optional[Expr] = None
    scope: str = ""
    args: tuple[Expr, ...] = field(default_factory=tuple)


def tokenize(text: str, source: str, comments: Optional[list[str]] = None) -> list[Token]:
    """The tokens of a script; its ``#`` comments (without the ``#``) go to ``comments``."""
    out, line, i = [], 1, 0
    text = "\n".join("" if raw.lstrip().startswith("$") else raw for raw in text.split("\n"))  # Polyscope markers
    while i < len(text):
        match = _TOKEN.match(text, i)
        if match is None or match.end() == i:
            rest = text[i:].lstrip(" \t\r")
            if not rest:
                break
            if text[i] == "\r":
                i += 1
                continue
            raise InputError(f"{source}:{line}: unexpected {rest[:1]!r}")
        kind = match.lastgroup
        if kind == "nl":
            out.append(Token("nl", "\n", line))
            line += 1
        elif kind == "comment":
            if comments is not None:
                comments.append(match.group(kind)[1:])
        else:
            out.append(Token("kw" if kind == "name" and match.group(kind) in KEYWORDS else kind, match.group(kind),
                             line))
        i = match.end()
    out.append(Token("nl", "\n", line))
    return out


class Parser:
    def __init__(self, tokens: list[Token], source: str) -> None:
        self.t, self.i, self.source = tokens, 0, source

    # --- cursor ---------------------------------------------------------------------------
    def peek(self, offset: int = 0) -> Token:
        return self.t[min(self.i + offset, len(self.t) - 1)]

    def error(self, message: str, token: Optional[Token] = None) -> InputError:
        return InputError(f"{self.source}:{(token or self.peek()).line}: {message}")

    def at(self, *texts: str) -> bool:
        return self.peek().text in texts and self.peek().kind in ("op", "kw")

    def take(self, *texts: str) -> Optional[Token]:
        if self.at(*texts):
            self.i += 1
            return self.t[self.i - 1]
        return None

    def expect(self, text: str) -> Token:
        tok = self.take(text)
        if tok is None:
            found = self.peek().text.replace("\n", "the end of the line")
            raise self.error(f"expected {text!r}, found {found!r}")
        return tok

    def name(self) -> Token:
        tok = self.peek()
        if tok.kind != "name":
            raise self.error(f"expected a name, found {tok.text.strip() or 'the end of the line'!r}")
        self.i += 1
        return tok

    def newlines(self) -> None:
        while self.peek().kind == "nl" and self.i < len(self.t) - 1:
            self.i += 1

    def end_of_statement(self) -> None:
        if self.peek().kind != "nl":
            raise self.error(f"unexpected {self.peek().text!r} after the statement")
        self.newlines()

    # --- statements -----------------------------------------------------------------------
    def program(self) -> tuple[Statement, ...]:
        self.newlines()
        body = self.block(("<eof>",))
        return body

    def block(self, closers: tuple[str, ...]) -> tuple[Statement, ...]:
        out = []
        while True:
            self.newlines()
            tok = self.peek()
            if self.i >= len(self.t) - 1:
                if "<eof>" in closers:
                    return tuple(out)
                raise self.error(f"the block is not closed: expected {' or '.join(closers)}")
            if tok.kind == "kw" and tok.text in closers:
                return tuple(out)
            out.append(self.statement())

    def statement(self) -> Statement:
        tok = self.peek()
        line = tok.line
        if tok.kind == "kw":
            word = tok.text
            if word in ("def", "thread", "sec"):
                return self.definition(word)
            if word == "if":
                return self.conditional()
            if word == "while":
                self.i += 1
                cond = self.expression()
                self.expect(":")
                body = self.block(("end",))
                self.expect("end")
                return Statement("while", line, branches=((cond, body),))
            if word == "for":
                return self.loop()
            if word in ("global", "local"):
                self.i += 1
                return self.assignment(word)
            if word == "return":
                self.i += 1
                value = None if self.peek().kind == "nl" else self.expression()
                self.end_of_statement()
                return Statement("return", line, value=value)
            if word in ("break", "continue", "halt", "pass", "enter_critical", "exit_critical"):
                self.i += 1
                self.end_of_statement()
                return Statement(word if word in ("break", "continue", "halt") else "pass", line)
            if word in ("run", "join", "kill"):
                return self.thread_control(line)
            raise self.error(f"{word!r} cannot start a statement")
        if tok.kind == "name" and (self.peek(1).text == "=" or self._index_assignment()):
            return self.assignment("")
        value = self.expression()
        self.end_of_statement()
        return Statement("expr", line, value=value)

    def _index_assignment(self) -> bool:
        """Whether ``name[…] =`` starts here."""
        if self.peek(1).text != "[":
            return False
        depth, k = 0, 1
        while self.peek(k).kind != "nl":
            text = self.peek(k).text
            depth += (text == "[") - (text == "]")
            if depth == 0:
                return self.peek(k + 1).text == "=" and self.peek(k + 1).kind == "op"
            k += 1
        return False

    def definition(self, kind: str) -> Statement:
        line = self.peek().line
        self.i += 1
        name = self.name().text
        params, defaults = [], []
        self.expect("(")
        while not self.take(")"):
            params.append(self.name().text)
            defaults.append(self.expression() if self.take("=") else None)
            if not self.take(","):
                self.expect(")")
                break
        self.expect(":")
        body = self.block(("end",))
        self.expect("end")
        return Statement("def", line, name=name, params=tuple(params), defaults=tuple(defaults), body=body,
                         scope=kind)

    def conditional(self) -> Statement:
        line = self.peek().line
        branches = []
        self.expect("if")
        while True:
            cond = self.expression()
            self.expect(":")
            branches.append((cond, self.block(("elif", "else", "end"))))
            if self.take("elif"):
                continue
            if self.take("else"):
                self.expect(":")
                branches.append((("bool", True), self.block(("end",))))
            self.expect("end")
            return Statement("if", line, branches=tuple(branches))

    def loop(self) -> Statement:
        line = self.peek().line
        self.expect("for")
        var = self.name().text
        self.expect("in")
        call = self.expression()
        if call[0] != "call" or call[1] != "range" or call[3]:
            raise self.error("a for loop runs over range(start, stop[, step])")
        self.expect(":")
        body = self.block(("end",))
        self.expect("end")
        return Statement("for", line, name=var, args=tuple(call[2]), body=body)

    def thread_control(self, line: int) -> Statement:
        """``run name()``, ``join handle``, ``kill handle``: threads are noted, not run."""
        word = self.peek().text
        self.i += 1
        target = self.name().text
        if self.take("("):
            self.expect(")")
        self.end_of_statement()
        return Statement("note", line, name=f"{word} {target}")

    def assignment(self, scope: str) -> Statement:
        line = self.peek().line
        name = self.name().text
        target: Expr = ("name", name)
        if self.take("["):
            target = ("index", target, self.expression())
            self.expect("]")
        self.expect("=")
        if self.peek().text == "run":  # handle = run thread(): the thread is noted, its handle unused
            return self.thread_control(line)
        value = self.expression()
        self.end_of_statement()
        return Statement("assign", line, target=target, value=value, scope=scope)

    # --- expressions ----------------------------------------------------------------------
    def expression(self, level: int = 0) -> Expr:
        """Binary operators of ``level`` (an index into ``_BINARY``) and tighter, left to right
        (precedence climbing: one pass over the operators, not one call per level)."""
        left = self.unary()
        while True:
            tok = self.peek()
            rank = _RANK.get(tok.text, -1) if tok.kind in ("op", "kw") else -1
            if rank < level:
                return left
            self.i += 1
            left = ("bin", tok.text, left, self.expression(rank + 1))

    def unary(self) -> Expr:
        if self.take("-"):
            return ("un", "-", self.unary())
        if self.take("+"):
            return self.unary()
        if self.take("not"):
            return ("un", "not", self.unary())
        return self.postfix(self.atom())

    def postfix(self, value: Expr) -> Expr:
        while self.take("["):
            value = ("index", value, self.expression())
            self.expect("]")
        return value

    def items(self, closer: str) -> tuple[Expr, ...]:
        out = []
        self.newlines_inside()
        while not self.take(closer):
            out.append(self.expression())
            self.newlines_inside()
            if not self.take(","):
                self.expect(closer)
                break
            self.newlines_inside()
        return tuple(out)

    def newlines_inside(self) -> None:
        while self.peek().kind == "nl" and self.i < len(self.t) - 1:
            self.i += 1

    def atom(self) -> Expr:
        tok = self.peek()
        if tok.kind == "num":
            self.i += 1
            text = tok.text
            return ("num", int(text) if re.fullmatch(r"\d+", text) else float(text))
        if tok.kind == "str":
            self.i += 1
            return ("str", tok.text[1:-1])
        if self.take("True"):
            return ("bool", True)
        if self.take("False"):
            return ("bool", False)
        if self.take("("):
            inner = self.expression()
            self.expect(")")
            return inner
        if self.take("["):
            return ("list", self.items("]"))
        if tok.kind == "name":
            self.i += 1
            if tok.text == "p" and self.take("["):
                return ("pose", self.items("]"))
            if self.take("("):
                return self.call(tok)
            return ("name", tok.text)
        raise self.error(f"unexpected {tok.text.strip() or 'end of the line'!r} in an expression")

    def call(self, name: Token) -> Expr:
        args, kwargs = [], []
        self.newlines_inside()
        while not self.take(")"):
            if self.peek().kind == "name" and self.peek(1).text == "=" and self.peek(1).kind == "op":
                key = self.name().text
                self.expect("=")
                kwargs.append((key, self.expression()))
            else:
                if kwargs:
                    raise self.error("a positional argument after a keyword argument")
                args.append(self.expression())
            self.newlines_inside()
            if not self.take(","):
                self.expect(")")
                break
            self.newlines_inside()
        return ("call", name.text, tuple(args), tuple(kwargs), name.line)


def parse_script(text: str, source: str) -> tuple[tuple[Statement, ...], tuple[str, ...]]:
    """The statements and the comments of a URScript file (InputError naming file:line on a syntax
    error)."""
    control = re.search(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]", text)
    if control:
        line = text[:control.start()].count("\n") + 1
        raise InputError(f"{source}:{line}: a control character; a script is plain text")
    comments: list[str] = []
    parser = Parser(tokenize(text, source, comments), source)
    return parser.program(), tuple(comments)


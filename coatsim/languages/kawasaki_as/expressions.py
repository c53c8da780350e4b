"""Expression grammar of AS, over the tokens of one line.

Precedence, loosest first: ``OR XOR``; ``AND``; ``NOT``; comparisons (``== <> < > <= >=``);
``BOR BXOR``; ``BAND``; ``+ -``; ``* / MOD``; unary ``- +``; ``^`` (right-associative);
primaries: numbers, strings, ``(...)``, variables (``p``, ``.x``, ``$s``, ``#j``, ``a[i, j]``),
built-in functions, ``TRANS(...)`` and other calls with empty arguments, ``SHIFT(p BY x, y, z)``,
``#[j1, ..., jn]``, and the constants ``TRUE FALSE ON OFF PI NULL HERE DEST``.

A run of left-associative operators of one precedence is one flat :class:`~ast.Chain` (a sum of
600 terms is no tree 600 deep); every other recursion (parentheses, calls, unary operators, a
tighter operator's operand, ``^``) counts against ``MAX_DEPTH``, so that no expression a line
holds can exhaust the interpreter's stack. Where an operand is expected, a keyword that is not an
operator is a variable's name (``value``, ``step``, ``len``: cells name variables so); any
``name(...)`` is a function call (arrays take ``[ ]``), the interpreter tells what it knows.
"""

from __future__ import annotations

from typing import Optional

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.lexer import Token
from coatsim.languages.kawasaki_as.source import AsSyntaxError, syntax_error

MAX_DEPTH = 64  # nesting of parentheses, calls, unary and tighter operators on one line

CONSTANTS = {"TRUE": -1.0, "ON": -1.0, "FALSE": 0.0, "OFF": 0.0, "PI": 3.141592653589793}
# Built-in values written without parentheses.
NULLARY = {"NULL", "HERE", "#HERE", "DEST", "#DEST", "MSPEED", "MSPEED2", "RANDOM", "$TIME", "ERROR", "TASKNO",
           "WHICHTASK", "PRIORITY"}
WORD_OPERATORS = {"AND", "OR", "XOR", "NOT", "MOD", "BAND", "BOR", "BXOR"}

_BINARY = {  # operator -> (binding power, right-associative)
    "OR": (1, False), "XOR": (1, False), "AND": (2, False),
    "==": (4, False), "<>": (4, False), "<": (4, False), ">": (4, False), "<=": (4, False), ">=": (4, False),
    "BOR": (5, False), "BXOR": (5, False), "BAND": (6, False),
    "+": (7, False), "-": (7, False), "*": (8, False), "/": (8, False), "MOD": (8, False),
    "^": (10, True),
}
_NOT_POWER, _UNARY_POWER = 3, 9


class Cursor:
    """Position in the tokens of one line; errors name the line and column."""

    def __init__(self, tokens: list[Token], source: str, line: int, width: int, text: str = "") -> None:
        self.tokens, self.source, self.line, self.width, self.text = tokens, source, line, width, text
        self.pos, self.depth = 0, 0

    # --- token access --------------------------------------------------------------------
    def error(self, message: str, token: Optional[Token] = None) -> AsSyntaxError:
        col = token.col if token is not None else self.width + 1
        return syntax_error(self.source, self.line, col, message)

    def peek(self, ahead: int = 0) -> Optional[Token]:
        i = self.pos + ahead
        return self.tokens[i] if i < len(self.tokens) else None

    def take(self) -> Optional[Token]:
        tok = self.peek()
        self.pos += tok is not None
        return tok

    def at_end(self) -> bool:
        return self.pos >= len(self.tokens)

    @staticmethod
    def found(tok: Optional[Token]) -> str:
        return tok.show() if tok is not None else "end of line"

    def is_op(self, *ops: str) -> bool:
        tok = self.peek()
        return tok is not None and tok.kind == "op" and tok.text in ops

    def is_word(self, *words: str) -> bool:
        tok = self.peek()
        return tok is not None and tok.kind == "name" and tok.upper in words

    def op(self, text: str, context: str) -> Token:
        tok = self.take()
        if tok is None or tok.kind != "op" or tok.text != text:
            raise self.error(f"expected '{text}' {context}, found {self.found(tok)}", tok)
        return tok

    def word(self, *words: str) -> Optional[str]:
        """Take the next token if it is one of the keywords ``words``."""
        if self.is_word(*words):
            return self.take().upper
        return None

    def qualifier(self, *words: str) -> Optional[str]:
        """Take the next token if it is one of the qualifiers ``words`` or a leading part of two
        letters or more of exactly one of them (``ALW`` for ALWAYS): programs typed on the pendant
        keep qualifiers shortened as they keep instruction words."""
        tok = self.peek()
        if tok is None or tok.kind != "name" or not tok.text.isalpha():
            return None
        matches = [w for w in words if w.startswith(tok.upper)]
        if tok.upper in words or (len(tok.text) >= 2 and len(matches) == 1):
            self.take()
            return tok.upper if tok.upper in words else matches[0]
        return None

    def expect_word(self, word: str, context: str) -> None:
        if self.word(word) is None:
            raise self.error(f"expected {word} {context}, found {self.found(self.peek())}", self.peek())

    def end(self, what: str) -> None:
        tok = self.peek()
        if tok is not None:
            raise self.error(f"unexpected {tok.show()} after the {what}; expected end of line", tok)

    def rest_text(self) -> str:
        """The source text from the current token to the last one, as written."""
        if self.at_end():
            return ""
        last = self.tokens[-1]
        if not self.text:
            return " ".join(t.text for t in self.tokens[self.pos:])
        return self.text[self.tokens[self.pos].col - 1:last.col - 1 + len(last.text)]

    # --- expressions ---------------------------------------------------------------------
    def expr(self, what: str = "an expression", power: int = 0) -> ast.Expr:
        """An expression whose operators bind tighter than ``power``; a run of one
        left-associative precedence level comes back flat."""
        left = self.prefix(what)
        rest: list[tuple[str, ast.Expr]] = []
        level = None
        while True:
            tok = self.peek()
            key = None if tok is None else tok.text if tok.kind == "op" else tok.upper if tok.kind == "name" else None
            spec = _BINARY.get(key) if key is not None else None
            if spec is None or spec[0] <= power:
                return _joined(left, rest)
            self.take()
            bp, right_assoc = spec
            operand = self.nested(lambda: self.expr("an operand", bp - 1 if right_assoc else bp))
            if right_assoc or (level is not None and bp != level):
                left, rest = _joined(left, rest), []
            if right_assoc:
                left, level = ast.Binary(key, left, operand), None
            else:
                rest.append((key, operand))
                level = bp

    def condition(self, what: str = "a condition") -> ast.Expr:
        """An expression used as a truth value; a stray '=' gets a hint."""
        value = self.expr(what)
        if self.is_op("="):
            raise self.error("'=' assigns; compare with '=='", self.peek())
        return value

    def prefix(self, what: str) -> ast.Expr:
        tok = self.peek()
        if tok is None:
            raise self.error(f"expected {what}, found end of line")
        if tok.kind == "op" and tok.text in ("-", "+"):
            self.take()
            return ast.Unary(tok.text, self.nested(lambda: self.expr("an operand", _UNARY_POWER - 1)))
        if tok.kind == "name" and tok.upper == "NOT":
            self.take()
            return ast.Unary("NOT", self.nested(lambda: self.expr("an operand", _NOT_POWER - 1)))
        return self.primary(what)

    def nested(self, parse):
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.error(f"expression nested more than {MAX_DEPTH} deep", self.peek())
        try:
            return parse()
        finally:
            self.depth -= 1

    def primary(self, what: str) -> ast.Expr:
        tok = self.take()
        if tok is None:
            raise self.error(f"expected {what}, found end of line")
        if tok.kind == "num":
            return ast.Num(float(tok.value))
        if tok.kind == "str":
            return ast.Str(str(tok.value))
        if tok.kind == "op":
            if tok.text == "(":
                inner = self.nested(lambda: self.expr("an expression"))
                self.op(")", "to close '('")
                return inner
            if tok.text == "#" and self.is_op("["):
                self.take()
                return ast.JointLiteral(self.nested(lambda: self.arguments("]", "a joint value")))
            raise self.error(f"expected {what}, found {tok.show()}", tok)
        word = tok.upper
        if word in WORD_OPERATORS:
            raise self.error(f"expected {what}, found {tok.show()}", tok)
        if tok.text.startswith("&") or tok.text.startswith(".&"):
            raise self.error(f"{tok.show()}: a by-reference argument is allowed only in CALL and $DECODE arguments", tok)
        if word == "SHIFT" and self.is_op("("):
            return self.shift()
        if self.is_op("("):
            return self.call(tok)
        if word in CONSTANTS:
            return ast.Num(CONSTANTS[word])
        if word in NULLARY:
            return ast.Call(word, ())
        return self.variable(tok)

    def variable(self, tok: Token) -> ast.Name:
        index: tuple[ast.Expr, ...] = ()
        if self.is_op("["):
            self.take()
            index = self.nested(lambda: self.arguments("]", "an array index"))
            if not index or any(i is None for i in index):
                raise self.error(f"expected an array index in {tok.text}[...]", tok)
        return ast.Name(tok.text, index)

    def call(self, tok: Token) -> ast.Expr:
        name = tok.upper
        if name.startswith("."):
            raise self.error(f"{tok.show()} is a local variable; an array element takes [ ], not ( )", tok)
        self.take()  # "("
        if name == "$ENCODE":
            return ast.Call(name, self.nested(lambda: self.format_items(")")))
        args = self.nested(lambda: self.arguments(")", "an argument", allow_ref=name == "$DECODE"))
        return ast.Call(name, args)

    def format_spec(self) -> ast.Format:
        """After '/': a format letter with its width, as in /D, /F8.3, /X2."""
        tok = self.take()
        if tok is None or tok.kind != "name":
            raise self.error(f"expected a format such as /D or /F8.3 after '/', found {self.found(tok)}", tok)
        spec = tok.upper
        if self.peek() is not None and self.peek().kind == "num" and self.peek().col == tok.col + len(tok.text):
            spec += self.take().text
        return ast.Format(spec)

    def format_items(self, close: Optional[str]) -> tuple[ast.Expr, ...]:
        """Values and /formats separated by commas, up to ``close`` (None: the end of the line)."""
        items: list[ast.Expr] = []
        while True:
            if close is not None and self.is_op(close):
                self.take()
                return tuple(items)
            if close is None and self.at_end():
                return tuple(items)
            if self.is_op("/"):
                self.take()
                items.append(self.format_spec())
            elif not self.is_op(","):
                items.append(self.expr("a value"))
            if self.is_op(","):
                self.take()
            elif not (self.is_op("/") or (close is not None and self.is_op(close)) or (close is None and self.at_end())):
                raise self.error(f"expected ',' between values, found {self.found(self.peek())}", self.peek())

    def arguments(self, close: str, what: str, allow_ref: bool = False) -> tuple[Optional[ast.Expr], ...]:
        """Comma-separated arguments up to ``close``; an empty argument is None."""
        args: list[Optional[ast.Expr]] = []
        if self.is_op(close):
            self.take()
            return ()
        while True:
            if self.is_op(",", close):
                args.append(None)
            else:
                args.append(self.argument(what, allow_ref))
            tok = self.take()
            if tok is not None and tok.kind == "op" and tok.text == close:
                return tuple(args)
            if tok is None or tok.kind != "op" or tok.text != ",":
                raise self.error(f"expected ',' or '{close}' after {what}, found {self.found(tok)}", tok)

    def argument(self, what: str, allow_ref: bool) -> ast.Expr:
        """An argument; where a CALL's arguments go (``allow_ref``) also ``&x`` / ``.&x`` by
        reference and whole arrays ``a[]`` / ``.&p[,]``."""
        tok = self.peek()
        if not allow_ref or tok is None or tok.kind != "name":
            return self.expr(what)
        ref = tok.text.startswith("&") or tok.text.startswith(".&")
        whole = self.whole_array()
        if not ref and whole is None:
            return self.expr(what)
        self.take()
        local = tok.text.startswith(".")
        bare = tok.text.lstrip(".&")
        text = ("." + bare) if local else bare
        if whole is not None:
            self.pos += whole - 1
            target = ast.Name(text, (), True)
        else:
            target = self.variable(Token("name", text, tok.col))
        return ast.Ref(target) if ref else target

    def whole_array(self) -> Optional[int]:
        """How many tokens ``a[]`` / ``a[, ,]`` (an entire array) spans from its name, else None."""
        nxt = self.peek(1)
        if nxt is None or nxt.kind != "op" or nxt.text != "[":
            return None
        i = 2
        while self.peek(i) is not None and self.peek(i).kind == "op" and self.peek(i).text == ",":
            i += 1
        tok = self.peek(i)
        return i + 1 if tok is not None and tok.kind == "op" and tok.text == "]" else None

    def shift(self) -> ast.Shift:
        """After 'SHIFT': ``(pose BY dx, dy, dz)``."""
        self.op("(", "after SHIFT")
        base = self.nested(lambda: self.expr("a pose"))
        self.expect_word("BY", "in SHIFT(pose BY dx, dy, dz)")
        delta = self.nested(lambda: self.arguments(")", "a SHIFT offset"))
        if not 1 <= len(delta) <= 3:
            raise self.error(f"SHIFT takes 3 offsets dx, dy, dz, found {len(delta)}")
        padded = tuple(delta) + (None,) * (3 - len(delta))
        return ast.Shift(base, (padded[0], padded[1], padded[2]))


def _joined(left: ast.Expr, rest: list[tuple[str, ast.Expr]]) -> ast.Expr:
    """``left`` followed by ``rest``: itself, a Binary of two operands, or a flat Chain."""
    if not rest:
        return left
    if len(rest) == 1:
        return ast.Binary(rest[0][0], left, rest[0][1])
    return ast.Chain(left, tuple(rest))

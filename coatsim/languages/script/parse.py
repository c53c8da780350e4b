"""A token stream with an expression parser (precedence climbing) configured per language."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

from coatsim.core.errors import InputError
from coatsim.languages.script import nodes as n
from coatsim.languages.script.tokens import END, NAME, NEWLINE, NUM, OP, STR, Token


@dataclass(frozen=True)
class Grammar:
    """A language's expressions: binary operators by precedence (higher binds tighter; all left
    associative), unary operators with their precedence, the index brackets, and how an
    aggregate literal is read (``aggregate`` called at its opening bracket)."""

    binary: dict[str, int]
    unary: dict[str, int]
    index_open: str
    index_close: str
    aggregate_open: str
    case_insensitive_words: bool = True


class Stream:
    """Tokens with a position; ``source`` names the file in messages."""

    def __init__(self, tokens: list[Token], source: str, grammar: Grammar,
                 aggregate: Optional[Callable[["Stream"], n.Expr]] = None,
                 argument: Optional[Callable[["Stream"], n.Arg]] = None) -> None:
        self.tokens, self.pos, self.source, self.grammar = tokens, 0, source, grammar
        self.aggregate = aggregate
        self.argument = argument

    # --- the stream -----------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.tokens[self.pos]

    def peek(self, k: int = 1) -> Token:
        return self.tokens[min(self.pos + k, len(self.tokens) - 1)]

    def next(self) -> Token:
        t = self.tokens[self.pos]
        if t.kind != END:
            self.pos += 1
        return t

    def error(self, message: str, line: Optional[int] = None) -> InputError:
        return InputError(f"{self.source}:{self.tok.line if line is None else line}: {message}")

    def is_op(self, *ops: str) -> bool:
        return self.tok.kind == OP and self.tok.text in ops

    def is_word(self, *words: str) -> bool:
        return self.tok.kind == NAME and self.tok.text.upper() in words

    def accept_op(self, op: str) -> bool:
        if self.is_op(op):
            self.next()
            return True
        return False

    def accept_word(self, word: str) -> bool:
        if self.is_word(word):
            self.next()
            return True
        return False

    def expect_op(self, op: str, what: str = "") -> Token:
        if not self.is_op(op):
            raise self.error(f"expected '{op}'{what}, found {self.shown()}")
        return self.next()

    def expect_word(self, word: str) -> Token:
        if not self.is_word(word):
            raise self.error(f"expected {word}, found {self.shown()}")
        return self.next()

    def expect_name(self, what: str = "a name") -> Token:
        if self.tok.kind != NAME:
            raise self.error(f"expected {what}, found {self.shown()}")
        return self.next()

    def shown(self) -> str:
        t = self.tok
        if t.kind == END:
            return "the end of the file"
        if t.kind == NEWLINE:
            return "the end of the line"
        return repr(t.text if t.kind != STR else f'"{t.text}"')

    def skip_newlines(self) -> None:
        while self.tok.kind == NEWLINE:
            self.next()

    def skip_line(self) -> None:
        while self.tok.kind not in (NEWLINE, END):
            self.next()

    # --- expressions ----------------------------------------------------------------------
    def _binary_op(self) -> Optional[str]:
        t = self.tok
        if t.kind == OP and t.text in self.grammar.binary:
            return t.text
        if t.kind == NAME and t.text.upper() in self.grammar.binary:
            return t.text.upper()
        return None

    def expression(self, min_prec: int = 0) -> n.Expr:
        left = self._unary()
        while True:
            op = self._binary_op()
            if op is None or self.grammar.binary[op] < min_prec:
                return left
            line = self.next().line
            right = self.expression(self.grammar.binary[op] + 1)
            left = n.Binary(op, left, right, line)

    def _unary(self) -> n.Expr:
        t = self.tok
        key = t.text.upper() if t.kind == NAME else t.text if t.kind == OP else None
        if key in self.grammar.unary:
            self.next()
            return n.Unary(key, self.expression(self.grammar.unary[key]), t.line)
        return self._postfix(self._primary())

    def _primary(self) -> n.Expr:
        t = self.tok
        if t.kind == NUM:
            self.next()
            return n.Num(float(t.text), t.line, t.text.isdigit())
        if t.kind == STR:
            self.next()
            return n.Str(t.text, t.line)
        if t.kind == NAME:
            self.next()
            if self.is_op("("):
                return n.Call(t.text, self.arguments(), t.line)
            return n.Name(t.text, t.line)
        if self.is_op("("):
            self.next()
            inner = self.expression()
            self.expect_op(")")
            return inner
        if self.is_op(self.grammar.aggregate_open) and self.aggregate is not None:
            return self.aggregate(self)
        raise self.error(f"expected a value, found {self.shown()}")

    def arguments(self) -> tuple[n.Arg, ...]:
        """``( a, b, \\opt := c )``: the stream at the opening parenthesis."""
        self.expect_op("(")
        args: list[n.Arg] = []
        while not self.is_op(")"):
            args.append(self.argument(self) if self.argument is not None else n.Arg(self.expression()))
            if not self.accept_op(","):
                if self.argument is not None and self.is_op("\\"):
                    continue  # RAPID: optional arguments follow without a comma
                break
        self.expect_op(")")
        return tuple(args)

    def _postfix(self, e: n.Expr) -> n.Expr:
        while True:
            if self.is_op(".") and self.peek().kind == NAME:
                self.next()
                e = n.Field(e, self.next().text, e.line)
            elif self.is_op(self.grammar.index_open):
                self.next()
                items = [self.expression()]
                while self.accept_op(","):
                    items.append(self.expression())
                self.expect_op(self.grammar.index_close)
                e = n.Index(e, tuple(items), e.line)
            else:
                return e

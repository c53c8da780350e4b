"""The cursor of the statement grammar: the expression grammar's cursor with the parts statements
share (a target name, expression lists, a label, call arguments)."""

from __future__ import annotations

from typing import Optional

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.expressions import Cursor


class StatementParser(Cursor):
    """Statement grammar on top of the expression grammar."""

    def target_name(self, what: str) -> ast.Name:
        tok = self.take()
        if tok is None or tok.kind != "name" or tok.text.startswith("&") or tok.text.startswith(".&"):
            raise self.error(f"expected {what}, found {self.found(tok)}", tok)
        return self.variable(tok)

    def expr_list(self, what: str) -> tuple[ast.Expr, ...]:
        items = [self.expr(what)]
        while self.is_op(","):
            self.take()
            items.append(self.expr(what))
        return tuple(items)

    def optional_list(self, what: str, most: int) -> tuple[Optional[ast.Expr], ...]:
        """Up to ``most`` comma-separated expressions, any of them empty (None)."""
        items: list[Optional[ast.Expr]] = []
        while True:
            items.append(None if self.at_end() or self.is_op(",") else self.expr(what))
            if not self.is_op(","):
                break
            self.take()
            if len(items) == most:
                raise self.error(f"too many values; expected at most {most} {what}s", self.peek())
        if all(i is None for i in items):
            raise self.error(f"expected {what}, found {self.found(self.peek())}", self.peek())
        return tuple(items)

    def arguments_until_end(self) -> tuple[ast.Expr, ...]:
        """Comma-separated arguments (by-reference ones allowed) up to the end of the line."""
        args = [self.argument("an argument", allow_ref=True)]
        while not self.at_end():
            self.op(",", "between arguments")
            args.append(self.argument("an argument", allow_ref=True))
        return tuple(args)

    def label(self) -> str:
        tok = self.take()
        if tok is not None and tok.kind == "num" and tok.text.isdigit():
            return str(int(tok.text))
        if tok is not None and tok.kind == "name" and tok.text[:1].isalpha():
            return tok.text.lower()
        raise self.error(f"expected a label (a step number or a name), found {self.found(tok)}", tok)

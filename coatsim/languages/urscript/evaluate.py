"""URScript values of expressions: variables (local, global, given by the reading, else an
unknown), numbers, truth, list and pose elements, operators. The interpreter's Expressions part
(see :mod:`.interpreter`): it provides ``globals``, ``options``, ``unknown``, ``source``, ``line``,
``error`` and ``call``."""

from __future__ import annotations

import math
from typing import Optional

from coatsim.core.errors import InputError
from coatsim.languages.urscript.parser import Expr
from coatsim.languages.urscript.values import PoseValue
from coatsim.languages.script.unknowns import Unset, require_known, unset_names


class Expressions:
    """Evaluation of a script's expressions."""

    def lookup(self, name: str, scope: Optional[dict]):
        if scope is not None and name in scope:
            return scope[name]
        if name in self.globals:
            return self.globals[name]
        if name in self.options.variables:
            return self.given(name)
        return self.unknown.read(name, f"{self.source}:{self.line}")

    def given(self, name: str):
        """A variable the reading gives: a number, or a pose p[...] / list [...] as text."""
        raw = self.options.variables[name]
        if isinstance(raw, (int, float)):
            return raw
        text = str(raw).strip()
        try:
            if not text.startswith(("p", "[")):
                return float(text)
            items = [float(v) for v in text.lstrip("p").strip("[]").split(",")]
        except ValueError:
            raise InputError(f"variable {name}: expected a number, p[x,y,z,rx,ry,rz] or a list [...], got {text[:40]!r}") \
                from None
        return PoseValue(items) if text.startswith("p") else items

    # --- expressions --------------------------------------------------------------------
    def number(self, value) -> float:
        require_known(value)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(f"expected a number, got {self.describe(value)}")
        return value

    @staticmethod
    def describe(value) -> str:
        if isinstance(value, PoseValue):
            return "a pose"
        if isinstance(value, list):
            return "a list"
        return "nothing" if value is None else f"{type(value).__name__} {str(value)[:20]!r}"

    def truth(self, value) -> bool:
        require_known(value)
        if isinstance(value, bool):
            return value
        return self.number(value) != 0

    def index(self, value, container) -> int:
        if not isinstance(container, (list, PoseValue)):
            raise self.error(f"only a list or a pose has elements, not {self.describe(container)}")
        k = self.number(value)
        if k != int(k) or not 0 <= k < len(container):
            raise self.error(f"index {k:g} is outside 0..{len(container) - 1}")
        return int(k)

    def evaluate(self, expr: Expr, scope: Optional[dict]):
        kind = expr[0]
        if kind in ("num", "str", "bool"):
            return expr[1]
        if kind == "name":
            return self.lookup(expr[1], scope)
        if kind == "list":
            return [self.evaluate(e, scope) for e in expr[1]]
        if kind == "pose":
            items = [self.evaluate(e, scope) for e in expr[1]]
            if unset_names(items):
                return Unset(unset_names(items))
            values = [self.number(item) for item in items]
            if len(values) != 6:
                raise self.error(f"a pose p[...] has 6 values, not {len(values)}")
            return PoseValue(values)
        if kind == "index":
            container, position = self.evaluate(expr[1], scope), self.evaluate(expr[2], scope)
            if unset_names((container, position)):
                return Unset(unset_names((container, position)))
            return container[self.index(position, container)]
        if kind == "un":
            value = self.evaluate(expr[2], scope)
            if isinstance(value, Unset):
                return value
            return (not self.truth(value)) if expr[1] == "not" else -self.number(value)
        if kind == "bin":
            return self.binary(expr[1], expr[2], expr[3], scope)
        return self.call(expr, scope)

    def binary(self, op: str, left: Expr, right: Expr, scope: Optional[dict]):
        a = self.evaluate(left, scope)
        if op in ("and", "or") and not isinstance(a, Unset):
            if self.truth(a) == (op == "or"):
                return op == "or"
            b = self.evaluate(right, scope)
            return b if isinstance(b, Unset) else self.truth(b)
        b = self.evaluate(right, scope)
        if unset_names((a, b)):
            return Unset(unset_names((a, b)))
        if op == "xor":
            return self.truth(a) != self.truth(b)
        if op in ("==", "!="):
            return (a == b) == (op == "==")
        if op == "+" and isinstance(a, str) and isinstance(b, str):
            return a + b
        x, y = self.number(a), self.number(b)
        if op in ("<", ">", "<=", ">="):
            return {"<": x < y, ">": x > y, "<=": x <= y, ">=": x >= y}[op]
        if op in ("/", "%") and y == 0:
            raise self.error("division by zero")
        try:
            result = x + y if op == "+" else x - y if op == "-" else x * y if op == "*" else x / y if op == "/" \
                else math.fmod(x, y)
        except (ValueError, OverflowError):
            result = math.nan
        if isinstance(result, float) and not math.isfinite(result):
            raise self.error("the value is not a finite number")
        return result

"""G-code parameters and the values of expressions.

Numbered parameters ``#1``..``#5999`` and named ones ``#<name>`` (case-insensitive); a parameter
never set reads 0 (RS274/NGC), except a named one, which is an error (LinuxCNC). The work offsets
live where LinuxCNC keeps them: G54 at #5221 (X, Y, Z, then A B C U V W, and #5230 the rotation
about Z in degrees), G55 at #5241 and so on by 20 up to G59.3 at #5381; the G92 offsets at
#5211. A program sets them with G10 L2/L20 and G92, or the cell gives them (the reading's
``variables``: ``{"5221": 700}`` or ``{"#5221": 700}``).
"""

from __future__ import annotations

import math
from typing import Callable, Mapping, Union

from coatsim.core.errors import InputError
from coatsim.languages.gcode.blocks import Expr

MAX_PARAMETER = 5999
WORK_OFFSET_BASE = 5221  # G54 X; G55 starts 20 further on
WORK_OFFSET_STEP = 20
WORK_ROTATION = 9  # #5230 (G54) holds the rotation about Z, deg
G92_BASE = 5211


def _fix(v: float) -> float:
    return float(math.floor(v))


_UNARY: dict[str, Callable[[float], float]] = {
    "ABS": abs, "ACOS": lambda v: math.degrees(math.acos(v)), "ASIN": lambda v: math.degrees(math.asin(v)),
    "COS": lambda v: math.cos(math.radians(v)), "EXP": math.exp, "FIX": _fix, "FUP": lambda v: float(math.ceil(v)),
    "LN": math.log, "ROUND": lambda v: float(math.floor(v + 0.5)), "SIN": lambda v: math.sin(math.radians(v)),
    "SQRT": math.sqrt, "TAN": lambda v: math.tan(math.radians(v)),
}


def _binary(op: str, a: float, b: float) -> float:
    if op in ("AND", "OR", "XOR"):
        x, y = a != 0.0, b != 0.0
        return float(x and y if op == "AND" else x or y if op == "OR" else x != y)
    comparisons = {"EQ": a == b, "NE": a != b, "GT": a > b, "GE": a >= b, "LT": a < b, "LE": a <= b}
    if op in comparisons:
        return float(comparisons[op])
    if op in ("MOD", "/") and not b:
        return math.nan
    if op in ("+", "-", "*"):
        return a + b if op == "+" else a - b if op == "-" else a * b
    return math.fmod(a, b) if op == "MOD" else a / b if op == "/" else a ** b


class Parameters:
    """The parameters of a running program; ``error(message)`` makes the InputError of the line
    being run."""

    def __init__(self, given: Mapping[str, Union[str, float]], error: Callable[[str], InputError]) -> None:
        self.numbered: dict[int, float] = {}
        self.named: dict[str, float] = {}
        self.error = error
        for key, raw in given.items():
            name = str(key).strip().lstrip("#")
            try:
                value = float(raw)
            except (TypeError, ValueError):
                continue  # a value of another language's kind: not a G-code parameter
            if name.isdigit():
                self.set(int(name), value)
            elif name.startswith("<") and name.endswith(">"):
                self.named[name[1:-1].upper()] = value

    def _index(self, value: float) -> int:
        index = round(value)
        if abs(value - index) > 1e-4 or not 1 <= index <= MAX_PARAMETER:
            raise self.error(f"parameter #{value:g} does not exist (1 to {MAX_PARAMETER})")
        return index

    def get(self, index: int) -> float:
        return self.numbered.get(index, 0.0)

    def set(self, index: int, value: float) -> None:
        self.numbered[self._index(index)] = value

    def assign(self, target: Union[Expr, str], value: float) -> None:
        """``#n = value`` (target an expression) or ``#<name> = value``."""
        if isinstance(target, str):
            self.named[target] = value
        else:
            self.set(self._index(self.evaluate(target)), value)

    def evaluate(self, expr: Expr) -> float:
        """The value of an expression; InputError for a domain error or an unset named parameter."""
        kind = expr[0]
        if kind == "num":
            return expr[1]
        if kind == "par":
            if isinstance(expr[1], str):
                if expr[1] not in self.named:
                    raise self.error(f"named parameter #<{expr[1].lower()}> is read before it is set")
                return self.named[expr[1]]
            return self.get(self._index(self.evaluate(expr[1])))
        if kind == "neg":
            return -self.evaluate(expr[1])
        if kind == "bin":
            try:
                result = _binary(expr[1], self.evaluate(expr[2]), self.evaluate(expr[3]))
            except (OverflowError, ZeroDivisionError, ValueError):
                result = math.nan
            result = math.nan if isinstance(result, complex) else result
        elif expr[1] == "EXISTS":
            target = expr[2][1]
            return float(target in self.named if isinstance(target, str) else True)
        elif expr[1] == "ATAN":
            result = math.degrees(math.atan2(self.evaluate(expr[2]), self.evaluate(expr[3])))
        else:
            try:
                result = _UNARY[expr[1]](self.evaluate(expr[2]))
            except (ValueError, OverflowError):
                result = math.nan
        if not math.isfinite(result):
            raise self.error("an expression has no finite value (division by zero, or a function outside its domain)")
        return float(result)

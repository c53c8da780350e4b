"""G-code parameters and the values of expressions.

Numbered parameters ``#1``..``#5999`` and named ones ``#<name>`` (case-insensitive). A parameter
the program reads but never sets holds a value the controller keeps (LinuxCNC's var file, a Fanuc
macro's common variable): it is an unknown (:mod:`coatsim.languages.script.unknowns`), listed
with where it is read; a parameter set from one is unknown too, and a block whose words need one
is skipped. The work offsets the motions use without naming them read 0 until set. The work offsets
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
from coatsim.languages.script.unknowns import DependsOn, UnknownLog

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

    def __init__(self, given: Mapping[str, Union[str, float]], error: Callable[[str], InputError],
                 where: Callable[[], str] = lambda: "") -> None:
        self.numbered: dict[int, float] = {}
        self.named: dict[str, float] = {}
        self.unset: dict[Union[int, str], tuple[str, ...]] = {}  # parameters set from unknowns
        self.unknown = UnknownLog("a parameter the controller keeps")
        self.error, self.where = error, where
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
        """Parameter ``index`` as a motion uses it (0 if never set); DependsOn if set from unknowns."""
        if index in self.unset:
            raise DependsOn(self.unset[index])
        return self.numbered.get(index, 0.0)

    def set(self, index: int, value: float) -> None:
        index = self._index(index)
        self.numbered[index] = value
        self.unset.pop(index, None)

    def assign(self, target: Union[Expr, str], value: Expr) -> None:
        """``#n = value`` (target an expression) or ``#<name> = value``; the parameter set from an
        unknown is unknown."""
        key: Union[int, str] = target if isinstance(target, str) else self._index(self.evaluate(target))
        try:
            number = self.evaluate(value)
        except DependsOn as unknown:
            self.unset[key] = unknown.names
            return
        if isinstance(key, str):
            self.named[key] = number
            self.unset.pop(key, None)
        else:
            self.set(key, number)

    def read(self, key: Union[int, str]) -> float:
        """A parameter a program reads: DependsOn naming the unknowns when it has no value."""
        if key in self.unset:
            raise DependsOn(self.unset[key])
        found = self.named.get(key) if isinstance(key, str) else self.numbered.get(key)
        if found is None:
            shown = f"#<{key.lower()}>" if isinstance(key, str) else f"#{key}"
            raise DependsOn(self.unknown.read(shown, self.where()).names)
        return found

    def evaluate(self, expr: Expr) -> float:
        """The value of an expression; InputError for a domain error, DependsOn for an unknown."""
        kind = expr[0]
        if kind == "num":
            return expr[1]
        if kind == "par":
            return self.read(expr[1] if isinstance(expr[1], str) else self._index(self.evaluate(expr[1])))
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
            return float(target in self.named or target in self.unset if isinstance(target, str) else True)
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

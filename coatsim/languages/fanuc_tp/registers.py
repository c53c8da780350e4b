"""The data a Fanuc program works on: registers, position registers, frames, signals.

The controller keeps registers ``R[i]``, position registers ``PR[i]``, user frames ``UFRAME[i]``
and tool frames ``UTOOL[i]`` between programs; an .LS file holds none of their values. A program
sets them, or the cell gives them (the reading's ``variables``: ``{"R[1]": 5, "PR[2]":
"x,y,z,w,p,r", "UFRAME[1]": "x,y,z,w,p,r", "UTOOL[1]": "…"}``, mm and deg). A register,
position register or user frame read before any value is an unknown
(:mod:`coatsim.languages.script.unknowns`): reading it raises DependsOn, a register set from one
is unknown too (``unset``), and the statement that needs one is skipped. A tool not given is the
cell's gun. ``UFRAME[0]`` is the world frame (the twin's robot
base), ``UTOOL[0]`` the flange. Position registers hold X, Y, Z, W, P, R (or joint values) and add
component by component, as on the controller (``PR[1]=PR[2]+PR[3]``). Inputs ``DI[i]`` come from
the reading's ``inputs``; any other signal the program reads before it sets it is OFF with a
warning.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Callable, Mapping, Optional, Union

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.languages.fanuc_tp.expressions import Expr
from coatsim.languages.fanuc_tp.positions import pose_of, values_of
from coatsim.languages.script.unknowns import DependsOn, UnknownLog

_KEY = re.compile(r"\s*(R|PR|UFRAME|UTOOL)\s*\[\s*(\d+)\s*\]\s*\Z", re.I)
_FUNCTIONS: dict[str, Callable[..., float]] = {
    "SQRT": math.sqrt, "SIN": lambda v: math.sin(math.radians(v)), "COS": lambda v: math.cos(math.radians(v)),
    "TAN": lambda v: math.tan(math.radians(v)), "ASIN": lambda v: math.degrees(math.asin(v)),
    "ACOS": lambda v: math.degrees(math.acos(v)), "ATAN": lambda v: math.degrees(math.atan(v)),
    "ATAN2": lambda y, x: math.degrees(math.atan2(y, x)), "LN": math.log, "EXP": math.exp, "ABS": abs,
    "TRUNC": lambda v: float(math.trunc(v)), "ROUND": lambda v: float(math.floor(v + 0.5)),
}


@dataclass(frozen=True)
class PositionValue:
    """A position register's value: X, Y, Z, W, P, R (``joints`` False) or J1..J6 (deg)."""

    values: tuple[float, ...]
    joints: bool = False

    def pose(self) -> Pose:
        return pose_of(self.values)


def _six(text: Union[str, float], key: str) -> tuple[float, ...]:
    try:
        values = tuple(float(v) for v in re.split(r"[,\s]+", str(text).strip(" []")) if v)
    except ValueError:
        values = ()
    if len(values) != 6 or not all(math.isfinite(v) for v in values):
        raise InputError(f"variable {key}: expected x,y,z,w,p,r (mm, deg), got {str(text)[:40]!r}")
    return values


class Registers:
    """Registers, frames and signals of one run; ``error(message)`` and ``warn(key, message)``
    speak for the line being run, ``where()`` names it; ``unknown`` the registers read before
    any value (with the lines that read each), ``unset`` those set from them."""

    def __init__(self, given: Mapping[str, Union[str, float]], inputs: Mapping[int, bool],
                 error: Callable[[str], InputError], warn: Callable[[str, str], None],
                 where: Callable[[], str] = lambda: "") -> None:
        self.error, self.warn, self.where = error, warn, where
        self.unknown = UnknownLog("a register the controller keeps")
        self.unset: dict[str, tuple[str, ...]] = {}  # "R[1]", "PR[2]", "UFRAME[3]" set from unknowns
        self.r: dict[int, float] = {}
        self.pr: dict[int, PositionValue] = {}
        self.frames: dict[str, dict[int, Pose]] = {"UFRAME": {0: Pose.identity()}, "UTOOL": {0: Pose.identity()}}
        self.outputs: dict[tuple[str, int], float] = {}
        self.inputs = dict(inputs)
        self.unknown_reads = 0  # reads of a signal nobody gives (a WAIT on one is taken as met)
        for key, value in given.items():
            match = _KEY.match(str(key))
            if match is None:
                continue
            kind, index = match.group(1).upper(), int(match.group(2))
            if kind == "R":
                try:
                    self.r[index] = float(value)
                except (TypeError, ValueError):
                    raise InputError(f"variable {key}: expected a number, got {str(value)[:40]!r}") from None
            elif kind == "PR":
                self.pr[index] = PositionValue(_six(value, key))
            else:
                self.frames[kind][index] = pose_of(_six(value, key))

    # --- values -------------------------------------------------------------------------
    def index(self, expr: Expr, args: tuple) -> int:
        value = self.evaluate(expr, args)
        if value != round(value) or not 0 <= value <= 1_000_000:
            raise self.error(f"index {value:g} is not a whole number >= 0")
        return int(value)

    def signal(self, kind: str, number: int) -> float:
        if kind == "DI" and number in self.inputs:
            return float(self.inputs[number])
        if (kind, number) in self.outputs:
            return self.outputs[(kind, number)]
        self.unknown_reads += 1
        self.warn(f"signal:{kind}{number}", f"{kind}[{number}] is not set by the program nor given; taken as OFF "
                  "(give its state in the inputs)")
        return 0.0

    def evaluate(self, expr: Expr, args: tuple) -> float:
        """The value of an expression (``args`` the AR[] of the running program)."""
        kind = expr[0]
        if kind == "num":
            return expr[1]
        if kind == "reg":
            return self._register(expr, args)
        if kind == "sys":
            self.warn(f"sys:{expr[1]}", f"system variable {expr[1]} is not simulated; taken as 0")
            return 0.0
        if kind == "not":
            return float(self.evaluate(expr[1], args) == 0.0)
        if kind == "neg":
            return -self.evaluate(expr[1], args)
        if kind == "fn":
            try:
                result = float(_FUNCTIONS[expr[1]](*(self.evaluate(a, args) for a in expr[2])))
            except (ValueError, TypeError, OverflowError):
                result = math.nan
        else:
            result = self._binary(expr[1], self.evaluate(expr[2], args), self.evaluate(expr[3], args))
        if not math.isfinite(result):
            raise self.error("an expression has no finite value (division by zero, or a function outside its domain)")
        return result

    @staticmethod
    def _binary(op: str, a: float, b: float) -> float:
        if op in ("AND", "OR"):
            return float((a != 0.0 and b != 0.0) if op == "AND" else (a != 0.0 or b != 0.0))
        table = {"=": a == b, "<>": a != b, "<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}
        if op in table:
            return float(table[op])
        if op in ("/", "MOD", "DIV") and b == 0.0:
            return math.nan
        try:
            if op in ("+", "-", "*"):
                return a + b if op == "+" else a - b if op == "-" else a * b
            return a / b if op == "/" else math.fmod(a, b) if op == "MOD" else float(math.trunc(a / b))
        except (ValueError, OverflowError):
            return math.nan

    def _register(self, expr: Expr, args: tuple) -> float:
        kind, number = expr[1], self.index(expr[2], args)
        if kind == "R":
            self.known(f"R[{number}]", number in self.r)
            return self.r[number]
        if kind == "AR":
            if not 1 <= number <= len(args) or isinstance(args[number - 1], str):
                raise self.error(f"AR[{number}]: the CALL gives no number there")
            return float(args[number - 1])
        if kind == "PR":
            if len(expr) < 4:
                raise self.error(f"PR[{number}] is a position; a value takes one element, PR[{number},j]")
            element = self.index(expr[3], args)
            value = self.position(number)
            if not 1 <= element <= len(value.values):
                raise self.error(f"PR[{number},{element}]: a position register has elements 1 to 6")
            return value.values[element - 1]
        return self.signal(kind, number)

    # --- positions and frames ------------------------------------------------------------
    def known(self, key: str, has_value: bool) -> None:
        """DependsOn when register ``key`` (``R[1]``) is set from unknowns or, ``has_value`` False,
        never set (an unknown read here)."""
        if key in self.unset:
            raise DependsOn(self.unset[key])
        if not has_value:
            raise DependsOn(self.unknown.read(key, self.where()).names)

    def position(self, number: int) -> PositionValue:
        self.known(f"PR[{number}]", number in self.pr)
        return self.pr[number]

    def frame(self, kind: str, number: int) -> Optional[Pose]:
        """UFRAME/UTOOL ``number`` (None: a tool the program does not give)."""
        found = self.frames[kind].get(number)
        if kind == "UFRAME" or f"{kind}[{number}]" in self.unset:
            self.known(f"{kind}[{number}]", found is not None)
        return found

    def set_element(self, number: int, element: int, value: float) -> None:
        """``PR[i,j] = value`` (an unset register becomes a Cartesian zero first)."""
        if f"PR[{number}]" in self.unset:
            return  # an element of a register set from unknowns: it stays unknown
        current = list(self.pr.get(number, PositionValue((0.0,) * 6)).values)
        if not 1 <= element <= len(current):
            raise self.error(f"PR[{number},{element}]: a position register has elements 1 to 6")
        current[element - 1] = value
        self.pr[number] = PositionValue(tuple(current), self.pr[number].joints if number in self.pr else False)

    def combine(self, items: tuple, args: tuple, here: Callable[[], Pose], joints: Callable[[], np.ndarray],
                point: Callable[[int], PositionValue]) -> PositionValue:
        """The value of ``LPOS``, ``JPOS``, ``PR[i]``, ``P[i]`` (its values as taught, in its own
        frames), ``UFRAME[i]``, ``UTOOL[i]`` summed element by element."""
        total: Optional[np.ndarray] = None
        kept = _cancelled(items)
        if not kept:  # PR[i]=PR[i]-PR[i], LPOS-LPOS: the idioms that clear a register, whatever it held
            return PositionValue((0.0,) * 6, any(atom[0] == "JPOS" for _, atom in items))
        is_joints = False
        for sign, atom in kept:
            if atom[0] == "LPOS":
                value = PositionValue(values_of(here()))
            elif atom[0] == "JPOS":
                value = PositionValue(tuple(float(v) for v in np.degrees(joints())), True)
            elif atom[0] == "PR":
                value = self.position(self.index(atom[1], args))
            elif atom[0] == "P":
                value = point(self.index(atom[1], args))
            else:
                frame = self.frame(atom[0], self.index(atom[1], args))
                if frame is None:
                    raise self.error(f"{atom[0]}[{self.index(atom[1], args)}] is not set by the program nor given")
                value = PositionValue(values_of(frame))
            vector = np.array(value.values) * (1.0 if sign == "+" else -1.0)
            total = vector if total is None else total + vector
            is_joints = value.joints
        return PositionValue(tuple(float(v) for v in total), is_joints)


def _cancelled(items: tuple) -> list:
    """The terms of a position sum without the pairs that cancel (the same atom added and taken)."""
    kept = list(items)
    changed = True
    while changed:
        changed = False
        for a in range(len(kept)):
            b = next((b for b in range(len(kept)) if kept[b][1] == kept[a][1] and kept[b][0] != kept[a][0]), None)
            if b is not None:
                kept = [x for k, x in enumerate(kept) if k not in (a, b)]
                changed = True
                break
    return kept

"""KRL expressions: numbers, strings, booleans, structures (``{X 1, Y 2}``), components, arrays,
the geometric operator ``A : B``, arithmetic and logic, the math functions and ``INV_POS``, names
looked up in the routine's locals, the data lists, the system variables and the values the reading
gives; a name none of them has raises :class:`Unknown` (the statement is skipped)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from coatsim.languages.kuka_krl import values as v
from coatsim.languages.kuka_krl.parser import SYNTAX, stream
from coatsim.languages.script import nodes as n
from coatsim.languages.script.tokens import END, NEWLINE, tokenize


class Unknown(Exception):
    """A name no file declares, or (``declared``) one declared without a value."""

    def __init__(self, name: str, declared: bool = False) -> None:
        self.name, self.declared = name, declared


class Expressions:
    """Evaluation; the interpreter provides ``frames``, ``globals``, ``system``, ``valueless``, ``int_names``,
    ``options``, ``routines``, ``source``, ``position``, ``error``, ``signal``, ``call`` and
    ``_stop_previous``."""

    def expr(self, tokens) -> n.Expr:
        st = stream(tokens, self.source)
        e = st.expression()
        if st.tok.kind != "end":
            raise st.error(f"unexpected {st.shown()}")
        return e

    def eval(self, e: n.Expr) -> Any:
        if isinstance(e, n.Num):
            return e.value
        if isinstance(e, n.Str):
            return e.value
        if isinstance(e, n.Name):
            return self.lookup(e.name)
        if isinstance(e, n.Aggregate):
            return v.Struct(e.type, {f: self.eval(item) for f, item in zip(e.fields, e.items)})
        if isinstance(e, n.Field):
            base = self.eval(e.base)
            if not isinstance(base, v.Struct) or e.field.upper() not in base.fields:
                raise self.error(f"no component {e.field} in this value")
            return base.fields[e.field.upper()]
        if isinstance(e, n.Index):
            if isinstance(e.base, n.Name) and e.base.name.upper() in ("$IN", "$OUT", "$OUT_C"):
                return self.signal(e.base.name.upper(), int(self._num(self.eval(e.index[0]))))
            if isinstance(e.base, n.Name) and e.base.name.upper() in ("TOOL_DATA", "BASE_DATA"):
                key = f"{e.base.name.upper()}[{int(self._num(self.eval(e.index[0])))}]"
                return self.lookup(key)
            base = self.eval(e.base)
            for i in e.index:
                k = int(self._num(self.eval(i)))
                if not isinstance(base, list) or not 1 <= k <= len(base):
                    raise self.error(f"index {k} out of the array")
                base = base[k - 1]
            return base
        if isinstance(e, n.Unary):
            x = self.eval(e.operand)
            if e.op in ("NOT", "B_NOT"):
                return not x if isinstance(x, bool) else float(~int(x))
            return -self._num(x) if e.op == "-" else self._num(x)
        if isinstance(e, n.Binary):
            return self._binary(e)
        if isinstance(e, n.Call):
            return self.function(e)
        raise self.error("cannot evaluate this expression")

    def _num(self, x: Any) -> float:
        if isinstance(x, bool) or not isinstance(x, float):
            raise self.error(f"a number where {x!r} is given")
        return x

    def _is_int(self, e: n.Expr) -> bool:
        """Whether ``e`` is of type INT: an INT divided by an INT is an INT, the quotient cut
        toward zero (KUKA System Software 8, "Arithmetic operators")."""
        if isinstance(e, n.Num):
            return e.integer
        if isinstance(e, (n.Name, n.Index)):
            base = e.base if isinstance(e, n.Index) else e
            return isinstance(base, n.Name) and base.name.upper() in self.int_names
        if isinstance(e, n.Unary):
            return e.op in ("+", "-") and self._is_int(e.operand)
        if isinstance(e, n.Binary):
            return e.op in ("+", "-", "*", "/") and self._is_int(e.left) and self._is_int(e.right)
        return False

    def _binary(self, e: n.Binary) -> Any:
        a, b = self.eval(e.left), self.eval(e.right)
        op = e.op
        if op == ":":
            if not (isinstance(a, v.Struct) and isinstance(b, v.Struct)):
                raise self.error("the geometric operator ':' joins two frames or positions")
            return v.compose(a, b)
        if op in ("AND", "OR", "EXOR"):
            return {"AND": a and b, "OR": a or b, "EXOR": a != b}[op]
        if op in ("==", "<>"):
            return (a == b) if op == "==" else (a != b)
        if isinstance(a, str) and isinstance(b, str) and op == "+":
            return a + b
        x, y = self._num(a), self._num(b)
        if op == "/":
            if y == 0:
                raise self.error("division by zero")
            return float(math.trunc(x / y)) if self._is_int(e.left) and self._is_int(e.right) else x / y
        if op.startswith("B_"):
            return float({"B_AND": int(x) & int(y), "B_OR": int(x) | int(y), "B_EXOR": int(x) ^ int(y)}[op])
        return {"+": x + y, "-": x - y, "*": x * y, "<": x < y, ">": x > y, "<=": x <= y, ">=": x >= y}[op]

    def lookup(self, name: str) -> Any:
        key = name.upper()
        if key in ("TRUE", "FALSE"):
            return key == "TRUE"
        if key.startswith("#"):
            return key
        found = self.frames[-1].get(key) if self.frames and key in self.frames[-1] else self.globals.get(key)
        if found is not None and id(found) not in self.valueless:
            return found
        if key in self.system:
            return self.system[key]
        if key == "$POS_ACT":
            self._stop_previous()
            return self.position.copy() if self.position is not None else v.default("E6POS")
        for given, text in self.options.variables.items():
            if given.upper() == key:
                return float(text) if is_number(text) else self.eval(self.expr(
                    [t for t in stream_tokens(str(text), self.source)]))
        if key in ("HOME", "XHOME") and found is None and self.options.kinematics is not None:
            return self.home_axes(name)
        raise Unknown(name, found is not None)

    def home_axes(self, name: str) -> v.Struct:
        """``HOME``/``XHOME`` of ``$config.dat``, which no file gives: the cell's home position."""
        self.warn("home", f"{name} is the controller's ($config.dat); the cell's home position is taken")
        joints = np.degrees(np.asarray(self.options.kinematics.home(1), dtype=float))
        return v.Struct("E6AXIS", {f"A{k + 1}": float(a) for k, a in enumerate(joints[:6])})

    def _stored(self, name: n.Name) -> Any:
        """The value held under ``name`` to set a component of, declared with a value or not."""
        key = name.name.upper()
        for scope in ((self.frames[-1],) if self.frames else ()) + (self.globals, self.system):
            if key in scope:
                return scope[key]
        return self.eval(name)

    def function(self, call: n.Call) -> Any:
        name = call.name.upper()
        args = [self.eval(a.value) for a in call.args]
        math_fns = {"SIN": lambda x: np.sin(np.radians(x)), "COS": lambda x: np.cos(np.radians(x)),
                    "TAN": lambda x: np.tan(np.radians(x)), "SQRT": np.sqrt, "ABS": abs,
                    "ACOS": lambda x: np.degrees(np.arccos(x)), "ATAN2": lambda y, x: np.degrees(np.arctan2(y, x))}
        if name in math_fns:
            return float(math_fns[name](*[self._num(a) for a in args]))
        if name == "INV_POS":
            return v.frame_of(v.pose_of(args[0]).inverse(), args[0].type or "FRAME")
        routine = self.routines.get(call.name.lower())
        if routine is None:
            raise Unknown(call.name)
        return self.call(routine, call.args)


def is_number(text: Any) -> bool:
    try:
        float(text)
    except (TypeError, ValueError):
        return False
    return True


def stream_tokens(text: str, source: str):
    return [t for t in tokenize(text, SYNTAX, source) if t.kind not in (NEWLINE, END)]

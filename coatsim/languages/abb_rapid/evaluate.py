"""RAPID expressions: operators, data lookup and the functions motion programs use (``Offs``,
``RelTool``, ``CRobT``, ``CJointT``, ``OrientZYX``, ``EulerZYX``, ``PoseMult``, ``PoseInv``,
``PoseVect``, math with angles in degrees, ``DInput``/``DOutput``, user FUNCs).

``Offs(p, x, y, z)`` displaces ``p`` in its object frame; ``RelTool(p, dx, dy, dz \\Rx \\Ry \\Rz)``
in the tool frame of ``p``, turning about x, then the new y, then the new z (ABB, RAPID
Instructions, Functions and Data types: Offs, RelTool).
"""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import matrix_to_abc, rot_x, rot_y, rot_z
from coatsim.languages.abb_rapid import data as d
from coatsim.languages.script import nodes as n


class Unknown(Exception):
    """A name no file declares (nor ``variables`` gives), or (``declared``) a position declared
    without a value and not set since: the statement reading it is skipped."""

    def __init__(self, name: str, line: int, declared: bool = False) -> None:
        super().__init__(name)
        self.name, self.line, self.declared = name, line, declared


def _arg_map(args: tuple[n.Arg, ...]) -> tuple[list[n.Expr], dict[str, Optional[n.Expr]]]:
    positional = [a.value for a in args if a.name is None]
    named = {a.name.lower(): a.value for a in args if a.name is not None}
    return positional, named


class Expressions:
    """Evaluation; the interpreter provides ``lookup``, ``call_function``, ``current_target``,
    ``signal_state``, ``error`` and ``where``."""

    def eval(self, e: n.Expr) -> Any:
        if isinstance(e, n.Num):
            return e.value
        if isinstance(e, n.Str):
            return e.value
        if isinstance(e, n.Name):
            return self.lookup(e.name, e.line)
        if isinstance(e, n.Aggregate):
            return [self.eval(item) for item in e.items]
        if isinstance(e, n.Field):
            base = self.eval(e.base)
            if not isinstance(base, d.Record) or e.field.lower() not in base.fields:
                raise self.error(f"no component {e.field} in {d._shown(base)}")
            return base.fields[e.field.lower()]
        if isinstance(e, n.Index):
            base = self.eval(e.base)
            for i in e.index:
                k = self.eval(i)
                if not isinstance(base, list) or not isinstance(k, float) or not (1 <= k <= len(base)) or k != int(k):
                    raise self.error(f"index {k!r} out of the array's 1..{len(base) if isinstance(base, list) else 0}")
                base = base[int(k) - 1]
            return base
        if isinstance(e, n.Unary):
            value = self.eval(e.operand)
            if e.op == "NOT":
                return not self._bool(value)
            if isinstance(value, d.Record) and value.type == "pos":
                return d.make_pos(-d.pos_array(value) if e.op == "-" else d.pos_array(value))
            return -self._num(value) if e.op == "-" else self._num(value)
        if isinstance(e, n.Binary):
            return self._binary(e)
        if isinstance(e, n.Call):
            return self.call_function(e)
        raise self.error(f"cannot evaluate {type(e).__name__}")

    def _num(self, value: Any) -> float:
        if isinstance(value, bool) or not isinstance(value, float):
            raise self.error(f"a number where {d._shown(value)} is given")
        return value

    def _bool(self, value: Any) -> bool:
        if not isinstance(value, bool):
            raise self.error(f"TRUE or FALSE where {d._shown(value)} is given")
        return value

    def _binary(self, e: n.Binary) -> Any:
        op = e.op
        if op in ("AND", "OR", "XOR"):
            a, b = self._bool(self.eval(e.left)), self._bool(self.eval(e.right))
            return {"AND": a and b, "OR": a or b, "XOR": a != b}[op]
        a, b = self.eval(e.left), self.eval(e.right)
        if op in ("=", "<>"):
            same = _equal(a, b)
            return same if op == "=" else not same
        if isinstance(a, str) and isinstance(b, str) and op == "+":
            return a + b
        pa, pb = isinstance(a, d.Record) and a.type == "pos", isinstance(b, d.Record) and b.type == "pos"
        if pa or pb:
            return self._pos_op(op, a, b)
        if isinstance(a, d.Record) and isinstance(b, d.Record) and a.type == b.type == "orient" and op == "*":
            rot = d.rotation_of(a, self.error) @ d.rotation_of(b, self.error)
            return d.make_orient(rot)
        x, y = self._num(a), self._num(b)
        if op in ("<", ">", "<=", ">="):
            return {"<": x < y, ">": x > y, "<=": x <= y, ">=": x >= y}[op]
        if op in ("/", "DIV", "MOD") and y == 0:
            raise self.error(f"division by zero ({op})")
        if op == "DIV":
            return float(math.trunc(x / y))
        if op == "MOD":
            return float(math.fmod(x, y))
        return {"+": x + y, "-": x - y, "*": x * y, "/": x / y}[op]

    def _pos_op(self, op: str, a: Any, b: Any) -> Any:
        if op in ("+", "-") and isinstance(a, d.Record) and isinstance(b, d.Record):
            return d.make_pos(d.pos_array(a) + (d.pos_array(b) if op == "+" else -d.pos_array(b)))
        if op == "*" and isinstance(a, d.Record) and isinstance(b, d.Record):
            return float(d.pos_array(a) @ d.pos_array(b))  # the scalar product
        if op in ("*", "/"):
            vec, k = (a, b) if isinstance(a, d.Record) else (b, a)
            k = self._num(k)
            return d.make_pos(d.pos_array(vec) * k if op == "*" else d.pos_array(vec) / k)
        raise self.error(f"operator {op} does not apply to a pos and {d._shown(b)}")

    # --- functions ------------------------------------------------------------------------
    def builtin_function(self, call: n.Call) -> Any:
        """A predefined function; None when ``call`` names none."""
        name = call.name.lower()
        pos, named = _arg_map(call.args)
        if name in _MATH:
            return self._math(call.name, _MATH[name], pos)
        for group in (self._number_function, self._pose_function, self._target_function):
            value = group(name, pos, named)
            if value is not None:
                return value
        return None

    def _math(self, shown: str, entry: tuple, pos: list) -> float:
        fn, count = entry
        values = [self._num(self.eval(a)) for a in pos]
        if len(values) != count:
            raise self.error(f"{shown} takes {count} argument{'s' if count > 1 else ''}")
        try:
            return float(fn(*values))
        except (ValueError, OverflowError):
            raise self.error(f"{shown}({', '.join(f'{v:g}' for v in values)}) is not defined") from None

    def _number_function(self, name: str, pos: list, named: dict) -> Any:
        """Rounding, signals, array sizes and strings."""
        if name in ("round", "trunc"):
            value = self._num(self.eval(pos[0]))
            decimals = int(self._num(self.eval(named["dec"]))) if named.get("dec") is not None else 0
            scale = 10.0 ** decimals
            return (round(value * scale) if name == "round" else math.trunc(value * scale)) / scale
        if name in ("dinput", "doutput", "testdi"):
            return self.signal_state(pos[0], name)
        if name == "dim":
            base = self.eval(pos[0])
            k = int(self._num(self.eval(pos[1])))
            for _ in range(k - 1):
                base = base[0]
            return float(len(base))
        if name == "numtostr":
            value = self._num(self.eval(pos[0]))
            return f"{value:.{int(self._num(self.eval(pos[1])))}f}"
        if name == "strlen":
            return float(len(self.eval(pos[0])))
        if name == "present":
            return self.present(pos[0])
        return None

    def _target_function(self, name: str, pos: list, named: dict) -> Any:
        """Functions of robtargets: offsets, the current position."""
        if name == "offs":
            p = self._target(pos[0], "robtarget")
            dx, dy, dz = (self._num(self.eval(a)) for a in pos[1:4])
            out = p.copy()
            out.fields["trans"] = d.make_pos(d.pos_array(p.fields["trans"]) + np.array([dx, dy, dz]))
            return out
        if name == "reltool":
            p = self._target(pos[0], "robtarget")
            dx, dy, dz = (self._num(self.eval(a)) for a in pos[1:4])
            turn = np.eye(3)
            for axis, rot in (("rx", rot_x), ("ry", rot_y), ("rz", rot_z)):
                if named.get(axis) is not None:
                    turn = turn @ rot(math.radians(self._num(self.eval(named[axis]))))
            pose = d.pose_of(p, self.error)
            return d.with_pose(p, pose @ Pose(turn, np.array([dx, dy, dz])))
        if name in ("crobt", "cpos"):
            target = self.current_target(named)
            return target if name == "crobt" else target.fields["trans"].copy()
        if name == "cjointt":
            return self.current_joints()
        return None

    def _pose_function(self, name: str, pos: list, named: dict) -> Any:
        """Orientations and poses: OrientZYX, EulerZYX, PoseMult, PoseInv, PoseVect."""
        if name == "orientzyx":
            z, y, x = (math.radians(self._num(self.eval(a))) for a in pos[:3])
            return d.make_orient(rot_z(z) @ rot_y(y) @ rot_x(x))
        if name == "eulerzyx":
            rot = d.rotation_of(self._target(pos[0], "orient"), self.error)
            z, y, x = matrix_to_abc(rot)
            axis = next((k for k in ("x", "y", "z") if k in named), None)
            if axis is None:
                raise self.error("EulerZYX needs one of \\X, \\Y, \\Z")
            return {"z": z, "y": y, "x": x}[axis]
        if name in ("posemult", "poseinv", "posevect"):
            a = d.pose_of(self._target(pos[0], "pose"), self.error)
            if name == "poseinv":
                return d.with_pose(d.record("pose", [0, 0, 0], [1, 0, 0, 0]), a.inverse())
            if name == "posemult":
                b = d.pose_of(self._target(pos[1], "pose"), self.error)
                return d.with_pose(d.record("pose", [0, 0, 0], [1, 0, 0, 0]), a @ b)
            p = d.pos_array(self._target(pos[1], "pos"))
            return d.make_pos(a.rotation @ p + a.translation_mm)
        return None

    def _target(self, e: n.Expr, type_: str) -> d.Record:
        return d.coerce(type_, self.eval(e), self.error)


def _equal(a: Any, b: Any) -> bool:
    if isinstance(a, d.Record) and isinstance(b, d.Record):
        return a.type == b.type and all(_equal(a.fields[k], b.fields[k]) for k in a.fields)
    return a == b


_MATH = {
    "abs": (abs, 1), "sqrt": (math.sqrt, 1), "exp": (math.exp, 1), "pow": (math.pow, 2),
    "sin": (lambda v: math.sin(math.radians(v)), 1), "cos": (lambda v: math.cos(math.radians(v)), 1),
    "tan": (lambda v: math.tan(math.radians(v)), 1), "asin": (lambda v: math.degrees(math.asin(v)), 1),
    "acos": (lambda v: math.degrees(math.acos(v)), 1), "atan": (lambda v: math.degrees(math.atan(v)), 1),
    "atan2": (lambda y, x: math.degrees(math.atan2(y, x)), 2),
}

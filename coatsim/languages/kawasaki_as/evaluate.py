"""Expression evaluation in the context a statement gives: a real, a string, a pose (a
transformation relative to the current BASE) or a joint value (degrees).

Reals follow AS: TRUE and ON are -1, FALSE and OFF 0; comparisons and AND/OR/XOR/NOT give
-1 or 0; BAND/BOR/BXOR work on the integer parts; trigonometry is in degrees; INT truncates
towards zero. Division by zero, a square root of a negative number and overflow stop the run
(exit 3); a value of the wrong kind is a program defect (exit 2); a variable no file gives is
an unknown (see :mod:`~coatsim.languages.kawasaki_as.unknowns`). A flat :class:`~ast.Chain` is folded
left to right in a loop, so a long sum costs no stack.
"""

from __future__ import annotations

import math
from typing import Optional, Union

import numpy as np

from coatsim.core.budgets import check_budget
from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.evaluate_calls import (
    POSE_FUNCTIONS,
    joint_call,
    pose_call,
    real_call,
)
from coatsim.languages.kawasaki_as.evaluate_strings import encode, string_call
from coatsim.languages.kawasaki_as.machine import Machine
from coatsim.languages.kawasaki_as.unknowns import NotSimulated
from coatsim.languages.kawasaki_as.values import PoseJoints

TRUE, FALSE = -1.0, 0.0
_WHERE = ("#HERE", "#DEST")  # the joint value where the robot is (the motion ended: DEST is HERE)
_COMPARE = {"==": lambda a, b: a == b, "<>": lambda a, b: a != b, "<": lambda a, b: a < b,
            ">": lambda a, b: a > b, "<=": lambda a, b: a <= b, ">=": lambda a, b: a >= b}


def _truth(x: float) -> float:
    return TRUE if x else FALSE


def _int(x: float) -> int:
    return int(math.trunc(x))


class Evaluator:
    """Evaluates expressions against the variables, signals and pose of an interpreter."""

    def __init__(self, run: Machine) -> None:
        self.run = run

    def error(self, message: str) -> InputError:
        return self.run.error(message)

    def failure(self, message: str) -> ExecutionError:
        return self.run.failure(message)

    # --- kinds ---------------------------------------------------------------------------
    def kind(self, e: ast.Expr) -> str:
        """'real', 'string', 'pose' or 'joint' (a name's kind from its prefix or its value)."""
        t = type(e)
        if t is ast.Str:
            return "string"
        if t is ast.Name:
            if e.kind != "value":
                return e.kind
            return "pose" if self.run.has_pose(e) and not self.run.has_real(e) else "real"
        if t is ast.Ref:
            return self.kind(e.target)
        if t is ast.Unary:
            return "real" if e.op == "NOT" else self.kind(e.operand)
        if t is ast.Binary:
            return self.kind(e.left) if e.op in ("+", "-") else "real"
        if t is ast.Chain:
            return self.kind(e.first) if e.rest[0][0] in ("+", "-") else "real"
        if t is ast.Call:
            if e.name.startswith("$"):
                return "string"
            if e.name.startswith("#"):
                return "joint"
            return "pose" if e.name in POSE_FUNCTIONS else "real"
        if t is ast.Shift:
            return "pose"
        if t is ast.JointLiteral:
            return "joint"
        return "real"

    def describe(self, e: ast.Expr) -> str:
        if isinstance(e, ast.Format):
            return f"the format /{e.spec}"
        if isinstance(e, ast.Name) and e.whole:
            return f"the whole array {e.name}[] (only a CALL passes one)"
        return {"string": "a string", "pose": "a pose", "joint": "a joint value"}.get(self.kind(e), "a number")

    # --- reals ---------------------------------------------------------------------------
    def real(self, e: ast.Expr) -> float:
        t = type(e)
        if t is ast.Num:
            return e.value
        if t is ast.Name and not e.whole:
            return self.run.get_real(e)
        if t is ast.Binary:
            return self.binary(e.op, e.left, e.right)
        if t is ast.Chain:
            return self.chain(e)
        if t is ast.Unary:
            if e.op == "NOT":
                return _truth(self.real(e.operand) == 0.0)
            value = self.real(e.operand)
            return -value if e.op == "-" else value
        if t is ast.Call:
            return real_call(self, e)
        raise self.error(f"expected a number, found {self.describe(e)}")

    def truth(self, e: ast.Expr) -> bool:
        return self.real(e) != 0.0

    def integer(self, e: ast.Expr, what: str) -> int:
        value = self.real(e)
        if value != math.floor(value):
            raise self.error(f"{what} must be a whole number, got {value:g}")
        return int(value)

    def binary(self, op: str, left: ast.Expr, right: ast.Expr) -> float:
        if op in _COMPARE:
            if "string" in (self.kind(left), self.kind(right)):
                return _truth(_COMPARE[op](self.string(left), self.string(right)))
            return _truth(_COMPARE[op](self.real(left), self.real(right)))
        if op == "AND":
            return _truth(self.truth(left) and self.truth(right))
        if op == "OR":
            return _truth(self.truth(left) or self.truth(right))
        return self.arithmetic(op, self.real(left), self.real(right))

    def chain(self, e: ast.Chain) -> float:
        """A flat run of one precedence, folded left to right (AND and OR short-circuit)."""
        op, second = e.rest[0]
        if op in ("AND", "OR", "XOR"):
            value = self.truth(e.first)
            for op, x in e.rest:
                if op == "OR":
                    value = value or self.truth(x)
                elif op == "AND":
                    value = value and self.truth(x)
                else:
                    value = value != self.truth(x)
            return _truth(value)
        if op in _COMPARE:
            acc = self.binary(op, e.first, second)  # (strings compare in the first pair only)
            for op, x in e.rest[1:]:
                acc = _truth(_COMPARE[op](acc, self.real(x)))
            return acc
        acc = self.real(e.first)
        for op, x in e.rest:
            acc = self.arithmetic(op, acc, self.real(x))
        return acc

    def arithmetic(self, op: str, a: float, b: float) -> float:
        if op == "+":
            out = a + b
        elif op == "-":
            out = a - b
        elif op == "*":
            out = a * b
        elif op == "/":
            if b == 0.0:
                raise self.failure("division by zero")
            out = a / b
        elif op == "MOD":
            if b == 0.0:
                raise self.failure("MOD by zero")
            out = math.fmod(a, b)
        elif op == "^":
            try:
                out = math.pow(a, b)
            except (ValueError, OverflowError):
                raise self.failure(f"{a:g} ^ {b:g} has no real value") from None
        elif op == "XOR":
            return _truth((a != 0.0) != (b != 0.0))
        elif op == "BAND":
            return float(_int(a) & _int(b))
        elif op == "BOR":
            return float(_int(a) | _int(b))
        else:  # BXOR
            return float(_int(a) ^ _int(b))
        if not math.isfinite(out):
            raise self.failure(f"arithmetic overflow in {op}")
        return out

    def arg(self, e: ast.Call, i: int) -> ast.Expr:
        if i >= len(e.args) or e.args[i] is None:
            raise self.error(f"{e.name} needs argument {i + 1}")
        return e.args[i]

    def arity(self, e: ast.Call, n: int) -> None:
        if len(e.args) != n:
            raise self.error(f"{e.name} takes {n} argument{'s' if n > 1 else ''}, found {len(e.args)}")

    # --- strings -------------------------------------------------------------------------
    def string(self, e: ast.Expr) -> str:
        t = type(e)
        if t is ast.Str:
            return e.value
        if t is ast.Name and e.kind == "string" and not e.whole:
            return self.run.get_string(e)
        if t is ast.Binary and e.op == "+":
            return self.joined([self.string(e.left), self.string(e.right)])
        if t is ast.Chain and all(op == "+" for op, _ in e.rest):
            return self.joined([self.string(e.first), *(self.string(x) for _, x in e.rest)])
        if t is ast.Call and e.name.startswith("$"):
            return string_call(self, e)
        raise self.error(f"expected a string, found {self.describe(e)}")

    def joined(self, parts: list[str]) -> str:
        """The strings one after the other, refused past the budget string_chars before they are
        joined (a few lines doubling a string would otherwise fill memory)."""
        check_budget(f"{self.run.where()}: characters of a string", sum(map(len, parts)), "string_chars",
                     "build shorter strings (a controller's string holds 128 characters)")
        return "".join(parts)

    def encode(self, items: tuple[Optional[ast.Expr], ...]) -> str:
        """$ENCODE / TYPE text: values in the current format (/D, /Fw.d, /Ew.d, /Gw.d, /Xn)."""
        return encode(self, items)

    # --- poses ---------------------------------------------------------------------------
    def pose(self, e: ast.Expr) -> Pose:
        t = type(e)
        if t is ast.Name and not e.whole:
            if e.kind == "joint":
                return self.run.joint_frame(self.run.get_joints(e))
            return self.run.get_pose(e)
        if t is ast.Binary:
            return self.compose(((e.op, e.right),), self.pose(e.left))
        if t is ast.Chain:
            return self.compose(e.rest, self.pose(e.first))
        if t is ast.Unary:
            if e.op == "-":
                return self.pose(e.operand).inverse()
            if e.op == "+":
                return self.pose(e.operand)
            raise self.error("NOT does not apply to poses")
        if t is ast.Shift:
            base = self.pose(e.base)
            delta = np.array([0.0 if d is None else self.real(d) for d in e.delta])
            return Pose(base.rotation, base.translation_mm + delta)
        if t is ast.Call:
            return pose_call(self, e)
        if t is ast.JointLiteral:
            return self.run.joint_frame(self.joints(e))
        raise self.error(f"expected a pose, found {self.describe(e)}")

    def compose(self, rest: tuple[tuple[str, ast.Expr], ...], frame: Pose) -> Pose:
        for op, x in rest:
            if op != "+":
                raise self.error("poses combine with '+' (and '-p' inverts p); 'a - b' is not a pose" if op == "-"
                                 else f"'{op}' does not apply to poses")
            frame = frame @ self.pose(x)
        return frame

    # --- joints --------------------------------------------------------------------------
    def joint_value(self, e: ast.Expr) -> Union[tuple[float, ...], PoseJoints]:
        """A joint value: its angles (deg), or the pose a POINT #j = p gave it."""
        if isinstance(e, ast.Name) and e.kind == "joint" and not e.whole:
            return self.run.get_joints(e)
        if isinstance(e, ast.Call) and e.name in _WHERE:
            return self.run.here_value()
        return self.joints(e)

    def joints(self, e: ast.Expr) -> tuple[float, ...]:
        """The angles (deg) of a joint value."""
        value = self.run.get_joints(e) if isinstance(e, ast.Name) and e.kind == "joint" and not e.whole else \
            self.run.here_value() if isinstance(e, ast.Call) and e.name in _WHERE else None
        if isinstance(value, PoseJoints):
            raise NotSimulated(f"the joint angles of {e.name} (taken from a pose) need the arm's inverse kinematics")
        if value is not None:
            return value
        if isinstance(e, ast.JointLiteral):
            if any(v is None for v in e.values):
                current = self.run.here_joints()
                return tuple(current[i] if v is None else self.real(v) for i, v in enumerate(e.values))
            return tuple(self.real(v) for v in e.values)
        if isinstance(e, ast.Call) and e.name.startswith("#"):
            return joint_call(self, e)
        if self.kind(e) == "pose":
            raise NotSimulated("a joint value from a pose needs the arm's inverse kinematics (POINT #j = pose keeps "
                               "the pose; JMOVE #j moves to it)")
        raise self.error(f"expected a joint value, found {self.describe(e)}")

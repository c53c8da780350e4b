"""Expression evaluation in the context a statement gives: a real, a string, a pose (a
transformation relative to the current BASE) or a joint value (degrees).

Reals follow AS: TRUE and ON are -1, FALSE and OFF 0; comparisons and AND/OR/XOR/NOT give
-1 or 0; BAND/BOR/BXOR work on the integer parts; trigonometry is in degrees; INT truncates
towards zero. Division by zero, a square root of a negative number and overflow stop the run
(exit 3); an undefined variable or a value of the wrong kind is a program defect (exit 2).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Optional

import numpy as np

from coatsim.core.errors import ExecutionError, InputError
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.evaluate_strings import encode, string_call, val
from coatsim.languages.kawasaki_as.values import (
    IDENTITY,
    Frame,
    frame_from_points,
    rotation_about,
)

if TYPE_CHECKING:  # pragma: no cover
    from coatsim.languages.kawasaki_as.interpreter import Interpreter

TRUE, FALSE = -1.0, 0.0
POSE_FUNCTIONS = {"TRANS", "RX", "RY", "RZ", "FRAME", "NULL", "HERE", "DEST", "INVERSE"}
_COMPARE = {"==": lambda a, b: a == b, "<>": lambda a, b: a != b, "<": lambda a, b: a < b,
            ">": lambda a, b: a > b, "<=": lambda a, b: a <= b, ">=": lambda a, b: a >= b}
_UNKNOWN_FUNCTIONS = {"TIMER", "UTIMER", "TASK", "PCSTATUS", "SYSDATA", "INRANGE", "TIME_MS", "ERROR"}


def _truth(x: float) -> float:
    return TRUE if x else FALSE


def _int(x: float) -> int:
    return int(math.trunc(x))


class Evaluator:
    """Evaluates expressions against the variables, signals and pose of an interpreter."""

    def __init__(self, run: "Interpreter") -> None:
        self.run = run

    def error(self, message: str) -> InputError:
        return self.run.error(message)

    def failure(self, message: str) -> ExecutionError:
        return self.run.failure(message)

    # --- kinds ---------------------------------------------------------------------------
    def kind(self, e: ast.Expr) -> str:
        """'real', 'string', 'pose' or 'joint' (a name's kind from its prefix or its value)."""
        if isinstance(e, ast.Str):
            return "string"
        if isinstance(e, ast.Name):
            if e.kind != "value":
                return e.kind
            return "pose" if self.run.has_pose(e) and not self.run.has_real(e) else "real"
        if isinstance(e, ast.Ref):
            return self.kind(e.target)
        if isinstance(e, ast.Unary):
            return "real" if e.op == "NOT" else self.kind(e.operand)
        if isinstance(e, ast.Binary):
            return self.kind(e.left) if e.op in ("+", "-") else "real"
        if isinstance(e, ast.Call):
            if e.name.startswith("$"):
                return "string"
            if e.name.startswith("#"):
                return "joint"
            return "pose" if e.name in POSE_FUNCTIONS else "real"
        if isinstance(e, ast.Shift):
            return "pose"
        if isinstance(e, ast.JointLiteral):
            return "joint"
        return "real"

    # --- reals ---------------------------------------------------------------------------
    def real(self, e: ast.Expr) -> float:
        t = type(e)
        if t is ast.Num:
            return e.value
        if t is ast.Name:
            return self.run.get_real(e)
        if t is ast.Binary:
            return self.binary(e)
        if t is ast.Unary:
            if e.op == "NOT":
                return _truth(self.real(e.operand) == 0.0)
            value = self.real(e.operand)
            return -value if e.op == "-" else value
        if t is ast.Call:
            return self.real_call(e)
        raise self.error(f"expected a number, found {self.describe(e)}")

    def describe(self, e: ast.Expr) -> str:
        if isinstance(e, ast.Format):
            return f"the format /{e.spec}"
        return {"string": "a string", "pose": "a pose", "joint": "a joint value"}.get(self.kind(e), "a number")

    def truth(self, e: ast.Expr) -> bool:
        return self.real(e) != 0.0

    def integer(self, e: ast.Expr, what: str) -> int:
        value = self.real(e)
        if value != math.floor(value):
            raise self.error(f"{what} must be a whole number, got {value:g}")
        return int(value)

    def binary(self, e: ast.Binary) -> float:
        op = e.op
        if op in _COMPARE:
            if "string" in (self.kind(e.left), self.kind(e.right)):
                return _truth(_COMPARE[op](self.string(e.left), self.string(e.right)))
            return _truth(_COMPARE[op](self.real(e.left), self.real(e.right)))
        if op == "AND":
            return _truth(self.truth(e.left) and self.truth(e.right))
        if op == "OR":
            return _truth(self.truth(e.left) or self.truth(e.right))
        a, b = self.real(e.left), self.real(e.right)
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

    def real_call(self, e: ast.Call) -> float:
        name, args = e.name, e.args
        if name in ("ABS", "SQRT", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "INT", "ROUND", "SIGN"):
            x = self.real(self.arg(e, 0))
            self.arity(e, 1)
            return self.math1(name, x)
        if name == "ATAN2":
            self.arity(e, 2)
            return math.degrees(math.atan2(self.real(self.arg(e, 0)), self.real(self.arg(e, 1))))
        if name in ("MAXVAL", "MINVAL"):
            values = [self.real(self.arg(e, i)) for i in range(len(args))]
            if not values:
                raise self.error(f"{name} needs at least one value")
            return max(values) if name == "MAXVAL" else min(values)
        if name == "LEN":
            self.arity(e, 1)
            return float(len(self.string(self.arg(e, 0))))
        if name == "ASC":
            text = self.string(self.arg(e, 0))
            i = self.integer(args[1], "ASC position") if len(args) > 1 and args[1] is not None else 1
            return float(ord(text[i - 1])) if 1 <= i <= len(text) else -1.0
        if name in ("VAL", "STRTOVAL"):
            return val(self.string(self.arg(e, 0)))
        if name == "INSTR":
            return self.instr(e)
        if name == "SIG":
            return self.run.sig([self.integer(self.arg(e, i), "a signal number") for i in range(len(args))])
        if name in ("BITS", "BITS32"):
            start, count = self.integer(self.arg(e, 0), "the first signal"), self.integer(self.arg(e, 1), "the count")
            return float(self.run.read_bits(start, count))
        if name == "DISTANCE":
            self.arity(e, 2)
            return float(np.linalg.norm(self.pose(self.arg(e, 0)).p - self.pose(self.arg(e, 1)).p))
        if name in ("DX", "DY", "DZ"):
            self.arity(e, 1)
            return float(self.pose(self.arg(e, 0)).p["XYZ".index(name[1])])
        if name == "DEXT":
            return self.dext(e)
        if name == "MSPEED":
            return 100.0
        if name == "RANDOM":
            return self.run.random()
        if name == "SWITCH":
            return _truth(self.run.switch_state(self.switch_name(e)))
        if name.startswith("EXIST"):
            return _truth(self.run.exists(name, self.string(self.arg(e, 0))))
        if name == "TASKNO":
            return 1.0
        if name in _UNKNOWN_FUNCTIONS:
            self.run.unknown(f"function:{name}", f"{name} is not simulated; it gives 0")
            return 0.0
        raise self.error(f"{name} gives {self.describe(e)}, expected a number")

    def math1(self, name: str, x: float) -> float:
        try:
            if name == "ABS":
                return abs(x)
            if name == "SQRT":
                return math.sqrt(x)
            if name in ("SIN", "COS", "TAN"):
                return getattr(math, name.lower())(math.radians(x))
            if name in ("ASIN", "ACOS", "ATAN"):
                return math.degrees(getattr(math, name.lower())(x))
            if name == "INT":
                return float(math.trunc(x))
            if name == "SIGN":
                return float((x > 0) - (x < 0))
            return float(math.floor(abs(x) + 0.5)) * (1.0 if x >= 0 else -1.0)  # ROUND: half away from zero
        except ValueError:
            raise self.failure(f"{name}({x:g}) has no real value") from None

    def switch_name(self, e: ast.Call) -> str:
        arg = self.arg(e, 0)
        if isinstance(arg, ast.Name) and not arg.index:
            return arg.name.upper()
        return self.string(arg).upper()

    def instr(self, e: ast.Call) -> float:
        if len(e.args) == 3:
            start = self.integer(self.arg(e, 0), "INSTR start")
            text, part = self.string(self.arg(e, 1)), self.string(self.arg(e, 2))
        else:
            self.arity(e, 2)
            start, text, part = 1, self.string(self.arg(e, 0)), self.string(self.arg(e, 1))
        return float(text.find(part, max(start, 1) - 1) + 1)

    def dext(self, e: ast.Call) -> float:
        self.arity(e, 2)
        n = self.integer(self.arg(e, 1), "the DEXT component")
        target = self.arg(e, 0)
        values = self.joints(target) if self.kind(target) == "joint" else self.pose(target).xyzoat()
        if not 1 <= n <= len(values):
            raise self.error(f"DEXT component {n} out of range 1..{len(values)}")
        return float(values[n - 1])

    def arg(self, e: ast.Call, i: int) -> ast.Expr:
        if i >= len(e.args) or e.args[i] is None:
            raise self.error(f"{e.name} needs argument {i + 1}")
        return e.args[i]

    def arity(self, e: ast.Call, n: int) -> None:
        if len(e.args) != n:
            raise self.error(f"{e.name} takes {n} argument{'s' if n > 1 else ''}, found {len(e.args)}")

    # --- strings -------------------------------------------------------------------------
    def string(self, e: ast.Expr) -> str:
        if isinstance(e, ast.Str):
            return e.value
        if isinstance(e, ast.Name) and e.kind == "string":
            return self.run.get_string(e)
        if isinstance(e, ast.Binary) and e.op == "+":
            return self.string(e.left) + self.string(e.right)
        if isinstance(e, ast.Call) and e.name.startswith("$"):
            return self.string_call(e)
        raise self.error(f"expected a string, found {self.describe(e)}")

    def string_call(self, e: ast.Call) -> str:
        return string_call(self, e)

    def encode(self, items: tuple[Optional[ast.Expr], ...]) -> str:
        """$ENCODE / TYPE text: values in the current format (/D, /Fw.d, /Ew.d, /Gw.d, /Xn)."""
        return encode(self, items)


    # --- poses ---------------------------------------------------------------------------
    def pose(self, e: ast.Expr) -> Frame:
        t = type(e)
        if t is ast.Name:
            if e.kind == "joint":
                return self.run.joint_frame(self.run.get_joints(e))
            return self.run.get_pose(e)
        if t is ast.Binary:
            if e.op == "+":
                return self.pose(e.left) * self.pose(e.right)
            if e.op == "-":
                raise self.error("poses combine with '+' (and '-p' inverts p); 'a - b' is not a pose")
            raise self.error(f"'{e.op}' does not apply to poses")
        if t is ast.Unary:
            if e.op == "-":
                return self.pose(e.operand).inverse()
            if e.op == "+":
                return self.pose(e.operand)
            raise self.error("NOT does not apply to poses")
        if t is ast.Shift:
            base = self.pose(e.base)
            delta = np.array([0.0 if d is None else self.real(d) for d in e.delta])
            return Frame(base.r, base.p + delta)
        if t is ast.Call:
            return self.pose_call(e)
        if t is ast.JointLiteral:
            return self.run.joint_frame(self.joints(e))
        raise self.error(f"expected a pose, found {self.describe(e)}")

    def pose_call(self, e: ast.Call) -> Frame:
        name = e.name
        if name == "TRANS":
            if len(e.args) > ast.MAX_AXES:
                raise self.error(f"TRANS takes x, y, z, o, a, t and external axes; found {len(e.args)} values")
            if any(a is not None for a in e.args[6:]):
                self.run.warn("trans-external-axes", "TRANS values beyond the 6th (external axes) are ignored")
            values = [0.0 if a is None else self.real(a) for a in e.args[:6]] + [0.0] * (6 - len(e.args[:6]))
            return Frame.from_xyzoat(*values)
        if name in ("RX", "RY", "RZ"):
            self.arity(e, 1)
            return rotation_about("XYZ".index(name[1]), self.real(self.arg(e, 0)))
        if name == "FRAME":
            self.arity(e, 4)
            p = [self.pose(self.arg(e, i)).p for i in range(4)]
            frame = frame_from_points(*p)
            if frame is None:
                raise self.failure("FRAME: the first three points do not span a plane")
            return frame
        if name == "NULL":
            return IDENTITY
        if name in ("HERE", "DEST"):
            return self.run.here()
        if name == "INVERSE":
            self.arity(e, 1)
            return self.pose(self.arg(e, 0)).inverse()
        if name in ("#HERE", "#DEST", "#PPOINT"):
            return self.run.joint_frame(self.joints(e))
        raise self.error(f"{name} gives {self.describe(e)}, expected a pose")

    # --- joints --------------------------------------------------------------------------
    def joints(self, e: ast.Expr) -> tuple[float, ...]:
        if isinstance(e, ast.Name) and e.kind == "joint":
            return self.run.get_joints(e)
        if isinstance(e, ast.JointLiteral):
            if any(v is None for v in e.values):
                current = self.run.here_joints()
                return tuple(current[i] if v is None else self.real(v) for i, v in enumerate(e.values))
            return tuple(self.real(v) for v in e.values)
        if isinstance(e, ast.Call) and e.name in ("#HERE", "#DEST"):
            return self.run.here_joints()
        if isinstance(e, ast.Call) and e.name == "#PPOINT":
            return tuple(0.0 if a is None else self.real(a) for a in e.args)
        if self.kind(e) == "pose":
            raise self.failure("a joint value from a pose needs the inverse kinematics of the arm, which the "
                               "interpreter does not solve; move to the pose with JMOVE instead")
        raise self.error(f"expected a joint value, found {self.describe(e)}")

"""The built-in functions of AS with a number, pose or joint value as result (the $-functions
are in :mod:`~coatsim.languages.kawasaki_as.evaluate_strings`).

Every function of the manual's function index parses. Those with a meaning for the twin are
evaluated; the others (timers, task and system state, currents and torques, encoder
temperatures) are noted once as not simulated and give 0, or no pose (what needs one is then
skipped). A call of a name outside the index is noted the same way.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat, xyzoat
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.evaluate_strings import val
from coatsim.languages.kawasaki_as.machine import Evaluation
from coatsim.languages.kawasaki_as.unknowns import NotSimulated
from coatsim.languages.kawasaki_as.values import (
    IDENTITY,
    average,
    frame_from_points,
    rotation_about,
)

_MATH1 = {"ABS", "SQRT", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "INT", "ROUND", "SIGN"}
# Functions of the index the twin does not compute: noted, 0 (or no pose).
NOT_SIMULATED = {
    "TIMER", "UTIMER", "TASK", "PCSTATUS", "SYSDATA", "INRANGE", "TIME_MS", "ERROR", "CURLIMM", "CURLIMP",
    "ENVCHKRATE", "GETENCTEMP", "IQARM", "SIG2", "STR_ID", "STR_ID2", "TRQNM", "PRIORITY", "MAXINDEX", "MININDEX",
    "CCENTER", "CSHIFT", "STRTOPOS", "TRADD", "TRSUB",
}
POSE_FUNCTIONS = {"TRANS", "RX", "RY", "RZ", "FRAME", "NULL", "HERE", "DEST", "INVERSE", "AVE_TRANS", "CCENTER",
                  "CSHIFT", "STRTOPOS", "TRADD", "TRSUB"}
_EXIST = {"EXISTREAL", "EXISTTRANS", "EXISTJOINT", "EXISTCHAR", "EXISTPGM", "EXISTDATA", "EXISTINTEGER",
          "EXISTLOCALCHAR", "EXISTLOCALINTEGER", "EXISTLOCALJOINT", "EXISTLOCALREAL", "EXISTLOCALTRANS"}
REAL_FUNCTIONS = _MATH1 | _EXIST | {
    "ATAN2", "MAXVAL", "MINVAL", "LEN", "ASC", "VAL", "STRTOVAL", "INSTR", "SIG", "BITS", "BITS32", "DISTANCE", "DX",
    "DY", "DZ", "DEXT", "MSPEED", "MSPEED2", "RANDOM", "SWITCH", "TASKNO", "WHICHTASK", "BCD", "DCB"}
JOINT_FUNCTIONS = {"#HERE", "#DEST", "#PPOINT", "#HOME"}


def not_simulated(ev: Evaluation, e: ast.Call, gives: str) -> None:
    """Note (once per function) that the run does not compute ``e``."""
    known = e.name in NOT_SIMULATED or e.name.lstrip("$") in NOT_SIMULATED
    what = "is not simulated" if known else \
        "is not a function of the AS index coatsim knows (an array takes [ ], not ( ))"
    ev.run.not_simulated(f"function:{e.name}", f"{e.name} {what}; it gives {gives}")


def real_call(ev: Evaluation, e: ast.Call) -> float:
    """The number a function gives."""
    name, args = e.name, e.args
    if name in _MATH1:
        x = ev.real(ev.arg(e, 0))
        ev.arity(e, 1)
        return _math1(ev, name, x)
    if name == "ATAN2":
        ev.arity(e, 2)
        return math.degrees(math.atan2(ev.real(ev.arg(e, 0)), ev.real(ev.arg(e, 1))))
    if name in ("MAXVAL", "MINVAL"):
        values = [ev.real(ev.arg(e, i)) for i in range(len(args))]
        if not values:
            raise ev.error(f"{name} needs at least one value")
        return max(values) if name == "MAXVAL" else min(values)
    if name == "LEN":
        ev.arity(e, 1)
        return float(len(ev.string(ev.arg(e, 0))))
    if name == "ASC":
        text = ev.string(ev.arg(e, 0))
        i = ev.integer(args[1], "ASC position") if len(args) > 1 and args[1] is not None else 1
        return float(ord(text[i - 1])) if 1 <= i <= len(text) else -1.0
    if name in ("VAL", "STRTOVAL"):
        return val(ev.string(ev.arg(e, 0)))
    if name == "INSTR":
        return _instr(ev, e)
    if name == "SIG":
        return ev.run.sig([ev.integer(ev.arg(e, i), "a signal number") for i in range(len(args))])
    if name in ("BITS", "BITS32"):
        start, count = ev.integer(ev.arg(e, 0), "the first signal"), ev.integer(ev.arg(e, 1), "the count")
        return float(ev.run.read_bits(start, count))
    if name in ("BCD", "DCB"):
        ev.arity(e, 1)
        return _bcd(ev, name, ev.integer(ev.arg(e, 0), f"the {name} value"))
    if name == "DISTANCE":
        ev.arity(e, 2)
        return float(np.linalg.norm(ev.pose(ev.arg(e, 0)).translation_mm - ev.pose(ev.arg(e, 1)).translation_mm))
    if name in ("DX", "DY", "DZ"):
        ev.arity(e, 1)
        return float(ev.pose(ev.arg(e, 0)).translation_mm["XYZ".index(name[1])])
    if name == "DEXT":
        return _dext(ev, e)
    if name in ("MSPEED", "MSPEED2"):
        return 100.0  # the monitor speed the twin runs at
    if name == "RANDOM":
        return ev.run.random()
    if name == "SWITCH":
        return -1.0 if ev.run.switch_state(_switch_name(ev, e)) else 0.0
    if name in _EXIST:
        return -1.0 if ev.run.exists(name, ev.string(ev.arg(e, 0))) else 0.0
    if name in ("TASKNO", "WHICHTASK"):
        return 1.0  # the robot program's task
    if name in POSE_FUNCTIONS or name.startswith("$") or name.startswith("#"):
        raise ev.error(f"{name} gives {ev.describe(e)}, expected a number")
    not_simulated(ev, e, "0")
    return 0.0


def _math1(ev: Evaluation, name: str, x: float) -> float:
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
        raise ev.failure(f"{name}({x:g}) has no real value") from None


def _bcd(ev: Evaluation, name: str, n: int) -> float:
    """BCD: a whole number 0..99 999 999 as binary-coded decimal (a digit per 4 bits, for
    BITS outputs); DCB: such a code back to its number."""
    if name == "BCD":
        if not 0 <= n <= 99_999_999:
            raise ev.failure(f"BCD({n}): takes a whole number from 0 to 99999999")
        return float(int(str(n), 16))
    digits = format(n, "x") if n >= 0 else "-"
    if not digits.isdigit():
        raise ev.failure(f"DCB({n}): {n} is not a binary-coded decimal (a digit per 4 bits, each 0..9)")
    return float(int(digits))


def _switch_name(ev: Evaluation, e: ast.Call) -> str:
    arg = ev.arg(e, 0)
    if isinstance(arg, ast.Name) and not arg.index:
        return arg.name.upper()
    return ev.string(arg).upper()


def _instr(ev: Evaluation, e: ast.Call) -> float:
    if len(e.args) == 3:
        start = ev.integer(ev.arg(e, 0), "INSTR start")
        text, part = ev.string(ev.arg(e, 1)), ev.string(ev.arg(e, 2))
    else:
        ev.arity(e, 2)
        start, text, part = 1, ev.string(ev.arg(e, 0)), ev.string(ev.arg(e, 1))
    return float(text.find(part, max(start, 1) - 1) + 1)


def _dext(ev: Evaluation, e: ast.Call) -> float:
    ev.arity(e, 2)
    n = ev.integer(ev.arg(e, 1), "the DEXT component")
    target = ev.arg(e, 0)
    values = ev.joints(target) if ev.kind(target) == "joint" else xyzoat(ev.pose(target))
    if not 1 <= n <= len(values):
        raise ev.error(f"DEXT component {n} out of range 1..{len(values)}")
    return float(values[n - 1])


def pose_call(ev: Evaluation, e: ast.Call) -> Pose:
    """The transformation a function gives."""
    name = e.name
    if name == "TRANS":
        if len(e.args) > ast.MAX_AXES:
            raise ev.error(f"TRANS takes x, y, z, o, a, t and external axes; found {len(e.args)} values")
        if any(a is not None for a in e.args[6:]):
            ev.run.warn("trans-external-axes", "TRANS values beyond the 6th (external axes) are ignored")
        values = [0.0 if a is None else ev.real(a) for a in e.args[:6]] + [0.0] * (6 - len(e.args[:6]))
        return pose_from_xyzoat(values)
    if name in ("RX", "RY", "RZ"):
        ev.arity(e, 1)
        return rotation_about("XYZ".index(name[1]), ev.real(ev.arg(e, 0)))
    if name == "FRAME":
        ev.arity(e, 4)
        p = [ev.pose(ev.arg(e, i)).translation_mm for i in range(4)]
        frame = frame_from_points(*p)
        if frame is None:
            raise ev.failure("FRAME: the first three points do not span a plane")
        return frame
    if name == "NULL":
        return IDENTITY
    if name in ("HERE", "DEST"):
        return ev.run.here()
    if name == "INVERSE":
        ev.arity(e, 1)
        return ev.pose(ev.arg(e, 0)).inverse()
    if name == "AVE_TRANS":
        ev.arity(e, 2)
        return average(ev.pose(ev.arg(e, 0)), ev.pose(ev.arg(e, 1)))
    if name.startswith("#"):
        return ev.run.joint_frame(ev.joint_value(e))
    if name in REAL_FUNCTIONS or name.startswith("$"):
        raise ev.error(f"{name} gives {ev.describe(e)}, expected a pose")
    not_simulated(ev, e, "no pose")
    raise NotSimulated(f"{name}(...) is not simulated, so its pose is unknown")


def joint_call(ev: Evaluation, e: ast.Call) -> tuple[float, ...]:
    """The joint value (deg) a #-function gives."""
    name = e.name
    if name in ("#HERE", "#DEST"):
        return ev.run.here_joints()
    if name == "#PPOINT":
        return tuple(0.0 if a is None else ev.real(a) for a in e.args)
    if name == "#HOME":
        number = ev.integer(e.args[0], "the HOME number") if e.args and e.args[0] is not None else 1
        return tuple(float(v) for v in np.degrees(ev.run.home_joints(number)))
    not_simulated(ev, e, "no joint value")
    raise NotSimulated(f"{name}(...) is not simulated, so its joint value is unknown")

"""The variables a running program reads and writes: globals and the locals of each CALL, by
kind; what no file gives (an *unknown*, see :mod:`~coatsim.languages.kawasaki_as.unknowns`) and
a condition that depends on one (taken with its default, reported); and values given from
outside the files (``NAME=VALUE``).

A part of the interpreter (``Interpreter`` derives from it), which provides ``stack``,
``globals``, ``eval``, ``controller``, ``base``, ``programs``, ``unknowns``, ``placing`` and its
``where``/``error``/``warn``.
"""

from __future__ import annotations

import math
import re
from typing import Mapping, Union

from coatsim.geometry.space.pose import Pose
from coatsim.core.errors import CoatsimError, InputError
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.expressions import Cursor
from coatsim.languages.kawasaki_as.lexer import tokenize
from coatsim.languages.kawasaki_as.parser import key as norm
from coatsim.languages.kawasaki_as.scope import KINDS, Scope
from coatsim.languages.kawasaki_as.unknowns import ABSENT, Absent

_DEFAULTS = {"real": 0.0, "string": ""}
_VARIABLE = re.compile(r"[$#]?[A-Za-z_][A-Za-z0-9_.]*(\[\s*\d+\s*(,\s*\d+\s*)*\])?\Z")


class Memory:
    """Variable access of a running program."""

    def scope_of(self, name: ast.Name) -> Scope:
        return self.stack[-1].scope if name.is_local else self.globals

    def key(self, name: ast.Name) -> str:
        if not name.index:
            return norm(name.name)
        parts = []
        for e in name.index:
            value = self.eval.real(e)
            if value != math.floor(value) or value < 0:
                raise self.error(f"array index of {name.name} must be a whole number >= 0, got {value:g}")
            parts.append(str(int(value)))
        return f"{norm(name.name)}[{','.join(parts)}]"

    def value(self, kind: str, name: ast.Name):
        """The value of ``name`` as a ``kind``; an unknown's default (or Absent) if none is given."""
        k = self.key(name)
        scope = self.scope_of(name)
        found = scope.get(kind, k)
        if found is ABSENT:
            self.unknowns.reads += 1
            raise Absent(f"{self.shown(name, k)} has no value (its assignment was skipped)")
        if found is not None:
            return found
        if kind == "pose" and k in ("tool", "base"):  # the functions TOOL and BASE: the frames in force
            frame = self.controller.tool_frame() if k == "tool" else self.base
            if frame is not None:
                return frame
        other = [o for o in ("real", "pose") if o != kind and kind in ("real", "pose") and scope.has(o, k)]
        if other:
            raise self.error(f"'{self.shown(name, k)}' is a {other[0]} variable, not a {kind}")
        return self.unknown(kind, name, k)

    def unknown(self, kind: str, name: ast.Name, k: str):
        """Note the read of a variable no file gives; its default (0, "") or Absent."""
        base = norm(name.name)
        if self.unknowns.read(base, kind, self.where(), self.shown(name, k)):
            self.warnings.add(f"unknown:{base}", self.unknowns.first[base].note())
        if kind in _DEFAULTS:
            if self.placing:
                raise Absent(f"{self.shown(name, k)} has no value, and a motion goes to no place the files do not give")
            return _DEFAULTS[kind]
        raise Absent(f"{'pose' if kind == 'pose' else 'joint value'} {self.shown(name, k)} has no value")

    def guarded(self, evaluate, e: ast.Expr, default):
        """``evaluate(e)``; what depends on an unknown is reported, and taken as ``default``
        where it cannot be computed."""
        before = self.unknowns.reads
        try:
            value = evaluate(e)
        except Absent as exc:
            value, why = default, exc.reason
        except CoatsimError as exc:
            if self.unknowns.reads == before:
                raise
            value, why = default, str(exc).split(": ", 1)[-1]
        else:
            if self.unknowns.reads == before:
                return value
            why = f"it reads {self.unknowns.last}, which has no value here"
        shown = ("true" if value else "false") if isinstance(value, bool) else f"{value!r}"
        self.warn(f"default:{self.where()}", f"this condition depends on what the run does not know ({why}); "
                  f"it is taken with the default: {shown}")
        return value

    @staticmethod
    def shown(name: ast.Name, k: str) -> str:
        return name.name + (k[k.index("["):] if "[" in k else "")

    def get_real(self, name: ast.Name) -> float:
        if name.kind != "value":
            raise self.error(f"expected a number, found the {'string' if name.kind == 'string' else 'joint value'} "
                             f"{name.name}")
        return self.value("real", name)

    def get_string(self, name: ast.Name) -> str:
        return self.value("string", name)

    def get_pose(self, name: ast.Name) -> Pose:
        return self.value("pose", name)

    def get_joints(self, name: ast.Name):
        return self.value("joint", name)

    def has_real(self, name: ast.Name) -> bool:
        return self.scope_of(name).has("real", self.key(name))

    def has_pose(self, name: ast.Name) -> bool:
        return self.scope_of(name).has("pose", self.key(name))

    def set(self, kind: str, name: ast.Name, value) -> None:
        scope, k = self.scope_of(name), self.key(name)
        before = scope.get(kind, k)
        if not (before is value or (isinstance(value, (float, str, tuple)) and type(before) is type(value)
                                    and before == value)):
            self.changes += 1  # (a loop that changes nothing repeats the same way: see Interpreter.jump)
        scope.set(kind, k, value)

    def set_string(self, name: ast.Name, value: str) -> None:
        self.set("string", name, value)

    def exists(self, function: str, text: str) -> bool:
        """EXIST...("name"): whether a variable (of the kind the function names, local for
        EXISTLOCAL...) or a program has a value."""
        if function == "EXISTPGM":
            return text.lower() in self.programs
        kinds = {"REAL": ("real",), "INTEGER": ("real",), "TRANS": ("pose",), "JOINT": ("joint",),
                 "CHAR": ("string",), "DATA": KINDS}[function.removeprefix("EXIST").removeprefix("LOCAL")]
        local = "LOCAL" in function or text.startswith(".")
        scope = self.stack[-1].scope if local and self.stack else self.globals
        k = norm("." + text.lstrip(".") if local else text)
        return bool(text) and any(scope.has(kind, k) and scope.get(kind, k) is not ABSENT for kind in kinds)

    # --- values given from outside --------------------------------------------------------
    def give(self, variables: Mapping[str, Union[str, float]]) -> None:
        """Set global variables to values given outside the files: a number, a string's text
        (for ``$name``), or an AS expression (``TRANS(600,0,300,0,180,0)``, ``#[0,0,90,0,90,0]``)."""
        for raw, given in variables.items():
            name = str(raw).strip()
            if not _VARIABLE.match(name):
                raise InputError(f"variable {name}: not an AS variable name (a global such as direction, $mode, "
                                 "#park or cnt[2])")
            target = Cursor(tokenize(name, f"variable {name}", 1), f"variable {name}", 1, len(name))
            target_name = target.variable(target.take())
            try:
                kind, value = self.given_value(target_name, given)
            except (CoatsimError, Absent) as exc:
                raise InputError(f"variable {name}={given}: {exc}") from None
            self.set(kind, target_name, value)

    def given_value(self, name: ast.Name, given: Union[str, float]) -> tuple[str, object]:
        if isinstance(given, (int, float)) and not isinstance(given, bool):
            if name.kind != "value":
                raise InputError(f"{name.name} takes a {'string' if name.kind == 'string' else 'joint value'}, "
                                 "not a number")
            return "real", float(given)
        text = str(given).strip()
        if name.kind == "string":
            return "string", text[1:-1] if len(text) >= 2 and text[0] == text[-1] == '"' else text
        c = Cursor(tokenize(text, "value", 1), "value", 1, len(text), text)
        e = c.expr("a value")
        c.end("value")
        if name.kind == "joint":
            return "joint", self.eval.joint_value(e)
        kind = self.eval.kind(e)
        if kind not in ("real", "pose"):
            raise InputError(f"expected a number or a pose for {name.name}, found {self.eval.describe(e)}")
        return kind, self.eval.real(e) if kind == "real" else self.eval.pose(e)

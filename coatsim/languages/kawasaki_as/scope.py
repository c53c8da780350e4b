"""Variables of the interpreter: the global tables of the loaded files and the local
variables of each program invocation, by kind (reals, strings, poses, joint values)."""

from __future__ import annotations

from typing import Iterable

from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.languages.kawasaki_as import ast

KINDS = ("real", "string", "pose", "joint")


class Scope:
    """One table per kind; poses from ``.TRANS`` are converted on first use."""

    def __init__(self) -> None:
        self.tables: dict[str, dict] = {k: {} for k in KINDS}
        self.trans: dict[str, ast.TransDef] = {}
        self.origin: dict[tuple[str, str], str] = {}  # (kind, key) -> "file:line" of a data definition

    def get(self, kind: str, key: str):
        table = self.tables[kind]
        if key in table:
            return table[key]
        if kind == "pose" and key in self.trans:
            values = self.trans[key].values
            frame = pose_from_xyzoat(values)
            table[key] = frame
            return frame
        return None

    def has(self, kind: str, key: str) -> bool:
        return key in self.tables[kind] or (kind == "pose" and key in self.trans)

    def array(self, name: str) -> list[tuple[str, str, object]]:
        """(kind, index "[i,j]", value) of every element of the array ``name`` (a key)."""
        prefix = name + "["
        out = []
        for kind in KINDS:
            keys = list(self.tables[kind]) + ([k for k in self.trans if k not in self.tables[kind]]
                                              if kind == "pose" else [])
            out += [(kind, k[len(name):], self.get(kind, k)) for k in keys if k.startswith(prefix)]
        return out

    def set(self, kind: str, key: str, value) -> None:
        self.tables[kind][key] = value

    def load(self, files: Iterable[ast.AsFile], warn) -> None:
        """The data sections of ``files``; a later definition wins, with a warning."""
        from coatsim.languages.kawasaki_as.parser import key as norm

        for f in files:
            entries = [("pose", d, d) for d in f.trans.values()] + [("joint", d, tuple(d.values)) for d in f.joints.values()] \
                + [("real", d, d.value) for d in f.reals.values()] + [("string", d, d.value) for d in f.strings.values()]
            for kind, d, value in entries:
                k = norm(d.name)
                where = f"{f.source}:{d.line}"
                before = self.origin.get((kind, k))
                if before is not None:
                    warn(f"redefined:{kind}:{k}", f"{where}: {d.name} is also defined at {before}; the later "
                         "definition is used")
                    self.tables[kind].pop(k, None)
                self.origin[(kind, k)] = where
                if kind == "pose":
                    self.trans[k] = value
                else:
                    self.tables[kind][k] = value

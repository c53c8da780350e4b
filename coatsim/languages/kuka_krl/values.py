"""KRL values: numbers, booleans, enums (``#BASE``), strings and structures (``FRAME``, ``POS``,
``E6POS``, ``AXIS``, ``E6AXIS``, and any other as named components); frames as Poses.

A-B-C are degrees about z, then the new y, then the new x: R = Rz(A)·Ry(B)·Rx(C) (KUKA
System Software 8, "Coordinate systems"; Roboception's KUKA XYZ-ABC pose format).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import abc_to_matrix, matrix_to_abc

FRAME_FIELDS = ("X", "Y", "Z", "A", "B", "C")
AXES = tuple(f"E{k}" for k in range(1, 7))
TYPES = {"FRAME": FRAME_FIELDS, "POS": FRAME_FIELDS + ("S", "T"), "E6POS": FRAME_FIELDS + ("S", "T") + AXES,
         "AXIS": tuple(f"A{k}" for k in range(1, 7)), "E6AXIS": tuple(f"A{k}" for k in range(1, 7)) + AXES}
BASIC = {"INT": 0.0, "REAL": 0.0, "BOOL": False, "CHAR": ""}


@dataclass
class Struct:
    """A structure value: its type (empty when not known) and the components given."""

    type: str
    fields: dict[str, Any] = field(default_factory=dict)

    def copy(self) -> "Struct":
        return Struct(self.type, {k: v.copy() if isinstance(v, Struct) else v for k, v in self.fields.items()})


def default(type_: str) -> Any:
    type_ = type_.upper()
    if type_ in BASIC:
        return BASIC[type_]
    if type_ in ("FRAME", "POS", "E6POS"):
        return Struct(type_, {k: 0.0 for k in FRAME_FIELDS})
    return Struct(type_)


def declared(type_: str) -> Any:
    """The value of a declaration without one: a position or axis set has no component until one is
    assigned (the controller holds them invalid); other types their default."""
    return Struct(type_.upper()) if type_.upper() in TYPES else default(type_)


def pose_of(value: Struct) -> Pose:
    """The Pose of a frame-like structure (missing components 0)."""
    f = value.fields
    get = lambda k: float(f.get(k, 0.0))  # noqa: E731
    return Pose(abc_to_matrix(get("A"), get("B"), get("C")), np.array([get("X"), get("Y"), get("Z")]))


def frame_of(pose: Pose, type_: str = "FRAME", like: Struct | None = None) -> Struct:
    """A structure of ``type_`` at ``pose`` (other components of ``like`` kept)."""
    a, b, c = matrix_to_abc(pose.rotation)
    out = like.copy() if like is not None else Struct(type_)
    out.type = like.type if like is not None and like.type else type_
    x, y, z = (float(v) for v in pose.translation_mm)
    out.fields.update({"X": x, "Y": y, "Z": z, "A": a, "B": b, "C": c})
    return out


def compose(a: Struct, b: Struct) -> Struct:
    """``a : b``: ``b`` given in the frame ``a`` (the geometric operator), of ``b``'s type."""
    return frame_of(pose_of(a) @ pose_of(b), b.type or "FRAME", b)

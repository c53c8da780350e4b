"""RAPID data: the record types a motion program uses, aggregates made typed values, the
predefined data (``v500``, ``z10``, ``fine``, ``tool0``, ``wobj0``, ``load0``), and poses.

Values are floats (``num``, ``dnum``), bools, strings, lists (arrays) and :class:`Record`.
Predefined speeds and zones follow the tables of ABB's RAPID Instructions, Functions and Data
types manual (``speeddata``, ``zonedata``): ``vN`` = [N, 500, 5000, 1000]; ``zN`` = [FALSE, N,
1.5 N, 1.5 N, 0.15 N, 1.5 N, 0.15 N] (``z0`` = 0.3 mm, ``z1`` = 1 mm and 0.1 deg);
``fine`` a stop point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import matrix_to_quaternion, quaternion_to_matrix

NUM = ("num", "dnum", "byte", "intnum")
_SIX = tuple(f"eax_{c}" for c in "abcdef")
RECORDS: dict[str, tuple[tuple[str, str], ...]] = {
    "pos": (("x", "num"), ("y", "num"), ("z", "num")),
    "orient": (("q1", "num"), ("q2", "num"), ("q3", "num"), ("q4", "num")),
    "pose": (("trans", "pos"), ("rot", "orient")),
    "confdata": (("cf1", "num"), ("cf4", "num"), ("cf6", "num"), ("cfx", "num")),
    "extjoint": tuple((f, "num") for f in _SIX),
    "robjoint": tuple((f"rax_{k}", "num") for k in range(1, 7)),
    "robtarget": (("trans", "pos"), ("rot", "orient"), ("robconf", "confdata"), ("extax", "extjoint")),
    "jointtarget": (("robax", "robjoint"), ("extax", "extjoint")),
    "loaddata": (("mass", "num"), ("cog", "pos"), ("aom", "orient"), ("ix", "num"), ("iy", "num"), ("iz", "num")),
    "tooldata": (("robhold", "bool"), ("tframe", "pose"), ("tload", "loaddata")),
    "wobjdata": (("robhold", "bool"), ("ufprog", "bool"), ("ufmec", "string"), ("uframe", "pose"),
                 ("oframe", "pose")),
    "speeddata": (("v_tcp", "num"), ("v_ori", "num"), ("v_leax", "num"), ("v_reax", "num")),
    "zonedata": (("finep", "bool"), ("pzone_tcp", "num"), ("pzone_ori", "num"), ("pzone_eax", "num"),
                 ("zone_ori", "num"), ("zone_leax", "num"), ("zone_reax", "num")),
}
SIGNALS = ("signaldo", "signaldi", "signalgo", "signalgi", "signalao", "signalai")
UNSET_AXIS = 9e9  # an external axis not in use


@dataclass
class Record:
    """A value of a record type: its ``type`` and its fields in order."""

    type: str
    fields: dict[str, Any]

    def copy(self) -> "Record":
        return Record(self.type, {k: v.copy() if isinstance(v, (Record, list)) else v for k, v in self.fields.items()})


def default(type_: str) -> Any:
    """The value a declaration without an initial value holds (zeros, FALSE, "")."""
    if type_ in RECORDS:
        return Record(type_, {f: default(t) for f, t in RECORDS[type_]})
    if type_ == "bool":
        return False
    if type_ == "string" or type_ in SIGNALS:
        return ""
    return 0.0


def coerce(type_: str, value: Any, where: Callable[[str], InputError]) -> Any:
    """``value`` as a ``type_`` value (an aggregate filled field by field); ``where`` makes the
    error naming the line."""
    if type_ in RECORDS:
        spec = RECORDS[type_]
        if isinstance(value, Record):
            if value.type != type_:
                raise where(f"a {value.type} where a {type_} is expected")
            return value.copy()
        if not isinstance(value, list) or len(value) != len(spec):
            raise where(f"a {type_} is an aggregate of {len(spec)} values [{', '.join(f for f, _ in spec)}], "
                        f"got {_shown(value)}")
        return Record(type_, {f: coerce(t, v, where) for (f, t), v in zip(spec, value)})
    if type_ in NUM:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise where(f"a number where {_shown(value)} is given")
        return float(value)
    if type_ == "bool":
        if not isinstance(value, bool):
            raise where(f"TRUE or FALSE where {_shown(value)} is given")
        return value
    if type_ == "string":
        if not isinstance(value, str):
            raise where(f"a string where {_shown(value)} is given")
        return value
    return value.copy() if isinstance(value, (Record, list)) else value  # a type coatsim does not model


def _shown(value: Any) -> str:
    if isinstance(value, Record):
        return f"a {value.type}"
    if isinstance(value, list):
        return f"an aggregate of {len(value)} values"
    if isinstance(value, bool):
        return "TRUE" if value else "FALSE"
    return repr(value)


def record(type_: str, *values: Any) -> Record:
    """A record of predefined data from plain values (nested lists for nested records)."""
    return coerce(type_, list(values), lambda m: InputError(m))


def _zone(n: float) -> Record:
    return record("zonedata", False, n, 1.5 * n, 1.5 * n, 0.15 * n, 1.5 * n, 0.15 * n)


_IDENTITY_POSE = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]]
PREDEFINED: dict[str, tuple[str, Any]] = {
    **{f"v{v}": ("speeddata", record("speeddata", float(v), 500.0, 5000.0, 1000.0))
       for v in (5, 10, 20, 30, 40, 50, 60, 80, 100, 150, 200, 300, 400, 500, 600, 800, 1000, 1500, 2000, 2500,
                 3000, 4000, 5000, 6000, 7000)},
    "vmax": ("speeddata", record("speeddata", 5000.0, 500.0, 5000.0, 1000.0)),
    **{f"z{z}": ("zonedata", _zone(float(z))) for z in (1, 5, 10, 15, 20, 30, 40, 50, 60, 80, 100, 150, 200)},
    "z0": ("zonedata", record("zonedata", False, 0.3, 0.3, 0.3, 0.03, 0.3, 0.03)),
    "fine": ("zonedata", record("zonedata", True, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)),
    "load0": ("loaddata", record("loaddata", 0.0, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], 0.0, 0.0, 0.0)),
    "tool0": ("tooldata", record("tooldata", True, _IDENTITY_POSE, [0.001, [0.0, 0.0, 0.001], [1.0, 0, 0, 0], 0, 0, 0])),
    "wobj0": ("wobjdata", record("wobjdata", False, True, "", _IDENTITY_POSE, _IDENTITY_POSE)),
    "pi": ("num", math.pi),
    "true": ("bool", True),
    "false": ("bool", False),
}


def pos_array(p: Record) -> np.ndarray:
    return np.array([p.fields["x"], p.fields["y"], p.fields["z"]], dtype=float)


def make_pos(xyz) -> Record:
    return Record("pos", {"x": float(xyz[0]), "y": float(xyz[1]), "z": float(xyz[2])})


def rotation_of(o: Record, where: Callable[[str], InputError]) -> np.ndarray:
    """The rotation of an ``orient`` (q1 the scalar part); InputError unless it is a unit
    quaternion within 1e-3 (the controller's own check is of this order), else normalised."""
    q = np.array([o.fields[k] for k in ("q1", "q2", "q3", "q4")], dtype=float)
    norm = float(np.linalg.norm(q))
    if not math.isfinite(norm) or abs(norm - 1.0) > 1e-3:
        raise where(f"orientation [{', '.join(f'{v:g}' for v in q)}] is not a unit quaternion (norm {norm:.6g})")
    return quaternion_to_matrix(*(q / norm))


def make_orient(rotation: np.ndarray) -> Record:
    q = matrix_to_quaternion(rotation)
    return Record("orient", {"q1": q[0], "q2": q[1], "q3": q[2], "q4": q[3]})


def pose_of(value: Record, where: Callable[[str], InputError]) -> Pose:
    """The Pose of a ``pose`` or ``robtarget`` (its ``trans`` and ``rot``)."""
    return Pose(rotation_of(value.fields["rot"], where), pos_array(value.fields["trans"]))


def with_pose(value: Record, pose: Pose) -> Record:
    """A copy of a ``pose`` or ``robtarget`` with ``trans`` and ``rot`` of ``pose``."""
    out = value.copy()
    out.fields["trans"] = make_pos(pose.translation_mm)
    out.fields["rot"] = make_orient(pose.rotation)
    return out


def make_robtarget(pose: Pose) -> Record:
    """A robtarget at ``pose`` (configuration 0, no external axes)."""
    return with_pose(record("robtarget", [0, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0], [UNSET_AXIS] * 6), pose)

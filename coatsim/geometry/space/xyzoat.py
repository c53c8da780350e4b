"""Poses as a person writes them: x, y, z (mm) and O-A-T (deg) — on the command line
(``--frame 700,0,200,0,0,0``), in scenarios and in Kawasaki AS programs."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import matrix_to_oat, oat_to_matrix


def pose_from_xyzoat(values: Sequence[float]) -> Pose:
    """The pose of x, y, z (mm), O, A, T (deg)."""
    x, y, z, o, a, t = (float(v) for v in values)
    return Pose(oat_to_matrix(o, a, t), np.array([x, y, z]))


def xyzoat(pose: Pose) -> tuple[float, float, float, float, float, float]:
    """x, y, z (mm) and O, A, T (deg) of a pose (T = 0 where only O ± T is defined)."""
    o, a, t = matrix_to_oat(pose.rotation)
    x, y, z = (float(v) for v in pose.translation_mm)
    return (x, y, z, o, a, t)


def parse_xyzoat(text: str, what: str) -> Pose:
    """Read "x,y,z,o,a,t"; InputError naming ``what`` (a parameter: callers reword it)."""
    parts = [p.strip() for p in text.split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) != 6 or not all(math.isfinite(v) for v in values):
        raise InputError(f"{what}: expected 6 comma-separated numbers x,y,z,o,a,t (mm, deg), got {text!r}",
                         parameters=(what,))
    return pose_from_xyzoat(values)


def format_xyzoat(pose: Pose) -> str:
    """"x,y,z,o,a,t" with the shortest exact-looking numbers (6 significant digits)."""
    return ",".join(f"{v:g}" for v in xyzoat(pose))

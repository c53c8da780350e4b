"""Poses as robot programs give them: x, y, z (mm) and O-A-T (deg), and the cell's defaults."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.path.oat import matrix_to_oat, oat_to_matrix


@dataclass(frozen=True)
class Frame:
    """A pose given as x, y, z (mm) and O-A-T (deg), as AS writes it."""

    x: float
    y: float
    z: float
    o: float
    a: float
    t: float

    @property
    def origin(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z], dtype=float)

    @property
    def rotation(self) -> np.ndarray:
        return oat_to_matrix(self.o, self.a, self.t)

    @classmethod
    def parse(cls, text: str, what: str = "--frame") -> Frame:
        """Read "x,y,z,o,a,t"; raises InputError naming ``what``."""
        parts = [p.strip() for p in text.split(",")]
        try:
            values = [float(p) for p in parts]
        except ValueError:
            values = []
        if len(values) != 6 or not all(math.isfinite(v) for v in values):
            raise InputError(f"{what}: expected 6 comma-separated numbers x,y,z,o,a,t (mm, deg), got {text!r}")
        return cls(*values)

    @classmethod
    def from_matrix(cls, position_mm: np.ndarray, rotation: np.ndarray) -> Frame:
        """The frame of a position (mm) and a rotation matrix."""
        return cls(*(float(v) for v in position_mm), *matrix_to_oat(rotation))

    def __str__(self) -> str:
        return ",".join(f"{v:g}" for v in (self.x, self.y, self.z, self.o, self.a, self.t))


DEFAULT_FRAME = Frame(*defaults.WORKPIECE_FRAME)
DEFAULT_TOOL = Frame(*defaults.GUN_TOOL)

"""Space curves: the 3-D input curve (x, y, z points) and reading a curve file of either kind."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.curves import ClosedMode, Curve, clean_points, make_curve, read_points_file


@dataclass(frozen=True, eq=False)
class SpaceCurve:
    """A dense polyline in space, mm, shape (n, 3), n >= 2, no consecutive duplicates.

    A closed curve repeats its first point as its last.
    """

    points: np.ndarray
    closed: bool
    name: str

    @property
    def length(self) -> float:
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())


def make_space_curve(points: np.ndarray, name: str, closed: ClosedMode = "auto") -> SpaceCurve:
    """Validate raw x,y,z points (the same checks and closure rule as a planar curve)."""
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise InputError(f"{name}: expected x,y,z points, got an array of shape {pts.shape}")
    return SpaceCurve(*clean_points(pts, name, closed), name)


def read_any_curve(path: str | Path, closed: ClosedMode = "auto") -> Curve | SpaceCurve:
    """A planar Curve for x,y columns, a SpaceCurve for x,y,z columns."""
    points = read_points_file(path)
    if points.shape[1] == 3:
        return make_space_curve(points, str(path), closed)
    return make_curve(points, str(path), closed)

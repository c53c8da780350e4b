"""Reading a ``coatsim.surfacepaths/1`` file: the passes a gun sprays over a 3-D part.

The contract (DESIGN.md): per pass the trace on the surface (``points``, mm, the part's own
frame), the outward unit ``normals`` there, whether the pass is ``closed``, and the lead-in and
lead-out points past the region's edge; the file's ``standoff_mm`` puts the tool centre point at
``point + standoff · normal`` and ``mesh.pose`` (x, y, z, O, A, T) the part in the cell. Every
defect is an InputError naming the file and the field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from coatsim.core.jsonfile import read_json
from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat

FORMAT = "coatsim.surfacepaths/1"
UNIT_TOL = 1e-3  # a normal this far from unit length is refused (it is normalised when closer)


@dataclass(frozen=True, eq=False)
class SurfacePass:
    """One pass: trace points (n, 3) mm and outward unit normals (n, 3) in the part's frame,
    ``closed`` (sprayed once around), lead-in (k, 3) and lead-out (m, 3) points in travel order."""

    points: np.ndarray
    normals: np.ndarray
    closed: bool
    lead_in: np.ndarray
    lead_out: np.ndarray

    def lead_lengths_mm(self) -> tuple[float, float]:
        """Length of the lead-in from its first point to the pass start, and of the lead-out from
        the pass end to its last point (0 without leads)."""
        def length(pts: np.ndarray) -> float:
            return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()) if len(pts) > 1 else 0.0

        lead_in = length(np.vstack((self.lead_in, self.points[:1]))) if len(self.lead_in) else 0.0
        lead_out = length(np.vstack((self.points[-1:], self.lead_out))) if len(self.lead_out) else 0.0
        return lead_in, lead_out


@dataclass(frozen=True, eq=False)
class SurfacePaths:
    """The passes of a file in spraying order, its stand-off (None: the file gives none), the
    part's pose in the cell (None: not given) and the mesh file named in it."""

    source: str
    passes: tuple[SurfacePass, ...]
    standoff_mm: float | None
    pose: Pose | None
    mesh_file: str | None


def is_surfacepaths(path: str | Path) -> bool:
    """Whether ``path`` is a JSON file whose ``format`` is surfacepaths (False when unreadable:
    the caller's own reading reports that)."""
    if not str(path).lower().endswith(".json"):
        return False
    try:
        doc = read_json(path, "surface paths file")
    except InputError:
        return False
    return isinstance(doc, dict) and doc.get("format") == FORMAT


def _array(value: Any, where: str, min_rows: int) -> np.ndarray:
    """A list of [x, y, z] as an (n, 3) float array."""
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        arr = np.zeros((0, 0))
    if arr.size == 0 and min_rows == 0 and isinstance(value, list):
        return np.zeros((0, 3))
    if arr.ndim != 2 or arr.shape[1] != 3 or len(arr) < min_rows:
        raise InputError(f"{where}: expected a list of at least {min_rows} [x, y, z] triples")
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        raise InputError(f"{where}[{int(np.argmax(bad))}]: not a finite [x, y, z]")
    return arr


def _pass(doc: Any, where: str) -> SurfacePass:
    if not isinstance(doc, dict):
        raise InputError(f"{where}: expected an object with points, normals, closed, lead_in, lead_out")
    points = _array(doc.get("points"), f"{where}.points", 2)
    normals = _array(doc.get("normals"), f"{where}.normals", 2)
    if normals.shape != points.shape:
        raise InputError(f"{where}.normals: {len(normals)} normals for {len(points)} points; give one per point")
    length = np.linalg.norm(normals, axis=1)
    bad = np.abs(length - 1.0) > UNIT_TOL
    if bad.any():
        k = int(np.argmax(bad))
        raise InputError(f"{where}.normals[{k}]: length {length[k]:.6g}, expected a unit vector")
    closed = doc.get("closed", False)
    if not isinstance(closed, bool):
        raise InputError(f"{where}.closed: expected true or false")
    lead_in = _array(doc.get("lead_in", []), f"{where}.lead_in", 0)
    lead_out = _array(doc.get("lead_out", []), f"{where}.lead_out", 0)
    return SurfacePass(points, normals / length[:, None], closed, lead_in, lead_out)


def read_surfacepaths(path: str | Path) -> SurfacePaths:
    """The passes of a surfacepaths file; InputError naming the file and field on any defect."""
    name = str(path)
    doc = read_json(path, "surface paths file")
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise InputError(f"{name}: format: expected {FORMAT!r} (a file written by coatsim plan)")
    if doc.get("units", "mm") != "mm":
        raise InputError(f"{name}: units: expected 'mm'")
    passes = doc.get("passes")
    if not isinstance(passes, list) or not passes:
        raise InputError(f"{name}: passes: expected a non-empty list of passes")
    standoff = doc.get("standoff_mm")
    if standoff is not None and not (isinstance(standoff, (int, float)) and math.isfinite(standoff) and standoff > 0):
        raise InputError(f"{name}: standoff_mm: expected a positive number of mm")
    mesh = doc.get("mesh") or {}
    if not isinstance(mesh, dict):
        raise InputError(f"{name}: mesh: expected an object (file, sha256, vertices, faces, pose)")
    pose = None
    if mesh.get("pose") is not None:
        values = mesh["pose"]
        if not (isinstance(values, list) and len(values) == 6
                and all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)):
            raise InputError(f"{name}: mesh.pose: expected [x, y, z, o, a, t] (mm, deg)")
        pose = pose_from_xyzoat(values)
    mesh_file = mesh.get("file")
    return SurfacePaths(name, tuple(_pass(p, f"{name}: passes[{k}]") for k, p in enumerate(passes)),
                        None if standoff is None else float(standoff), pose,
                        mesh_file if isinstance(mesh_file, str) else None)

"""Surface paths: the planned traces on a part, and the ``coatsim.surfacepaths/1`` file.

All lengths are millimetres in the part's own frame. ``points`` lie on the surface (the trace of
the spray axis), ``normals`` are the outward unit normals there (smoothed), the tool centre point
is ``point + standoff * normal``; passes are in spraying order. A lead-in runs straight from its
points to the pass's first point, a lead-out from the last point through its points; along them
the gun axis keeps the normal of the pass end. The file is written deterministically (the same
plan gives the same bytes); timings never go into it (``stats.seconds`` is null).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional

import numpy as np

from coatsim.core.jsonfile import read_json
from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text

FORMAT = "coatsim.surfacepaths/1"
PATTERNS = ("raster", "geodesic", "boundary")
#: decimals written: 1 nm for lengths, 1e-9 for unit normals
LENGTH_DECIMALS = 6
NORMAL_DECIMALS = 9


@dataclass(frozen=True, eq=False)
class Pass:
    """One pass: points (n, 3) on the surface, unit normals (n, 3), whether it is a closed loop,
    lead-in and lead-out points (k, 3) (empty for a loop)."""

    points: np.ndarray
    normals: np.ndarray
    closed: bool
    lead_in: np.ndarray
    lead_out: np.ndarray

    def tcp_mm(self, standoff_mm: float) -> np.ndarray:
        """Tool centre points (n, 3): each point moved ``standoff_mm`` along its normal."""
        return self.points + standoff_mm * self.normals

    @property
    def length_mm(self) -> float:
        pts = np.vstack([self.points, self.points[:1]]) if self.closed else self.points
        return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


@dataclass(frozen=True)
class MeshInfo:
    """The part mesh a plan belongs to: file, SHA-256, vertex and triangle counts (as read and
    repaired), the part's pose in the cell (x, y, z mm, O, A, T deg)."""

    file: str
    sha256: str
    vertices: int
    faces: int
    pose: tuple[float, float, float, float, float, float] = (0.0,) * 6


@dataclass(frozen=True)
class PlanStats:
    """Figures of a plan: pass count, region area (mm^2), coverage (share of the region within
    half a spacing of a pass), spacing along the surface (min, median, max mm; None without
    neighbouring passes), the normal smoothing length (mm), the largest angle between a
    smoothed normal and a face around it (deg; on a coarsely faceted mesh the faces around one
    vertex differ by as much) and the largest angle by which a pass normal leaves the cone of
    the face normals near its point in its feature region (deg; the independent check's figure,
    verify.py)."""

    passes: int
    region_area_mm2: float
    coverage: float
    spacing_min_mm: Optional[float]
    spacing_median_mm: Optional[float]
    spacing_max_mm: Optional[float]
    normal_smoothing_mm: float
    normal_max_angle_deg: float
    normal_off_faces_deg: float = 0.0


@dataclass(frozen=True, eq=False)
class SurfacePaths:
    """A plan: the mesh, the pattern, spacing, stand-off, expected ripple (%), passes, figures.
    ``notes`` (what planning noticed) and ``timings_s`` (CPU seconds per stage) are not part of
    the file."""

    mesh: MeshInfo
    pattern: str
    spacing_mm: float
    standoff_mm: float
    ripple_pct: float
    passes: tuple[Pass, ...]
    stats: PlanStats
    notes: tuple[str, ...] = ()
    timings_s: tuple[tuple[str, float], ...] = field(default=())

    def tcp_mm(self) -> list[np.ndarray]:
        """Tool centre points of every pass, at the plan's stand-off."""
        return [p.tcp_mm(self.standoff_mm) for p in self.passes]


def _round(array: np.ndarray, decimals: int) -> list:
    return (np.round(np.asarray(array, dtype=float), decimals) + 0.0).tolist()


def _number(value: Optional[float], decimals: int = LENGTH_DECIMALS) -> Optional[float]:
    return None if value is None else round(float(value), decimals) + 0.0


def to_document(paths: SurfacePaths) -> dict[str, Any]:
    """The JSON document of a plan (plain lists and numbers)."""
    m, s = paths.mesh, paths.stats
    return {
        "format": FORMAT, "units": "mm",
        "mesh": {"file": m.file, "sha256": m.sha256, "vertices": m.vertices, "faces": m.faces,
                 "pose": [_number(v) for v in m.pose]},
        "pattern": paths.pattern, "spacing_mm": _number(paths.spacing_mm), "standoff_mm": _number(paths.standoff_mm),
        "ripple_pct": _number(paths.ripple_pct, 4),
        "passes": [{"points": _round(p.points, LENGTH_DECIMALS), "normals": _round(p.normals, NORMAL_DECIMALS),
                    "closed": bool(p.closed), "lead_in": _round(p.lead_in, LENGTH_DECIMALS),
                    "lead_out": _round(p.lead_out, LENGTH_DECIMALS)} for p in paths.passes],
        "stats": {"passes": s.passes, "region_area_mm2": _number(s.region_area_mm2, 3),
                  "coverage": _number(s.coverage, 6),
                  "spacing_along_surface_mm": {"min": _number(s.spacing_min_mm), "median": _number(s.spacing_median_mm),
                                               "max": _number(s.spacing_max_mm)},
                  "normal_smoothing_mm": _number(s.normal_smoothing_mm),
                  "normal_max_angle_deg": _number(s.normal_max_angle_deg, 4),
                  "normal_off_faces_deg": _number(s.normal_off_faces_deg, 4),
                  "seconds": None},
    }


def dumps(paths: SurfacePaths) -> str:
    """The file's text: the header keys one per line, each pass on its own line."""
    doc = to_document(paths)
    passes = doc.pop("passes")
    stats = doc.pop("stats")
    lines = [f"  {json.dumps(k)}: {json.dumps(v, separators=(', ', ': '))}," for k, v in doc.items()]
    body = ",\n".join(f"    {json.dumps(p, separators=(',', ':'))}" for p in passes)
    lines.append(f'  "passes": [\n{body}\n  ],' if passes else '  "passes": [],')
    lines.append(f'  "stats": {json.dumps(stats, separators=(", ", ": "))}')
    return "{\n" + "\n".join(lines) + "\n}\n"


def write_surfacepaths(path: str | Path, paths: SurfacePaths) -> None:
    """Write the plan to ``path`` atomically."""
    write_text(path, dumps(paths))


def read_surfacepaths(path: str | Path) -> SurfacePaths:
    """Read a ``coatsim.surfacepaths/1`` file; an InputError naming the field at fault."""
    path = Path(path)
    return from_document(read_json(path, "surface paths file"), str(path))


def _field(doc: Any, key: str, where: str) -> Any:
    if not isinstance(doc, dict) or key not in doc:
        raise InputError(f"{where}: missing field {key!r}")
    return doc[key]


def _positive(doc: Any, key: str, where: str, allow_zero: bool = False) -> float:
    value = _field(doc, key, where)
    if not (_finite(value) and (value > 0 or (allow_zero and value == 0))):
        raise InputError(f"{where}.{key}: expected a {'non-negative' if allow_zero else 'positive'} number")
    return float(value)


def _points(value: Any, where: str, allow_empty: bool) -> np.ndarray:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = np.zeros((0, 0))
    if array.size == 0 and allow_empty and isinstance(value, list):
        return np.zeros((0, 3))
    if array.ndim != 2 or array.shape[1] != 3 or len(array) < (0 if allow_empty else 2) or not np.isfinite(array).all():
        need = "" if allow_empty else "at least two "
        raise InputError(f"{where}: expected a list of {need}[x, y, z] points with finite coordinates")
    return array


def _pass(doc: Any, where: str) -> Pass:
    points = _points(_field(doc, "points", where), f"{where}.points", False)
    normals = _points(_field(doc, "normals", where), f"{where}.normals", False)
    if normals.shape != points.shape or np.abs(np.linalg.norm(normals, axis=1) - 1).max() > 1e-6:
        raise InputError(f"{where}.normals: expected one unit vector per point")
    closed = _field(doc, "closed", where)
    if not isinstance(closed, bool):
        raise InputError(f"{where}.closed: expected true or false")
    lead_in = _points(_field(doc, "lead_in", where), f"{where}.lead_in", True)
    lead_out = _points(_field(doc, "lead_out", where), f"{where}.lead_out", True)
    return Pass(points, normals, closed, lead_in, lead_out)


def _optional(value: Any, where: str) -> Optional[float]:
    if value is not None and not _finite(value):
        raise InputError(f"{where}: expected a number or null")
    return None if value is None else float(value)


def from_document(doc: Any, where: str) -> SurfacePaths:
    """A plan from its JSON document (``where`` names it in errors)."""
    if _field(doc, "format", where) != FORMAT:
        raise InputError(f"{where}: format must be {FORMAT!r}, found {str(doc.get('format'))[:40]!r}")
    if _field(doc, "units", where) != "mm":
        raise InputError(f"{where}.units: must be 'mm'")
    mesh = _field(doc, "mesh", where)
    pose = _field(mesh, "pose", f"{where}.mesh")
    if not (isinstance(pose, list) and len(pose) == 6 and all(map(_finite, pose))):
        raise InputError(f"{where}.mesh.pose: expected [x, y, z, o, a, t]")
    counts = [_field(mesh, k, f"{where}.mesh") for k in ("vertices", "faces")]
    if not all(isinstance(c, int) and not isinstance(c, bool) and c >= 0 for c in counts):
        raise InputError(f"{where}.mesh: vertices and faces must be counts")
    info = MeshInfo(str(_field(mesh, "file", f"{where}.mesh")), str(_field(mesh, "sha256", f"{where}.mesh")),
                    counts[0], counts[1], tuple(float(v) for v in pose))
    pattern = _field(doc, "pattern", where)
    if pattern not in PATTERNS:
        raise InputError(f"{where}.pattern: expected one of {', '.join(PATTERNS)}")
    raw = _field(doc, "passes", where)
    if not isinstance(raw, list):
        raise InputError(f"{where}.passes: expected a list")
    passes = tuple(_pass(p, f"{where}.passes[{k}]") for k, p in enumerate(raw))
    st = _field(doc, "stats", where)
    gaps = _field(st, "spacing_along_surface_mm", f"{where}.stats")
    stats = PlanStats(len(passes), _positive(st, "region_area_mm2", f"{where}.stats", True),
                      _positive(st, "coverage", f"{where}.stats", True),
                      *(_optional(_field(gaps, k, f"{where}.stats.spacing_along_surface_mm"),
                                  f"{where}.stats.spacing_along_surface_mm.{k}") for k in ("min", "median", "max")),
                      _positive(st, "normal_smoothing_mm", f"{where}.stats", True),
                      _positive(st, "normal_max_angle_deg", f"{where}.stats", True),
                      _positive(st, "normal_off_faces_deg", f"{where}.stats", True) if "normal_off_faces_deg" in st
                      else 0.0)
    return SurfacePaths(info, pattern, _positive(doc, "spacing_mm", where), _positive(doc, "standoff_mm", where),
                        _positive(doc, "ripple_pct", where, True), passes, stats)


def _finite(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)

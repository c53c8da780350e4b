"""Input curves: the planar Curve value, file readers (CSV/TXT/NPY, x,y or x,y,z columns) and
closure detection."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, MAX_CURVE_FILE_BYTES, MAX_CURVE_POINTS, check_budget
from coatsim.core.errors import InputError, shown

ClosedMode = Literal["auto", "yes", "no"]
CLOSE_FRACTION = 1e-4  # first/last within this fraction of the length -> closed
MIN_LENGTH_MM = 1e-6  # a shorter curve is no curve to spray (and leaves no room for float round-off)


@dataclass(frozen=True, eq=False)
class Curve:
    """A dense planar polyline in mm, shape (n, 2), n >= 2, no consecutive duplicates.

    A closed curve repeats its first point as its last.
    """

    points: np.ndarray
    closed: bool
    name: str

    @property
    def length(self) -> float:
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())

    def transformed(self, matrix: np.ndarray, offset: np.ndarray, scale: float = 1.0) -> Curve:
        pts = scale * self.points @ np.asarray(matrix, float).T + np.asarray(offset, float)
        return Curve(pts, self.closed, self.name)


def make_curve(points: np.ndarray, name: str, closed: ClosedMode = "auto") -> Curve:
    """Validate raw points and build a Curve.

    Drops consecutive duplicate points silently; rejects NaN/inf, fewer than two distinct
    points and zero length with an InputError naming ``name``.
    """
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise InputError(f"{name}: expected x,y points, got an array of shape {pts.shape}")
    return Curve(*clean_points(pts, name, closed), name)


def clean_points(pts: np.ndarray, name: str, closed: ClosedMode) -> tuple[np.ndarray, bool]:
    """The checks and clean-up of make_curve for points (n, d) of any dimension d: returns
    (points, closed), a closed curve repeating its first point as its last."""
    if len(pts) == 0:
        raise InputError(f"{name}: no points")
    check_budget(f"{name}: curve points", len(pts), MAX_CURVE_POINTS, "thin the curve out")
    bad = ~np.isfinite(pts).all(axis=1)
    if bad.any():
        raise InputError(f"{name}: point {int(np.argmax(bad)) + 1} is not finite (NaN or inf)")
    far = np.abs(pts).max(axis=1) > MAX_ABS_COORDINATE_MM
    if far.any():
        raise InputError(f"{name}: point {int(np.argmax(far)) + 1} lies beyond {MAX_ABS_COORDINATE_MM:g} mm from the "
                         "origin; give coordinates in mm near the part")
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.any(np.diff(pts, axis=0) != 0.0, axis=1)
    pts = pts[keep]
    if len(pts) < 2:
        what = "one point" if keep.size == 1 else "all points are equal"
        raise InputError(f"{name}: a curve needs at least two distinct points ({what})")
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    if not length >= MIN_LENGTH_MM:
        raise InputError(f"{name}: the curve is {length:.3g} mm long; give at least {MIN_LENGTH_MM:g} mm (coordinates in mm)")
    gap = float(np.linalg.norm(pts[-1] - pts[0]))
    if closed == "auto":
        is_closed = len(pts) >= 4 and gap <= CLOSE_FRACTION * length
    else:
        is_closed = closed == "yes"
    if is_closed:
        if gap <= CLOSE_FRACTION * length:
            pts = np.vstack((pts[:-1], pts[:1]))  # snap the closing point onto the first
        else:
            pts = np.vstack((pts, pts[:1]))
        if len(pts) < 4:
            raise InputError(f"{name}: a closed curve needs at least three distinct points")
    return pts, is_closed


_SEPARATORS = re.compile(r"[,;\s]+")


def _read_text_points(path: Path) -> np.ndarray:
    check_budget(f"{path}: bytes of curve text", path.stat().st_size, MAX_CURVE_FILE_BYTES,
                 "thin the curve out or save it as an (n, 2) or (n, 3) .npy array")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text file (expected x,y or x,y,z columns)") from None
    rows: list[list[float]] = []
    header_seen = False
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if ";" in line:  # semicolon-separated files may use decimal commas
            fields = [f.replace(",", ".") for f in re.split(r"[;\s]+", line) if f]
        else:
            fields = [f for f in _SEPARATORS.split(line) if f]
        try:
            values = [float(f) for f in fields]
        except ValueError:
            if not rows and not header_seen and not _is_float(fields[0]):
                header_seen = True
                continue  # header row: its first field is a name such as "x" or "x (mm)"
            column = next(k for k, f in enumerate(fields, start=1) if not _is_float(f))
            raise InputError(f"{path}:{number}: field {column} is not a number: {shown(fields[column - 1])} "
                             "(expected x,y or x,y,z columns)") from None
        if len(values) < 2:
            raise InputError(f"{path}:{number}: expected two columns x,y (or three x,y,z), found {len(values)}")
        if len(values) > 3:
            raise InputError(f"{path}:{number}: {len(values)} numeric columns; a curve has x,y or x,y,z (mm)")
        if rows and len(values) != len(rows[0]):
            raise InputError(f"{path}:{number}: {len(values)} columns where the rows above have {len(rows[0])}")
        if not all(math.isfinite(v) for v in values):
            raise InputError(f"{path}:{number}: value is not finite (NaN or inf)")
        rows.append(values)
    if not rows:
        raise InputError(f"{path}: no points (empty file)")
    return np.asarray(rows, dtype=float)


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _read_npy_points(path: Path) -> np.ndarray:
    with open(path, "rb") as handle:
        if handle.read(6) != b"\x93NUMPY":
            raise InputError(f"{path}: not a .npy file (no NumPy header); save the points with numpy.save")
    try:
        data = np.load(path, allow_pickle=False, mmap_mode="r")  # the header first: shape before reading
    except (ValueError, OSError) as exc:
        raise InputError(f"{path}: not a readable .npy array ({str(exc).splitlines()[0][:120]})") from None
    if data.ndim == 2:
        check_budget(f"{path}: curve points", data.shape[0], MAX_CURVE_POINTS, "thin the curve out")
    real = np.issubdtype(data.dtype, np.integer) or np.issubdtype(data.dtype, np.floating)
    if data.ndim != 2 or data.shape[1] not in (2, 3) or not real:
        raise InputError(f"{path}: expected a real-valued (n, 2) or (n, 3) array of x,y or x,y,z, got {data.dtype} {data.shape}")
    return data.astype(float)


def read_points_file(path: str | Path) -> np.ndarray:
    """The raw points of a curve file: (n, 2) for x,y columns, (n, 3) for x,y,z. CSV/TXT
    (comma, space, tab or semicolon; optional header; '#' comments) or NPY."""
    path = Path(path)
    if not path.exists():
        raise InputError(f"{path}: no such file")
    if path.is_dir():
        raise InputError(f"{path}: is a folder, expected a curve file")
    try:
        return _read_npy_points(path) if path.suffix.lower() == ".npy" else _read_text_points(path)
    except PermissionError:
        raise InputError(f"{path}: permission denied") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror or exc})") from None


def read_curve_file(path: str | Path, closed: ClosedMode = "auto") -> Curve:
    """Read a planar curve (x,y columns, see read_points_file); a 3-D curve (x,y,z) is refused:
    it is never read as a plane curve."""
    points = read_points_file(path)
    if points.shape[1] == 3:
        raise InputError(f"{path}: a 3-D curve (x,y,z columns); a planar x,y curve is needed here "
                         "(3-D curves are segmented in space, not programmed from the plane)")
    return make_curve(points, str(path), closed)

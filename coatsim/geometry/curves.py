"""Input curves: the planar Curve value, file readers (CSV/TXT/NPY, x,y or x,y,z columns) and
closure detection."""

from __future__ import annotations

import io
import re
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, check_budget
from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.fileio import read_input
from coatsim.core.number_text import read_rows, table_text
from coatsim.core.units import UNIT_SPELLINGS, UNITS_MM

ClosedMode = Literal["auto", "yes", "no"]
CLOSE_FRACTION = 1e-4  # first/last within this fraction of the length -> closed
CLOSE_SPACINGS = 1.5  # or within this many of the spacings at the ends, the curve running on across the gap
CLOSE_MIN_POINTS = 8  # ... for a curve of at least this many points
CLOSE_TURN_DEG = 120.0  # ... no turn at either end of the gap sharper than this (not doubling back)
CLOSE_SMOOTH, CLOSE_SMOOTH_DEG = 2.0, 5.0  # ... and at one end a turn at most 2x the turn before it + 5 deg
SNAP_NOTE_MM = 0.01  # an automatic closure that moves the last point further than this says so
_HEADER_FIELD = re.compile(r'([xyz])\s*[_-]?\s*(?:[\[(]\s*([^\])]*?)\s*[\])]|([a-z"]+))?', re.IGNORECASE)  # x, X [mm], y_in
_UNIT_WORDS = {"cm": "centimetres", "m": "metres", "in": "inches"}
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

    Args:
        points: an (n, 2) array, mm.
        name: how errors name the input (a file, a built-in curve).
        closed: ``auto`` (closed when the ends meet, or when a loop is given without its closing
            point: the gap about one point spacing and the curve running on across it), ``yes``
            or ``no``.

    Returns:
        The Curve.

    Raises:
        InputError: non-finite values, fewer than two distinct points, zero length.
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
    check_budget(f"{name}: distinct curve points", len(pts), "curve_points", "thin the curve out")
    if len(pts) < 2:
        what = "one point" if keep.size == 1 else "all points are equal"
        raise InputError(f"{name}: a curve needs at least two distinct points ({what})")
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    if not length >= MIN_LENGTH_MM:
        raise InputError(f"{name}: the curve is {length:.3g} mm long; give at least {MIN_LENGTH_MM:g} mm (coordinates in mm)")
    gap = float(np.linalg.norm(pts[-1] - pts[0]))
    meets = gap <= CLOSE_FRACTION * length  # (ends_meet)
    if closed == "auto":
        is_closed = len(pts) >= 4 and meets
        if not is_closed and _runs_across_gap(pts):
            is_closed = True
            warnings.warn(f"{name}: read as closed, its ends {gap:.4g} mm apart, about one point spacing, the curve "
                          "running on across the gap (closed='no' keeps it open)", CoatsimWarning, stacklevel=3)
    else:
        is_closed = closed == "yes"
    if is_closed:
        if meets:
            if closed == "auto" and gap > SNAP_NOTE_MM:
                warnings.warn(f"{name}: read as closed, its ends {gap:.4g} mm apart ({gap / length:.2g} of its length): "
                              "the last point is moved onto the first (closed='no' keeps it open)",
                              CoatsimWarning, stacklevel=3)
            pts = np.vstack((pts[:-1], pts[:1]))  # snap the closing point onto the first
        else:
            pts = np.vstack((pts, pts[:1]))
        if len(pts) < 4:
            raise InputError(f"{name}: a closed curve needs at least three distinct points")
    return pts, is_closed


def ends_meet(points: np.ndarray) -> bool:
    """Whether the first and last point coincide within CLOSE_FRACTION of the length: a path that
    returns to its start (a program's path is closed only so)."""
    length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    return bool(np.linalg.norm(points[-1] - points[0]) <= CLOSE_FRACTION * length)


def _runs_across_gap(pts: np.ndarray) -> bool:
    """Whether a curve whose ends do not meet is still a loop given without its closing point:
    the gap is no wider than CLOSE_SPACINGS of the spacings at its ends, the curve runs on
    across it at one end at least (turning onto or off it no more than CLOSE_SMOOTH times the
    turn at the point before, plus CLOSE_SMOOTH_DEG: the other end may be a corner), and at
    neither end does it double back (a turn sharper than CLOSE_TURN_DEG)."""
    if len(pts) < CLOSE_MIN_POINTS:
        return False
    steps = np.diff(np.vstack((pts[-3:], pts[:3])), axis=0)  # two before the gap, the gap, two after
    widths = np.linalg.norm(steps, axis=1)
    if widths[2] > CLOSE_SPACINGS * max(widths[1], widths[3]):
        return False
    unit = steps / widths[:, None]
    turn = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", unit[:-1], unit[1:]), -1.0, 1.0)))
    before_onto, onto, off, after_off = turn  # at the last point but one, the last (onto the gap), the first, the second
    smooth = (onto <= CLOSE_SMOOTH * before_onto + CLOSE_SMOOTH_DEG) or (off <= CLOSE_SMOOTH * after_off + CLOSE_SMOOTH_DEG)
    return bool(smooth and max(onto, off) < CLOSE_TURN_DEG)


def _read_text_points(path: Path) -> np.ndarray:
    data = read_input(path, "curve file", "curve_file_bytes")
    try:
        text = table_text(data)
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text (nor UTF-16 or UTF-32 with a byte-order mark; expected x,y or x,y,z "
                         "columns; save it as UTF-8 text "
                         "or an (n, 2) or (n, 3) .npy array)") from None
    rows = read_rows(text, str(path), "x,y or x,y,z columns")
    widths = rows.widths
    named = _named_columns(rows.header, path)
    if named is not None:
        index, unit = named
        short = widths != len(rows.header)
        if short.any():
            k = int(np.argmax(short))
            raise InputError(f"{path}:{int(rows.lines[k])}: {int(widths[k])} values where the header names "
                             f"{len(rows.header)} columns")
    wrong = (widths < 2) | (widths > 3) | (widths != widths[:1])
    if named is None and wrong.any():
        k = int(np.argmax(wrong))
        number, count = int(rows.lines[k]), int(widths[k])
        if count < 2:
            raise InputError(f"{path}:{number}: expected two columns x,y (or three x,y,z), found {count}")
        if count > 3:
            raise InputError(f"{path}:{number}: {count} numeric columns; a curve has x,y or x,y,z (mm), or a header "
                             "naming its x, y (and z) columns among others (i,x,y,z)")
        raise InputError(f"{path}:{number}: {count} columns where the rows above have {int(widths[0])}")
    if not len(widths):
        raise InputError(f"{path}: no points (empty file)")
    for note in rows.notes:
        warnings.warn(note, CoatsimWarning, stacklevel=2)
    if named is None:
        return rows.flat.reshape(-1, int(widths[0]))
    if index != list(range(len(rows.header))):
        warnings.warn(f"{path}: read the columns {', '.join(rows.header[k] for k in index)} of "
                      f"{', '.join(rows.header)} as x, y{', z' if len(index) == 3 else ''}", CoatsimWarning, stacklevel=2)
    if unit != "mm":
        warnings.warn(f"{path}: read in {_UNIT_WORDS[unit]} as its header says ({', '.join(rows.header[k] for k in index)}), "
                      "converted to mm", CoatsimWarning, stacklevel=2)
    return rows.columns(index) * UNITS_MM[unit]


def _coordinate(field: str) -> tuple[str, str] | None:
    """The axis (x, y or z) and the unit ("" when none; "?" and the text for a unit in brackets
    that is none of UNIT_SPELLINGS) a header field names ("x", "X [mm]", "y_in", "z(inch)",
    "x mm"); None for any other field."""
    text = field.strip()
    if len(text) > 1 and text[0] == text[-1] and text[0] in "'\"":  # a quoted field
        text = text[1:-1].strip()
    found = _HEADER_FIELD.fullmatch(text)
    if found is None:
        return None
    bracketed, word = found.group(2), found.group(3) or ""
    if bracketed is not None:  # "x [ft]" names an axis in a unit not read: said, not taken for mm
        return found.group(1).lower(), UNIT_SPELLINGS.get(bracketed.lower(), f"?{bracketed}")
    if word and word.lower() not in UNIT_SPELLINGS:
        return None
    return found.group(1).lower(), UNIT_SPELLINGS.get(word.lower(), "")


def _named_columns(header: list[str], path: Path) -> tuple[list[int], str] | None:
    """Where a header names an x and a y column (and a z): their indices and the unit the header
    gives them (mm when it gives none); None where it names no x and y, the columns then being
    x, y (and z) in order. InputError where the named columns give different units."""
    axes: dict[str, tuple[int, str]] = {}
    for k, field in enumerate(header):
        coordinate = _coordinate(field)
        if coordinate is not None and coordinate[0] not in axes:
            axes[coordinate[0]] = (k, coordinate[1])
    if "x" not in axes or "y" not in axes:
        return None
    picked = [axes[a] for a in ("x", "y", "z") if a in axes]
    units = sorted({unit for _, unit in picked} - {""})
    unknown = [header[k] for k, unit in picked if unit.startswith("?")]
    if unknown:
        raise InputError(f"{path}: column {unknown[0]!r}: a unit not read; give the coordinates in "
                         f"{', '.join(UNITS_MM)}")
    if len(units) > 1:
        raise InputError(f"{path}: the header gives the coordinates different units ({', '.join(units)}); "
                         "give them in one unit")
    return [k for k, _ in picked], units[0] if units else "mm"


def _read_npy_points(path: Path) -> np.ndarray:
    data = read_input(path, "curve file", "curve_file_bytes")
    if not data.startswith(b"\x93NUMPY"):
        raise InputError(f"{path}: not a .npy file (no NumPy header); save the points with numpy.save")
    stream = io.BytesIO(data)
    try:  # the header first: shape and type before the array is built
        version = np.lib.format.read_magic(stream)
        read_header = {(1, 0): np.lib.format.read_array_header_1_0, (2, 0): np.lib.format.read_array_header_2_0}
        if version not in read_header:
            raise ValueError(f"format version {version[0]}.{version[1]}; save it with numpy.save of plain numbers")
        shape, fortran, dtype = read_header[version](stream)
    except (ValueError, OSError, SyntaxError, TypeError) as exc:
        raise InputError(f"{path}: not a readable .npy array ({str(exc).splitlines()[0][:120]})") from None
    real = np.issubdtype(dtype, np.integer) or np.issubdtype(dtype, np.floating)
    if len(shape) != 2 or shape[1] not in (2, 3) or not real:
        raise InputError(f"{path}: expected a real-valued (n, 2) or (n, 3) array of x,y or x,y,z, got {dtype} {shape}")
    if shape[0] * shape[1] * dtype.itemsize != len(data) - stream.tell():
        raise InputError(f"{path}: the array holds {len(data) - stream.tell()} bytes where its header promises "
                         f"{shape[0]} x {shape[1]} values of {dtype.itemsize} bytes (a truncated file?)")
    flat = np.frombuffer(data, dtype=dtype, offset=stream.tell())
    return flat.reshape(shape, order="F" if fortran else "C").astype(float)


def read_points_file(path: str | Path) -> np.ndarray:
    """The raw points of a curve file: (n, 2) for x,y columns, (n, 3) for x,y,z. CSV/TXT
    (comma, space, tab or semicolon; decimal commas and other written forms of numbers as
    coatsim.core.number_text reads them; optional header; '#' comments) or NPY."""
    path = Path(path)
    return _read_npy_points(path) if path.suffix.lower() == ".npy" else _read_text_points(path)


def read_curve_file(path: str | Path, closed: ClosedMode = "auto") -> Curve:
    """Read a planar curve (x,y columns, see read_points_file); a 3-D curve (x,y,z) is refused:
    it is never read as a plane curve."""
    points = read_points_file(path)
    if points.shape[1] == 3:
        raise InputError(f"{path}: a 3-D curve (x,y,z columns); a planar x,y curve is needed here "
                         "(3-D curves are segmented in space, not programmed from the plane; a program sprays one "
                         "with the gun's fixed direction given, spray_axis)", parameters=("spray_axis",))
    return make_curve(points, str(path), closed)

"""Polysegment JSON (``coatsim.polysegment/1``): the file contract of ``coatsim segment -o``."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.core.jsonfile import read_json
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line, Segment

FORMAT = "coatsim.polysegment/1"


def _point(p: tuple[float, float]) -> list[float]:
    return [float(p[0]), float(p[1])]


def segment_to_dict(seg: Segment) -> dict[str, Any]:
    if isinstance(seg, Arc):
        return {"kind": "arc", "start": _point(seg.start), "end": _point(seg.end),
                "center": _point(seg.center), "radius": float(seg.radius), "sweep": float(seg.sweep)}
    return {"kind": "line", "start": _point(seg.start), "end": _point(seg.end)}


def polysegment_document(poly: Polysegment, tolerance_mm: float, stats: dict[str, Any]) -> dict[str, Any]:
    """The JSON document (a dict) for a polysegment and its stats."""
    return {
        "format": FORMAT,
        "units": "mm",
        "closed": bool(poly.closed),
        "tolerance_mm": float(tolerance_mm),
        "segments": [segment_to_dict(s) for s in poly.segments],
        "corners": [int(k) for k in poly.corners],
        "speed_limited": [[float(v) for v in stretch] for stretch in poly.speed_limited],
        "stats": stats,
    }


def write_polysegment_json(path: str | Path, segmentation) -> None:
    """Write a Segmentation (see coatsim.geometry.segment) as polysegment JSON, atomically."""
    doc = polysegment_document(segmentation.polysegment, segmentation.tolerance_mm, segmentation.stats())
    write_text(path, json.dumps(doc, indent=2) + "\n")


def _number(value: Any, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(f"{where}: expected a finite number, got {value!r}")
    return float(value)


def _xy(value: Any, where: str) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise InputError(f"{where}: expected [x, y], got {value!r}")
    return _number(value[0], where), _number(value[1], where)


def polysegment_from_document(doc: Any, source: str) -> Polysegment:
    """Validate a parsed document; every defect names the field at fault."""
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise InputError(f"{source}: not a polysegment file (expected \"format\": \"{FORMAT}\")")
    segs_in = doc.get("segments")
    if not isinstance(segs_in, list) or not segs_in:
        raise InputError(f"{source}: segments: expected a non-empty list")
    segments: list[Segment] = []
    for i, item in enumerate(segs_in):
        where = f"{source}: segments[{i}]"
        if not isinstance(item, dict) or item.get("kind") not in ("line", "arc"):
            raise InputError(f"{where}.kind: expected \"line\" or \"arc\"")
        start, end = _xy(item.get("start"), f"{where}.start"), _xy(item.get("end"), f"{where}.end")
        if segments and segments[-1].end != start:
            raise InputError(f"{where}.start: does not equal the end of segments[{i - 1}]")
        if item["kind"] == "line":
            segments.append(Line(start, end))
            continue
        center = _xy(item.get("center"), f"{where}.center")
        radius = _number(item.get("radius"), f"{where}.radius")
        sweep = _number(item.get("sweep"), f"{where}.sweep")
        if radius <= 0 or sweep == 0:
            raise InputError(f"{where}: an arc needs radius > 0 and a non-zero sweep")
        for name, p in (("start", start), ("end", end)):
            off = abs(math.dist(p, center) - radius)
            if off > 1e-6 * max(1.0, radius):
                raise InputError(f"{where}.{name}: lies {off:.3g} mm off the arc's circle")
        arc = Arc(start, end, center, radius, sweep)
        reached = arc.points(np.array([arc.length]))[0]
        if math.dist(reached, end) > 1e-6 * max(1.0, radius):
            raise InputError(f"{where}.sweep: a sweep of {sweep:g} rad from start does not reach end")
        segments.append(arc)
    closed = doc.get("closed", False)
    if not isinstance(closed, bool):
        raise InputError(f"{source}: closed: expected true or false")
    corners = doc.get("corners", [])
    if not isinstance(corners, list) or not all(isinstance(k, int) and 0 <= k < len(segments) for k in corners):
        raise InputError(f"{source}: corners: expected junction indices 0..{len(segments) - 1}")
    length = float(sum(s.length for s in segments))
    return Polysegment(tuple(segments), closed=closed, corners=tuple(corners),
                       speed_limited=_speed_limited(doc.get("speed_limited", []), length, source))


def _speed_limited(value: Any, length: float, source: str) -> tuple[tuple[float, float, float], ...]:
    """Validate ``speed_limited``: [[s0, s1, v_max], ...] with 0 <= s0 <= s1 <= the length (mm)
    and v_max >= 0 (mm/s); an older file without the key has none."""
    if not isinstance(value, list):
        raise InputError(f"{source}: speed_limited: expected a list of [s0, s1, v_max]")
    out = []
    slack = 1e-6 * max(1.0, length)
    for i, item in enumerate(value):
        where = f"{source}: speed_limited[{i}]"
        if not isinstance(item, list) or len(item) != 3:
            raise InputError(f"{where}: expected [s0, s1, v_max] (mm, mm, mm/s)")
        s0, s1, v = (_number(x, where) for x in item)
        if not (-slack <= s0 <= s1 <= length + slack) or v < 0:
            raise InputError(f"{where}: need 0 <= s0 <= s1 <= {length:.6g} mm (the path length) and v_max >= 0")
        out.append((s0, s1, v))
    return tuple(out)


def read_json_document(path: Path) -> Any:
    """The parsed JSON of ``path``; a missing, unreadable, invalid or too deeply nested file is an
    InputError (coatsim.core.jsonfile)."""
    return read_json(path, "JSON document")


def read_polysegment_json(path: str | Path) -> Polysegment:
    """Read and validate a polysegment JSON file."""
    return polysegment_from_document(read_json_document(Path(path)), str(path))

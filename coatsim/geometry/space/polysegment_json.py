"""Polysegment JSON version 2 (``coatsim.polysegment/2``): the file of a 3-D chain.

Segments are ``{"kind": "line", "start": [x,y,z], "end": [x,y,z]}`` or ``{"kind": "arc",
"start", "end", "center", "normal": [unit], "radius", "sweep"}`` with ``sweep > 0`` the angle
turned counter-clockwise about ``normal``; ``closed``, ``corners``, ``tolerance_mm``,
``speed_limited`` and ``stats`` as in version 1. A segment may carry ``"axes": {"start",
"via", "end"}``: the unit tool axis there (an orientation-aware fit), on every segment or
none. Floats are written with Python's shortest round-trip repr, so reading gives back the
very same numbers.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.geometry.polysegment_json import _number, _speed_limited, read_json_document
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3

FORMAT = "coatsim.polysegment/2"
ON_CIRCLE = 1e-6  # an arc's ends lie this close (relative to max(1, r)) to its circle
UNIT = 1e-9  # a normal or axis this close to unit length


def _xyz(p: np.ndarray) -> list[float]:
    return [float(v) for v in p]


def segment_to_dict3(seg: Segment3, axes: tuple | None = None) -> dict[str, Any]:
    if isinstance(seg, Arc3):
        out = {"kind": "arc", "start": _xyz(seg.start), "end": _xyz(seg.end), "center": _xyz(seg.center),
               "normal": _xyz(seg.normal), "radius": float(seg.radius), "sweep": float(seg.sweep)}
    else:
        out = {"kind": "line", "start": _xyz(seg.start), "end": _xyz(seg.end)}
    if axes is not None:
        out["axes"] = {name: [float(v) for v in axis] for name, axis in zip(("start", "via", "end"), axes)}
    return out


def chain_document(chain: SpaceChain, tolerance_mm: float, stats: dict[str, Any]) -> dict[str, Any]:
    """The JSON document (a dict) of a 3-D chain and its stats."""
    axes = chain.axes or (None,) * chain.n_segments
    return {
        "format": FORMAT,
        "units": "mm",
        "closed": bool(chain.closed),
        "tolerance_mm": float(tolerance_mm),
        "segments": [segment_to_dict3(s, a) for s, a in zip(chain.segments, axes)],
        "corners": [int(k) for k in chain.corners],
        "speed_limited": [[float(v) for v in stretch] for stretch in chain.speed_limited],
        "stats": stats,
    }


def write_chain_json(path: str | Path, chain: SpaceChain, tolerance_mm: float, stats: dict[str, Any]) -> None:
    """Write a chain as polysegment/2 JSON, atomically."""
    write_text(path, json.dumps(chain_document(chain, tolerance_mm, stats), indent=2) + "\n")


def _vector(value: Any, where: str) -> np.ndarray:
    if not isinstance(value, list) or len(value) != 3:
        raise InputError(f"{where}: expected [x, y, z], got {value!r}")
    return np.array([_number(v, where) for v in value])


def _unit(value: Any, where: str) -> np.ndarray:
    v = _vector(value, where)
    if abs(float(np.linalg.norm(v)) - 1.0) > UNIT:
        raise InputError(f"{where}: expected a unit vector, its length is {float(np.linalg.norm(v)):.12g}")
    return v


def _arc(item: dict, start: np.ndarray, end: np.ndarray, where: str) -> Arc3:
    center = _vector(item.get("center"), f"{where}.center")
    normal = _unit(item.get("normal"), f"{where}.normal")
    radius = _number(item.get("radius"), f"{where}.radius")
    sweep = _number(item.get("sweep"), f"{where}.sweep")
    if not (radius > 0 and 0 < sweep <= 2 * math.pi):
        raise InputError(f"{where}: an arc needs radius > 0 and 0 < sweep <= 2π (counter-clockwise about normal)")
    slack = ON_CIRCLE * max(1.0, radius)
    for name, p in (("start", start), ("end", end)):
        rel = p - center
        off = math.hypot(float(np.linalg.norm(rel - (rel @ normal) * normal)) - radius, float(rel @ normal))
        if off > slack:
            raise InputError(f"{where}.{name}: lies {off:.3g} mm off the arc's circle")
    arc = Arc3(start, end, center, normal, radius, sweep)
    reached = arc.points(np.array([arc.length]))[0]
    if float(np.linalg.norm(reached - end)) > slack:
        raise InputError(f"{where}.sweep: a sweep of {sweep:g} rad about normal from start does not reach end")
    return arc


def chain_from_document(doc: Any, source: str) -> SpaceChain:
    """Validate a parsed polysegment/2 document; every defect names the field at fault."""
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise InputError(f"{source}: not a 3-D polysegment file (expected \"format\": \"{FORMAT}\")")
    items = doc.get("segments")
    if not isinstance(items, list) or not items:
        raise InputError(f"{source}: segments: expected a non-empty list")
    segments: list[Segment3] = []
    axes: list[tuple] = []
    for i, item in enumerate(items):
        where = f"{source}: segments[{i}]"
        if not isinstance(item, dict) or item.get("kind") not in ("line", "arc"):
            raise InputError(f"{where}.kind: expected \"line\" or \"arc\"")
        start, end = _vector(item.get("start"), f"{where}.start"), _vector(item.get("end"), f"{where}.end")
        if segments and not np.array_equal(segments[-1].end, start):
            raise InputError(f"{where}.start: does not equal the end of segments[{i - 1}]")
        segments.append(Line3(start, end) if item["kind"] == "line" else _arc(item, start, end, where))
        if "axes" in item:
            got = item["axes"]
            if not isinstance(got, dict):
                raise InputError(f"{where}.axes: expected {{\"start\", \"via\", \"end\"}} unit vectors")
            axes.append(tuple(tuple(float(v) for v in _unit(got.get(k), f"{where}.axes.{k}")) for k in ("start", "via", "end")))
    if axes and len(axes) != len(segments):
        raise InputError(f"{source}: segments: axes are given on {len(axes)} of {len(segments)} segments; give them on all or none")
    closed = doc.get("closed", False)
    if not isinstance(closed, bool):
        raise InputError(f"{source}: closed: expected true or false")
    corners = doc.get("corners", [])
    if not isinstance(corners, list) or not all(isinstance(k, int) and not isinstance(k, bool) and 0 <= k < len(segments) for k in corners):
        raise InputError(f"{source}: corners: expected junction indices 0..{len(segments) - 1}")
    length = float(sum(s.length for s in segments))
    return SpaceChain(tuple(segments), closed, tuple(corners),
                      _speed_limited(doc.get("speed_limited", []), length, source), tuple(axes))


def read_chain_json(path: str | Path) -> SpaceChain:
    """Read and validate a polysegment/2 file."""
    return chain_from_document(read_json_document(Path(path)), str(path))

"""Part JSON (``coatsim.part/1``): several contours, each a complete polysegment/1 document.

``{"format": "coatsim.part/1", "units": "mm", "source": "part.dxf", "tolerance_mm": 0.1,
"join_tolerance_mm": 0.001, "contours": [<polysegment/1>, ...], "notes": [...],
"stats": {...}}``; contours in drawing order. A drawing with one contour is written as a
plain polysegment/1 document instead.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.polysegment_json import FORMAT as POLYSEGMENT_FORMAT
from coatsim.geometry.polysegment_json import (
    polysegment_document,
    polysegment_from_document,
    read_json_document,
)
from coatsim.geometry.space.polysegment_json import FORMAT as SPACE_FORMAT

FORMAT = "coatsim.part/1"


@dataclass(frozen=True, eq=False)
class PartFile:
    """The contours of a part file (or of a polysegment file: one contour) and the tolerance
    they were fitted with, if the file says."""

    contours: tuple[Polysegment, ...]
    tolerance_mm: float | None
    source: str


def part_document(part) -> dict[str, Any]:
    """The JSON document of a PartSegmentation (see coatsim.geometry.cad)."""
    return {
        "format": FORMAT,
        "units": "mm",
        "source": part.source,
        "tolerance_mm": float(part.tolerance_mm),
        "join_tolerance_mm": float(part.join_tolerance_mm),
        "contours": [polysegment_document(c.polysegment, c.tolerance_mm, c.stats()) for c in part.contours],
        "notes": list(part.notes),
        "stats": part.stats(),
    }


def write_part_json(path: str | Path, part) -> None:
    """Write a PartSegmentation: a part document, or a polysegment document for one contour."""
    if len(part.contours) == 1:
        c = part.contours[0]
        doc = polysegment_document(c.polysegment, c.tolerance_mm, c.stats())
    else:
        doc = part_document(part)
    write_text(path, json.dumps(doc, indent=2) + "\n")


def _tolerance(value: Any) -> float | None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0
    return float(value) if ok else None


def part_from_document(doc: Any, source: str) -> PartFile:
    """Validate a parsed part or polysegment document; defects name the field at fault."""
    if isinstance(doc, dict) and doc.get("format") == POLYSEGMENT_FORMAT:
        return PartFile((polysegment_from_document(doc, source),), _tolerance(doc.get("tolerance_mm")), source)
    if isinstance(doc, dict) and doc.get("format") == SPACE_FORMAT:
        raise InputError(f"{source}: a 3-D polysegment (\"{SPACE_FORMAT}\") gives no spray axis along the curve; "
                         "give the gun's fixed direction (spray_axis), or write the program from the surface paths "
                         "it was fitted from (\"coatsim.surfacepaths/1\", which carry the normals)",
                         parameters=("spray_axis",))
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise InputError(f"{source}: not a part or polysegment file (expected \"format\": \"{FORMAT}\" "
                         f"or \"{POLYSEGMENT_FORMAT}\")")
    items = doc.get("contours")
    if not isinstance(items, list) or not items:
        raise InputError(f"{source}: contours: expected a non-empty list of polysegment documents")
    contours = tuple(polysegment_from_document(item, f"{source}: contours[{k}]") for k, item in enumerate(items))
    tolerance = _tolerance(doc.get("tolerance_mm"))
    if tolerance is None:
        found = [_tolerance(item.get("tolerance_mm")) for item in items]
        tolerance = max(found) if all(t is not None for t in found) else None
    return PartFile(contours, tolerance, source)


def read_part_json(path: str | Path) -> PartFile:
    """Read and validate a part (or polysegment) JSON file."""
    return part_from_document(read_json_document(Path(path)), str(path))

"""Geometry stage: curves, the angular characteristic function, polysegment fitting, I/O."""

from __future__ import annotations

from coatsim.geometry.builtin_curves import BUILTINS, builtin_curve, parse_builtin_spec
from coatsim.geometry.curves import ClosedMode, Curve, make_curve, read_curve_file
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.polysegment_json import read_polysegment_json, write_polysegment_json
from coatsim.geometry.primitives import Arc, Line, Segment
from coatsim.geometry.segment import METHODS, Segmentation, segment_curve


def load_curve(spec: str, closed: ClosedMode = "auto") -> Curve:
    """A curve from a file path (CSV/TXT/NPY) or ``builtin:NAME[:key=value,...]``."""
    if spec.startswith("builtin:"):
        curve = parse_builtin_spec(spec)
        return curve if closed == "auto" else make_curve(curve.points, curve.name, closed)
    return read_curve_file(spec, closed)


__all__ = [
    "Arc", "BUILTINS", "ClosedMode", "Curve", "Line", "Polysegment", "Segment",
    "METHODS", "Segmentation", "builtin_curve", "chain", "load_curve", "make_curve",
    "read_curve_file", "read_polysegment_json", "segment_curve", "write_polysegment_json",
]

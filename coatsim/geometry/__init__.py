"""Geometry stage: curves, the angular characteristic function, polysegment fitting, I/O.

Names are imported from their modules on first use (PEP 562), so that importing one light module
(``coatsim.geometry.polysegment``, as the program stage does) does not load the fitter and scipy.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

_EXPORTS = {
    "BUILTINS": "builtin_curves", "builtin_curve": "builtin_curves", "parse_builtin_spec": "builtin_curves",
    "ClosedMode": "curves", "Curve": "curves", "make_curve": "curves", "read_curve_file": "curves",
    "Polysegment": "polysegment", "chain": "polysegment",
    "read_polysegment_json": "polysegment_json", "write_polysegment_json": "polysegment_json",
    "Arc": "primitives", "Line": "primitives", "Segment": "primitives",
    "METHODS": "segment", "Segmentation": "segment", "segment_curve": "segment",
}

if TYPE_CHECKING:
    from coatsim.geometry.builtin_curves import BUILTINS, builtin_curve
    from coatsim.geometry.curves import ClosedMode, Curve, make_curve, read_curve_file
    from coatsim.geometry.polysegment import Polysegment, chain
    from coatsim.geometry.polysegment_json import read_polysegment_json, write_polysegment_json
    from coatsim.geometry.primitives import Arc, Line, Segment
    from coatsim.geometry.segment import METHODS, Segmentation, segment_curve


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'coatsim.geometry' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"coatsim.geometry.{module}"), name)
    globals()[name] = value
    return value


def load_curve(spec: str, closed: ClosedMode = "auto") -> Curve:
    """A curve from a file path (CSV/TXT/NPY) or ``builtin:NAME[:key=value,...]``."""
    from coatsim.geometry.builtin_curves import parse_builtin_spec
    from coatsim.geometry.curves import read_curve_file

    if spec.startswith("builtin:"):
        return parse_builtin_spec(spec, closed)
    return read_curve_file(spec, closed)


__all__ = [
    "Arc", "BUILTINS", "ClosedMode", "Curve", "Line", "Polysegment", "Segment",
    "METHODS", "Segmentation", "builtin_curve", "chain", "load_curve", "make_curve",
    "read_curve_file", "read_polysegment_json", "segment_curve", "write_polysegment_json",
]

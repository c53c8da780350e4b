"""Read a drawing: the DXF or SVG reader, picked by the file's suffix."""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

from coatsim.core.errors import InputError
from coatsim.geometry.cad.drawing import DRAWING_SUFFIXES, Drawing
from coatsim.geometry.cad.dxf_reader import read_dxf
from coatsim.geometry.cad.svg_reader import read_svg


def read_drawing(path: str | Path, layers: Sequence[str] | None = None, flatten_mm: float = 0.001) -> Drawing:
    """Read a DXF or SVG drawing; ``layers`` selects layers by name (default: every visible
    geometry layer); free-form curves are sampled within ``flatten_mm``."""
    path = Path(path)
    if not path.exists():
        raise InputError(f"{path}: no such file")
    if path.is_dir():
        raise InputError(f"{path}: is a folder, expected a drawing")
    if not flatten_mm > 0:
        raise ValueError("flatten_mm must be > 0")
    if path.suffix.lower() == ".dxf":
        return read_dxf(path, layers, flatten_mm)
    if path.suffix.lower() == ".svg":
        return read_svg(path, layers, flatten_mm)
    raise InputError(f"{path}: not a drawing (expected {' or '.join(DRAWING_SUFFIXES)})")

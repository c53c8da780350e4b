"""Read a drawing: the DXF or SVG reader, picked by the file's suffix; what either reads is
checked to lie within the coordinate budget before it is chained."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.core.budgets import MAX_ABS_COORDINATE_MM
from coatsim.core.errors import InputError
from coatsim.geometry.cad.drawing import DRAWING_SUFFIXES, Drawing
from coatsim.geometry.cad.dxf_reader import read_dxf
from coatsim.geometry.cad.pieces import FreePiece, Piece
from coatsim.geometry.cad.svg_reader import read_svg
from coatsim.geometry.primitives import Arc


def read_drawing(path: str | Path, layers: Sequence[str] | None = None, flatten_mm: float = 0.001) -> Drawing:
    """Read a DXF or SVG drawing; ``layers`` selects layers by name (default: every visible
    geometry layer); free-form curves are sampled within ``flatten_mm``."""
    path = Path(path)
    if not flatten_mm > 0:
        raise ValueError("flatten_mm must be > 0")
    if path.suffix.lower() == ".dxf":
        drawing = read_dxf(path, layers, flatten_mm)
    elif path.suffix.lower() == ".svg":
        drawing = read_svg(path, layers, flatten_mm)
    else:
        raise InputError(f"{path}: not a drawing (expected {' or '.join(DRAWING_SUFFIXES)})")
    for piece in drawing.pieces:
        far = _extent_mm(piece)
        if not far <= MAX_ABS_COORDINATE_MM:
            where = "is not finite" if not math.isfinite(far) else f"reaches {far:.3g} mm from the origin"
            raise InputError(f"{path}: {piece.source}: {where}; coatsim reads drawings within "
                             f"{MAX_ABS_COORDINATE_MM:g} mm of the origin (check the drawing's units)")
    return drawing


def _extent_mm(piece: Piece) -> float:
    """The largest coordinate a piece reaches (inf or nan when it is not finite)."""
    if isinstance(piece, FreePiece):
        return float(np.abs(piece.points).max()) if np.isfinite(piece.points).all() else math.inf
    seg = piece.segment
    far = max(abs(c) for c in (*seg.start, *seg.end))
    if isinstance(seg, Arc):
        far = max(far, max(abs(c) for c in seg.center) + abs(seg.radius))
    return far if math.isfinite(far) else math.inf

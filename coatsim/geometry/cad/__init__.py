"""Drawings in: DXF (ezdxf) and SVG (svgelements) read into pieces, chained into contours,
and made into one polysegment per contour, native lines and arcs kept exactly."""

from __future__ import annotations

from coatsim.geometry.cad.drawing import DRAWING_SUFFIXES, Drawing, is_drawing
from coatsim.geometry.cad.read import read_drawing
from coatsim.geometry.cad.segment_drawing import ContourSegmentation, PartSegmentation, segment_drawing

__all__ = ["DRAWING_SUFFIXES", "ContourSegmentation", "Drawing", "PartSegmentation", "is_drawing", "read_drawing",
           "segment_drawing"]

"""A text outline (glyphs of a sans face as cubic Béziers and lines, written by
scripts/bench_cad.py's generator) fitted at σ: within σ of the drawn curves, G1 outside the
corners, and no more segments than measured when the fitter's
look-ahead and LP were made faster (the same fits)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from coatsim.geometry.cad import segment_drawing

from cad_helpers import max_distance

TEXT = Path(__file__).resolve().parents[2] / "data" / "text_outline_sea.svg"  # "Sea", 30 mm high, 76 pieces
TOL = 0.1
SEGMENTS = 52  # measured; the fit is deterministic, so more would be a regression


@pytest.fixture(scope="module")
def part():
    return segment_drawing(TEXT, TOL)


def test_text_outline_is_within_sigma_of_every_glyph(part):
    st = part.stats()
    assert st["n_contours"] == 5 and st["n_closed"] == 5 and st["input_primitives"] == 76
    assert st["max_deviation_mm"] <= TOL
    for contour in part.contours:
        assert max_distance(contour.curve.points, contour.polysegment) <= TOL + 0.02  # sampled check, spacing 0.02


def test_text_outline_is_g1_outside_corners_and_no_longer(part):
    st = part.stats()
    assert st["max_tangent_break_deg"] <= 1e-6
    assert st["n_segments"] <= SEGMENTS
    assert all(math.isfinite(c.max_deviation_mm) for c in part.contours)

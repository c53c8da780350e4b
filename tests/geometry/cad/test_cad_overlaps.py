"""Collinear lines that overlap are kept and reported; lines that only touch, or run
parallel nearby, are not."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st

from coatsim.geometry.cad.overlaps import overlapping_lines
from coatsim.geometry.cad.pieces import line_piece

TOL = 0.001


def _line(a, b, name):
    return line_piece(np.array(a, float), np.array(b, float), name)


@settings(max_examples=60, deadline=None)
@given(st.floats(0, 2 * math.pi), st.floats(-100, 100), st.floats(-100, 100), st.floats(1, 50), st.floats(-60, 60),
       st.floats(1, 50), st.booleans())
def test_overlap_found_exactly_when_the_shared_length_exceeds_the_tolerance(angle, x, y, len1, shift, len2, flip):
    d = np.array([math.cos(angle), math.sin(angle)])
    p = np.array([x, y])
    first = _line(p, p + len1 * d, "first")
    a, b = p + shift * d, p + (shift + len2) * d
    second = _line(b, a, "second") if flip else _line(a, b, "second")
    shared = min(len1, shift + len2) - max(0.0, shift)
    found = overlapping_lines([first, second], TOL)
    if shared > 2 * TOL:
        assert [(s.source, t.source) for s, t in found] == [("first", "second")]
    elif shared < TOL / 2:
        assert found == []


def test_parallel_lines_apart_and_touching_lines_are_not_overlaps():
    pieces = [_line((0, 0), (10, 0), "a"), _line((10, 0), (20, 0), "b"), _line((0, 0.01), (10, 0.01), "c"),
              _line((0, 0), (0, 10), "d")]
    assert overlapping_lines(pieces, TOL) == []


def test_overlap_is_noted_by_the_chaining():
    from coatsim.geometry.cad.chaining import chain_pieces

    chaining = chain_pieces([_line((0, 40), (20, 40), "L1"), _line((10, 40), (30, 40), "L2")], TOL)
    assert len(chaining.contours) == 2
    assert any("overlap" in n and "L1" in n and "L2" in n for n in chaining.notes)

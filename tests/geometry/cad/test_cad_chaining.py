"""Chaining pieces into contours: any order and direction, closure, duplicates and
zero-length pieces, branches, near misses, tangency of joins."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, Line
from coatsim.geometry.cad.chaining import TANGENT_FREE_DEG, _duplicates, chain_pieces
from coatsim.geometry.cad.pieces import FreePiece, NativePiece

JOIN = 1e-3


def native(seg, name: str = "piece") -> NativePiece:
    return NativePiece(seg, name)


def square(size: float = 10.0) -> list[NativePiece]:
    p = [(0.0, 0.0), (size, 0.0), (size, size), (0.0, size)]
    return [native(Line(p[k], p[(k + 1) % 4]), f"edge {k}") for k in range(4)]


@settings(max_examples=60, deadline=None)
@given(order=st.permutations(list(range(4))), flips=st.lists(st.booleans(), min_size=4, max_size=4),
       jitter=st.lists(st.floats(-0.3 * JOIN, 0.3 * JOIN), min_size=16, max_size=16))
def test_any_order_direction_and_small_gaps_give_one_closed_contour(order, flips, jitter):
    pieces = []
    for k in order:
        seg = square()[k].segment
        j = jitter[4 * k: 4 * k + 4]
        seg = Line((seg.start[0] + j[0], seg.start[1] + j[1]), (seg.end[0] + j[2], seg.end[1] + j[3]))
        pieces.append(native(seg.reversed() if flips[k] else seg, f"edge {k}"))
    (contour,) = chain_pieces(pieces, JOIN).contours
    assert contour.closed and len(contour.pieces) == 4
    # ends coincide exactly; the first drawn piece starts the contour, in its drawn direction
    for a, b in zip(contour.pieces, contour.pieces[1:] + contour.pieces[:1]):
        assert a.end == b.start
    assert contour.pieces[0].source == pieces[0].source
    first = pieces[0].segment
    assert math.dist(contour.pieces[0].start, first.start) <= JOIN and math.dist(contour.pieces[0].end, first.end) <= JOIN
    assert contour.tangent == (False,) * 4


def test_duplicates_and_zero_length_pieces_are_dropped_with_notes():
    pieces = square() + [native(Line((10.0, 0.0), (0.0, 0.0)), "copy"), native(Line((5.0, 5.0), (5.0, 5.0005)), "dot")]
    chaining = chain_pieces(pieces, JOIN)
    assert len(chaining.contours) == 1 and len(chaining.contours[0].pieces) == 4
    assert any("duplicate" in n and "copy" in n for n in chaining.notes)
    assert any("zero-length" in n and "dot" in n for n in chaining.notes)


def test_branches_pair_the_straightest_continuation():
    # a plus sign drawn as four arms from the centre: the straight lines pair up
    arms = [native(Line((0.0, 0.0), (math.cos(a) * 10, math.sin(a) * 10)), f"arm {k}")
            for k, a in enumerate((0.0, math.pi / 2, math.pi, 3 * math.pi / 2))]
    chaining = chain_pieces(arms, JOIN)
    assert len(chaining.contours) == 2
    for contour in chaining.contours:
        assert contour.tangent == (True,) and not contour.closed
    assert any("three or more pieces meet" in n for n in chaining.notes)


@pytest.mark.parametrize("second_first", [False, True])
def test_closed_paths_touching_at_a_corner_stay_two(second_first):
    # two squares drawn as closed paths, the second's corner on the first's: the straightest
    # pairing at the shared corner is any, but each path is followed as it was drawn
    def path(x0: float, y0: float, name: str) -> list[NativePiece]:
        p = [(x0, y0), (x0 + 10.0, y0), (x0 + 10.0, y0 + 10.0), (x0, y0 + 10.0)]
        return [NativePiece(Line(p[k], p[(k + 1) % 4]), f"{name} segment {k + 1}", name) for k in range(4)]

    a, b = path(0.0, 0.0, "A"), path(10.0, 10.0, "B")
    contours = chain_pieces(b + a if second_first else a + b, JOIN).contours
    assert len(contours) == 2 and all(c.closed and len(c.pieces) == 4 for c in contours)
    assert {frozenset(p.path for p in c.pieces) for c in contours} == {frozenset("A"), frozenset("B")}


def test_a_path_crossing_its_own_vertex_is_followed_as_drawn():
    # a bow tie drawn as one path through its centre twice: one closed contour in drawn order
    p = [(0.0, 0.0), (10.0, 10.0), (20.0, 0.0), (20.0, 20.0), (10.0, 10.0), (0.0, 20.0)]
    pieces = [NativePiece(Line(p[k], p[(k + 1) % 6]), f"bow segment {k + 1}", "bow") for k in range(6)]
    (contour,) = chain_pieces(pieces, JOIN).contours
    assert contour.closed and [q.source for q in contour.pieces] == [q.source for q in pieces]


def test_near_miss_is_joined_and_noted():
    pieces = [native(Line((0.0, 0.0), (10.0, 0.0)), "LINE #A"), native(Line((10.01, 0.0), (20.0, 0.0)), "LINE #B")]
    chaining = chain_pieces(pieces, JOIN, "d.dxf", near_mm=0.1)
    (contour,) = chaining.contours
    assert contour.pieces[0].end == contour.pieces[1].start and contour.moved_mm == pytest.approx(0.005)
    assert any("largest gap closed is 0.01 mm, at (10, 0) between LINE #A and LINE #B" in n for n in chaining.notes)
    assert len(chain_pieces(pieces, JOIN, "d.dxf").contours) == 2  # without near_mm: two open contours


def test_near_miss_wider_than_half_the_tolerance_stays_apart_and_is_named():
    pieces = [native(Line((0.0, 0.0), (10.0, 0.0)), "LINE #A"), native(Line((10.08, 0.0), (20.0, 0.0)), "LINE #B")]
    chaining = chain_pieces(pieces, JOIN, "d.dxf", near_mm=0.1)
    assert len(chaining.contours) == 2 and all(c.moved_mm == 0.0 for c in chaining.contours)
    assert any("first LINE #A at (10, 0), 0.08 mm from LINE #B" in n for n in chaining.notes)


def test_nearly_closed_contour_is_closed():
    pts = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0), (0.0, 0.02)]
    pieces = [native(Line(a, b), f"e{k}") for k, (a, b) in enumerate(zip(pts[:-1], pts[1:]))]
    chaining = chain_pieces(pieces, JOIN, "d.dxf", near_mm=0.1)
    (contour,) = chaining.contours
    assert contour.closed and contour.pieces[-1].end == contour.pieces[0].start
    assert any("largest gap closed is 0.02 mm" in n for n in chaining.notes)


def test_nearest_ends_pair_first_and_each_end_once():
    """Three ends within the tolerance of each other: the nearest two are joined, the third
    ends its contour (and is named)."""
    pieces = [native(Line((0.0, 0.0), (10.0, 0.0)), "A"), native(Line((10.01, 0.0), (10.01, 10.0)), "B"),
              native(Line((10.0, -0.03), (20.0, -5.0)), "C")]
    chaining = chain_pieces(pieces, JOIN, "d.dxf", near_mm=0.1)
    assert sorted(len(c.pieces) for c in chaining.contours) == [1, 2]
    joined = next(c for c in chaining.contours if len(c.pieces) == 2)
    assert {p.source for p in joined.pieces} == {"A", "B"}


def test_tangency_native_exact_and_free_within_its_limit():
    line = native(Line((-10.0, 0.0), (0.0, 0.0)))
    arc = native(Arc((0.0, 0.0), (10.0, 10.0), (0.0, 10.0), 10.0, math.pi / 2))
    kink = native(Line((10.0, 10.0), (20.0, 10.3)))
    (contour,) = chain_pieces([line, arc, kink], JOIN).contours
    assert contour.tangent == (True, False)
    t = np.linspace(0.0, 1.0, 50)
    small = math.radians(TANGENT_FREE_DEG / 2)
    free = FreePiece(np.column_stack((20.0 + 10 * t, 10.3 + 3 * t ** 2)), small + math.atan2(0.3, 10.0), 0.5, "spline")
    (contour,) = chain_pieces([line, arc, kink, free], JOIN).contours
    assert contour.tangent == (True, False, True)


def test_arc_keeps_its_end_and_second_arc_its_radius_at_a_gap():
    a = native(Arc((0.0, 0.0), (10.0, 10.0), (0.0, 10.0), 10.0, math.pi / 2))
    b = native(Arc((10.0, 10.0004), (20.0, 20.0), (20.0, 10.0), 10.0, -math.pi / 2))
    (contour,) = chain_pieces([a, b], JOIN).contours
    first, second = (p.segment for p in contour.pieces)
    assert first == a.segment and second.start == first.end and second.radius == 10.0
    assert math.dist(second.end, (20.0, 20.0)) < 1e-12
    for arc in (first, second):
        for p in (arc.start, arc.end):
            assert abs(math.dist(p, arc.center) - arc.radius) < 1e-12


def _pairwise_duplicates(pieces, tol: float) -> set[int]:
    """The definition, pair by pair: a later piece with the same or swapped ends (within tol) and
    a length within 2 tol of an earlier piece that is itself kept."""
    duplicate: set[int] = set()
    for i, a in enumerate(pieces):
        for j in range(i + 1, len(pieces)):
            b = pieces[j]
            same = math.dist(a.start, b.start) <= tol and math.dist(a.end, b.end) <= tol
            flipped = math.dist(a.start, b.end) <= tol and math.dist(a.end, b.start) <= tol
            if (same or flipped) and i not in duplicate and abs(a.length - b.length) <= 2 * tol:
                duplicate.add(j)
    return duplicate


@settings(max_examples=80, deadline=None)
@given(ends=st.lists(st.tuples(st.sampled_from([0.0, 1.0, 3.0]), st.sampled_from([0.0, 2.0]),
                               st.sampled_from([0.0, 1.0, 3.0]), st.sampled_from([0.0, 2.0]),
                               st.floats(-0.6 * JOIN, 0.6 * JOIN)), min_size=2, max_size=14))
def test_duplicates_are_the_pairwise_definition(ends):
    """Near-copies, flipped copies and copies of copies (within the join tolerance of one
    another but not of the first) give the same set as the pairwise definition."""
    pieces = [native(Line((x0 + e, y0), (x1, y1 + e))) for x0, y0, x1, y1, e in ends if (x0, y0) != (x1, y1)]
    assume(len(pieces) >= 2)
    assert _duplicates(pieces, JOIN) == _pairwise_duplicates(pieces, JOIN)


def test_ten_thousand_copies_of_one_piece_become_one():
    """A drawing that repeats one piece (an SVG <use> fanned out) keeps one copy; the lookup is
    per kept piece, so the copies cost no pair list (was 50 million pairs)."""
    pieces = [native(Line((0.0, 0.0), (1.0, 0.0)), f"copy {k}") for k in range(10_000)]
    chaining = chain_pieces(pieces, JOIN)
    (contour,) = chaining.contours
    assert len(contour.pieces) == 1 and contour.pieces[0].source == "copy 0"
    assert any("dropped 9999 duplicate pieces" in n for n in chaining.notes)

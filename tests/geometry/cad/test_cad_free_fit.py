"""How free-form stretches reach the fitter: densified on their own chords, and translated
copies (arrays of parts, repeated glyphs) sharing one fit."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings, strategies as st
from hypothesis.extra.numpy import arrays

from coatsim.geometry.cad import segment_drawing
from coatsim.geometry.cad.contour_fit import densified

from cad_helpers import max_distance, write_dxf

TOL = 0.1


@settings(max_examples=40, deadline=None)
@given(arrays(float, st.tuples(st.integers(2, 12), st.just(2)), elements=st.floats(-50, 50).map(lambda v: round(v, 6))), st.floats(0.05, 5.0))
def test_densified_is_the_same_polyline_with_short_chords(points, step):
    dense = densified(points, step)
    # every original vertex is kept exactly, in order
    pos = 0
    for p in points:
        hits = np.flatnonzero((dense[pos:] == p).all(axis=1))
        assert len(hits), "an original vertex is missing"
        pos += int(hits[0])
    assert (dense[0] == points[0]).all() and (dense[-1] == points[-1]).all()
    # chords no longer than the step (where the input's were longer), all points on the input's chords
    assert np.linalg.norm(np.diff(dense, axis=0), axis=1).max() <= max(step * (1 + 1e-9), 1e-12) or len(dense) == len(points)
    for q in dense:
        d = min(_to_segment(q, a, b) for a, b in zip(points[:-1], points[1:]))
        assert d <= 1e-9 * max(1.0, float(np.abs(points).max()))


def _to_segment(q, a, b) -> float:
    ab = b - a
    t = 0.0 if float(ab @ ab) == 0.0 else float(np.clip((q - a) @ ab / (ab @ ab), 0.0, 1.0))
    return float(np.linalg.norm(q - (a + t * ab)))


def _spline_points(x: float, y: float) -> list[tuple[float, float]]:
    return [(x, y), (x + 15, y + 12), (x + 30, y - 5), (x + 45, y + 8), (x + 60, y)]


def test_translated_copies_share_one_fit_and_each_is_within_tolerance(tmp_path):
    offsets = [(0.0, 0.0), (123.456, -7.25), (1e4 + 0.1, 3e3)]

    def draw(msp, doc):
        for x, y in offsets:
            msp.add_spline(fit_points=_spline_points(x, y))

    path = write_dxf(tmp_path, draw)
    part = segment_drawing(path, TOL)
    polys = [c.polysegment for c in part.contours]
    assert len(polys) == 3 and len({p.n_segments for p in polys}) == 1
    for (x, y), poly, contour in zip(offsets, polys, part.contours):
        for s, r in zip(poly.segments, polys[0].segments):
            assert math.dist(s.start, (r.start[0] + x, r.start[1] + y)) < 1e-6
        assert poly.segments[0].start == tuple(contour.curve.points[0])
        assert poly.segments[-1].end == tuple(contour.curve.points[-1])
        assert contour.max_deviation_mm <= TOL
        # independently of the fitter's own check: the chain against the drawn spline
        assert max_distance(contour.curve.points, poly) <= TOL + 0.005

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


def _bezier(control: np.ndarray, n: int = 60) -> np.ndarray:
    t = np.linspace(0.0, 1.0, n)[:, None]
    p0, p1, p2, p3 = control
    return (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t ** 2 * p2 + t ** 3 * p3


def _certified(chain, original, copy: np.ndarray, bound: float, tol: float) -> None:
    """The chain of a copy: on its end points exactly, G1, every heading the original's (so the
    pinned end tangents are kept as the original keeps them), and within the bound it claims of
    the copy's polyline by the exact two-sided Hausdorff distance."""
    from coatsim.geometry.deviation import hausdorff
    from coatsim.geometry.polysegment import Polysegment

    assert chain[0].start == tuple(copy[0]) and chain[-1].end == tuple(copy[-1])
    for a, b in zip(chain[:-1], chain[1:]):
        assert math.dist(a.end, b.start) <= 1e-9
        assert abs(math.remainder(b.start_heading - a.end_heading, 2 * math.pi)) <= 1e-9
    assert [s.kind for s in chain] == [s.kind for s in original]
    for s, r in zip(chain, original):
        assert abs(math.remainder(s.start_heading - r.start_heading, 2 * math.pi)) <= 1e-9
        assert abs(math.remainder(s.end_heading - r.end_heading, 2 * math.pi)) <= 1e-9
    measured = hausdorff(densified(copy, TOL), Polysegment(tuple(chain))).hausdorff
    assert measured <= bound + 1e-9 and bound <= tol


STRETCH = st.tuples(*[st.tuples(st.floats(-30, 30), st.floats(-30, 30))] * 2).map(
    lambda inner: np.array([(0.0, 0.0), *inner, (40.0, 5.0)]))
PINS = st.sampled_from([(False, False), (True, False), (False, True), (True, True)])


def _pins(points: np.ndarray, which) -> tuple:
    """The stretch's own end tangents where ``which`` pins them (as a tangent native neighbour would)."""
    start, end = points[1] - points[0], points[-1] - points[-2]
    return (math.atan2(start[1], start[0]) if which[0] else None, math.atan2(end[1], end[0]) if which[1] else None)


@settings(max_examples=8, deadline=None)
@given(STRETCH, PINS, st.tuples(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4)))
def test_a_translated_copy_reuses_the_fit_moved_and_stays_certified(control, which, shift):
    """An exact copy (up to the round-off of the translation) gets the original's chain moved:
    every segment the original's translated within 1e-9, with the certificate checked exactly.
    (A fresh fit of the copy is not compared: the fitter's LP has degenerate optima, so its
    joints move with the absolute position, by up to 0.2 mm at equal counts.)"""
    from coatsim.geometry.cad.contour_fit import _fit_free

    points = _bezier(control)
    pins = _pins(points, which)
    cache: dict = {}
    original, _ = _fit_free(points, TOL - 0.005, False, *pins, None, cache)
    copy = points + np.array(shift)
    chain, bound = _fit_free(copy, TOL - 0.005, False, *pins, None, cache)
    assert len(chain) == len(original)
    for s, r in zip(chain, original):
        moved = r.transformed(np.eye(2), np.array(shift), 1.0)
        assert type(s) is type(r) and math.dist(s.start, moved.start) <= 1e-9 and math.dist(s.end, moved.end) <= 1e-9
    _certified(chain, original, copy, bound, TOL - 0.005)


@settings(max_examples=8, deadline=None)
@given(STRETCH, PINS, st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)), st.sampled_from([3, 4, 5]))
def test_a_copy_with_rounded_coordinates_is_reused_only_when_certified(control, which, shift, decimals):
    """Exporters round coordinates, so a repeated glyph is a copy to 1e-4 mm only: its chain is
    the original's moved and its end gap closed along lines (every heading kept), and the
    deviation bound holds by the exact check; or the copy is fitted afresh."""
    from coatsim.geometry.cad.fit_copies import reuse, Fitted
    from coatsim.geometry.cad.contour_fit import _fit_free

    points = np.round(_bezier(control), decimals)
    pins = _pins(points, which)
    original, dev = _fit_free(points, TOL - 0.005, False, *pins)
    copy = np.round(points + np.array(shift), decimals)
    reused = reuse([Fitted(points, *pins, original, dev)], copy, TOL - 0.005, *pins)
    if reused is not None:
        chain, bound = reused
        _certified(chain, original, copy, bound, TOL - 0.005)


def test_repeated_glyphs_at_rounded_coordinates_are_fitted_once(tmp_path, monkeypatch):
    """The 'S' of a text outline drawn three times, shifted by amounts that round differently
    at 4 decimals: the copies need no fit of their own, and every contour stays within σ."""
    import coatsim.geometry.cad.contour_fit as contour_fit
    from pathlib import Path

    from cad_helpers import write_svg

    text = (Path(__file__).resolve().parents[2] / "data" / "text_outline_sea.svg").read_text(encoding="utf-8")
    glyph = text[text.index('d="') + 3:text.index(" Z") + 2]  # the first glyph's outline
    numbers = [float(v) for v in glyph.replace("M", " ").replace("L", " ").replace("C", " ").replace("Z", " ").split()]
    fits = []
    real = contour_fit.fit_run
    monkeypatch.setattr(contour_fit, "fit_run", lambda *a, **k: fits.append(1) or real(*a, **k))

    def shifted(dx: float, dy: float) -> str:
        values = iter(enumerate(numbers))
        out = []
        for token in glyph.split():
            if token in "MLCZ":
                out.append(token)
            else:
                k, v = next(values)
                out.append(f"{v + (dy if k % 2 else dx):.4f}")
        return " ".join(out)

    counts = []
    for copies in (1, 3):
        fits.clear()
        body = "\n".join(f'<path d="{shifted(dx, dy)}" fill="none" stroke="black"/>'
                         for dx, dy in [(0.0, 0.0), (31.23457, 0.00004), (62.46911, 10.00007)][:copies])
        part = segment_drawing(write_svg(tmp_path, body, name=f"glyphs_{copies}.svg",
                                         attrs='width="200mm" height="100mm" viewBox="-10 -60 200 100"'), TOL)
        counts.append(len(fits))
        assert part.stats()["max_deviation_mm"] <= TOL and part.stats()["max_tangent_break_deg"] <= 1e-6
        for contour in part.contours:
            assert max_distance(contour.curve.points, contour.polysegment) <= TOL + 0.005
        assert len({c.polysegment.n_segments for c in part.contours}) == 1
    assert counts[1] == counts[0] > 0

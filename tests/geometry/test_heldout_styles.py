"""Held-out input styles (issue 16): curves the fitter was not tuned on, written the way other
people's data comes — digitising noise, scanned jitter along and across the track, uneven and
sparse sampling, hairpins, many-turn spirals, clothoids, huge and tiny scales, coordinates far
from the origin, metre-like units, clockwise loops — each checked for the contract: the
tolerance (exact and brute force), G1 off corners, no arc much tighter than the curve itself,
no segment below the minimum length unless the fit is one segment, a smooth seam."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st

from coatsim.geometry import Arc, make_curve, segment_curve

from geometry_helpers import assert_contract as assert_fitter_contract
from geometry_helpers import tangent_breaks

G1 = 1e-9
FEW = settings(max_examples=4, deadline=None, derandomize=True, database=None,
               phases=[Phase.explicit, Phase.generate])  # a failing fit is slow to shrink


@dataclass(frozen=True)
class Style:
    """A parametric curve p(t), t in [t0, t1], with its sampling and disturbance."""

    f: Callable[[np.ndarray], np.ndarray]
    t0: float
    t1: float
    closed: bool

    def dense(self, n: int = 200_001) -> tuple[np.ndarray, np.ndarray]:
        xy = self.f(np.linspace(self.t0, self.t1, n))
        s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))))
        return xy, s

    def sample(self, at_share: np.ndarray) -> np.ndarray:
        """Points at the given shares (0..1) of the arc length, on the curve."""
        xy, s = self.dense()
        at = np.asarray(at_share) * s[-1]
        pts = np.column_stack((np.interp(at, s, xy[:, 0]), np.interp(at, s, xy[:, 1])))
        if self.closed:
            pts[-1] = pts[0]
        return pts

    def tightest_radius(self) -> float:
        t = np.linspace(self.t0, self.t1, 200_001)
        d1 = np.gradient(self.f(t), t, axis=0)
        d2 = np.gradient(d1, t, axis=0)
        kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
        return float(1.0 / np.abs(kappa[2:-2]).max())


def _ellipse(a: float, b: float, centre=(0.0, 0.0), clockwise: bool = False) -> Style:
    sign = -1.0 if clockwise else 1.0
    return Style(lambda t: np.column_stack((centre[0] + a * np.cos(t), centre[1] + sign * b * np.sin(t))),
                 0.0, 2 * math.pi, True)


def _hairpin(radius: float, leg: float) -> Style:
    """A leg, a half circle of ``radius``, a leg back (a paperclip end), smooth by C1 only:
    parametrised by arc length."""
    half = math.pi * radius

    def f(t: np.ndarray) -> np.ndarray:
        x = np.where(t < leg, t, np.where(t < leg + half, leg + radius * np.sin((t - leg) / radius), leg - (t - leg - half)))
        y = np.where(t < leg, 0.0, np.where(t < leg + half, radius - radius * np.cos((t - leg) / radius), 2 * radius))
        return np.column_stack((x, y))
    return Style(f, 0.0, 2 * leg + half, False)


def _clothoid(length: float, end_radius: float) -> Style:
    from scipy.special import fresnel

    scale = math.sqrt(math.pi * length * end_radius)

    def f(t: np.ndarray) -> np.ndarray:
        s_, c_ = fresnel(t / scale)
        return scale * np.column_stack((c_, s_))
    return Style(f, 0.0, length, False)


def _spiral(turns: float, pitch: float, inner: float) -> Style:
    return Style(lambda t: np.column_stack(((inner + pitch * t / (2 * math.pi)) * np.cos(t),
                                            (inner + pitch * t / (2 * math.pi)) * np.sin(t))), 0.0, 2 * math.pi * turns, False)


def _limacon_loop(a: float, b: float) -> Style:
    """r = a + b cos t with b > a: a loop inside the loop (the curve crosses itself)."""
    return Style(lambda t: np.column_stack(((a + b * np.cos(t)) * np.cos(t), (a + b * np.cos(t)) * np.sin(t))),
                 0.0, 2 * math.pi, True)


def _kidney(scale: float) -> Style:
    """A bean: a loop with one concave bay (curvature changes sign twice)."""
    return Style(lambda t: scale * np.column_stack((np.cos(t) + 0.35 * np.cos(2 * t), np.sin(t) + 0.12 * np.sin(3 * t))),
                 0.0, 2 * math.pi, True)


def assert_contract(curve, seg, tol: float) -> None:
    """The fitter's contract on the curve's points, and a closed chain's seam tangent-continuous
    unless the curve has corners."""
    assert_fitter_contract(seg, tol, curve.points)
    poly = seg.polysegment
    if poly.closed:
        assert len(poly.corners) > 0 or tangent_breaks(poly)[-1][1] <= G1


def assert_honest(seg, tol: float, tightest: float, min_length: float | None = None) -> None:
    """No arc much tighter than the curve (0.8 x its tightest radius: the fit may be 1.25 x
    tighter than its robust local estimate), no segment below the minimum length but a lone
    one, the seam segments no exception."""
    poly = seg.polysegment
    assert seg.limits_kept is True
    for k, s in enumerate(poly.segments):
        if isinstance(s, Arc):
            assert s.radius >= 0.8 * tightest, f"segment {k}: r {s.radius:.4g} mm, curve's tightest {tightest:.4g} mm"
    shortest = min(s.length for s in poly.segments)
    floor = 5 * tol if min_length is None else min_length
    assert poly.n_segments == 1 or shortest >= 0.98 * floor, f"a segment of {shortest:.4g} mm"


# ---------------------------------------------------------------- clean curves in new styles


CLEAN = {
    # name: (style, points, tolerance)
    "hairpin r=4": (_hairpin(4.0, 60.0), 1500, 0.05),
    "clothoid to r=15": (_clothoid(150.0, 15.0), 1200, 0.05),
    "spiral, 8 turns": (_spiral(8.0, 6.0, 10.0), 6000, 0.1),
    "limacon with inner loop": (_limacon_loop(20.0, 40.0), 3000, 0.1),
    "kidney bean": (_kidney(60.0), 2000, 0.05),
    "clockwise ellipse": (_ellipse(90.0, 35.0, clockwise=True), 2000, 0.05),
    "ellipse 500 km from the origin": (_ellipse(80.0, 50.0, centre=(5e5, -3e5)), 2000, 0.05),
    "ellipse of 50 m": (_ellipse(5e4, 2e4), 3000, 5.0),
    "ellipse of 2 mm": (_ellipse(2.0, 1.0), 1500, 0.002),
    "ellipse in metres": (_ellipse(0.09, 0.035), 2000, 5e-5),
}


@pytest.mark.parametrize("name", list(CLEAN))
def test_clean_curves_in_new_styles_keep_the_contract(name):
    style, points, tol = CLEAN[name]
    curve = make_curve(style.sample(np.linspace(0.0, 1.0, points)), name, "yes" if style.closed else "no")
    seg = segment_curve(curve, tol)
    assert_contract(curve, seg, tol)
    assert_honest(seg, tol, style.tightest_radius())


# ---------------------------------------------------------------- sampling and noise


@FEW
@given(seed=st.integers(0, 2**32 - 1), spread=st.floats(0.2, 0.9))
def test_uneven_sampling_keeps_the_contract(seed, spread):
    """Points at random arc lengths: gaps from (1 - spread) to (1 + spread) times the mean."""
    style = _kidney(50.0)
    gaps = 1.0 + spread * np.random.default_rng(seed).uniform(-1.0, 1.0, 1500)
    at = np.concatenate(([0.0], np.cumsum(gaps))) / gaps.sum()
    curve = make_curve(style.sample(at), "uneven", "yes")
    seg = segment_curve(curve, 0.05)
    assert_contract(curve, seg, 0.05)
    assert_honest(seg, 0.05, style.tightest_radius())


def scanned_ellipse(seed: int, share: float, tol: float) -> tuple[Style, np.ndarray]:
    """Scanner-like data on an ellipse: lateral noise of ``share`` σ (each coordinate) and
    along-track jitter of a quarter of the spacing."""
    style = _ellipse(70.0, 40.0)
    rng = np.random.default_rng(seed)
    n = 2500
    at = (np.arange(n) + rng.uniform(-0.25, 0.25, n)) / (n - 1)
    at[0], at[-1] = 0.0, 1.0
    pts = style.sample(np.clip(at, 0.0, 1.0))
    pts[:-1] += rng.normal(0.0, share * tol, (n - 1, 2))
    pts[-1] = pts[0]
    return style, pts


@FEW
@given(seed=st.integers(0, 2**32 - 1), share=st.floats(0.02, 0.1))
def test_scanned_jitter_keeps_the_contract_and_the_curvature(seed, share):
    tol = 0.1
    style, pts = scanned_ellipse(seed, share, tol)
    curve = make_curve(pts, "scan", "yes")
    seg = segment_curve(curve, tol)
    assert_contract(curve, seg, tol)
    assert_honest(seg, tol, style.tightest_radius())


@pytest.mark.xfail(strict=True, reason="measured: noise of σ/4 (std per coordinate, 2500 points, seed 0) leaves the "
                   "band fit no room (extremes ±0.09 mm in a ±0.1 mm band): every try fails and the fillet fallback "
                   "gives 964 segments, some 1e-9 mm long, arcs of r 0.035 mm (curve: 22.9 mm); also at σ 0.15 (347) "
                   "and σ 0.2 (163)")
def test_scanned_jitter_of_a_quarter_sigma_keeps_honest_arcs():
    tol = 0.1
    style, pts = scanned_ellipse(0, 0.25, tol)
    curve = make_curve(pts, "scan", "yes")
    seg = segment_curve(curve, tol)
    assert_contract(curve, seg, tol)
    assert_honest(seg, tol, style.tightest_radius())


@pytest.mark.parametrize("points,tol", [(40, 0.1), (90, 0.05)])
def test_sparse_polygons_of_a_circle_are_one_circle(points, tol):
    """A circle of r 50 mm given by a few vertices (sagitta of an edge above σ, below 2σ):
    one circle passes between the vertices and the edges."""
    style = _ellipse(50.0, 50.0)
    curve = make_curve(style.sample(np.linspace(0.0, 1.0, points)), "sparse", "yes")
    seg = segment_curve(curve, tol)
    assert_contract(curve, seg, tol)
    assert len(seg.polysegment.corners) == 0
    centres = {(round(s.center[0], 6), round(s.center[1], 6), round(s.radius, 6)) for s in seg.polysegment.segments}
    assert len(centres) == 1 and seg.polysegment.n_lines == 0


def test_a_sparse_polygon_below_its_tolerance_keeps_its_vertices_and_says_so():
    """The 39-gon of r 50 mm at σ 0.05: its edges lie 0.16 mm inside the circle through its
    vertices, so no arc as gentle as its turning stays within σ of vertices and edges: it
    comes back as its own lines, a corner at every vertex, and a note with the σ needed."""
    style = _ellipse(50.0, 50.0)
    curve = make_curve(style.sample(np.linspace(0.0, 1.0, 40)), "sparse", "yes")
    seg = segment_curve(curve, 0.05)
    assert_contract(curve, seg, 0.05)
    assert seg.polysegment.n_lines == seg.polysegment.n_segments == 39
    assert len(seg.polysegment.corners) == 39
    assert any("below what the polyline allows" in n for n in seg.notes)


@pytest.mark.xfail(strict=True, reason="measured: scanned jitter at share 0.041 (seed 1250) gives one arc of r 17.6 mm "
                   "on an ellipse whose tightest radius is 22.9 mm (0.77 of it, below the 0.8 asked)")
def test_scanned_jitter_seed_1250_keeps_honest_arcs():
    tol = 0.1
    style, pts = scanned_ellipse(1250, 0.040862052389780024, tol)
    curve = make_curve(pts, "scan", "yes")
    seg = segment_curve(curve, tol)
    assert_contract(curve, seg, tol)
    assert_honest(seg, tol, style.tightest_radius())


@pytest.mark.parametrize("seam_deg, points", [
    (0.0, 2400), (9.0, 2400), (18.0, 2400), (27.0, 2400), (36.0, 2400),
    pytest.param(0.0, 1200, marks=pytest.mark.xfail(strict=True, reason="measured limit: sampled with 1 200 points from "
                                                    "a petal's tip, the first band fit closes neither from the look-ahead's "
                                                    "slope nor along the seam's tangent, and the landed one keeps 30 "
                                                    "segments at 0.92 σ")),
])
def test_a_five_petal_flower_uses_its_tolerance_from_any_seam(seam_deg, points):
    # r = 30 + 8 cos 5θ, closed: from a seam at a petal's tip (0) or near it (9 deg) the band
    # fit's start slope left the loop no closing pair, narrowed bands gave a loose chain and the
    # first chain within σ (31 at 0.4 σ) was kept over 21 that missed by 4 %; now as few as
    # from a seam between tip and valley (20 to 22)
    t = np.radians(seam_deg) + np.linspace(0.0, 2 * math.pi, points, endpoint=False)
    r = 30.0 + 8.0 * np.cos(5 * t)
    curve = make_curve(np.column_stack([r * np.cos(t), r * np.sin(t)]), "flower", "yes")
    seg = segment_curve(curve, 0.5)
    assert_contract(curve, seg, 0.5)
    assert seg.polysegment.n_segments <= 22

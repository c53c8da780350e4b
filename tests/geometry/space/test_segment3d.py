"""The 3-D fit: planar curves in any orientation give their 2-D fit; space curves within σ,
G1, honest; the certified 3-D deviation against a brute-force dense oracle; polysegment/2."""

from __future__ import annotations

import functools
import json
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.geometry import builtin_curve, make_curve, segment_curve
from coatsim.geometry.curves import read_curve_file
from coatsim.geometry.space.biarc import biarc
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import SpaceCurve, make_space_curve, read_any_curve
from coatsim.geometry.space.deviation import hausdorff3
from coatsim.geometry.space.families import FAMILIES, HELD_OUT
from coatsim.geometry.space.greedy import greedy_knots
from coatsim.geometry.space.polysegment_json import chain_document, chain_from_document, read_chain_json, write_chain_json
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3
from coatsim.geometry.space.segment import segment_space_curve

from strategies import poses, unit_vectors


ALL_FAMILIES = {**FAMILIES, **HELD_OUT}
# measured at 1500 points and σ 0.1: the G1 chain needs more pieces than the kinked greedy
# arcs on these (the torus section: every start at 8 pieces, the greedy's count, stalls
# 0.125 mm off, its misses equal on every piece)
ABOVE_GREEDY = {"torus"}


@functools.lru_cache(maxsize=None)
def fitted(name: str, tol: float):
    return segment_space_curve(make_space_curve(ALL_FAMILIES[name](1500), name), tol)


def brute_hausdorff(points: np.ndarray, chain: SpaceChain, step: float) -> float:
    """Both directions between dense samples of the polyline and of the chain (KD-trees)."""
    from scipy.spatial import cKDTree

    dense = [points[:1]]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, int(math.ceil(np.linalg.norm(b - a) / step)))
        dense.append(a + np.linspace(0, 1, n + 1)[1:, None] * (b - a))
    poly = np.vstack(dense)
    ours = chain.sample(step)[0]
    return max(cKDTree(ours).query(poly)[0].max(), cKDTree(poly).query(ours)[0].max())


def assert_g1(chain: SpaceChain) -> None:
    breaks = chain.junction_breaks()
    smooth = [k for k in range(len(breaks)) if k not in chain.corners]
    assert np.all(breaks[smooth] < 1e-9), breaks[smooth].max()
    for a, b in zip(chain.segments[:-1], chain.segments[1:]):
        assert np.array_equal(a.end, b.start)


@pytest.mark.parametrize("name", ["paper-spiral", "ellipse", "cam", "rounded-rectangle"])
@pytest.mark.parametrize("seed", [0, 1])
def test_planar_curve_in_any_orientation_gives_its_2d_fit(name, seed):
    curve = builtin_curve(name)
    flat = segment_curve(curve, 0.1)
    rng = np.random.default_rng(seed)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    pose = Pose(q * np.sign(np.linalg.det(q)), rng.normal(scale=300, size=3))
    pts = pose.apply(np.column_stack((curve.points, np.zeros(len(curve.points)))))
    fit = segment_space_curve(make_space_curve(pts, name, "yes" if curve.closed else "no"), 0.1)
    assert fit.planar_pose is not None
    assert fit.chain.n_segments == flat.polysegment.n_segments
    assert fit.chain.n_arcs == flat.polysegment.n_arcs and len(fit.chain.corners) == len(flat.polysegment.corners)
    assert fit.max_deviation_mm <= 0.1
    assert_g1(fit.chain)


@settings(max_examples=10, deadline=None)
@given(poses(), st.floats(5.0, 200.0))
def test_circle_in_a_random_plane_is_one_circle(pose, radius):
    t = np.linspace(0, 2 * math.pi, 800)
    flat = np.column_stack((radius * np.cos(t), radius * np.sin(t), np.zeros_like(t)))
    fit = segment_space_curve(make_space_curve(pose.apply(flat), "circle"), 0.05)
    arcs = fit.chain.segments
    assert all(isinstance(a, Arc3) for a in arcs) and fit.chain.closed
    centre = pose.translation_mm
    for a in arcs:  # every arc on the one circle
        assert np.linalg.norm(a.center - centre) < 0.05 and abs(a.radius - radius) < 0.05
        assert abs(abs(a.normal @ pose.rotation[:, 2]) - 1) < 1e-9 and a.normal @ arcs[0].normal > 0
    assert math.fsum(a.sweep for a in arcs) == pytest.approx(2 * math.pi, abs=1e-6)
    assert fit.chain.n_segments == 1 == segment_curve(make_curve(flat[:, :2], "c"), 0.05).polysegment.n_segments


def test_helix_within_tolerance_with_fewer_segments_as_it_grows():
    counts = []
    for tol in (0.05, 0.1, 0.5):
        fit = fitted("helix", tol)
        assert fit.planar_pose is None and fit.max_deviation_mm <= tol and fit.limits_kept
        counts.append(fit.chain.n_segments)
        assert_g1(fit.chain)
    assert counts[0] > counts[1] > counts[2]


@pytest.mark.parametrize("name", sorted(ALL_FAMILIES))
def test_space_families_within_tolerance_g1_and_honest(name):
    fit = fitted(name, 0.1)
    assert fit.max_deviation_mm <= 0.1
    assert brute_hausdorff(fit.curve.points, fit.chain, 0.005) <= 0.1 + 0.005
    assert_g1(fit.chain)
    assert fit.limits_kept
    profile_radius = fit.input_min_radius_mm
    tightest = min((s.radius for s in fit.chain.segments if isinstance(s, Arc3)), default=math.inf)
    assert tightest >= profile_radius / 1.25  # no arc much tighter than the curve anywhere


@pytest.mark.parametrize("name", [
    pytest.param(n, marks=pytest.mark.xfail(strict=True, reason="measured: more pieces than the greedy"))
    if n in ABOVE_GREEDY else n for n in sorted(ALL_FAMILIES)])
def test_no_more_segments_than_the_greedy_fitter(name):
    """The G1 chain against the greedy 3-D arc fitter (kinks at every junction) on the same points."""
    fit = fitted(name, 0.1)
    assert fit.chain.n_segments <= len(greedy_knots(fit.curve.points, 0.1)) - 1


@pytest.mark.slow
def test_a_local_optimum_does_not_end_the_search_for_a_chain():
    """The trefoil at σ 0.5 mm: chains of 11 to 14 pieces stall 0.69 to 0.50 mm off, no curvature
    cap or minimum length holding them; the search goes on to larger counts and merges down
    (it fell back to 18 biarcs when a plateau ended it, at 400 points 20)."""
    fit = segment_space_curve(make_space_curve(HELD_OUT["trefoil"](400), "trefoil"), 0.5)
    assert fit.max_deviation_mm <= 0.5 and fit.limits_kept and fit.added_corners == 0
    assert_g1(fit.chain)
    assert fit.chain.n_segments <= 15


def test_the_trefoil_at_half_a_millimetre_fits_its_fewest_g1_pieces():
    """The trefoil at σ 0.5 mm, 1500 points: 15 pieces (the greedy's kinked arcs: 11). Measured:
    every start at 12 or 13 pieces stalls 0.69 / 0.56 mm off, at 14 pieces 0.5007 mm, its
    misses equal on every piece; the loop's other seams are searched from 14 pieces only."""
    fit = fitted("trefoil", 0.5)
    assert fit.max_deviation_mm <= 0.5 and fit.limits_kept and fit.added_corners == 0
    assert_g1(fit.chain)
    assert fit.chain.n_segments <= 15


@settings(max_examples=6, deadline=None)
@given(poses(), st.floats(15.0, 80.0), st.floats(5.0, 60.0), st.sampled_from([0.05, 0.2]))
def test_random_helices_within_tolerance_by_a_dense_oracle(pose, radius, rise_per_turn, tol):
    """Helices of any radius, pitch and placement: within σ by the brute-force oracle, G1,
    and no more pieces than the greedy fitter."""
    t = np.linspace(0.0, 4 * math.pi, 1200)
    pts = pose.apply(np.column_stack((radius * np.cos(t), radius * np.sin(t), rise_per_turn * t / (2 * math.pi))))
    fit = segment_space_curve(make_space_curve(pts, "helix"), tol)
    assert fit.max_deviation_mm <= tol
    assert brute_hausdorff(pts, fit.chain, tol / 20) <= tol * 1.05
    assert_g1(fit.chain)
    assert fit.chain.n_segments <= len(greedy_knots(pts, tol)) - 1


def noisy_twist(seed: int, n: int, scatter: float) -> np.ndarray:
    """A space curve of three sines at irregular samples with Gaussian scatter (mm)."""
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0.0, 1.0, n))
    t[[0, -1]] = 0.0, 1.0
    amplitude, frequency, phase = rng.uniform(30, 60, 3), rng.uniform(1.0, 2.5, 3), rng.uniform(0, 2 * math.pi, 3)
    pts = np.column_stack([amplitude[k] * np.sin(frequency[k] * math.pi * t + phase[k]) for k in range(3)])
    return pts + rng.normal(scale=scatter, size=pts.shape)


@settings(max_examples=3, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([0.005, 0.01]))
def test_noisy_space_curves_no_more_segments_than_the_greedy_fitter(seed, scatter):
    """Scatter a tenth of σ or less: no more pieces than the greedy fitter (the fit's frames
    jittered with the noise from vertex to vertex, its knots stalled, and it took 10 to 30 %
    more pieces than the greedy)."""
    pts = noisy_twist(seed, 800, scatter)
    fit = segment_space_curve(make_space_curve(pts, "noisy"), 0.1)
    assert fit.max_deviation_mm <= 0.1
    assert_g1(fit.chain)
    assert fit.chain.n_segments <= len(greedy_knots(pts, 0.1)) - 1


@st.composite
def chains_and_polylines(draw):
    """A random G1 chain of biarcs and a polyline wandering near it."""
    rng = np.random.default_rng(draw(st.integers(0, 2**31)))
    knots = np.cumsum(rng.normal(scale=20, size=(4, 3)) + [25, 0, 0], axis=0)
    tangents = [draw(unit_vectors()) for _ in knots]
    segments = []
    for k in range(3):
        pair = biarc(knots[k], tangents[k], knots[k + 1], tangents[k + 1], draw(st.sampled_from([0.5, 1.0, 2.0])))
        assume(pair is not None)
        segments.extend(s for s in pair if s.length > 1e-6)
    chain = SpaceChain(tuple(segments))
    s = np.sort(rng.uniform(0, 1, draw(st.integers(5, 60)))) * chain.length
    base = chain.sample(chain.length / 400)
    pts = np.array([base[0][np.argmin(np.abs(base[1] - v))] for v in s])
    pts = pts + rng.normal(scale=draw(st.sampled_from([0.01, 0.3, 3.0])), size=pts.shape)
    return chain, pts


@settings(max_examples=30, deadline=None)
@given(chains_and_polylines())
def test_deviation_against_a_dense_oracle(data):
    chain, pts = data
    assume(len(np.unique(pts, axis=0)) >= 2)
    exact = hausdorff3(pts, chain, 0.1).hausdorff
    step = 0.01
    oracle = brute_hausdorff(pts, chain, step)
    assert oracle - step <= exact <= oracle + step  # both within half a sample step of the truth


def test_polysegment2_round_trip(tmp_path):
    fit = fitted("torus", 0.1)
    path = tmp_path / "torus.json"
    write_chain_json(path, fit.chain, 0.1, fit.stats())
    doc = json.loads(path.read_text())
    assert doc["format"] == "coatsim.polysegment/2" and doc["segments"][0]["kind"] == "arc"
    back = read_chain_json(path)
    assert back.n_segments == fit.chain.n_segments and back.closed == fit.chain.closed
    for a, b in zip(back.segments, fit.chain.segments):
        assert np.array_equal(a.start, b.start) and np.array_equal(a.end, b.end)
        if isinstance(a, Arc3):
            assert np.array_equal(a.center, b.center) and a.sweep == b.sweep and a.radius == b.radius
    assert chain_document(back, 0.1, fit.stats()) == doc


@pytest.mark.parametrize("edit, field", [
    (lambda d: d["segments"][0].update(normal=[0, 0, 2]), "segments[0].normal"),
    (lambda d: d["segments"][0].update(sweep=-1.0), "segments[0]"),
    (lambda d: d["segments"][1].update(start=[0, 0, 0]), "segments[1].start"),
    (lambda d: d["segments"][0].update(radius=d["segments"][0]["radius"] * 1.01), "segments[0].start"),
    (lambda d: d.update(format="coatsim.polysegment/1"), "not a 3-D polysegment"),
])
def test_polysegment2_defects_name_their_field(edit, field):
    doc = chain_document(fitted("torus", 0.1).chain, 0.1, {})
    edit(doc)
    with pytest.raises(InputError, match=field.replace("[", r"\[").replace("]", r"\]")):
        chain_from_document(doc, "t.json")


def test_three_columns_make_a_space_curve(tmp_path):
    path = tmp_path / "xyz.csv"
    path.write_text("x,y,z\n0,0,0\n1,1,5\n2,4,9\n")
    curve = read_any_curve(path)
    assert isinstance(curve, SpaceCurve) and curve.points.shape == (3, 3)
    with pytest.raises(InputError, match="3-D curve"):
        read_curve_file(path)
    np.save(tmp_path / "xyz.npy", curve.points)
    assert isinstance(read_any_curve(tmp_path / "xyz.npy"), SpaceCurve)
    (tmp_path / "four.csv").write_text("0,0,0\n1,1,5,7\n")
    with pytest.raises(InputError, match=r"four.csv:2: 4 numeric columns"):
        read_any_curve(tmp_path / "four.csv")
    (tmp_path / "mixed.csv").write_text("0,0,0\n1,1\n")
    with pytest.raises(InputError, match=r"mixed.csv:2: 2 columns where the rows above have 3"):
        read_any_curve(tmp_path / "mixed.csv")
    np.save(tmp_path / "wide.npy", np.zeros((4, 5)))
    with pytest.raises(InputError, match=r"\(n, 2\) or \(n, 3\)"):
        read_any_curve(tmp_path / "wide.npy")


def test_segment_command_on_a_3d_curve(tmp_path, run_cli):
    path = tmp_path / "helix.csv"
    np.savetxt(path, FAMILIES["helix"](1500), delimiter=",")
    out, plot = tmp_path / "helix.json", tmp_path / "helix.png"
    code, stdout, stderr = run_cli(["segment", str(path), "--tol", "0.1", "-o", str(out), "--plot", str(plot)])
    assert code == 0, stderr
    assert "not planar" in stdout and json.loads(out.read_text())["format"] == "coatsim.polysegment/2"
    png = plot.read_bytes()
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 20_000 and f"wrote {plot}" in stdout
    code, _, stderr = run_cli(["segment", str(path), "--method", "paper"])
    assert code == 2 and stderr.count("\n") == 1 and "default method only" in stderr
    code, _, stderr = run_cli(["segment", str(path), "--tol", "-1"])
    assert code == 2 and "--tol" in stderr


def test_speed_limits_on_a_space_curve():
    """At v²/a below the helix's radius (40.5 mm) nothing is limited; above it every arc is a
    speed-limited stretch whose v_max is √(a·r)."""
    curve = make_space_curve(FAMILIES["helix"](1500), "helix")
    free = segment_space_curve(curve, 0.1, speed_mm_s=300.0, tool_accel_mm_s2=5000.0)  # v²/a = 18 mm
    assert free.chain.speed_limited == () and free.max_deviation_mm <= 0.1
    fast = segment_space_curve(curve, 0.1, speed_mm_s=600.0, tool_accel_mm_s2=5000.0)  # v²/a = 72 mm
    (s0, s1, v_max), = fast.chain.speed_limited
    assert s0 == 0.0 and s1 == pytest.approx(fast.chain.length)
    assert v_max == pytest.approx(math.sqrt(5000.0 * min(s.radius for s in fast.chain.segments)))
    assert "speed-limited" in fast.summary()
    with pytest.raises(InputError, match="go together"):
        segment_space_curve(curve, 0.1, speed_mm_s=600.0)


def test_a_true_corner_in_space_is_kept():
    """Two helical arcs meeting at 90 degrees: one listed corner there, G1 everywhere else."""
    t = np.linspace(0.0, math.pi, 800)
    first = np.column_stack((40 * np.cos(t), 40 * np.sin(t), 10 * t))
    turn = Pose(np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]), np.zeros(3))
    second = turn.apply(first - first[0]) + first[-1]
    fit = segment_space_curve(make_space_curve(np.vstack((first, second[1:])), "kinked"), 0.1)
    assert len(fit.chain.corners) == 1 and fit.max_deviation_mm <= 0.1
    k = fit.chain.corners[0]
    assert np.allclose(fit.chain.segments[k].end, first[-1])
    assert_g1(fit.chain)


def test_a_sparse_polyline_keeps_its_vertices_as_corners():
    pts = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 5], [0, 10, 10.0]])
    fit = segment_space_curve(make_space_curve(pts, "sparse"), 0.1)
    assert [s.kind for s in fit.chain.segments] == ["line"] * 3 and fit.chain.corners == (0, 1)
    assert fit.max_deviation_mm < 1e-9


@settings(max_examples=15, deadline=None)
@given(st.integers(0, 2**31), st.integers(4, 40), st.sampled_from([0.05, 0.5, 2.0]))
def test_no_tangent_break_is_left_unlisted(seed, n, tol):
    """Whatever the input (random walks in space, sparse or dense), the chain is within σ and
    every junction is tangent-continuous or a listed corner."""
    rng = np.random.default_rng(seed)
    pts = np.cumsum(rng.normal(scale=rng.choice([0.2, 5.0, 30.0]), size=(n, 3)), axis=0)
    try:
        curve = make_space_curve(pts, "walk")
    except InputError:
        return
    fit = segment_space_curve(curve, tol)
    assert fit.max_deviation_mm <= tol
    assert fit.chain.max_tangent_break() <= 1e-9


# --- straight stretches and bends --------------------------------------------------------------
def _leg(a: np.ndarray, b: np.ndarray, step: float = 0.5) -> np.ndarray:
    m = int(math.ceil(np.linalg.norm(b - a) / step))
    return a + (b - a) * np.linspace(0, 1, m + 1)[:-1, None]


def _bend(centre, u, w, radius, sweep, step: float = 0.5) -> np.ndarray:
    m = int(math.ceil(radius * sweep / step))
    t = np.linspace(0, sweep, m + 1)[:-1, None]
    return centre + radius * (u * np.cos(t) + w * np.sin(t))


def pipe_centreline() -> np.ndarray:
    """Line 100, bend r 40 through 90° in XY, line 80, bend r 60 through 90° in YZ, line 120 (mm)."""
    x, y, z = np.eye(3)
    return np.vstack([_leg(np.r_[0.0, 0, 0], np.r_[100.0, 0, 0]), _bend(np.r_[100.0, 40, 0], -y, x, 40, math.pi / 2),
                      _leg(np.r_[140.0, 40, 0], np.r_[140.0, 120, 0]), _bend(np.r_[140.0, 120, 60], -z, y, 60, math.pi / 2),
                      _leg(np.r_[140.0, 180, 60], np.r_[140.0, 180, 180]), [[140.0, 180, 180]]])


@pytest.mark.parametrize("tol", [0.05, 0.1, 0.5])
def test_a_pipe_centreline_comes_back_as_its_lines_and_bends(tol):
    fit = segment_space_curve(make_space_curve(pipe_centreline(), "pipe"), tol)
    segs = fit.chain.segments
    assert [s.kind for s in segs] == ["line", "arc", "line", "arc", "line"] and fit.chain.corners == ()
    assert segs[1].radius == pytest.approx(40, rel=0.01) and segs[3].radius == pytest.approx(60, rel=0.01)
    assert abs(segs[1].normal @ [0, 0, 1]) > 0.999 and abs(segs[3].normal @ [1, 0, 0]) > 0.999
    assert [s.length for s in segs[::2]] == pytest.approx([100, 80, 120], abs=2 * tol)
    assert fit.max_deviation_mm <= tol and brute_hausdorff(fit.curve.points, fit.chain, tol / 20) <= tol * 1.05
    assert_g1(fit.chain)


def _route(seed: int) -> tuple[np.ndarray, int]:
    """Straight legs of 80-200 mm in random directions, turning 30-150° in bends of r 10-50 mm."""
    rng = np.random.default_rng(seed)
    legs = int(rng.integers(2, 5))
    u = rng.normal(size=3)
    u /= np.linalg.norm(u)
    points, here = [], np.zeros(3)
    for k in range(legs):
        length = rng.uniform(80, 200)
        points.append(_leg(here, here + u * length))
        here = here + u * length
        if k < legs - 1:
            turn, radius = rng.uniform(math.radians(30), math.radians(150)), rng.uniform(10, 50)
            w = rng.normal(size=3)
            w -= (w @ u) * u
            w /= np.linalg.norm(w)
            points.append(_bend(here + radius * w, -w, u, radius, turn))
            here = here + radius * w + radius * (-w * math.cos(turn) + u * math.sin(turn))
            u = math.cos(turn) * u + math.sin(turn) * w
    return np.vstack(points + [here[None]]), legs


@pytest.mark.parametrize("seed", range(6))
def test_random_pipe_routes_give_a_line_per_leg_and_an_arc_per_bend(seed):
    points, legs = _route(seed)
    fit = segment_space_curve(make_space_curve(points, "route", "no"), 0.1)
    assert "".join(s.kind[0] for s in fit.chain.segments) == "la" * (legs - 1) + "l"
    assert fit.max_deviation_mm <= 0.1 and fit.chain.corners == ()
    assert_g1(fit.chain)


def test_a_helix_with_straight_leads_keeps_them_as_lines():
    t = np.linspace(0, 4 * math.pi, 1200)
    helix = np.column_stack((50 * np.cos(t), 50 * np.sin(t), 20 * t))
    into = np.array([0, 50, 20.0]) / math.hypot(50, 20)
    out = np.array([-50 * math.sin(t[-1]), 50 * math.cos(t[-1]), 20.0]) / math.hypot(50, 20)
    points = np.vstack((helix[0] - into * np.linspace(100, 0, 200, endpoint=False)[:, None], helix,
                        helix[-1] + out * np.linspace(0, 100, 201)[1:, None]))
    fit = segment_space_curve(make_space_curve(points, "leads"), 0.1)
    segs = fit.chain.segments
    assert segs[0].kind == segs[-1].kind == "line" and segs[0].length > 99 and segs[-1].length > 99
    assert all(s.kind == "arc" for s in segs[1:-1]) and fit.max_deviation_mm <= 0.1
    assert_g1(fit.chain)


def test_a_closed_loop_keeps_its_straight_sides_as_lines_and_its_seam_smooth():
    """A racetrack 200 x 100 mm (corners r 20) bent over a cylinder (z = x² / 500): its short
    sides stay straight, its long sides curve; the loop is fitted from the start of a straight
    side round to it again, G1 across the seam."""
    legs = []
    for k, (p0, p1, c) in enumerate((((-80, -50), (80, -50), (80, -30)), ((100, -30), (100, 30), (80, 30)),
                                      ((80, 50), (-80, 50), (-80, 30)), ((-100, 30), (-100, -30), (-80, -30)))):
        legs.append(_leg(np.r_[p0, 0.0], np.r_[p1, 0.0]))
        t = -math.pi / 2 + k * math.pi / 2
        legs.append(_bend(np.r_[c, 0.0], np.r_[math.cos(t), math.sin(t), 0.0],
                          np.r_[-math.sin(t), math.cos(t), 0.0], 20.0, math.pi / 2))
    flat = np.vstack(legs + [legs[0][:1]])
    points = flat + np.column_stack((0 * flat[:, 0], 0 * flat[:, 0], flat[:, 0] ** 2 / 500))
    fit = segment_space_curve(make_space_curve(points, "racetrack"), 0.1)
    lines = [s for s in fit.chain.segments if s.kind == "line"]
    assert fit.chain.closed and fit.planar_pose is None and fit.chain.corners == () and len(lines) == 2
    assert all(abs(s.direction @ [0, 1, 0]) > 0.9999 and s.length > 55 for s in lines)
    assert fit.max_deviation_mm <= 0.1 and brute_hausdorff(fit.curve.points, fit.chain, 0.005) <= 0.105
    assert_g1(fit.chain) and max(fit.chain.junction_breaks()) < 1e-9  # the seam's too


def filleted_loop(corners: np.ndarray, radius: float) -> np.ndarray:
    """A closed polygon through ``corners`` (k, 3) with every vertex rounded by an arc of
    ``radius`` in the plane of its two legs, from the middle of the first leg, every 0.5 mm."""
    k = len(corners)
    pieces, tangent_points = [], []
    for i in range(k):
        a, v, b = corners[i - 1], corners[i], corners[(i + 1) % k]
        u1, u2 = (v - a) / np.linalg.norm(v - a), (b - v) / np.linalg.norm(b - v)
        turn = math.acos(float(np.clip(u1 @ u2, -1, 1)))
        inward = (u2 - (u2 @ u1) * u1) / np.linalg.norm(u2 - (u2 @ u1) * u1)
        d = radius * math.tan(turn / 2)
        tangent_points.append((v - u1 * d, v + u2 * d))
        pieces.append(_bend(v - u1 * d + inward * radius, -inward, u1, radius, turn))
    start = (corners[0] + corners[1]) / 2
    out = [_leg(start, tangent_points[1][0])]
    for i in range(1, k + 1):
        out += [pieces[i % k], _leg(tangent_points[i % k][1], tangent_points[(i + 1) % k][0] if i < k else start)]
    return np.vstack(out + [start[None]])


@pytest.mark.parametrize("tol", [0.05, 0.2])
def test_a_closed_pipe_loop_in_space_is_a_line_per_leg_and_an_arc_per_bend(tol):
    """A skew quadrilateral (not planar) with every corner bent r 25: a line per leg and an arc
    per bend, but the bend the loop closes on, which may take two (lines in space found from
    points are a hair skew, and each bend re-aims the line after it: the last one cannot also
    keep the first line's direction); it came back as nine arcs, its legs of radius km."""
    corners = np.array([[0.0, 0, 0], [200, 0, 0], [200, 150, 0], [0, 150, 120]])
    fit = segment_space_curve(make_space_curve(filleted_loop(corners, 25.0), "loop", "yes"), tol)
    kinds = "".join(s.kind[0] for s in fit.chain.segments)
    assert fit.planar_pose is None and fit.chain.closed and fit.chain.corners == ()
    assert kinds.count("l") == 4 and kinds.count("a") <= 5 and "ll" not in kinds + kinds[0]
    lines = sorted(s.length for s in fit.chain.segments if s.kind == "line")
    assert lines == pytest.approx([100, 132.2, 150, 173.4], abs=1.0)  # the legs between the tangent points
    assert sum(s.radius == pytest.approx(25, rel=0.01) for s in fit.chain.segments if s.kind == "arc") >= 3
    assert fit.max_deviation_mm <= tol and brute_hausdorff(fit.curve.points, fit.chain, tol / 20) <= tol * 1.05
    assert_g1(fit.chain) and max(fit.chain.junction_breaks()) < 1e-9

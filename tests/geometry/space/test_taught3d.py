"""Sparse space polylines (taught points) fitted between their vertices: a helix taught with a
few points per turn came back as its own lines, a corner at every vertex (29 moves, 29 lines)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.geometry.space.taught import guide3, is_sparse3
from coatsim.geometry.scatter import scatter_mm
from coatsim.geometry.space.nearest import polyline_index

from strategies import rotations
from test_segment3d import assert_g1, brute_hausdorff


def taught_helix(per_turn: int, radius: float, rise: float, turns: int = 3) -> tuple[np.ndarray, float]:
    """A helix taught with ``per_turn`` points a turn, and its chordal deviation (the largest
    distance of the helix from an edge, the same on every edge)."""
    t = np.linspace(0.0, 2 * math.pi * turns, per_turn * turns + 1)
    helix = lambda t: np.column_stack((radius * np.cos(t), radius * np.sin(t), rise * t / (2 * math.pi)))  # noqa: E731
    poly = helix(t)
    inner = helix(np.linspace(0.0, t[1], 2001)) - poly[0]
    d = (poly[1] - poly[0]) / np.linalg.norm(poly[1] - poly[0])
    return poly, float(np.linalg.norm(inner - np.outer(inner @ d, d), axis=1).max())


@settings(max_examples=5, deadline=None)
@given(per_turn=st.integers(6, 12), radius=st.floats(30.0, 80.0), rise=st.floats(10.0, 45.0),
       share=st.floats(0.75, 1.0), rotation=rotations())
def test_a_taught_helix_is_fitted_between_its_vertices(per_turn, radius, rise, share, rotation):
    """σ a share of the chordal deviation: at most half the moves (measured on 46 random helices
    of radius 20–80 mm, rise 10–60 mm a turn: 0.22–0.48 at 6–12 points a turn, 0.40–0.60 at 5;
    at most 0.44 in the ranges drawn here; before, one line per move), within σ by the certified
    check and by a dense oracle, G1 with no corner."""
    poly, sag = taught_helix(per_turn, radius, rise)
    poly = poly @ rotation.T
    tol = share * sag
    fit = segment_space_curve(make_space_curve(poly, "taught helix", "no"), tol)
    assert fit.chain.n_segments <= 0.5 * (len(poly) - 1)
    assert fit.chain.corners == ()
    assert_g1(fit.chain)
    assert fit.max_deviation_mm <= tol
    assert brute_hausdorff(poly, fit.chain, tol / 20) <= tol * 1.05


def test_a_taught_closed_space_curve_is_fitted_between_its_vertices():
    """A wave round a cylinder taught with 30 points (σ 1.05 mm, its chordal deviation): 24
    segments with corners before; now 12, a closed G1 loop."""
    t = np.linspace(0.0, 2 * math.pi, 31)
    poly = np.column_stack((50 * np.cos(t), 50 * np.sin(t), 15 * np.sin(3 * t)))
    poly[-1] = poly[0]
    fit = segment_space_curve(make_space_curve(poly, "taught wave", "yes"), 1.05)
    assert fit.chain.closed and fit.chain.corners == () and fit.chain.n_segments <= 12
    assert fit.max_deviation_mm <= 1.05 and brute_hausdorff(poly, fit.chain, 0.02) <= 1.05 * 1.02


def test_a_taught_corner_is_kept():
    """Two taught helical arcs (12 points a turn, each turning 30°) meeting at a vertex that
    turns 120°: that vertex is a corner, the rest is fitted between the vertices."""
    first, sag = taught_helix(12, 40.0, 20.0, turns=2)
    arrive = first[-1] - first[-2]
    arrive /= np.linalg.norm(arrive)
    side = np.cross(arrive, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    leave = math.cos(math.radians(120)) * arrive + math.sin(math.radians(120)) * side
    turn = Rotation.align_vectors([leave], [first[1] - first[0]])[0].as_matrix()
    poly = np.vstack((first, ((first - first[0]) @ turn.T + first[-1])[1:]))
    fit = segment_space_curve(make_space_curve(poly, "kinked", "no"), sag)
    assert len(fit.chain.corners) == 1
    assert np.allclose(fit.chain.segments[fit.chain.corners[0]].end, first[-1], atol=1e-9)
    assert fit.chain.n_segments < 0.5 * (len(poly) - 1) and fit.max_deviation_mm <= sag
    assert_g1(fit.chain)


@pytest.mark.parametrize("per_turn", [6, 10])
def test_the_guide_runs_between_the_vertices_and_the_edges(per_turn):
    """The guide passes inside each vertex and outside its edges, within σ/2 of both (its
    roundings' apex at most σ), and starts and ends at the polyline's ends."""
    poly, sag = taught_helix(per_turn, 40.0, 30.0)
    assert is_sparse3(poly, False, sag)
    guide = guide3(poly, False, sag, 20.0)
    assert np.array_equal(guide[0], poly[0]) and np.array_equal(guide[-1], poly[-1])
    assert polyline_index(poly)[0].distance(guide)[0].max() <= sag / 2 + 1e-9
    vertex_gap = polyline_index(guide)[0].distance(poly[1:-1])[0]
    assert np.all(vertex_gap > 0.1 * sag) and np.all(vertex_gap <= sag / 2 + 1e-9)


def test_a_dense_curve_is_not_sparse():
    t = np.linspace(0.0, 6 * math.pi, 3000)
    helix = np.column_stack((40 * np.cos(t), 40 * np.sin(t), 5 * t))
    assert not is_sparse3(helix, False, 0.05)


def test_segment_command_on_a_taught_helix(tmp_path, run_cli):
    """A user's taught points (31, ten a turn, written as `x y z` with a header) at σ 2 mm."""
    poly, _ = taught_helix(10, 40.0, 30.0)
    path = tmp_path / "taught.txt"
    np.savetxt(path, poly, header="x y z", fmt="%.4f")
    out = tmp_path / "taught.json"
    code, stdout, stderr = run_cli(["segment", str(path), "--tol", "2", "-o", str(out)])
    assert code == 0, stderr
    doc = json.loads(out.read_text())
    assert doc["format"] == "coatsim.polysegment/2" and doc["corners"] == []
    assert len(doc["segments"]) <= 10 and all(s["kind"] == "arc" for s in doc["segments"])


def test_noisy_dense_points_are_no_taught_polyline_and_say_why_their_arcs_are_tight():
    """A helix on points 0.15 mm apart with noise 0.025 mm at σ 0.1: a few steps are 2σ long and
    turn (noise), which made it 'sparse' (and its guide was fitted for nothing: 21 s); its arcs
    follow the noise with loosened caps, and a note now says the scatter, measured in space."""
    rng = np.random.default_rng(1)
    t = np.linspace(0.0, 2 * math.pi, 1675)
    pts = np.column_stack((40 * np.cos(t), 40 * np.sin(t), 30 * t / (2 * math.pi))) + rng.normal(scale=0.025, size=(1675, 3))
    assert not is_sparse3(pts, False, 0.1)
    fit = segment_space_curve(make_space_curve(pts, "noisy helix", "no"), 0.1)
    assert fit.max_deviation_mm <= 0.1 and fit.limits_kept is False
    assert any("scatter about 0.025 mm" in note for note in fit.notes)
    assert scatter_mm(pts, False) == pytest.approx(0.025, rel=0.1)

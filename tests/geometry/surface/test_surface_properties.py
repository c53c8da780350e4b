"""Properties of plans: a rigid motion moves the passes with the part, a finer mesh barely moves
them, the ripple formula against a direct sum, the file round trip."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.geometry.surface import Facing, FromBoundary, FromPoints, Pass, part_from_arrays, plan
from coatsim.geometry.surface.spacing import ripple_pct, spacing_for_ripple
from coatsim.geometry.surface.surfacepaths import MeshInfo, PlanStats, SurfacePaths, dumps, from_document
from surface_helpers import SPACING, options, tube


def _patch(radius: float, n_around: int, n_along: int) -> tuple[np.ndarray, np.ndarray]:
    """A 110-degree strip of a cylinder about z (facing +x), 120 mm long."""
    vertices, faces = tube(radius, 120.0, n_around, n_along)
    angle = np.arctan2(vertices[:, 1], vertices[:, 0])
    keep = np.all(np.abs(angle[faces]) < math.radians(55.0) + 1e-9, axis=1)
    used, local = np.unique(faces[keep], return_inverse=True)
    return vertices[used], local.reshape(-1, 3)


def _rotation(a: float, b: float, c: float) -> np.ndarray:
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    rz = np.array([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rx = np.array([[1, 0, 0], [0, cc, -sc], [0, sc, cc]])
    return rz @ ry @ rx


PATCH = _patch(60.0, 144, 25)  # no edge at a refinement threshold (5 mm, 2.3 mm)


@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(-math.pi, math.pi), st.floats(-1.5, 1.5), st.floats(-math.pi, math.pi),
       st.tuples(*[st.floats(-500.0, 500.0)] * 3))
def test_a_rigid_motion_moves_the_passes_with_the_part(a, b, c, shift):
    rotation, shift = _rotation(a, b, c), np.array(shift)
    vertices, faces = PATCH
    kw = dict(region=Facing((1.0, 0.0, 0.0)), step_direction=(0.0, 1.0, 0.0), max_edge_mm=2.3)
    here = plan(part_from_arrays(vertices, faces), options(**kw))
    moved_kw = dict(region=Facing(tuple(rotation @ [1.0, 0, 0])), step_direction=tuple(rotation @ [0, 1.0, 0]),
                    max_edge_mm=2.3)
    there = plan(part_from_arrays(vertices @ rotation.T + shift, faces), options(**moved_kw))
    assert len(here.passes) == len(there.passes)
    for p, q in zip(here.passes, there.passes):
        assert len(p.points) == len(q.points)
        assert np.abs(p.points @ rotation.T + shift - q.points).max() < 1e-4
        assert np.abs(p.normals @ rotation.T - q.normals).max() < 1e-6
        assert np.abs(p.lead_in @ rotation.T + shift - q.lead_in).max(initial=0) < 1e-4


def _deviation(coarse: SurfacePaths, fine: SurfacePaths) -> float:
    """Largest distance from a point of a coarse pass to the corresponding fine pass (same order)."""
    from scipy.spatial import cKDTree

    return max(float(cKDTree(q.points).query(p.points)[0].max()) for p, q in zip(coarse.passes, fine.passes))


@pytest.mark.parametrize("pattern, start", [("raster", FromBoundary()), ("geodesic", FromBoundary()),
                                            ("geodesic", FromPoints(((60.0, 0.0, 0.0),))), ("boundary", FromBoundary())])
def test_a_finer_mesh_moves_the_passes_far_less_than_the_spacing(pattern, start):
    kw = dict(pattern=pattern, region=Facing((1.0, 0.0, 0.0)))
    if pattern == "geodesic":
        kw["start"] = start
    else:
        kw["step_direction"] = (0.0, 1.0, 0.0) if pattern == "raster" else None
    coarse = plan(part_from_arrays(*_patch(60.0, 72, 12)), options(max_edge_mm=2.5, **kw))
    fine = plan(part_from_arrays(*_patch(60.0, 144, 24)), options(max_edge_mm=1.25, **kw))
    assert len(coarse.passes) == len(fine.passes)
    assert _deviation(coarse, fine) < 0.1 * SPACING


@given(st.floats(0.5, 50.0), st.floats(0.01, 99.0))
def test_spacing_for_a_ripple_gives_that_ripple(sigma, ripple):
    assert ripple_pct(spacing_for_ripple(ripple, sigma), sigma) == pytest.approx(ripple, rel=1e-9)


@pytest.mark.parametrize("ratio", [1.5, 1.8, 2.0, 2.2])
def test_the_ripple_formula_matches_a_direct_sum_of_tracks(ratio):
    sigma, spacing = 5.0, 5.0 * ratio
    y = np.linspace(0.0, spacing, 2001)
    tracks = np.arange(-30, 31) * spacing
    thickness = np.exp(-0.5 * ((y[:, None] - tracks[None, :]) / sigma) ** 2).sum(axis=1)
    measured = 100 * np.ptp(thickness) / thickness.mean()
    assert ripple_pct(spacing, sigma) == pytest.approx(measured, rel=0.01)


_point = st.tuples(*[st.floats(-1e4, 1e4, allow_nan=False)] * 3)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.lists(_point, min_size=2, max_size=6), st.booleans(), st.integers(0, 2)),
                min_size=0, max_size=4))
def test_the_file_round_trips(raw):
    passes = []
    for points, closed, leads in raw:
        p = np.array(points)
        normals = np.tile([0.0, 0.6, 0.8], (len(p), 1))
        lead = p[:1] - 1.0 if leads and not closed else np.zeros((0, 3))
        passes.append(Pass(p, normals, closed, lead, lead))
    stats = PlanStats(len(passes), 1234.5, 0.98, 9.5, 10.0, 10.5, 5.0, 3.25)
    paths = SurfacePaths(MeshInfo("part.stl", "0" * 64, 10, 12, (700.0, 0, 200, 0, 0, 0)), "geodesic", 10.0, 100.0,
                         2.8768, tuple(passes), stats)
    text = dumps(paths)
    again = from_document(json.loads(text), "paths.json")
    assert dumps(again) == text

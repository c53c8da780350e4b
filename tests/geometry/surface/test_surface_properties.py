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
from coatsim.geometry.surface.shapes import grid_faces
from surface_helpers import SPACING, grid, options, tube


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


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(11.0, 140.0), st.booleans())
def test_raster_gaps_share_the_region_evenly_and_never_exceed_the_spacing(width, curved):
    """A region that is no whole number of spacings wide: every gap along the surface is at most
    the spacing and all are equal (to twice EVEN_FRACTION), the fewest passes that do so, the
    outer passes half a spacing in (a sliver of a step is left at the far end instead of a pass)."""
    from coatsim.geometry.surface.raster import END_SLIVER_FRACTION, EVEN_FRACTION

    if curved:  # a strip of a cylinder of radius 60 mm: the gaps are arcs
        radius = 60.0
        angle = width / radius
        phi = np.linspace(-angle / 2, angle / 2, int(width) + 2)
        z = np.linspace(0.0, 40.0, 5)
        pp, zz = np.meshgrid(phi, z, indexing="ij")
        vertices = np.column_stack([radius * np.cos(pp.ravel()), radius * np.sin(pp.ravel()), zz.ravel()])
        faces = grid_faces(len(phi), len(z))
        kw = dict(region=Facing((1.0, 0.0, 0.0)), step_direction=(0.0, 1.0, 0.0))
    else:
        vertices, faces = grid(40.0, width, 4, int(width) + 1)
        kw = dict(step_direction=(0.0, 1.0, 0.0))
    paths = plan(part_from_arrays(vertices, faces), options(**kw))
    ys = np.sort([float(np.mean(p.points[:, 1])) for p in paths.passes])
    along = radius * np.arcsin(ys / radius) + width / 2 if curved else ys
    gaps = np.diff(along)
    span = width - SPACING  # from the first pass to the last plane, half a spacing in from either end
    facets = 0.02 if curved else 1e-6  # the strip's chords against the arc
    assert along[0] == pytest.approx(SPACING / 2, abs=facets)
    slack = 2 * EVEN_FRACTION * SPACING
    if len(gaps):  # as the planner measures them along the surface
        s = paths.stats
        assert s.spacing_max_mm <= SPACING * (1 + 1e-9) and s.spacing_max_mm - s.spacing_min_mm <= slack
        assert np.ptp(gaps) <= slack + facets
    whole, left = divmod(span, SPACING)
    if abs(left - END_SLIVER_FRACTION * SPACING) > 1e-3:  # not on the sliver rule's edge
        sliver = left <= END_SLIVER_FRACTION * SPACING
        assert len(gaps) == int(whole) + (0 if sliver else 1)
        assert width - along[-1] == pytest.approx(SPACING / 2 + (left if sliver else 0.0), abs=slack + facets)


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

"""Points on a surface (closest point, fields read there) and the coarse copy of a mesh."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.spray.decimate import decimate
from coatsim.spray.locate import locate
from coatsim.spray.surfaces import cylinder, plate

PLATE = plate(120.0, 80.0, 2.0, np.eye(4))


@settings(max_examples=40, deadline=None)
@given(x=st.floats(-59.0, 59.0), y=st.floats(-39.0, 39.0), z=st.floats(-5.0, 5.0))
def test_the_closest_point_of_a_plate_is_straight_below(x, y, z):
    found = locate(PLATE, np.array([[x, y, z]]))
    assert found.distance_mm[0] == pytest.approx(abs(z), abs=1e-9)
    point = found.field(PLATE, PLATE.vertices)[0]
    assert point == pytest.approx([x, y, 0.0], abs=1e-9)
    # a linear field is read exactly
    assert found.field(PLATE, 3.0 * PLATE.vertices[:, 0] - PLATE.vertices[:, 1])[0] == pytest.approx(3 * x - y, abs=1e-9)


def test_points_beyond_the_edge_land_on_it():
    found = locate(PLATE, np.array([[70.0, 0.0, 0.0], [0.0, -50.0, 3.0]]))
    assert found.field(PLATE, PLATE.vertices)[:, :2] == pytest.approx(np.array([[60.0, 0.0], [0.0, -40.0]]), abs=1e-9)
    assert found.distance_mm == pytest.approx([10.0, np.hypot(10.0, 3.0)])


def test_a_point_above_a_cylinder_lands_on_its_surface():
    surface = cylinder(50.0, 60.0, 1.5, "y", np.eye(4))
    found = locate(surface, np.array([[0.0, 0.0, 60.0]]))
    assert found.distance_mm[0] == pytest.approx(10.0, abs=0.05)


@pytest.mark.parametrize("surface", [PLATE, cylinder(50.0, 60.0, 1.0, "y", np.eye(4))], ids=["plate", "cylinder"])
def test_the_coarse_mesh_keeps_the_shape_and_the_field(surface):
    coarse = decimate(surface, 2000)
    assert len(coarse.faces) <= 2000 * 1.15 < len(surface.faces)
    assert coarse.faces.max() < len(coarse.vertices) and len(np.unique(coarse.cluster)) == len(coarse.vertices)
    # every coarse vertex lies close to the fine surface
    assert locate(surface, coarse.vertices).distance_mm.max() < 1.0
    field = np.sin(surface.vertices[:, 0] / 20.0) + 2.0
    on_coarse = coarse.field(field)
    total = np.bincount(coarse.cluster, weights=coarse.weight)
    assert (on_coarse * total).sum() == pytest.approx((field * coarse.weight).sum())  # the area-weighted mean
    assert np.allclose(np.linalg.norm(coarse.normals, axis=1), 1.0)
    assert decimate(surface, 10 ** 7).faces is surface.faces

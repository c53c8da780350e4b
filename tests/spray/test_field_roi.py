"""The ``field`` region of interest: the sprayed band without the edge band along its own border,
the distance measured along the surface."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.spray.coating_metrics import ROI_KINDS, inside
from coatsim.spray.surfaces import Surface, plate


def test_field_is_a_roi_kind() -> None:
    assert "field" in ROI_KINDS


@pytest.mark.parametrize("margin", [0.5, 3.0, 5.0])
def test_inside_a_strip_keeps_what_is_the_margin_from_its_edges(margin: float) -> None:
    """A strip |y| < 10 mm of a 1 mm grid: the vertices at least ``margin`` from the first row
    outside it along the grid's edges are those with |y| <= 10 - margin."""
    surface = plate(60.0, 60.0, 1.0)
    y = surface.vertices[:, 1]
    got = inside(surface, np.abs(y) < 10 - 1e-9, margin)
    assert (got == (np.abs(y) <= 10 - margin + 1e-9)).all()


def test_the_far_side_of_a_thin_part_is_not_near() -> None:
    """Two sheets 1 mm apart, not joined: all of the upper one is far from the lower along the surface."""
    top, bottom = plate(40.0, 40.0, 2.0), plate(40.0, 40.0, 2.0, np.diag([1.0, 1.0, 1.0, 1.0]))
    vertices = np.vstack([top.vertices + [0, 0, 1.0], bottom.vertices])
    faces = np.vstack([top.faces, bottom.faces + top.n_vertices])
    both = Surface("two", "mesh", vertices, faces, np.tile([0, 0, 1.0], (len(vertices), 1)),
                   np.ones(len(vertices)), vertices[:, :2], ("x", "y"))
    mask = np.arange(len(vertices)) < top.n_vertices
    assert (inside(both, mask, 5.0) == mask).all()


def test_a_zero_margin_or_a_full_mask_changes_nothing() -> None:
    surface = plate(10.0, 10.0, 1.0)
    mask = surface.vertices[:, 0] > 0
    assert (inside(surface, mask, 0.0) == mask).all()
    assert inside(surface, np.ones(surface.n_vertices, bool), 3.0).all()

"""The ``field`` region of interest: the sprayed band without the edge band along its own border."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.distance import cdist

from coatsim.spray.coating_metrics import ROI_KINDS, inside


def test_field_is_a_roi_kind() -> None:
    assert "field" in ROI_KINDS


@pytest.mark.parametrize("margin", [0.0, 0.7, 2.5])
def test_inside_keeps_the_vertices_at_least_the_margin_from_the_outside(margin: float) -> None:
    rng = np.random.default_rng(3)
    vertices = rng.uniform(-10, 10, size=(400, 3))
    mask = np.linalg.norm(vertices, axis=1) < 8
    got = inside(vertices, mask, margin)
    nearest = cdist(vertices, vertices[~mask]).min(axis=1)
    assert (got == (mask & (nearest >= margin))).all()


def test_inside_of_everything_is_everything() -> None:
    vertices = np.zeros((3, 3))
    mask = np.ones(3, dtype=bool)
    assert inside(vertices, mask, 5.0).all()

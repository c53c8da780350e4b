"""The heat maps' pixel grid: a field linear in the view is reproduced at every pixel centre on
the part, pixels off the part are empty, and any triangulation of the same region gives the
same image of such a field."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import Delaunay

from coatsim.report.raster import view_raster
from coatsim.spray.surfaces import cylinder, plate


def centres(raster) -> np.ndarray:
    """Pixel centres (rows * columns, 2) in view mm, row-major, row 0 at the bottom."""
    x0, x1, y0, y1 = raster.extent
    rows, cols = raster.shape
    x = x0 + (np.arange(cols) + 0.5) * (x1 - x0) / cols
    y = y0 + (np.arange(rows) + 0.5) * (y1 - y0) / rows
    xx, yy = np.meshgrid(x, y)
    return np.column_stack((xx.ravel(), yy.ravel()))


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10_000), st.integers(20, 200), st.tuples(*[st.floats(-5.0, 5.0)] * 3))
def test_a_linear_field_is_exact_on_the_part_and_empty_off_it(seed, columns, coefficients) -> None:
    rng = np.random.default_rng(seed)
    points = rng.uniform(-40.0, 40.0, (200, 2)) * [1.0, 0.6]
    hull = Delaunay(points)
    raster = view_raster(points, hull.simplices, columns)
    a, b, c = coefficients
    image = raster.image(a + b * points[:, 0] + c * points[:, 1]).ravel()
    p = centres(raster)
    on = ~np.isnan(image)
    np.testing.assert_allclose(image[on], a + b * p[on, 0] + c * p[on, 1], atol=1e-9 * (1 + abs(b) + abs(c)) * 40)
    inside = hull.find_simplex(p, tol=-1e-7) >= 0     # inside by a margin
    outside = hull.find_simplex(p, tol=1e-7) < 0      # outside by a margin
    assert on[inside].all() and not on[outside].any()


def test_a_plate_fills_its_grid_and_a_cylinder_its_unrolled_view() -> None:
    for surface in (plate(120.0, 60.0, 2.0), cylinder(20.0, 90.0, 2.5, "y")):
        raster = view_raster(surface.view, surface.faces, 100)
        assert raster.shape[1] == 100
        image = raster.image(surface.view[:, 0])
        assert not np.isnan(image).any()
        lo, hi = surface.view.min(axis=0), surface.view.max(axis=0)
        assert raster.extent[0] == lo[0] and raster.extent[1] == hi[0]
        assert raster.extent[2] == lo[1] and raster.extent[3] >= hi[1]

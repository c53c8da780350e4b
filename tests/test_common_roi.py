"""A run measures every variant's coating on the same region of interest."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.report.results import VariantRun
from coatsim.run.pipeline import on_common_roi
from coatsim.spray.coat import coat
from coatsim.spray.deposition import SprayModel
from coatsim.spray.footprints import Gaussian
from coatsim.spray.surfaces import plate

from spray.spray_helpers import line_log


def _run(name: str, y_mm: float, surface, model) -> VariantRun:
    # two passes 0.3 mm apart sit on either side of the band edge of a row of vertices
    result = coat(line_log([-40.0, y_mm, 100.0], [40.0, y_mm, 100.0], speed=200.0), surface, model,
                  target_um=10.0, band_halfwidth_mm=5.0, edge_band_mm=5.0)
    return VariantRun(name, None, None, result, {"coating": {"thickness_cv": result.metrics["thickness_cv"]}})


def test_every_variant_is_measured_on_the_vertices_all_bands_share():
    surface = plate(120.0, 60.0, 2.5)
    model = SprayModel(Gaussian(5.0), 40.0, 100.0)
    runs = [_run("polysegment", 0.1, surface, model), _run("polyline-blend", -0.2, surface, model)]
    own = [r.coating.roi for r in runs]
    assert not np.array_equal(*own)
    measured = on_common_roi(runs, 10.0)
    common = own[0] & own[1]
    for before, after in zip(runs, measured):
        assert np.array_equal(after.coating.roi, common)
        assert after.coating.metrics["roi_vertices"] == int(common.sum())
        assert after.groups["coating"]["thickness_cv"] == pytest.approx(after.coating.metrics["thickness_cv"])
        assert np.array_equal(after.coating.thickness_um, before.coating.thickness_um)
    # measured on the same vertices, the two passes are as even as each other
    cvs = [r.coating.metrics["thickness_cv"] for r in measured]
    assert cvs[0] == pytest.approx(cvs[1], rel=0.05)


def test_disjoint_regions_are_an_input_error():
    surface = plate(120.0, 60.0, 2.5)
    model = SprayModel(Gaussian(5.0), 40.0, 100.0)
    runs = [_run("polysegment", 15.0, surface, model), _run("polyline-blend", -15.0, surface, model)]
    with pytest.raises(InputError, match="share no vertex"):
        on_common_roi(runs, 10.0)

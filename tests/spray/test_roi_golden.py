"""The region of interest computed only as far as the edge band needs gives byte-identical
coating results: the golden fingerprints were written with the full border distance. The ROI
mask and the thickness field must match bit for bit; the metrics are sums over them, whose last
bit depends on numpy's summation order (it differs between numpy builds), so they match to 1e-13."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.spray.coat import coat
from coatsim.spray.coating_metrics import away_from_border
from coatsim.spray.surfaces import border_distance, cylinder, plate
from roi_cases import GOLDEN, cases, fingerprint
from spray_helpers import gun


@pytest.fixture(scope="module")
def golden() -> dict:
    return json.loads(GOLDEN.read_text(encoding="utf-8"))


@pytest.mark.parametrize("name", ["plate band", "plate part edge 4", "cylinder band", "mesh part"])
def test_coat_results_are_byte_identical_to_the_golden_file(name, golden, tmp_path):
    kwargs = dict(cases(tmp_path))[name]
    found, expected = fingerprint(coat(model=gun(), **kwargs)), golden[name]
    assert (found["roi_sha256"], found["thickness_sha256"]) == (expected["roi_sha256"], expected["thickness_sha256"])
    assert found["metrics"].keys() == expected["metrics"].keys()
    for key, value in expected["metrics"].items():
        assert float(found["metrics"][key]) == pytest.approx(float(value), rel=1e-13, abs=0.0), key


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["plate", "cylinder"]), st.floats(0.0, 40.0), st.sampled_from([1.0, 2.5, 4.0]))
def test_a_bounded_border_search_keeps_every_distance_inside_the_band(kind, edge, spacing):
    """Up to the band the bounded distance equals the full one (same floats), beyond it is inf;
    so the mask `distance >= band` is the same either way, also for vertices exactly on it."""
    surface = plate(100, 70, spacing) if kind == "plate" else cylinder(30, 90, spacing, "y")
    full = border_distance(surface, spacing)
    bounded = border_distance(surface, spacing, within_mm=edge)
    inside = full < edge
    np.testing.assert_array_equal(bounded[inside], full[inside])
    assert np.all(bounded[~inside] >= edge)
    np.testing.assert_array_equal(away_from_border(surface, edge, spacing), full >= edge)

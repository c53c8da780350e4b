"""The metric catalogue, the generated metrics reference page and the assembled metrics document agree."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.primitives import Line
from coatsim.report.catalogue import GROUPS, METRICS, markdown_table, names
from coatsim.report.metrics import assemble, coating_group, plain, segmentation_group, to_json


def test_the_reference_page_lists_exactly_the_catalogue(reference_metric_names: list[str]) -> None:
    assert reference_metric_names == list(METRICS)


def test_markdown_table_has_three_cells_per_row() -> None:
    for row in markdown_table().splitlines():
        assert row.count("|") == 4, row


def test_every_metric_has_a_group_unit_and_meaning() -> None:
    for key, info in METRICS.items():
        group, _, name = key.partition(".")
        assert group in GROUPS and name and info.unit and info.meaning


def _groups(value: float) -> dict:
    return {g: {n: value for n in names(g)} for g in GROUPS}


def test_assemble_orders_groups_and_replaces_nan_by_null() -> None:
    doc = assemble({"name": "x"}, {"polysegment": _groups(float("nan")), "polyline-stop": _groups(np.float64(2.0))}, [])
    assert list(doc) == ["format", "mode", "scenario", "variants", "warnings", "gates", "passed"]
    assert doc["warnings"] == []
    assert doc["variants"]["polysegment"]["coating"]["thickness_cv"] is None
    assert type(doc["variants"]["polyline-stop"]["motion"]["speed_cv"]) is float
    assert json.loads(to_json(doc)) == doc
    assert doc["passed"] is True


def test_assemble_rejects_a_group_that_does_not_match_the_catalogue() -> None:
    groups = _groups(1.0)
    groups["motion"]["surprise"] = 1.0
    with pytest.raises(ValueError, match="extra"):
        assemble({}, {"polysegment": groups}, [])


def test_plain_converts_numpy_values() -> None:
    assert plain({"a": np.int64(3), "b": [np.float32(1.5), np.bool_(True)], "c": float("inf")}) == \
        {"a": 3, "b": [1.5, True], "c": None}


def test_segmentation_group_of_a_line_arc_chain_and_of_a_polyline() -> None:
    poly = Polysegment(chain((0.0, 0.0), 0.0, [0.0, 1 / 20, 0.0], [40.0, 10 * math.pi, 40.0]))
    points, _ = poly.sample(0.05)
    g = segmentation_group(points, poly, 0.1, 20.0)
    assert (g["n_segments"], g["n_arcs"], g["n_lines"], g["n_corners"]) == (3, 1, 2, 0)
    chord = 10 * math.pi / math.ceil(10 * math.pi / 0.05)
    assert g["max_deviation_mm"] == pytest.approx(chord**2 / (8 * 20), rel=1e-3)  # sagitta of the arc's chords
    assert g["max_tangent_break_deg"] < 1e-9
    assert g["curve_length_mm"] == pytest.approx(80 + 10 * math.pi)
    assert g["max_curvature_jump_per_mm"] == pytest.approx(1 / 20)  # line -> arc of radius 20 -> line
    # a square corner and a 10-degree kink
    kink = math.radians(10)
    lines = Polysegment((Line((0.0, 0.0), (10.0, 0.0)), Line((10.0, 0.0), (10.0, 10.0)),
                         Line((10.0, 10.0), (10.0 - 10 * math.sin(kink), 10.0 + 10 * math.cos(kink)))))
    g = segmentation_group(np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]), lines, 0.1, 20.0)
    assert g["n_corners"] == 1
    assert g["max_tangent_break_deg"] == pytest.approx(10.0)
    assert g["max_curvature_jump_per_mm"] == 0.0
    assert g["max_deviation_mm"] == pytest.approx(10.0)  # the third line ends 10 mm past the input


def test_coating_group_takes_the_catalogue_names_and_derives_mass_balance() -> None:
    stage = {n: 1.0 for n in names("coating")} | {"deposited_volume_mm3": 99.0, "sprayed_volume_mm3": 100.0,
                                                    "roi_area_mm2": 5.0}
    g = coating_group(stage)
    assert sorted(g) == sorted(names("coating"))
    assert g["mass_balance_error"] == pytest.approx(0.01)

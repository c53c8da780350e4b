"""Sweep files: schema errors name the key and the line; points, their ids and their axes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.sweep.points import expand, point_id
from coatsim.sweep.spec import load_sweep

from sweep_helpers import BASE, SWEEP, write_case


def expand_text(tmp_path: Path, text: str, base: str = BASE):
    return expand(load_sweep(write_case(tmp_path, text, base)))


def error_of(tmp_path: Path, text: str, base: str = BASE) -> str:
    with pytest.raises(InputError) as info:
        expand_text(tmp_path, text, base)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_grid_product_then_points_with_base_values_filled(tmp_path):
    axes, points = expand_text(tmp_path, SWEEP)
    assert axes == ("motion.speed_mm_s", "segmentation.tolerance_mm", "workpiece.pose.position_mm")
    assert [dict(p.axes) for p in points] == [
        {"motion.speed_mm_s": 150.0, "segmentation.tolerance_mm": 0.05, "workpiece.pose.position_mm": [700.0, 0.0, 200.0]},
        {"motion.speed_mm_s": 150.0, "segmentation.tolerance_mm": 0.2, "workpiece.pose.position_mm": [700.0, 0.0, 200.0]},
        {"motion.speed_mm_s": 250.0, "segmentation.tolerance_mm": 0.05, "workpiece.pose.position_mm": [700.0, 0.0, 200.0]},
        {"motion.speed_mm_s": 250.0, "segmentation.tolerance_mm": 0.2, "workpiece.pose.position_mm": [700.0, 0.0, 200.0]},
        {"motion.speed_mm_s": 200.0, "segmentation.tolerance_mm": 0.1, "workpiece.pose.position_mm": [2000.0, 0.0, 200.0]},
    ]
    assert len({p.id for p in points}) == 5
    assert all(p.invalid is None and p.scenario is not None for p in points)
    assert points[0].scenario["motion"]["speed_mm_s"] == 150.0
    assert points[0].scenario["segmentation"]["tolerance_mm"] == 0.05
    assert points[4].scenario["workpiece"]["pose"]["position_mm"] == [2000.0, 0.0, 200.0]


@pytest.mark.parametrize("sweep, expected", [
    ("base: scenario/base.yaml\ngrid:\n  motion.sped_mm_s: [100, 200]\n",
     "sweep.yaml:3: grid.motion.sped_mm_s: unknown scenario key; did you mean 'speed_mm_s'?"),
    ("base: scenario/base.yaml\npoints:\n  - {gun.standoff_mm: 90}\n  - {gunn.standoff_mm: 90}\n",
     "sweep.yaml:4: points[1].gunn.standoff_mm: gunn: unknown scenario key; did you mean 'gun'?"),
    ("base: scenario/base.yaml\ngrid:\n  workpiece.radius_mm: [10]\n",
     "sweep.yaml:3: grid.workpiece.radius_mm: unknown scenario key; allowed: kind, pose, size_mm"),
    ("base: scenario/base.yaml\ngrid:\n  motion.speed_mm_s: [100, fast]\n",
     "sweep.yaml:3: grid.motion.speed_mm_s: Input should be a valid number (got 'fast')"),
    ("base: scenario/base.yaml\npoints:\n  - {gun.signal: 1.5}\n",
     "sweep.yaml:3: points[0].gun.signal: Input should be a valid integer"),
    ("base: scenario/base.yaml\ngrid:\n  segmentation.method: [optimal, papper]\n",
     "sweep.yaml:3: grid.segmentation.method: Input should be 'optimal' or 'paper' (got 'papper')"),
    ("base: scenario/base.yaml\ngrid:\n  motion.speed_mm_s.fast: [1]\n",
     "sweep.yaml:3: grid.motion.speed_mm_s.fast: motion.speed_mm_s is not a mapping"),
    ("base: scenario/base.yaml\ngrid:\n  gates.3.threshold: [1]\n",
     "sweep.yaml:3: grid.gates.3.threshold: no list item 3 in the base scenario"),
    ("base: scenario/base.yaml\ngrid:\n  variants: [[polysegment]]\n  gates.0.variant: [polyline-stop]\n",
     "sweep.yaml:4: grid.gates.0.variant: makes the scenario invalid: gates[0].variant: variant 'polyline-stop' is not run"),
])
def test_bad_key_or_type_names_the_key_and_line(tmp_path, sweep, expected):
    assert expected in error_of(tmp_path, sweep)


@pytest.mark.parametrize("sweep, expected", [
    ("base: scenario/base.yaml\nfast: yes please\ngrid: {motion.speed_mm_s: [1]}\n",
     "sweep.yaml:2: fast: Input should be a valid boolean"),
    ("base: scenario/base.yaml\ngrid: {motion.speed_mm_s: 100}\n",
     "sweep.yaml:2: grid.motion.speed_mm_s: Input should be a valid list"),
    ("base: scenario/base.yaml\ngrid: {motion.speed_mm_s: []}\n", "motion.speed_mm_s: give at least one value"),
    ("base: scenario/base.yaml\ngird: {motion.speed_mm_s: [1]}\n", "sweep.yaml:2: gird: unknown key; did you mean 'grid'?"),
    ("base: scenario/base.yaml\n", "a sweep needs 'grid'"),
    ("grid: {motion.speed_mm_s: [1]}\n", "base: required key is missing"),
    ("base: scenario/base.yaml\ngrid: {'motion..speed': [1]}\n", "is not a dotted scenario key"),
    ("base: scenario/base.yaml\ngrid: {motion.speed_mm_s: [1]}\nmetrics: [coating.thickness_vc]\n",
     "sweep.yaml:3: metrics[0]: unknown metric 'coating.thickness_vc'; did you mean 'coating.thickness_cv'?"),
    ("base: scenario/nothere.yaml\ngrid: {motion.speed_mm_s: [1]}\n", "nothere.yaml: no such file"),
    ("base: scenario/base.yaml\ngrid: {motion.speed_mm_s: [100, 200]}\npoints:\n  - {motion.speed_mm_s: 200.0}\n",
     "sweep.yaml:4: points[0] repeats the grid point motion.speed_mm_s=200"),
])
def test_bad_sweep_file(tmp_path, sweep, expected):
    assert expected in error_of(tmp_path, sweep)


def test_out_of_range_value_is_an_invalid_point_not_a_file_error(tmp_path):
    _, points = expand_text(tmp_path, "base: scenario/base.yaml\ngrid: {motion.speed_mm_s: [100, -5, 0]}\n")
    assert [p.invalid for p in points] == [
        None,
        "motion.speed_mm_s: Input should be greater than 0 (got -5)",
        "motion.speed_mm_s: Input should be greater than 0 (got 0)",
    ]
    assert points[1].scenario is None and points[1].axes["motion.speed_mm_s"] == -5


def test_cli_bad_sweep_file_exits_2_with_one_line(tmp_path, run_cli):
    path = write_case(tmp_path, "base: scenario/base.yaml\ngrid:\n  motion.sped_mm_s: [100]\n")
    code, out, err = run_cli(["sweep", str(path), "-o", str(tmp_path / "out")])
    assert code == 2
    assert err.strip().splitlines() == [
        f"coatsim: error: {path}:3: grid.motion.sped_mm_s: unknown scenario key; did you mean 'speed_mm_s'?"]
    assert not (tmp_path / "out").exists()


values = st.one_of(st.integers(-1000, 1000), st.floats(-1e3, 1e3, allow_nan=False), st.booleans(),
                   st.text("abc:=", max_size=5))


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.dictionaries(st.sampled_from(["a.b", "c", "d.0.e", "x_y.z"]), values, min_size=1))
def test_point_id_is_stable_under_key_order_and_int_float_spelling(params):
    reordered = dict(reversed(list(params.items())))
    as_float = {k: float(v) if isinstance(v, int) and not isinstance(v, bool) else v for k, v in params.items()}
    assert point_id(params) == point_id(reordered) == point_id(as_float)
    assert len(point_id(params)) == 64 and int(point_id(params), 16) >= 0
    changed = dict(params, extra_key=1)
    assert point_id(changed) != point_id(params)


def test_ids_do_not_depend_on_the_order_of_the_sweep_file(tmp_path):
    a = expand_text(tmp_path / "a", SWEEP)[1]
    swapped = SWEEP.replace("  motion.speed_mm_s: [150, 250]\n  segmentation.tolerance_mm: [0.05, 0.2]\n",
                            "  segmentation.tolerance_mm: [0.2, 0.05]\n  motion.speed_mm_s: [250.0, 150]\n")
    b = expand_text(tmp_path / "b", swapped)[1]
    assert sorted(p.id for p in a) == sorted(p.id for p in b)
    by_id = {p.id: json.dumps(p.scenario, sort_keys=True) for p in a}
    assert all(by_id[p.id] == json.dumps(p.scenario, sort_keys=True) for p in b)


@pytest.mark.parametrize("path", sorted((Path(__file__).resolve().parents[2] / "sweeps").glob("*.yaml")),
                         ids=lambda p: p.name)
def test_shipped_sweeps_expand_into_valid_points(path):
    axes, points = expand(load_sweep(path))
    assert axes and len(points) >= 2 and all(p.invalid is None for p in points)
    assert len({p.id for p in points}) == len(points)

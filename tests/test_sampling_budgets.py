"""Curves sampled coarser than their own features and polysegments longer than a program are
refused before the work, with the count, the budget and what would fix it."""

from __future__ import annotations

import json

import numpy as np
import pytest

from cli_helpers import cli
from coatsim.core.budgets import BudgetExceeded
from coatsim.geometry.builtin_curves import parse_builtin_spec
from coatsim.geometry.sampling_check import check_sampling, reversals


def test_a_finely_sampled_curve_never_doubles_back_and_a_zigzag_always_does():
    t = np.linspace(0, 2 * np.pi, 2000)
    assert reversals(np.c_[np.cos(t), np.sin(t)]) == 0
    zigzag = np.c_[np.arange(50.0), np.arange(50) % 2 * 5.0]
    assert reversals(zigzag) == 48
    assert reversals(np.repeat(zigzag, 3, axis=0)) == 48  # repeated points are skipped, not counted
    assert reversals(np.c_[np.arange(5.0), np.zeros(5), np.arange(5) % 2 * 5.0]) == 3  # 3-D points too


def test_random_points_double_back_at_about_a_third_of_them_or_more():
    """Uniform random chord directions turn by more than 90 degrees half the time."""
    points = np.random.default_rng(3).uniform(0, 100, (4000, 2))
    assert 0.3 < reversals(points) / 3998 < 0.9


@pytest.mark.parametrize("spec", ["builtin:sine:wavelength=1e-6", "builtin:paper-spiral:turns=1e6"])
def test_builtins_with_more_features_than_points_are_refused_before_the_fit(spec):
    curve = parse_builtin_spec(spec)
    with pytest.raises(BudgetExceeded, match="doubles back.*curve_reversals"):
        check_sampling(curve.points, curve.name)


def test_shipped_builtins_are_within_the_budget():
    for spec in ("builtin:ellipse", "builtin:paper-spiral", "builtin:sine", "builtin:raster", "builtin:polygon"):
        curve = parse_builtin_spec(spec)
        check_sampling(curve.points, curve.name)


def test_random_points_are_refused_by_segment_in_one_line(tmp_path):
    path = tmp_path / "r.csv"
    np.savetxt(path, np.random.default_rng(1).uniform(0, 100, (3000, 2)), delimiter=",")
    code, _, err = cli("segment", path, "--tol", "0.1")
    assert code == 2 and err.count("\n") == 1, err
    assert "doubles back" in err and "--budget curve_reversals=N" in err


def test_random_points_in_space_are_refused_by_segment_in_one_line(tmp_path):
    """The 3-D fit holds the same rule: x, y, z columns of random points are refused before it."""
    path = tmp_path / "r3.csv"
    np.savetxt(path, np.random.default_rng(2).uniform(0, 100, (3000, 3)), delimiter=",")
    code, _, err = cli("segment", path, "--tol", "0.1")
    assert code == 2 and err.count("\n") == 1, err
    assert "doubles back" in err and "--budget curve_reversals=N" in err


def test_a_polysegment_with_more_segments_than_program_lines_is_refused_before_the_program(tmp_path, monkeypatch):
    monkeypatch.setenv("COATSIM_BUDGET", "")  # the in-process command sets it: restored afterwards
    doc = {"format": "coatsim.polysegment/1", "units": "mm", "closed": False, "tolerance_mm": 0.1, "corners": [],
           "segments": [{"kind": "line", "start": [i, 0.0], "end": [i + 1.0, 0.0]} for i in range(50)]}
    (tmp_path / "p.json").write_text(json.dumps(doc))
    code, _, err = cli("--budget", "program_lines=40", "program", tmp_path / "p.json", "-o", tmp_path / "p.as")
    assert code == 2 and err.count("\n") == 1, err
    assert "at least one move for each of its 50 segments: 54 needed, over the budget of 40" in err
    assert not (tmp_path / "p.as").exists()

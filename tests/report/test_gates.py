"""Gate evaluation over a metrics dict."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import pytest
from hypothesis import given
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.report.gates import OPERATORS, evaluate_gate, evaluate_gates, metric_value

VARIANTS = {
    "polysegment": {"coating": {"thickness_cv": 0.05, "n": 3}, "motion": {"n_stops": 0, "speed_cv": None}},
    "polyline-stop": {"coating": {"thickness_cv": 0.20, "n": 3}, "motion": {"n_stops": 17, "speed_cv": 0.3}},
}


@dataclass(frozen=True)
class Gate:
    metric: str
    op: str
    threshold: Optional[float] = None
    compare_to: Optional[str] = None
    factor: float = 1.0
    variant: str = "polysegment"


def test_threshold_gate_passes_and_fails() -> None:
    assert evaluate_gate(Gate("coating.thickness_cv", "<", 0.1), VARIANTS).passed
    result = evaluate_gate(Gate("coating.thickness_cv", "<", 0.01), VARIANTS)
    assert not result.passed and result.value == 0.05 and result.reference == 0.01
    assert result.label == "coating.thickness_cv [polysegment] < 0.01"


def test_comparison_gate_uses_factor_times_other_variant() -> None:
    r = evaluate_gate(Gate("coating.thickness_cv", "<", compare_to="polyline-stop"), VARIANTS)
    assert r.passed and r.reference == pytest.approx(0.20)
    r = evaluate_gate(Gate("coating.thickness_cv", "<", compare_to="polyline-stop", factor=0.2), VARIANTS)
    assert not r.passed and r.reference == pytest.approx(0.04)
    assert r.label == "coating.thickness_cv [polysegment] < 0.2 x polyline-stop"


def test_equality_and_counts() -> None:
    assert evaluate_gate(Gate("motion.n_stops", "==", 0), VARIANTS).passed
    assert not evaluate_gate(Gate("motion.n_stops", "==", 0, variant="polyline-stop"), VARIANTS).passed


def test_undefined_metric_fails_the_gate() -> None:
    r = evaluate_gate(Gate("motion.speed_cv", "<", 1.0), VARIANTS)
    assert r.value is None and not r.passed
    r = evaluate_gate(Gate("motion.speed_cv", ">", compare_to="polysegment", variant="polyline-stop"), VARIANTS)
    assert r.reference is None and not r.passed


@pytest.mark.parametrize("metric", ["coating.thickness", "cost.total", "thickness_cv"])
def test_unknown_metric_is_an_input_error_listing_known_ones(metric: str) -> None:
    with pytest.raises(InputError, match="unknown metric") as info:
        metric_value(VARIANTS, "polysegment", metric)
    assert "coating.thickness_cv" in str(info.value)


def test_unknown_variant_is_an_input_error() -> None:
    with pytest.raises(InputError, match="not run"):
        evaluate_gates([Gate("coating.thickness_cv", "<", compare_to="polyline-blend")], VARIANTS)


@given(value=st.floats(-1e6, 1e6), threshold=st.floats(-1e6, 1e6), op=st.sampled_from(sorted(OPERATORS)))
def test_gate_agrees_with_python_comparison(value: float, threshold: float, op: str) -> None:
    variants = {"polysegment": {"motion": {"x": value}}}
    expected = {"<": value < threshold, "<=": value <= threshold, ">": value > threshold,
                ">=": value >= threshold, "==": value == threshold}[op]
    assert evaluate_gate(Gate("motion.x", op, threshold), variants).passed is expected


THREE = {
    "polysegment": {"coating": {"thickness_cv": 0.10}, "motion": {"min_speed_ratio": 0.99, "n": 2}},
    "polyline-stop": {"coating": {"thickness_cv": 0.40}, "motion": {"min_speed_ratio": 0.01, "n": 2}},
    "polyline-blend": {"coating": {"thickness_cv": 0.09}, "motion": {"min_speed_ratio": None, "n": 3}},
}
BOTH = ("polyline-stop", "polyline-blend")


def test_best_of_several_variants_is_the_strictest_reference() -> None:
    r = evaluate_gate(Gate("coating.thickness_cv", "<=", compare_to=BOTH, factor=1.05), THREE)
    assert not r.passed and r.reference == pytest.approx(0.0945) and r.reference_variant == "polyline-blend"
    assert r.label == "coating.thickness_cv [polysegment] <= 1.05 x best of (polyline-stop, polyline-blend)"
    r = evaluate_gate(Gate("coating.thickness_cv", "<=", compare_to=BOTH, factor=1.2), THREE)
    assert r.passed and r.compare_to == BOTH
    ratio = evaluate_gate(Gate("motion.min_speed_ratio", ">=", compare_to=["polyline-stop"]), THREE)
    assert ratio.passed and ratio.label == "motion.min_speed_ratio [polysegment] >= best of (polyline-stop)"


def test_best_of_fails_when_any_compared_value_is_undefined() -> None:
    r = evaluate_gate(Gate("motion.min_speed_ratio", ">=", compare_to=BOTH), THREE)
    assert not r.passed and r.reference is None and r.reference_variant == "polyline-blend"


def test_best_of_equality_holds_only_against_every_variant() -> None:
    r = evaluate_gate(Gate("motion.n", "==", compare_to=BOTH), THREE)
    assert not r.passed and r.reference == 3 and r.reference_variant == "polyline-blend"
    assert evaluate_gate(Gate("motion.n", "==", compare_to=["polyline-stop"]), THREE).passed


values = st.floats(-1e6, 1e6, allow_nan=False)


@given(values, st.lists(values, min_size=1, max_size=4), st.sampled_from(sorted(OPERATORS)),
       st.floats(0.5, 2.0))
def test_best_of_passes_exactly_when_every_single_comparison_passes(mine, others, op, factor) -> None:
    names = [f"v{k}" for k in range(len(others))]
    variants = {"me": {"g": {"m": mine}}, **{n: {"g": {"m": x}} for n, x in zip(names, others)}}
    best = evaluate_gate(Gate("g.m", op, compare_to=tuple(names), factor=factor, variant="me"), variants)
    each = [evaluate_gate(Gate("g.m", op, compare_to=n, factor=factor, variant="me"), variants).passed for n in names]
    assert best.passed == all(each)

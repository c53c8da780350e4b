"""The verdict: what the polysegment wins and loses against each polyline, in words and %."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from coatsim.report.verdict import CRITERIA, TIE_RELATIVE, compare, verdict


def variant(cycle=2.0, ratio=0.99, at_speed=0.98, cv=0.05, thick=0.0):
    return {"motion": {"cycle_time_s": cycle, "min_speed_ratio": ratio, "fraction_at_speed": at_speed},
            "coating": {"thickness_cv": cv, "thick_spot_fraction": thick}}


def document(**variants):
    return {"variants": {k.replace("_", "-"): v for k, v in variants.items()}}


def test_a_loss_is_named_with_its_percentage():
    doc = document(polysegment=variant(cv=0.0873), polyline_stop=variant(cycle=3.0, ratio=0.01, cv=0.55, thick=0.25),
                   polyline_blend=variant(cycle=2.1, ratio=0.71, at_speed=0.87, cv=0.0654))
    stop, blend = verdict(doc).comparisons
    assert stop.against == "polyline-stop" and not stop.by("loss")
    assert [o.criterion.label for o in blend.by("loss")] == ["thickness CV"]
    assert blend.by("loss")[0].change_pct == pytest.approx(100 * (0.0873 - 0.0654) / 0.0654)
    assert "loses thickness CV (+33.5 %)" in blend.headline
    assert blend.headline.startswith("Against polyline-blend, the polysegment wins cycle time (-4.8 %), lowest speed")
    assert "ties thick spots" in blend.headline
    assert "wins nothing" not in blend.headline and "loses nothing" in stop.headline


def test_equal_runs_tie_everywhere_and_say_so():
    doc = document(polysegment=variant(), polyline_blend=variant(cv=0.05 * (1 + TIE_RELATIVE / 2)))
    (blend,) = verdict(doc).comparisons
    assert all(o.outcome == "tie" for o in blend.outcomes)
    assert "wins nothing; loses nothing; ties cycle time" in blend.headline


def test_undefined_and_zero_references():
    doc = document(polysegment=variant(ratio=None, thick=0.02), polyline_blend=variant(thick=0.0))
    (blend,) = verdict(doc).comparisons
    ratio = next(o for o in blend.outcomes if o.criterion.key == "motion.min_speed_ratio")
    thick = next(o for o in blend.outcomes if o.criterion.key == "coating.thick_spot_fraction")
    assert ratio.outcome == "undefined" and ratio.change_pct is None
    assert thick.outcome == "loss" and thick.change_pct is None
    assert "loses thick spots (0.02 vs 0)" in blend.headline and "cannot compare lowest speed" in blend.headline


def test_huge_gains_read_as_factors():
    doc = document(polysegment=variant(ratio=0.99), polyline_stop=variant(ratio=0.002))
    assert "lowest speed (495x)" in verdict(doc).comparisons[0].headline


def test_without_the_polysegment_or_a_polyline_there_is_nothing_to_say():
    assert verdict(document(polyline_stop=variant(), polyline_blend=variant())).comparisons == ()
    assert verdict(document(polysegment=variant())).comparisons == ()


values = st.floats(0.0, 100.0, allow_nan=False)


@given(st.sampled_from(CRITERIA), values, values)
def test_outcome_follows_the_numbers(criterion, mine, theirs):
    o = compare(criterion, mine, theirs)
    better = mine > theirs if criterion.higher_is_better else mine < theirs
    if o.outcome == "win":
        assert better
    elif o.outcome == "loss":
        assert not better and mine != theirs
    else:
        assert o.outcome == "tie" and abs(mine - theirs) <= max(TIE_RELATIVE * theirs, criterion.resolution)
    if o.outcome != "tie":
        mirrored = compare(criterion, theirs, mine)
        assert mirrored.outcome in ("tie", "loss" if o.outcome == "win" else "win")

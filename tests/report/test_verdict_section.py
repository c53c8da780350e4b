"""The verdict section: its words follow the numbers (a loss is called a loss), its bar chart (HTML),
the gates in one line."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.report.sections.verdict import OUTCOME_COLOURS, bar_chart, bar_rows, gates_line, paragraph
from coatsim.report.verdict import CRITERIA, overall, verdict


def variant(cycle=2.0, ratio=0.99, at_speed=0.98, cv=0.05, thick=0.0):
    return {"motion": {"cycle_time_s": cycle, "min_speed_ratio": ratio, "fraction_at_speed": at_speed},
            "coating": {"thickness_cv": cv, "thick_spot_fraction": thick}}


GATES = [{"label": "coating.thickness_cv [polysegment] < polyline-blend", "value": 0.08, "reference": 0.06,
          "passed": False}, {"label": "motion.stops [polysegment] == 0", "value": 0, "reference": 0, "passed": True}]


def test_a_polysegment_that_loses_is_said_to_lose():
    doc = {"variants": {"polysegment": variant(cycle=2.6, ratio=0.6, at_speed=0.7, cv=0.09, thick=0.1),
                        "polyline-blend": variant()}}
    text = paragraph(verdict(doc), GATES)
    assert text.startswith("The polysegment loses: it wins no measure and loses cycle time against polyline-blend "
                           "(+30.0 %); lowest speed against polyline-blend (-39.4 %)")
    assert "wins or ties" not in text and "wins nothing" in text
    assert text.endswith("Gates: 1 of 2 passed; FAILED: coating.thickness_cv [polysegment] < polyline-blend "
                         "(value 0.08, reference 0.06).")


def test_a_mixed_result_names_its_losses_and_a_clean_win_says_no_loss():
    doc = {"variants": {"polysegment": variant(cv=0.08), "polyline-stop": variant(cycle=3.0, cv=0.3),
                        "polyline-blend": variant(cv=0.05)}}
    assert overall(verdict(doc)).startswith("A mixed result: the polysegment wins 2 and loses 1")
    assert "thickness CV against polyline-blend (+60.0 %)" in overall(verdict(doc))
    doc["variants"]["polysegment"] = variant(cv=0.04)
    assert overall(verdict(doc)) == ("The polysegment wins or ties every measure against every polyline variant "
                                     "(3 wins, no loss).")
    assert gates_line([]) == "This scenario defines no gates."
    assert overall(verdict({"variants": {"polysegment": variant()}})).startswith("No polyline variant")


@settings(max_examples=60, deadline=None)
@given(mine=st.tuples(*[st.floats(0.01, 10.0)] * 5), theirs=st.tuples(*[st.floats(0.01, 10.0)] * 5))
def test_the_words_follow_the_outcomes(mine, theirs):
    doc = {"variants": {"polysegment": variant(*mine), "polyline-stop": variant(*theirs)}}
    result = verdict(doc)
    (c,) = result.comparisons
    text = overall(result)
    losses, wins = c.by("loss"), c.by("win")
    assert ("loses" in text) == bool(losses)
    for o in losses:
        assert o.criterion.label in text
    if wins and not losses:
        assert "no loss" in text


def test_the_bar_chart_draws_each_measure_clipped_and_coloured_by_outcome():
    doc = {"variants": {"polysegment": variant(), "polyline-stop": variant(cycle=3.0, ratio=0.001, cv=0.6),
                        "user-program": variant(ratio=None)}}
    result = verdict(doc)
    html = bar_chart(result)
    assert html == bar_chart(result)  # deterministic
    assert html.count("<caption>against ") == 2 and html.count('<td class="track">') == 2 * len(CRITERIA)
    stop = dict((label, (width, outcome)) for label, width, outcome, _ in bar_rows(result.comparisons[0]))
    assert stop["lowest speed"] == (100.0, "win")  # +98 900 %: clipped at the edge
    assert stop["cycle time"] == (pytest.approx(100.0 / 3.0), "win")  # 2 s against 3 s: 33 % shorter
    assert stop["fraction at speed"] == (0.0, "tie")
    # the clipped bar runs from the zero line to the right edge, in the win colour, labelled with its value
    assert f'left:50.00%;width:50.00%;background:{OUTCOME_COLOURS["win"]}"></span></td><td class="l">win 990x' in html
    user = dict((label, outcome) for label, _, outcome, _ in bar_rows(result.comparisons[1]))
    assert user["lowest speed"] == "undefined"


def test_a_loss_is_drawn_left_of_the_zero_line():
    doc = {"variants": {"polysegment": variant(cv=0.075), "polyline-blend": variant(cv=0.05)}}
    html = bar_chart(verdict(doc))
    # CV +50 %: the bar ends at the zero line (50 %) and is 25 % of the track long, in the loss colour
    assert f'left:25.00%;width:25.00%;background:{OUTCOME_COLOURS["loss"]}"></span></td><td class="l">loss +50.0 %' in html

"""Every registered language: a plan written and read back is the same path (moves, poses,
gun, process record), so a new language gets this check by being registered."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.languages.registry import DEFAULT_LANGUAGE, LANGUAGES, language, language_of
from coatsim.path.build import VARIANTS, ProgramOptions
from coatsim.path.part_program import build_part_program
from coatsim.path.language import ReadOptions
from coatsim.path.arcs import move_length
from coatsim.path.placement import Placement, centering_offset

from program_helpers import arc_spiral, roundrect


def _poses(move):
    return [p for p in (getattr(move, "start", None), getattr(move, "via", None), getattr(move, "end", None),
                        getattr(move, "target", None)) if p is not None]


@pytest.mark.parametrize("name", sorted(LANGUAGES))
@pytest.mark.parametrize("variant", VARIANTS)
def test_plan_text_read_is_the_same_path(name, variant, tmp_path):
    lang = language(name)
    contours = [roundrect(), arc_spiral()]
    placement = Placement(lead_in_mm=20.0, lead_out_mm=15.0, offset_xy=centering_offset(contours[0]))
    options = ProgramOptions(variant=variant, speed_mm_s=300.0, accuracy_mm=0.5)
    built = build_part_program(contours, placement, options, tolerance_mm=0.1, source="shapes", language=lang)
    path = tmp_path / f"prog{lang.suffixes[0]}"
    path.write_text(built.text)
    toolpath = lang.read([path], ReadOptions())
    assert language_of([path]) is lang
    # every sprayed path comes back whole: the same sprayed length as the plan, contour by contour
    planned = [p.curve_length_mm + p.lead_in_mm + p.lead_out_mm for p in built.plan.paths]
    sprayed = sum(move_length(m) for m in toolpath.spray_moves)
    closed = [c.closed for c in built.curves]
    expected = sum(length - (p.lead_in_mm + p.lead_out_mm if c else 0.0)
                   for length, p, c in zip(planned, built.plan.paths, closed))
    assert sprayed == pytest.approx(expected, rel=1e-6, abs=1e-4)
    # the process record round-trips (speed limits to the 4 decimals a program carries)
    record, back = built.plan.process, toolpath.process
    assert (back.variant, back.source, back.contour_order) == (record.variant, record.source, record.contour_order)
    assert back.lead_in_mm == pytest.approx(record.lead_in_mm) and back.lead_out_mm == pytest.approx(record.lead_out_mm)
    assert [(c.closed, c.leads_sprayed) for c in back.contours] == [(c.closed, c.leads_sprayed) for c in record.contours]
    for a, b in zip(back.contours, record.contours):
        assert np.allclose([(s.s0_mm, s.s1_mm, s.v_max_mm_s) for s in a.speed_limits],
                           [(s.s0_mm, s.s1_mm, s.v_max_mm_s) for s in b.speed_limits], atol=1e-4)
    # every pose is finite, every programmed speed the plan's
    assert all(np.isfinite(p.translation_mm).all() for m in toolpath.moves for p in _poses(m))
    assert {m.settings.speed_mm_s for m in toolpath.spray_moves} == {300.0}
    assert all(math.isfinite(move_length(m)) for m in toolpath.moves if m.kind != "joint")


def test_unknown_language_lists_the_valid_names():
    with pytest.raises(InputError, match="expected one of " + DEFAULT_LANGUAGE):
        language("cobol")


def test_a_suffix_no_language_claims_reads_with_the_default(tmp_path):
    assert language_of([tmp_path / "prog.txt"]) is LANGUAGES[DEFAULT_LANGUAGE]

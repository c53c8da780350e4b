"""What coatsim writes into a program is validated (issue 14, item 1): names follow the AS rules
or are refused with one line, comments are one line of printable ASCII, and whatever text a
user gives, the program parses back to the same motion with no extra statement."""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH, check_name, program_name, sanitize_comment
from coatsim.path.build import ProgramOptions, build_program
from coatsim.path.plan import ProgramPlan
from coatsim.path.placement import Placement

from program_helpers import roundrect

AS_NAME = re.compile(r"[A-Za-z][A-Za-z0-9._]{0,14}\Z")
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("name", ["a", "coat_1", "p.x", "A2345678901234b", "gripper.type"])
def test_valid_names(name):
    assert check_name(name) == name


@pytest.mark.parametrize("name", ["", "1abc", "_x", "bad name!", "inj()\n  SIGNAL 1 ;", "a" * 16, ".local", "x-y",
                                  "\u00e9t\u00e9", "p;1"])
def test_invalid_names_are_one_line_errors(name):
    with pytest.raises(InputError) as info:
        check_name(name, "--name")
    assert "\n" not in str(info.value) and "not a valid AS name" in str(info.value)


@SETTINGS
@given(st.text(max_size=30))
def test_check_name_follows_the_as_rules(text):
    if AS_NAME.match(text):
        assert check_name(text) == text
    else:
        with pytest.raises(InputError):
            check_name(text)
    made = program_name(text)
    assert AS_NAME.match(made) and len(made) <= MAX_NAME_LENGTH


def _baseline():
    return build_program(roundrect(), Placement(), ProgramOptions(name="rr"), language=KAWASAKI_AS, tolerance_mm=0.1, source="rr")


BASELINE = _baseline()
BASE_TOOLPATH = interpret(parse_as(BASELINE.text, "base.as"))
BASE_STEPS = len(parse_as(BASELINE.text).programs[0].body)


def _same_motion(text: str) -> None:
    f = parse_as(text, "w.as")
    assert len(f.programs) == 1 and len(f.programs[0].body) == BASE_STEPS
    tp = interpret(f)
    assert len(tp.moves) == len(BASE_TOOLPATH.moves)
    for a, b in zip(tp.moves, BASE_TOOLPATH.moves):
        end_a = a.target if a.kind == "joint" else a.end
        end_b = b.target if b.kind == "joint" else b.end
        assert a.kind == b.kind and a.spray == b.spray and np.allclose(end_a.translation_mm, end_b.translation_mm)


@SETTINGS
@given(st.text(max_size=80), st.text(max_size=40))
def test_any_comment_or_source_text_leaves_the_motion_alone(comment, source):
    plan: ProgramPlan = BASELINE.plan
    from dataclasses import replace
    from coatsim.languages.kawasaki_as.writer import write_as

    text = write_as(replace(plan, comments=(comment, comment + "\n  SIGNAL 1"),
                            process=replace(plan.process, source=source + "\n  SIGNAL 1")))
    assert all(32 <= ord(ch) < 127 for line in text.splitlines() for ch in line)
    _same_motion(text)


@SETTINGS
@given(st.text(max_size=20))
def test_program_names_from_the_user(name):
    if not AS_NAME.match(name):
        with pytest.raises(InputError):
            build_program(roundrect(), Placement(), ProgramOptions(name=name), language=KAWASAKI_AS, tolerance_mm=0.1,
                          source="rr")
        return
    built = build_program(roundrect(), Placement(), ProgramOptions(name=name), language=KAWASAKI_AS, tolerance_mm=0.1,
                          source="rr")
    assert built.text.startswith(f".PROGRAM {name}()\n")
    _same_motion(built.text)


@SETTINGS
@given(st.text(max_size=60))
def test_sources_with_any_text(source):
    built = build_program(roundrect(), Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source=source or "x")
    assert AS_NAME.match(built.plan.name)
    f = parse_as(built.text)
    assert len(f.programs[0].body) == BASE_STEPS


def test_sanitize_comment():
    assert sanitize_comment("a\nb\r\tc\u00e9") == "a?b??c?" and len(sanitize_comment("x" * 500)) == 200


def test_injection_through_the_cli_writes_nothing(tmp_path, run_cli):
    out = tmp_path / "p.as"
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--name", "inj()\n  SIGNAL 1 ;", "-o", str(out)])
    assert code == 2 and err.count("\n") == 1 and "not a valid AS name" in err and not out.exists()
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--name", "a_name_too_long16", "-o", str(out)])
    assert code == 2 and "at most 15 characters" in err and not out.exists()
    code, _, err = run_cli(["program", "builtin:ellipse", "--tol", "0.1", "--name", "ok_name.v2", "-o", str(out)])
    assert code == 0 and out.read_text().startswith(".PROGRAM ok_name.v2()")

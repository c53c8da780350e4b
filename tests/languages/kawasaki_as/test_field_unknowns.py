"""Variables a program reads that no file gives (kept in the controller's memory): the program is
read, each is named once with its first line, a branch that depends on one is taken with its
default and reported, a statement that cannot run without one is skipped; NAME=VALUE (the
command line's ``--set``, a scenario's ``variables``) gives them."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.run.variant_spec import ProgramVariantSpec

from styles import STYLES, ends, notes, run_text, styled, ys

POSES = ".TRANS\nb1 620 -150 260 0 180 0\nb2 760 -150 260 0 180 0\nb3 760 150 260 0 180 0\n.END\n"
BRANCH = ("SPEED 100 MM/S ALWAYS\nJMOVE b1\nIF direction == 8 THEN\nLMOVE b2\nELSE\nLMOVE b3\nEND\n"
          '$cnt[0] = $cnt[0] + "x"\nTYPE "beads: ", $cnt[0]')


@pytest.mark.parametrize("style", STYLES)
def test_a_branch_on_an_unknown_is_taken_with_its_default_and_reported(style):
    run = run_text(styled(BRANCH, style, POSES))
    assert ys(run) == [-150, 150]  # direction 0: ELSE
    names = [u.name for u in run.unknowns]
    assert names == ["direction", "$cnt"] and [u.kind for u in run.unknowns] == ["real", "string"]
    first = 4 if style != "backup" else 10
    assert run.unknowns[0].where == f"f.as:{first}" and run.unknowns[1].shown.lower() == "$cnt[0]"
    text = notes(run)
    assert f"f.as:{first}: direction (real) is read but no file gives it a value" in \
        text.replace("Direction", "direction")
    assert f"f.as:{first}: this condition depends on what the run does not know" in text
    assert run.skipped == ()


@pytest.mark.parametrize("style", STYLES)
def test_given_values_replace_the_unknowns(style):
    run = run_text(styled(BRANCH, style, POSES), variables={"direction": 8, "$cnt[0]": "ab"})
    assert ys(run) == [-150, -150]
    assert run.unknowns == () and "depends on" not in notes(run)


def test_values_of_every_kind_are_given_as_text_or_numbers():
    text = (".PROGRAM t()\n  JMOVE #park\n  LMOVE pick\n  LMOVE SHIFT(pick BY gap, 0, 0)\n  TYPE $mode\n"
            "  IF $mode == \"auto\" THEN\n    LMOVE SHIFT(pick BY 0, cnt[2], 0)\n  END\n.END\n")
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    run = run_text(text, kinematics=CellKinematics(load_cell()), variables={
        "#park": "#[0, 0, 35, 0, 55, 0]", "pick": "TRANS(600, 0, 300, 0, 180, 0)", "gap": "2 * 25", "$mode": "auto",
        "cnt[2]": 7.0})
    assert np.allclose([p.translation_mm for p in ends(run)[1:]], [[600, 0, 300], [650, 0, 300], [600, 7, 300]])
    assert run.unknowns == () and run.skipped == ()
    assert run_text('.PROGRAM t()\n  $a = $m\n.END\n', variables={"$m": '"quoted"'}).unknowns == ()


@pytest.mark.parametrize("name,value,words", [
    (".x", "1", "not an AS variable name"), ("a b", "1", "not an AS variable name"),
    ("x", "TRANS(1, 2", "expected ',' or ')'"), ("$s", 5.0, "takes a string, not a number"),
    ("x", '"text"', "expected a number or a pose for x, found a string"), ("#j", "3", "expected a joint value"),
    ("p", "SHIFT(q BY 1, 0, 0)", "pose q has no value"),
])
def test_a_bad_value_is_one_line_naming_the_variable(name, value, words):
    with pytest.raises(InputError) as info:
        run_text(".PROGRAM t()\n.END\n", variables={name: value})
    assert str(info.value).startswith(f"variable {name}") and words in str(info.value), str(info.value)
    assert "\n" not in str(info.value)


def test_a_given_value_wins_over_the_files_data():
    run = run_text(".PROGRAM t()\n  JMOVE p\n.END\n.TRANS\np 600 0 300 0 180 0\n.END\n",
                   variables={"p": "TRANS(700, 0, 300, 0, 180, 0)"})
    assert ends(run)[0].translation_mm[0] == pytest.approx(700.0)


@pytest.mark.parametrize("style", STYLES)
def test_a_motion_to_a_pose_no_file_gives_is_skipped_and_simulation_refuses(style):
    body = "SPEED 200 MM/S ALWAYS\nJMOVE b3\nJMOVE p.home\nLMOVE b1\nSIGNAL 1\nLMOVE b2\nSIGNAL -1\nJMOVE p.home"
    run = run_text(styled(body, style, POSES))
    assert len(run.toolpath.moves) == 3 and len(run.skipped) == 2
    assert "JMOVE skipped: pose p.home has no value" in run.skipped[0].replace("P.home", "p.home")
    assert [u.kind for u in run.unknowns] == ["pose"]
    with pytest.raises(InputError, match=r"f\.as:\d+: JMOVE skipped: .* \(and 1 more\); a simulation runs every"):
        run.require_complete()
    whole = run_text(styled(body, style, POSES), variables={"p.home": "TRANS(650, 0, 400, 0, 180, 0)"})
    assert len(whole.toolpath.moves) == 5 and whole.skipped == ()
    whole.require_complete()


def test_what_follows_from_an_absent_pose_is_absent_too():
    run = run_text(".PROGRAM t()\n  POINT .a = SHIFT(fix BY 0, 0, 50)\n  JMOVE b1\n  LMOVE .a\n  C1MOVE .a\n"
                   "  C2MOVE b3\n  LMOVE b2\n  x = DX(fix)\n.END\n" + POSES)
    assert [m.kind for m in run.toolpath.moves] == ["joint", "line"]
    assert [s.split(": ", 1)[1].split(" skipped")[0] for s in run.skipped] == ["POINT", "LMOVE", "C1MOVE", "C2MOVE",
                                                                                "assignment"]
    assert "the arc's C1MOVE (line 5) was skipped" in run.skipped[3]
    assert ".a has no value (its assignment was skipped)" in run.skipped[1]
    assert [u.name for u in run.unknowns] == ["fix"]


def test_a_statement_that_fails_for_want_of_a_value_is_skipped_not_refused():
    run = run_text(".PROGRAM t()\n  SPEED bead.speed MM/S ALWAYS\n  SIGNAL o.gun\n  x = 1 / divisor\n  JMOVE b1\n.END\n"
                   + POSES)
    assert len(run.toolpath.moves) == 1 and len(run.skipped) == 3
    assert "SPEED skipped: it reads bead.speed, which has no value here, and then SPEED must be > 0" in run.skipped[0]
    assert "SIGNAL skipped: it reads o.gun" in run.skipped[1] and "division by zero" in run.skipped[2]


def test_a_wait_on_an_unknown_is_taken_as_satisfied():
    run = run_text(".PROGRAM t()\n  WAIT part.ready\n  JMOVE b1\n.END\n" + POSES)
    assert len(run.toolpath.moves) == 1 and "WAIT: the condition depends on what the simulation does not know" in \
        notes(run)


def test_unknown_bounds_and_case_subjects_take_their_defaults():
    run = run_text(".PROGRAM t()\n  JMOVE b1\n  FOR .i = 1 TO layers\n    LMOVE b2\n  END\n  CASE part.type OF\n"
                   "    VALUE 0:\n      LMOVE b3\n    ANY :\n      LMOVE b1\n  END\n.END\n" + POSES)
    assert ys(run) == [-150, 150]
    assert notes(run).count("this condition depends on what the run does not know") == 2


def test_a_local_read_before_its_value_is_zero_and_named_as_a_local():
    run = run_text(".PROGRAM t()\n  .cnt = .cnt + 1\n  TYPE .cnt\n.END\n")
    assert notes(run) == ("f.as:2: the local .cnt (real) is read before any value is given; taken as 0 (a motion "
                          "built from it is skipped)")


def test_a_call_of_a_program_not_loaded_is_skipped_with_a_note():
    run = run_text(".PROGRAM t()\n  CALL vision.get(.x)\n  JMOVE b1\n.END\n" + POSES)
    assert len(run.toolpath.moves) == 1
    assert run.skipped == ("f.as:2: CALL skipped: no program named 'vision.get' is loaded (one kept on the "
                           "controller?; loaded: t)",)


def test_a_parameter_left_without_value_is_unknown_in_the_callee():
    run = run_text(".PROGRAM t()\n  CALL go(pick)\n.END\n.PROGRAM go(.p)\n  JMOVE .p\n.END\n")
    assert run.skipped == ("f.as:5: JMOVE skipped: pose .p has no value",)


def test_unknown_functions_and_not_simulated_ones_are_noted_once():
    run = run_text(".PROGRAM t()\n  FOR .i = 1 TO 3\n    .t = TIMER(1) + my.func(2)\n    $d = $DATE(1)\n  END\n"
                   "  IF INRANGE(b1) THEN\n    JMOVE b1\n  END\n.END\n" + POSES)
    text = notes(run)
    assert text.count("TIMER is not simulated; it gives 0") == 1 and "$DATE is not simulated" in text
    assert "MY.FUNC is not a function of the AS index coatsim knows (an array takes [ ], not ( )); it gives 0" in text
    assert "f.as:6: this condition depends on what the run does not know (it reads INRANGE" in text
    assert run.toolpath.moves == ()


def test_scenario_program_variants_take_variables():
    spec = ProgramVariantSpec(name="mine", program="m.as", variables={"direction": 8, "$mode": "auto",
                                                                        "pick": "TRANS(600,0,300,0,180,0)"})
    assert spec.variables == {"direction": 8.0, "$mode": "auto", "pick": "TRANS(600,0,300,0,180,0)"}
    assert ProgramVariantSpec(name="mine", program="m.as").variables == {}


def test_check_program_names_unknowns_and_reads_with_set(tmp_path, run_cli):
    path = tmp_path / "cell.as"
    path.write_text(styled(BRANCH + "\nSIGNAL 1\nLMOVE b2\nSIGNAL -1", "backup", POSES))
    code, out, err = run_cli(["check-program", str(path)])
    assert code == 0 and err == ""
    assert f"warning: {path}:10: direction (real) is read but no file gives it a value" in out
    assert "read with 2 unknown variables and 0 statements skipped" in out
    code, out, err = run_cli(["check-program", str(path), "--set", "direction=8", "--set", "$cnt[0]=x"])
    assert code == 0 and "unknown" not in out and "is read but" not in out
    code, out, err = run_cli(["check-program", str(path), "--set", "direction"])
    assert code == 2 and err == "coatsim: error: --set 'direction': expected NAME=VALUE, as in direction=8 or " \
        "'pick=TRANS(600,0,300,0,180,0)'\n"
    code, out, err = run_cli(["check-program", str(path), "--set", "x=TRANS(1,"])
    assert code == 2 and err.startswith("coatsim: error: variable x=TRANS(1,: ") and err.count("\n") == 1



def test_a_scenario_variant_reads_its_program_with_the_variables_it_gives(tmp_path):
    from coatsim.robot.cell import load_cell
    from coatsim.run.scenario import load_scenario
    from coatsim.run.scenario_inputs import read_user_program

    (tmp_path / "mine.as").write_text(".PROGRAM mine()\n  SPEED spray.speed MM/S ALWAYS\n  JMOVE p.home\n  LMOVE b1\n"
                                      "  BREAK\n  SIGNAL 1\n  LMOVE b2\n  BREAK\n  SIGNAL -1\n.END\n" + POSES)
    scenario = tmp_path / "s.yaml"
    scenario.write_text("name: s\nworkpiece: {kind: plate, size_mm: [100, 100]}\nvariants:\n"
                        "  - {name: mine, program: mine.as, variables: {spray.speed: 150, "
                        "p.home: 'TRANS(650, 0, 400, 0, 180, 0)'}}\n  - polysegment\n")
    loaded = load_scenario(scenario)
    toolpath, _ = read_user_program(loaded, loaded.spec.programs[0], load_cell())
    assert len(toolpath.moves) == 3 and toolpath.moves[1].settings.speed_mm_s == 150.0
    scenario.write_text(scenario.read_text().replace("spray.speed: 150, ", ""))
    loaded = load_scenario(scenario)
    with pytest.raises(InputError, match=r"variant mine: .*mine\.as:2: SPEED skipped: it reads spray\.speed"):
        read_user_program(loaded, loaded.spec.programs[0], load_cell())


def test_a_signal_another_task_sets_is_unknown_until_the_program_sets_it():
    """An internal signal a PC program sets, an output set before the program starts: read as
    OFF with a note, a wait for one taken as satisfied; once the program sets it, it is known."""
    run = run_text(".PROGRAM t()\n  WAIT SIG(2010)\n  SWAIT 2011\n  IF SIG(9) THEN\n    JMOVE b1\n  END\n  SIGNAL 9\n"
                   "  IF SIG(9) THEN\n    JMOVE b2\n  END\n.END\n" + POSES)
    assert ys(run) == [-150] and run.skipped == ()
    text = notes(run)
    assert "f.as:2: WAIT: the condition depends on what the simulation does not know" in text
    assert "f.as:3: SWAIT 2011: internal signal 2011 is not given" in text
    assert "f.as:4: output 9 is not given; taken as OFF" in text
    given = run_text(".PROGRAM t()\n  IF SIG(2010) THEN\n    JMOVE b1\n  END\n.END\n" + POSES, inputs={2010: True})
    assert ys(given) == [-150] and notes(given) == ""


def test_a_motion_to_a_place_made_of_unknown_numbers_is_skipped_not_made_up():
    """A real no file gives reads as 0 in a condition, but a motion or a pose built from one goes
    nowhere: LMOVE TRANS(x, ...) with x unknown would drive the arm to x = 0."""
    run = run_text(".PROGRAM t()\n  JMOVE b1\n  LMOVE TRANS(x.start, 0, 300, 0, 180, 0)\n"
                   "  POINT .p = SHIFT(b1 BY gap, 0, 0)\n  LMOVE .p\n  LAPPRO b2, depth\n  DRAW dx\n"
                   "  IF x.start > 5 THEN\n    LMOVE b3\n  END\n.END\n" + POSES)
    assert len(run.toolpath.moves) == 1
    assert [s.split(": ", 1)[1].split(" skipped")[0] for s in run.skipped] == ["LMOVE", "POINT", "LMOVE", "LAPPRO",
                                                                               "DRAW"]
    assert "x.start has no value, and a motion goes to no place the files do not give" in run.skipped[0]
    assert [u.name for u in run.unknowns] == ["x.start", "gap", "depth", "dx"]
    given = run_text(".PROGRAM t()\n  JMOVE b1\n  LMOVE TRANS(x.start, 0, 300, 0, 180, 0)\n.END\n" + POSES,
                     variables={"x.start": 650.0})
    assert np.allclose(ends(given)[1].translation_mm, [650, 0, 300]) and given.skipped == ()


def test_the_reals_of_a_decompose_skipped_have_no_value_after_it():
    run = run_text(".PROGRAM t()\n  v[1] = 600\n  v[2] = 0\n  v[3] = 300\n  DECOMPOSE v[1] = wp\n"
                   "  JMOVE TRANS(v[1], v[2], v[3], 0, 180, 0)\n.END\n")
    assert run.toolpath.moves == ()
    assert "JMOVE skipped: v[1] has no value (its assignment was skipped)" in run.skipped[1]


def test_a_home_the_cell_has_no_keyframe_for_is_an_unknown_joint_value():
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    text = ".PROGRAM t()\n  HOME 2\n  JMOVE b1\n.END\n" + POSES
    kin = CellKinematics(load_cell())
    run = run_text(text, kinematics=kin)
    assert len(run.toolpath.moves) == 1 and "HOME skipped: joint value #home2 has no value" in run.skipped[0]
    assert [u.name for u in run.unknowns] == ["#home2"]
    given = run_text(text, kinematics=kin, variables={"#home2": "#[10, 20, -30, 0, 40, 0]"})
    assert len(given.toolpath.moves) == 2 and given.skipped == ()
    assert np.allclose(np.degrees(given.toolpath.moves[0].joints_rad), [10, 20, -30, 0, 40, 0])


def test_poses_whose_external_axes_differ_are_a_problem_not_a_silent_path(tmp_path):
    """A rail or positioner moving between poses changes the tool's path over the part; the twin
    does not move external axes, so check-program says so (poses without external values, tools
    and frames, do not count)."""
    from coatsim.languages.registry import language
    from coatsim.path.check import check_program
    from coatsim.path.language import ReadOptions

    path = tmp_path / "trk.as"
    path.write_text(".PROGRAM trk()\n  TOOL gun\n  JMOVE a\n  SIGNAL 1\n  LMOVE b\n  SIGNAL -1\n.END\n.TRANS\n"
                    "gun 0 0 250 0 0 0\na 600 0 300 0 180 0 0\nb 700 0 300 0 180 0 500\n.END\n")
    problems = check_program(path, language("kawasaki-as"), ReadOptions()).problems
    assert any("different external axis values" in p and "a 0" in p and "b 500" in p for p in problems), problems
    path.write_text(path.read_text().replace("0 180 0 500", "0 180 0 0"))
    assert not any("external" in p for p in check_program(path, language("kawasaki-as"), ReadOptions()).problems)

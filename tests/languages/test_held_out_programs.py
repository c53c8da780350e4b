"""Programs written as their authors' tools and hands write them (tests/languages/data/held_out):
a RobotStudio export, a hand-written module with a stripe procedure, a part-family module with
late-bound calls and a library of FUNCs in RAPID; a KSS 8 inline-form program with its .dat, a
hand-written KRC2-style program, RoboDK's post and a program with interrupts and frames in KRL;
a Roboguide backup with a called macro, register stripes, position registers by hand and rings
with an OFFSET CONDITION in Fanuc TP; a Polyscope export, helper functions, a thread and an
offline post in URScript; Fusion 360, Mastercam (inches), LinuxCNC and SheetCAM/Mach3 posts and a
Fanuc macro program in G-code. Each reads to the moves the program means (checked by hand)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from coatsim.core.errors import CoatsimError
from coatsim.languages.registry import language
from coatsim.path.language import ReadOptions
from coatsim.robot.cell import load_cell
from coatsim.robot.kinematics import CellKinematics

from cli_helpers import cli

HELD_OUT = Path(__file__).parent / "data" / "held_out"
GUN_250 = "{X 0,Y 0,Z 250,A 0,B 0,C 0}"


@pytest.fixture(scope="module")
def kinematics():
    return CellKinematics(load_cell())


def read(kinematics, name: str, *files: str, gun: int = 1, **variables: str):
    return language(name).reading([HELD_OUT / f for f in files],
                                  ReadOptions(variables=variables, gun_signal=gun, kinematics=kinematics))


def ends(reading) -> list[tuple]:
    return [(m.kind, bool(m.spray), tuple(np.round((m.target if m.kind == "joint" else m.end).translation_mm, 3)))
            for m in reading.toolpath.moves]


def sprayed(reading) -> list[tuple]:
    return [(kind, end[:2]) for kind, spray, end in ends(reading) if spray]


def test_rapid_robotstudio_export(kinematics):
    r = read(kinematics, "rapid", "r_studio_panel.mod")
    assert not r.skipped and len(r.toolpath.moves) == 12  # the path procedure run twice by a FOR loop
    assert sprayed(r)[:3] == [("line", (820.0, -80.0)), ("arc", (820.0, 0.0)), ("line", (660.0, 0.0))]


def test_rapid_incr_and_a_pers_parameter_passed_back(kinematics):
    """``Incr k`` ends the WHILE loop (it was skipped: a loop that never ended); ``done`` is the
    caller's nDone."""
    r = read(kinematics, "rapid", "r_stripes_offs.mod", do_spray="1")
    assert not r.skipped
    assert sprayed(r) == [("line", (750.0, -60.0)), ("line", (600.0, -35.0)), ("line", (750.0, -10.0)),
                          ("line", (600.0, 15.0))]
    assert r.toolpath.moves[2].settings.speed_mm_s == 250 and r.toolpath.moves[2].settings.accuracy_mm == 2


def test_rapid_pers_parameter_is_the_callers_data(kinematics, tmp_path):
    text = ("MODULE m\n  PERS num n := 0;\n  CONST robtarget p := [[600,0,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
            "  PROC main()\n    MoveJ p, v100, fine, tool0;\n    bump n;\n    bump n;\n    Add n, 10;\n    Decr n;\n"
            "    MoveL Offs(p, n, 0, 0), v100, fine, tool0;\n    Clear n;\n    MoveL Offs(p, n, 0, 0), v100, fine, tool0;\n"
            "  ENDPROC\n  PROC bump(INOUT num k)\n    Incr k;\n  ENDPROC\nENDMODULE\n")
    (tmp_path / "m.mod").write_text(text)
    r = language("rapid").reading([tmp_path / "m.mod"], ReadOptions())
    assert [m.end.translation_mm[0] for m in r.toolpath.moves[1:]] == [611.0, 600.0]


def test_rapid_late_bound_call_by_its_string(kinematics):
    r = read(kinematics, "rapid", "r_test_reltool.mod", do_Gun="1")
    assert not r.skipped
    assert [end for kind, end in sprayed(r) if kind == "arc"] == [(720.0, 0.0), (680.0, 0.0), (740.0, 0.0), (660.0, 0.0)]


def test_rapid_funcs_switch_parameters_and_a_turned_work_object(kinematics):
    r = read(kinematics, "rapid", "r_paint_func.mod", doSpray="1")
    assert not r.skipped and len(sprayed(r)) == 7
    assert sprayed(r)[0] == ("line", (768.177, 20.838))  # (120, 0) turned 10 degrees, plus (650, 0)


def test_krl_inline_forms_with_their_dat(kinematics):
    """FDAT_ACT's tool number, LDAT_ACT's approximation distance, C_DIS C_DIS, PTP XHOME."""
    r = read(kinematics, "krl", "coat_panel.src", **{"TOOL_DATA[1]": GUN_250})
    assert not r.skipped and sprayed(r) == [("line", (760.0, -80.0)), ("arc", (760.0, 0.0)), ("line", (620.0, 0.0))]
    assert r.toolpath.moves[3].settings.accuracy_mm == 3.0 and r.toolpath.moves[3].settings.speed_mm_s == 300
    home = r.toolpath.moves[0]
    assert home.kind == "joint" and np.allclose(home.joints_rad, kinematics.home(1))
    missing = read(kinematics, "krl", "coat_panel.src")  # the tool of $config.dat: its motions are skipped
    assert missing.skipped and any("TOOL_DATA[1]" in u for u in missing.unknowns)


def test_krl_bare_ini_int_division_and_lin_rel_in_the_base(kinematics):
    r = read(kinematics, "krl", "stripes.src", gun=3)
    assert not r.skipped
    assert [end for _, end in sprayed(r)][::2] == [(750.0, -40.0), (600.0, -15.0), (750.0, 10.0), (600.0, 35.0)]
    assert ends(r)[-1][2] == (600.0, 35.0, 350.0)  # LIN_REL {Z 50}: up in the base, the gun points down


def test_krl_lin_rel_tool_moves_along_the_tool(kinematics, tmp_path):
    src = ("DEF p( )\n  INI\n  $TOOL = {X 0,Y 0,Z 250,A 0,B 0,C 0}\n  PTP {X 600,Y 0,Z 300,A 0,B 180,C 0}\n"
           "  LIN_REL {Z 50} #TOOL\n  LIN_REL {Z 50}\nEND\n")
    (tmp_path / "p.src").write_text(src)
    r = language("krl").reading([tmp_path / "p.src"], ReadOptions())
    assert [tuple(m.end.translation_mm) for m in r.toolpath.moves[1:]] == [(600, 0, 250), (600, 0, 300)]


def test_krl_robodk_post_frames_and_axis_ptp(kinematics):
    r = read(kinematics, "krl", "robodk_frames.src")
    assert not r.skipped and len(sprayed(r)) == 3
    first = r.toolpath.moves[0]
    assert first.kind == "joint" and np.allclose(np.degrees(first.joints_rad), [0, -90, 90, 0, 90, 0])
    assert sprayed(r)[0] == ("line", (771.962, -4.641))  # base turned 30 degrees about z


def test_krl_interrupts_geometric_operator_and_deffct(kinematics):
    r = read(kinematics, "krl", "gun_watch.src", gun=2, **{"TOOL_DATA[2]": GUN_250})
    assert not r.skipped and len(sprayed(r)) == 12 and sprayed(r)[0] == ("line", (800.0, 20.0))
    assert ends(r)[-2][2] == (680.0, 110.0, 360.0)
    assert any("interrupts are noted" in w for w in r.toolpath.warnings)


def test_fanuc_roboguide_backup_with_a_called_macro(kinematics):
    r = read(kinematics, "fanuc", "F_PANEL.LS", "GUN_PURGE.LS", gun=101,
             **{"UFRAME[2]": "600,-20,200,0,0,0", "UTOOL[1]": "0,0,250,0,0,0"})
    assert not r.skipped
    assert sprayed(r) == [("line", (720.0, -70.0)), ("arc", (770.0, -20.0)), ("line", (770.0, 30.0)),
                          ("line", (620.0, 30.0))]


def test_fanuc_register_cleared_by_subtracting_itself(kinematics):
    r = read(kinematics, "fanuc", "STRIPE_R.LS", **{"UFRAME[1]": "600,-20,200,0,0,0", "UTOOL[1]": "0,0,250,0,0,0"})
    assert not r.skipped and not r.unknowns
    assert sprayed(r) == [("line", (750.0, y)) for y in (-20.0, 5.0, 30.0, 55.0)]


def test_fanuc_offset_condition_reads_the_register_at_each_motion(kinematics):
    r = read(kinematics, "fanuc", "RINGS.LS", gun=2, **{"UTOOL[1]": "0,0,250,0,0,0"})
    assert not r.skipped
    assert [end for kind, end in sprayed(r)] == [(700.0, 0.0), (620.0, 0.0), (800.0, 0.0), (720.0, 0.0)]


def test_fanuc_position_registers_override_inc_and_cm_per_min(kinematics):
    r = read(kinematics, "fanuc", "PR_HAND.LS", **{"PR[20]": "650,0,200,0,0,0", "UTOOL[2]": "0,0,250,0,0,0",
                                                   "PR[5]": "0,0,160,180,0,0", "PR[7]": "0,0,0,0,0,0", "R[9]": "1"})
    assert [end for _, end in sprayed(r)] == [(650.0, 0.0), (650.0, 40.0), (670.0, 40.0)]
    assert [m.settings.speed_mm_s for m in r.toolpath.moves[2:5]] == [150.0, 150.0, 150.0]  # OVERRIDE=50%


def test_urscript_polyscope_export_with_movep_and_a_feature(kinematics):
    r = read(kinematics, "urscript", "coat_lid.script", gun=0)
    assert not r.skipped
    assert sprayed(r) == [("line", (770.0, -80.0)), ("arc", (770.0, -20.0)), ("line", (650.0, -20.0))]


def test_urscript_pose_literals_inside_functions_are_counted(kinematics):
    r = read(kinematics, "urscript", "grid_func.script")
    assert r.n_poses == 4 and len(r.toolpath.moves) == 37 and not r.skipped


def test_urscript_thread_handle_and_kill_are_noted(kinematics):
    r = read(kinematics, "urscript", "spray_thread.script", gun=2)
    assert [kind for kind, _ in sprayed(r)] == ["arc"] * 4
    assert any("kill th" in w for w in r.toolpath.warnings)


def test_urscript_offline_post_in_a_turned_frame(kinematics):
    r = read(kinematics, "urscript", "offline_post.script")
    assert sprayed(r) == [("line", (726.603, -30.0)), ("line", (696.603, 21.962)), ("line", (610.0, -28.038))]


@pytest.mark.parametrize("name, sprayed_arcs, first", [
    ("fusion_panel.nc", 3, ("line", (610.0, -60.0))),
    ("mastercam_inch.nc", 4, ("line", (619.999, 0.0))),
    ("sheetcam_plasma.tap", 4, ("line", (650.0, -40.0))),
])
def test_gcode_cam_posts(kinematics, name, sprayed_arcs, first):
    r = read(kinematics, "gcode", name)
    paths = [s for s in sprayed(r) if s[0] != "joint"]
    assert not r.skipped and paths[0] == first and sum(k == "arc" for k, _ in paths) == sprayed_arcs


def test_gcode_linuxcnc_sub_call_and_arcs_in_xz_and_yz(kinematics):
    r = read(kinematics, "gcode", "linuxcnc_planes.ngc")
    assert not r.skipped
    arcs = [m for m in r.toolpath.moves if m.kind == "arc"]
    assert [tuple(np.round(m.via.translation_mm, 3)) for m in arcs] == [(650.0, 0.0, 270.0), (680.0, 45.0, 285.0)]


def test_gcode_fanuc_macro_loop_goto_and_a_subprogram_called_twice(kinematics):
    r = read(kinematics, "gcode", "fanuc_macro.nc")
    assert not r.skipped
    assert [end for kind, end in sprayed(r) if kind == "arc"] == [(740.0, -15.0), (740.0, 10.0), (740.0, 35.0)]
    assert ends(r)[-1][2] == (740.0, 35.0, 350.0)  # G4 X0.5 is a dwell, not a move to X 0.5
    assert [d.seconds for d in r.toolpath.dwells][-2:] == [0.5, 0.5]


def test_convert_to_another_language_needs_none_of_the_originals_values(tmp_path):
    """The standalone program carries its own frames and tool: the values given for the original
    (a Fanuc frame, a KRL tool) are not read back in the target language."""
    out = tmp_path / "panel.as"
    code, _, err = cli("convert", HELD_OUT / "F_PANEL.LS", HELD_OUT / "GUN_PURGE.LS", "--gun", "101", "--tol", "0.2",
                       "--set", "UFRAME[2]=600,-20,200,0,0,0", "--set", "UTOOL[1]=0,0,250,0,0,0", "--to", "as", "-o", out)
    assert code == 0, err
    assert out.read_text().count("C2MOVE") >= 1


def test_check_program_counts_every_sprayed_move_once_in_its_summary():
    """A CAM post switches the gun on before a rapid: the summary's sprayed length is the sum of
    the sprayed stretches it lists (joint and rapid moves as chords), never a different number."""
    import re

    code, out, err = cli("check-program", HELD_OUT / "fusion_panel.nc")
    assert code == 0, err
    summary = float(re.search(r"\(sprayed ([0-9.]+) mm\)", out).group(1))
    runs = [float(x) for x in re.findall(r"^sprayed: .* ([0-9.]+) mm$", out, flags=re.M)]
    assert runs and summary == pytest.approx(sum(runs), abs=2e-3)
    assert float(re.search(r"path length ([0-9.]+) mm", out).group(1)) >= summary

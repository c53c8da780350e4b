"""The same sprayed path as different authors write G-code: LinuxCNC by hand (lower case, spaces,
``;`` comments, named parameters), a Fanuc-style control (``%``, ``O`` number, ``N`` numbers,
``G01``, trailing decimal points, words run together), a CAM post for a mill (header comments,
``T1 M6``, ``S`` words, ``R``-format arcs), a laser/plasma sender (``M3 S``, words without spaces)
and incremental coordinates (``G91``). Every style reads as the same moves."""

from __future__ import annotations

import numpy as np
import pytest

from language_plans import read_text

STYLES = {
    "linuxcnc": """; spray one side of a rounded corner
g21 g90 g17 ; mm, absolute
#<feed> = 1200
g64 p0.2
g0 x0 y0 z50
g1 z10 f#<feed>   ; down
g4 p0
m3                ; gun on
g1 x40
g3 x50 y10 i0 j10 ; the corner
g1 y30
m5
g1 z50
m2
""",
    "fanuc": """%
O1001 (SPRAY)
N10 G90G21G17
N20 G64 P0.2
N30 G00 X0. Y0. Z50.
N40 G01 Z10. F1200.
N50 G04 P0
N60 M03
N70 G01X40.
N80 G03X50.Y10.I0.J10.
N90 G01Y30.
N100 M05
N110 Z50.
N120 M30
%
""",
    "cam": """(PROGRAM: SPRAY)
(POST: generic mill)
(T1 D=0. - spray gun)
N10 G90 G94 G17
N15 G21
N20 G54
N25 T1 M6
N30 S1000 M5
N35 G64 P0.2
N40 G0 X0. Y0. Z50.
N45 G43 Z50. H1
N50 G1 Z10. F1200.
N55 G4 P0
N60 M3
N65 X40.
N70 G3 X50. Y10. R10.
N75 G1 Y30.
N80 M5
N85 Z50.
N90 M30
""",
    "sender": """G21
G90
G64P0.2
G0X0Y0Z50
G1Z10F1200
G4P0
M3 S1000
G1X40
G3X50Y10I0J10
G1Y30
M5
G1Z50
""",
    "incremental": """(relative moves)
G21 G90
G0 X0 Y0 Z50
G91 G64 P0.2
G1 Z-40 F1200
G4 P0
M3
G1 X40
G3 X10 Y10 I0 J10
G1 Y20
M5
G1 Z40
G90
""",
}


def summary(tp):
    return [(m.kind, bool(m.spray), tuple(np.round((m.target if m.kind == "joint" else m.end).translation_mm, 9)),
             round(m.settings.speed_mm_s, 9), m.settings.accuracy_mm) for m in tp.moves]


@pytest.mark.parametrize("style", sorted(STYLES))
def test_every_style_reads_as_the_same_moves(style, tmp_path):
    expected = summary(read_text("gcode", STYLES["linuxcnc"], tmp_path, suffix=".ngc"))
    assert summary(read_text("gcode", STYLES[style], tmp_path, suffix=".nc")) == expected
    assert [m[0] for m in expected] == ["joint", "line", "line", "arc", "line", "line"]
    assert [m[1] for m in expected] == [False, False, True, True, True, False]


# A CAM post for a milling control: program number, tool comment, G91.1, machine-coordinate G53
# retracts, tool change and length offset, the gun on the spindle codes (on before the travel).
CAM_POST = """%
O1001 (SPRAY TRACK)
(T1  D=10. CR=0. - ZMIN=-1. - FLAT END MILL)
N10 G90 G94 G17 G91.1
N15 G21
N20 G53 G0 Z0.
(2D CONTOUR1)
N25 T1 M6
N30 S5000 M3
N35 G54
N40 G0 X-20. Y0.
N45 G43 Z15. H1
N50 G0 Z5.
N55 G1 Z0. F1000.
N60 G1 X0. F3000.
N65 G2 X20. Y0. I10. J0.
N70 G3 X40. Y0. I10. J0.
N75 G1 X60.
N80 G0 Z15.
N85 M5
N90 G53 G0 Z0.
N95 M30
%
"""


def test_a_cam_post_reads_with_its_arcs_and_retracts(tmp_path):
    """Its first move (G53 G0 Z0) keeps X and Y where the tool is: without the cell that is a
    one-line error, with it the robot's home pose."""
    from coatsim.core.errors import InputError
    from coatsim.path.arcs import move_length
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    with pytest.raises(InputError, match=r"prog.nc:6: G0 needs to know where the tool is"):
        read_text("gcode", CAM_POST, tmp_path, suffix=".nc")
    tp = read_text("gcode", CAM_POST, tmp_path, suffix=".nc", kinematics=CellKinematics(load_cell()))
    arcs = [m for m in tp.moves if m.kind == "arc"]
    assert len(arcs) == 2 and all(m.spray for m in arcs)
    assert sum(move_length(m) for m in arcs) == pytest.approx(2 * np.pi * 10.0, abs=1e-6)  # two half circles
    assert np.allclose(arcs[-1].end.translation_mm, [40, 0, 0], atol=1e-9)
    assert np.allclose(tp.moves[-1].target.translation_mm[2], 0.0)  # G53 G0 Z0: machine zero

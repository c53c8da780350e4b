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

"""A linear first motion (RAPID MoveL, KRL LIN) is read from where the twin's arm stands when the
program starts, the cell's home, with a warning; without the cell it is refused (unknown start)."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.core.errors import ExecutionError
from coatsim.languages.registry import language
from coatsim.path.language import ReadOptions
from coatsim.robot.cell import load_cell
from coatsim.robot.kinematics import CellKinematics

RAPID = ("MODULE M\n  CONST robtarget a:=[[600,-50,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
         "  CONST robtarget b:=[[800,-50,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
         "  PROC main()\n    MoveL a,v300,fine,tool0;\n    MoveL b,v300,fine,tool0;\n  ENDPROC\nENDMODULE\n")
KRL = "DEF first( )\n  $VEL.CP = 0.3\n  LIN {X 600,Y -50,Z 300,A 0,B 90,C 0}\n  LIN {X 800,Y -50,Z 300,A 0,B 90,C 0}\nEND\n"


@pytest.mark.parametrize("name,suffix,text,word", [("abb-rapid", ".mod", RAPID, "MoveL"),
                                                  ("kuka-krl", ".src", KRL, "LIN")])
def test_a_linear_first_motion_starts_at_the_cells_home(tmp_path, name, suffix, text, word):
    path = tmp_path / f"first{suffix}"
    path.write_text(text)
    kin = CellKinematics(load_cell())
    reading = language(name).reading([path], ReadOptions(kinematics=kin))
    first = reading.toolpath.moves[0]
    assert np.allclose(first.start.translation_mm, kin.forward(kin.home(1), first.settings.tool).translation_mm)
    assert any(f"{word} is the first motion: it starts from the cell's home" in w for w in reading.toolpath.warnings)
    assert len(reading.toolpath.moves) == 2
    with pytest.raises(ExecutionError, match=f"{word} is the first motion: the robot's position before it is unknown"):
        language(name).reading([path], ReadOptions())

"""Errors keep their class, exit code and details when a caller says where they happened."""

import numpy as np

from coatsim.core.errors import InputError
from coatsim.robot.ik import UnreachablePose


def test_prefixed_keeps_class_and_details() -> None:
    exc = UnreachablePose("out of reach", step="line 3", position_mm=np.zeros(3), rotation=np.eye(3),
                          q_near=np.zeros(6), reason="out of reach")
    said = exc.prefixed("variant arcs")
    assert type(said) is UnreachablePose and said.exit_code == 3
    assert str(said) == "variant arcs: out of reach"
    assert said.step == "line 3" and said.reason == "out of reach"
    assert str(exc) == "out of reach"  # the original is untouched


def test_reworded_then_prefixed() -> None:
    exc = InputError("tolerance_mm must be positive", parameters=("tolerance_mm",))
    said = exc.reworded({"tolerance_mm": "--tol"}).prefixed("part.dxf")
    assert str(said) == "part.dxf: --tol must be positive" and said.parameters == ("tolerance_mm",)

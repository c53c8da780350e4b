"""What several commands share: the tool acceleration in the flags' units, the inputs a cell sets,
the variables the controller keeps."""

from __future__ import annotations

import math
from typing import Optional

from coatsim.cli.flags import fail


def tool_accel_mm_s2(tool_accel_m_s2: Optional[float]) -> float:
    """--tool-accel (m/s²) in mm/s², or the cell model's when not given."""
    if tool_accel_m_s2 is None:
        from coatsim.robot.cell import load_cell

        return load_cell().tool_accel_mm_s2
    if not (math.isfinite(tool_accel_m_s2) and tool_accel_m_s2 > 0):
        fail(f"--tool-accel: must be a positive number of m/s², got {tool_accel_m_s2}")
    return tool_accel_m_s2 * 1000.0


def input_states(text: Optional[str]) -> dict[int, bool]:
    """--inputs 1001,-1002 as {1001: True, 1002: False} (empty when not given)."""
    if text is None:
        return {}
    from coatsim.languages.kawasaki_as.io_model import parse_inputs

    return parse_inputs(text, "--inputs")


LANGUAGE_HELP = ("Language of the program files (kawasaki-as, abb-rapid, kuka-krl, ...; or a part of the name: "
                 "rapid) [default: by their suffix, else by their opening].")
SET_HELP = ("A variable the files do not give (the controller keeps it), NAME=VALUE; repeatable: direction=8, "
            "'$mode=auto', 'pick=TRANS(600,0,300,0,180,0)', '#park=#[0,0,35,0,55,0]'.")


def variables(settings: Optional[list[str]]) -> dict[str, str]:
    """--set NAME=VALUE values as {name: value text}."""
    out: dict[str, str] = {}
    for text in settings or []:
        name, sep, value = text.partition("=")
        if not sep or not name.strip():
            fail(f"--set {text!r}: expected NAME=VALUE, as in direction=8 or 'pick=TRANS(600,0,300,0,180,0)'")
        out[name.strip()] = value.strip()
    return out

"""KUKA KRL behind coatsim's language interface."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Sequence

from coatsim.languages.kuka_krl.names import MAX_NAME_LENGTH, check_name, program_name
from coatsim.languages.kuka_krl.writer import MAX_ARC_SWEEP_DEG, MAX_COORDINATE_MM, split_files, write_krl
from coatsim.path.language import Capabilities, ReadOptions
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import ToolPath

# DEF name( ... ) ends its line (URScript's def name(): has a colon after it).
_OPENING = re.compile(r"^\s*(&ACCESS|(GLOBAL\s+)?DEF\s+\w+\s*\([^)]*\)\s*($|;)|DEFDAT\s)", re.IGNORECASE | re.MULTILINE)


class KukaKrl:
    """Writes a ``.src``/``.dat`` pair (LIN/CIRC with C_DIS, $VEL.CP, $TOOL/$BASE, E6POS data)
    and reads programs as WorkVisual, the pendant and people write them (folds, INI, BAS)."""

    name = "kuka-krl"
    title = "KUKA KRL"
    suffixes = (".src", ".dat", ".sub")

    def __init__(self, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> None:
        self.max_arc_sweep_deg = max_arc_sweep_deg
        self.capabilities = Capabilities(arc_planes="any", max_arc_sweep_deg=max_arc_sweep_deg,
                                         blend="C_DIS within $APO.CDIS mm; no approximation: an exact stop",
                                         max_name_length=MAX_NAME_LENGTH, max_coordinate_mm=MAX_COORDINATE_MM,
                                         rotation="A-B-C (Rz·Ry·Rx, deg)", motions="LIN/CIRC", named_by_file=True,
                                         program_files=(".src", ".dat"))

    def write(self, plan: ProgramPlan) -> str:
        return write_krl(plan, self.max_arc_sweep_deg)

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        return split_files(text)

    def recognizes(self, text: str) -> bool:
        return _OPENING.search(text) is not None

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        return self.reading(files, options).toolpath_to_run(options.gun_signal, options.needs_spray, str(files[0]))

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        from coatsim.languages.kuka_krl.interpreter import read_krl  # the interpreter loads when a program is read

        return read_krl(files, options)

    def check_name(self, name: str, what: str) -> str:
        return check_name(name, what)

    def program_name(self, text: str) -> str:
        return program_name(text)


KUKA_KRL = KukaKrl()

"""The typed results of a scenario run: each variant carried through every stage, and the run.

The pipeline (coatsim.run) builds them; the report reads them. They live below the report so
that both can name them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Optional

from coatsim.path.part_program import PartProgram
from coatsim.path.surface_program import SurfaceProgram
from coatsim.path.toolpath import ToolPath
from coatsim.path.user import UserProgram
from coatsim.robot.execute import Execution
from coatsim.spray.coat import CoatingResult


@dataclass(frozen=True, eq=False)
class VariantRun:
    """One program variant carried through every stage."""

    name: str
    program: PartProgram | UserProgram | SurfaceProgram
    execution: Execution
    coating: CoatingResult
    groups: dict[str, dict[str, float | int | None]]
    contour_groups: tuple[dict[str, dict[str, float | int | None]], ...] = ()
    toolpath: Optional[ToolPath] = None  # the program as read back (the report ties events to its lines)
    program_file: str = ""  # the name of the program's (main) file in the output folder


@dataclass(frozen=True, eq=False)
class RunResult:
    """A finished run: every variant, the metrics document and the files written; with
    ``keep_going``, ``failures`` holds the one-line error of each variant that could not run."""

    outdir: Path
    variants: tuple[VariantRun, ...]
    document: dict
    files: tuple[Path, ...]
    failures: Mapping[str, str] = field(default_factory=dict)
    segmentation_s: float = 0.0  # the fitter's wall time (reported on request, never written)
    report_s: float = 0.0        # wall time of the thickness files, the video and report.html

    @property
    def passed(self) -> bool:
        return bool(self.document["passed"])

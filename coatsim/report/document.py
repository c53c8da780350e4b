"""report.html of a run: every section built from the run's values and its metrics document.

Sections, in the order of the design's "Report sections" contract: ``verdict`` (what the
polysegment wins and loses, :mod:`coatsim.report.verdict`), ``speed``, ``thickness-along-track``,
``maps``, ``warnings``, ``view3d``, ``program``, ``metrics``, then ``summary`` and ``gates``; one
module each in :mod:`coatsim.report.sections`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, Optional, Sequence

from coatsim import __version__
from coatsim.core.fileio import write_text
from coatsim.report.data import ReportData
from coatsim.report.html import Section, render_html

SECTION_IDS = ("verdict", "speed", "thickness-along-track", "maps", "warnings", "view3d", "program", "metrics",
               "summary", "gates")


def build_sections(data: ReportData, cell: Optional[Any] = None, video: Optional[str] = None) -> list[Section]:
    """Every section of the report, in order."""
    from coatsim.report.sections import (
        maps,
        program,
        speed,
        tables,
        track,
        verdict,
        view3d,
        warnings,
    )

    document = data.document
    return [
        verdict.section(data),
        speed.section(data),
        track.section(data),
        maps.section(data),
        warnings.section(data),
        view3d.section(data, cell, video),
        program.section(data),
        tables.metrics_section(data),
        tables.summary_section(data),
        tables.gates_section(document["gates"], document["passed"]),
    ]


def write_report(path: Path, loaded: Any, contours: Sequence[Any], runs: Sequence[Any], document: Mapping[str, Any],
                 notes: Sequence[str] = (), *, cell: Optional[Any] = None, video: Optional[str] = None) -> None:
    """Write the self-contained report.html of a run: ``contours`` are the segmentations of the
    curve (one) or of the contours of a part, ``runs`` the variants' runs, ``notes`` what reading
    a drawing noted, ``cell`` the robot cell (for the 3-D pictures), ``video`` the name of the
    run's MP4 beside the report, if one was made."""
    data = ReportData(loaded, tuple(contours), tuple(runs), document, tuple(notes))
    sections = build_sections(data, cell, video)
    subtitle = f"coatsim {__version__}, scenario {loaded.path.name}, {document['mode']} mode"
    write_text(path, render_html(f"coatsim report: {loaded.spec.name}", subtitle, sections))

"""report.html of a run: every section built from the run's values and its metrics document.

Sections, in the order of the design's "Report sections" contract: ``verdict`` (what the
polysegment wins and loses, :mod:`coatsim.report.verdict`), ``speed``, ``thickness-along-track``,
``maps``, ``warnings``, ``view3d``, ``program``, ``metrics``, then ``summary`` and ``gates``; one
module each in :mod:`coatsim.report.sections`.
"""

from __future__ import annotations

import gc
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator, Mapping, Optional, Sequence

from coatsim.geometry.segment import Segmentation
from coatsim.report.results import VariantRun
from coatsim import __version__
from coatsim.core.fileio import write_text
from coatsim.report.data import LoadedScenario, ReportData
from coatsim.report.html import Section, render_html

SECTION_IDS = ("verdict", "speed", "thickness-along-track", "maps", "warnings", "view3d", "program", "metrics",
               "summary", "gates")


def build_sections(data: ReportData, video: Optional[str] = None) -> list[Section]:
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
        view3d.section(data, video),
        program.section(data),
        tables.metrics_section(data),
        tables.summary_section(data),
        tables.gates_section(document["gates"], document["passed"]),
    ]


@contextmanager
def collector_paused() -> Iterator[None]:
    """The cyclic garbage collector off while the report is drawn: drawing makes many
    short-lived objects that refer to each other (figures, artists, transforms), and collecting
    them as they come costs about a sixth of the report; the collector finds them on its next pass."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def write_report(path: Path, loaded: LoadedScenario, contours: Sequence[Segmentation], runs: Sequence[VariantRun],
                 document: Mapping[str, Any],
                 notes: Sequence[str] = (), *, video: Optional[str] = None) -> None:
    """Write the self-contained report.html of a run from its results and its metrics document
    alone (no stage is run again): ``contours`` are the segmentations of the curve (one) or of
    the contours of a part, ``runs`` the variants' runs, ``notes`` what reading a drawing noted,
    ``video`` the name of the run's MP4 beside the report, if one was made."""
    data = ReportData(loaded, tuple(contours), tuple(runs), document, tuple(notes))
    with collector_paused():
        sections = build_sections(data, video)
    subtitle = f"coatsim {__version__}, scenario {loaded.path.name}, {document['mode']} mode"
    write_text(path, render_html(f"coatsim report: {loaded.spec.name}", subtitle, sections))

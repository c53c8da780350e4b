"""report.html of a run on a 3-D part: the curve report's verdict, warnings, 3-D view, metrics
and gates, with the part's own sections (coatsim.report.sections.part) in place of the curve's.

Sections, in order: ``verdict``, ``speed`` (the spray spot along each pass), ``histogram``,
``maps`` (thickness, spray angle, stand-off on the part), ``warnings``, ``view3d``, ``program``
(the plan and the programs), ``metrics``, ``summary``, ``gates``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, Sequence

from coatsim import __version__
from coatsim.core.fileio import write_text
from coatsim.report.data import LoadedScenario, ReportData
from coatsim.report.document import collector_paused
from coatsim.report.html import Section, render_html
from coatsim.report.results import VariantRun

PART_SECTION_IDS = ("verdict", "speed", "histogram", "maps", "warnings", "view3d", "program", "metrics", "summary",
                    "gates")


def build_part_sections(data: ReportData) -> list[Section]:
    """Every section of a part's report, in order."""
    from coatsim.report.sections import part, tables, verdict, view3d, warnings

    document = data.document
    return [
        verdict.section(data),
        part.speed_section(data),
        part.histogram_section(data),
        part.maps_section(data),
        warnings.section(data),
        view3d.section(data),
        part.program_section(data),
        tables.metrics_section(data),
        part.summary_section(data),
        tables.gates_section(document["gates"], document["passed"]),
    ]


def write_part_report(path: Path, loaded: LoadedScenario, runs: Sequence[VariantRun], document: Mapping[str, Any],
                      notes: Sequence[str] = ()) -> None:
    """Write the self-contained report.html of a run on a part from its results and metrics
    document alone; ``notes`` are what reading the mesh and planning noted."""
    data = ReportData(loaded, (), tuple(runs), document, tuple(notes))
    with collector_paused():
        sections = build_part_sections(data)
    subtitle = f"coatsim {__version__}, scenario {loaded.path.name} (a 3-D part), {document['mode']} mode"
    write_text(path, render_html(f"coatsim report: {loaded.spec.name}", subtitle, sections))

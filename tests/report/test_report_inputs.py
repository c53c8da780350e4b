"""The report stage draws from the run's results and its metrics document alone: while
report.html is written no stage runs again (no deposit, no coat, no arm simulation, no fit,
no deviation check, no program written or read), and the numbers it shows are the metrics
document's."""

from __future__ import annotations

import copy
import re
import sys
from pathlib import Path

import pytest
from small_scenario import SMALL

import coatsim.report.document as document
from coatsim.geometry import segment_curve
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fit import fit_run
from coatsim.languages.kawasaki_as.language import KawasakiAs
from coatsim.path.part_program import build_part_program
from coatsim.robot.execute import execute
from coatsim.run.pipeline import run_scenario
from coatsim.spray.coat import coat, remeasured
from coatsim.spray.coating_metrics import coating_metrics, region_of_interest
from coatsim.spray.deposition import deposit

STAGES = {f.__code__: f.__qualname__ for f in (deposit, coat, remeasured, coating_metrics, region_of_interest,
                                                  execute, segment_curve, fit_run, hausdorff, KawasakiAs.read,
                                                  build_part_program)}


@pytest.fixture(scope="module")
def report_call(tmp_path_factory: pytest.TempPathFactory) -> tuple[tuple, dict, set[str]]:
    """A fast run of the small scenario: the arguments its report was written with and the
    stage functions called while it was written."""
    folder = tmp_path_factory.mktemp("inputs")
    scenario = folder / "small_job.yaml"
    scenario.write_text(SMALL, encoding="utf-8")
    seen: dict = {}
    called: set[str] = set()
    original = document.write_report

    def hook(frame, event, arg):  # noqa: ARG001 (the profile hook's signature)
        if event == "call" and frame.f_code in STAGES:
            called.add(STAGES[frame.f_code])

    def traced(*args, **kwargs):
        seen.update(args=args, kwargs=kwargs)
        sys.setprofile(hook)
        try:
            return original(*args, **kwargs)
        finally:
            sys.setprofile(None)

    document.write_report = traced
    try:
        run_scenario(scenario, folder / "out", fast=True, progress=False)
    finally:
        document.write_report = original
    return seen["args"], seen["kwargs"], called


def test_writing_the_report_runs_no_stage_again(report_call) -> None:
    args, _, called = report_call
    assert args[0].name == "report.html" and args[0].is_file()
    assert called == set()


def test_the_numbers_shown_are_the_metrics_documents(report_call, tmp_path: Path) -> None:
    """The same run reported with an edited metrics document shows the edited numbers."""
    (_, loaded, contours, runs, doc, *rest), kwargs, _ = report_call
    edited = copy.deepcopy(doc)
    edited["variants"]["polyline-blend"]["coating"]["thickness_cv"] = 0.4321
    edited["variants"]["polyline-stop"]["coating"]["thickness_cv"] = 0.9876
    edited["variants"]["polysegment"]["motion"]["cycle_time_s"] = 12.345
    path = tmp_path / "report.html"
    document.write_report(path, loaded, contours, runs, edited, *rest, **kwargs)
    html = path.read_text(encoding="utf-8")
    maps = html[html.index('<section id="maps">'):html.index('<section id="warnings">')]
    assert "lowest thickness CV (43.2 %)" in maps  # the best polyline by the document's CV
    table = html[html.index('<section id="metrics">'):html.index('<section id="summary">')]
    assert re.search(r">cycle time on the curve</td><td class=\"l\">s</td><td>12\.35</td>", table)

"""`coatsim run --junit FILE`: the gates as JUnit XML that CI test reporters read."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from junitparser import Error, Failure, JUnitXml

from coatsim.report.junit import error_junit, gates_junit


def test_one_testcase_per_gate_with_the_summary_line_as_failure_message(small_report) -> None:
    code, out, _, outdir = small_report
    document = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    gates = document["gates"]
    xml = JUnitXml.fromfile(str(outdir.parent / "gates.xml"))  # the reader CI plugins are built on
    suites = list(xml)
    assert len(suites) == 1
    suite = suites[0]
    assert suite.name == "coatsim.small_job"
    cases = list(suite)
    assert [c.name for c in cases] == [g["label"] for g in gates]
    assert [c.classname for c in cases] == [f"coatsim.small_job.{g['variant']}" for g in gates]
    assert suite.tests == len(gates) and suite.failures == sum(not g["passed"] for g in gates) == 1
    for case, gate in zip(cases, gates):
        if gate["passed"]:
            assert case.is_passed
        else:
            [failure] = case.result
            assert isinstance(failure, Failure)
            assert failure.message in out.splitlines()  # the gate's line, as the console prints it
            assert failure.message.startswith("FAIL  coating.thickness_cv [polysegment] < 0")
    assert code == 1


def test_the_same_document_gives_the_same_bytes(small_report) -> None:
    *_, outdir = small_report
    document = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    assert gates_junit(document) == (outdir.parent / "gates.xml").read_text(encoding="utf-8")


def test_labels_with_markup_characters_are_escaped() -> None:
    gate = {"label": 'coating.thickness_cv [a<b & "c"] < 0.1', "variant": "a<b", "passed": False,
            "value": 0.2, "reference": 0.1}
    text = gates_junit({"scenario": {"name": "x"}, "gates": [gate]})
    case = ET.fromstring(text).find("testsuite/testcase")
    assert case is not None and case.get("name") == gate["label"] and case.get("classname") == "coatsim.x.a<b"
    assert case.find("failure").get("message").startswith("FAIL  " + gate["label"])


def test_a_scenario_without_gates_is_an_empty_suite() -> None:
    root = ET.fromstring(gates_junit({"scenario": {"name": "x"}, "gates": []}))
    assert root.find("testsuite").get("tests") == "0" and root.find("testsuite/testcase") is None


def test_a_run_that_stops_before_its_gates_is_one_error(run_cli, tmp_path: Path) -> None:
    scenario = tmp_path / "broken.yaml"
    scenario.write_text("name: broken\ncurve: {file: missing.csv}\nworkpiece: {kind: plate, size_mm: [100, 100]}\n",
                        encoding="utf-8")
    report = tmp_path / "gates.xml"
    code, _, err = run_cli(["run", str(scenario), "--fast", "-o", str(tmp_path / "out"), "--junit", str(report)])
    assert code == 2
    [suite] = list(JUnitXml.fromfile(str(report)))
    [case] = list(suite)
    [error] = case.result
    assert isinstance(error, Error) and error.message in err and "missing.csv" in error.message


def test_the_junit_file_may_not_be_the_scenario(run_cli, tmp_path: Path) -> None:
    scenario = tmp_path / "s.yaml"
    scenario.write_text("name: s\n", encoding="utf-8")
    code, _, err = run_cli(["run", str(scenario), "--junit", str(scenario)])
    assert code == 2 and "--junit" in err and scenario.read_text(encoding="utf-8") == "name: s\n"


@pytest.mark.parametrize("text", [error_junit("x", "boom: <bad> & 'worse'", "ExecutionError")])
def test_error_reports_parse(text: str) -> None:
    assert ET.fromstring(text).find("testsuite/testcase/error").get("message") == "boom: <bad> & 'worse'"

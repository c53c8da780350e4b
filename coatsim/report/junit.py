"""The gates of a run as JUnit XML, the test-report format CI servers read (GitLab's unit test
reports, Jenkins' JUnit plugin, GitHub actions that publish test results).

One ``<testsuite>`` per run, one ``<testcase>`` per gate (a gate judges one metric of one
variant): its ``classname`` is ``coatsim.<scenario>.<variant>``, its ``name`` the gate's label,
and a failed gate holds a ``<failure>`` whose message is the gate's line of the console summary.
A run that stopped before its gates were evaluated is one test case with an ``<error>``.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Any, Mapping

from coatsim.report.summary import gate_line


def _suite(name: str, tests: int, failures: int, errors: int) -> ET.Element:
    return ET.Element("testsuite", {"name": f"coatsim.{name}", "tests": str(tests), "failures": str(failures),
                                    "errors": str(errors), "skipped": "0", "time": "0"})


def _xml(suite: ET.Element) -> str:
    suites = ET.Element("testsuites", {k: suite.get(k, "") for k in ("name", "tests", "failures", "errors", "time")})
    suites.append(suite)
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


def gates_junit(document: Mapping[str, Any]) -> str:
    """JUnit XML of the gates of a ``metrics.json`` document (``coatsim.metrics/1``)."""
    name = str(document["scenario"]["name"])
    gates = document["gates"]
    failed = [g for g in gates if not g["passed"]]
    suite = _suite(name, len(gates), len(failed), 0)
    for gate in gates:
        case = ET.SubElement(suite, "testcase", {"classname": f"coatsim.{name}.{gate['variant']}",
                                                 "name": gate["label"], "time": "0"})
        if not gate["passed"]:
            line = gate_line(gate)
            failure = ET.SubElement(case, "failure", {"message": line, "type": "GateFailure"})
            failure.text = line
    return _xml(suite)


def error_junit(scenario: str, message: str, kind: str) -> str:
    """JUnit XML of a run that stopped before its gates (``kind``: the error's class name)."""
    suite = _suite(scenario, 1, 0, 1)
    case = ET.SubElement(suite, "testcase", {"classname": f"coatsim.{scenario}", "name": "run", "time": "0"})
    error = ET.SubElement(case, "error", {"message": message, "type": kind})
    error.text = message
    return _xml(suite)

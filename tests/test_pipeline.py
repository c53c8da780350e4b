"""`coatsim run` end to end with the real stack: programs, arm, coat, metrics, report, exit codes."""

from __future__ import annotations

import contextlib
from html import escape
import io
import json
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from coatsim.cli import main
from coatsim.languages.kawasaki_as.files import read_toolpath
from coatsim.report.document import SECTION_IDS
from coatsim.report.verdict import verdict
from coatsim.robot.trajectory_log import read_trajectory_csv
from coatsim.run.scenario import VARIANTS

from small_scenario import SMALL



@dataclass(frozen=True)
class Cli:
    code: int
    out: str
    err: str


def run_cli(*args: str) -> Cli:
    """Run the console entry point in-process and capture its exit code and output."""
    out, err = io.StringIO(), io.StringIO()
    argv = sys.argv
    sys.argv = ["coatsim", *args]
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), pytest.raises(SystemExit) as info:
            main()
    finally:
        sys.argv = argv
    return Cli(int(info.value.code or 0), out.getvalue(), err.getvalue())


@pytest.fixture(scope="module")
def small_run(small_report: tuple[int, str, str, Path]) -> tuple[Cli, Path]:
    code, out, err, outdir = small_report
    return Cli(code, out, err), outdir


def test_a_failing_gate_exits_1_after_writing_everything(small_run: tuple[Cli, Path]) -> None:
    cli, outdir = small_run
    assert cli.code == 1, cli.err
    assert cli.err.count("\n") == 1 and "coatsim: error: 1 gate(s) failed: coating.thickness_cv [polysegment] < 0" in cli.err
    expected = {"polysegment.json", "metrics.json", "report.html", ".coatsim-outputs.json"}
    expected |= {f"{v}.{ext}" for v in VARIANTS for ext in ("as", "trajectory.csv", "thickness.ply", "thickness.glb")}
    assert {p.name for p in outdir.iterdir()} == expected
    for variant in VARIANTS:
        assert variant in cli.out.splitlines()[0]
    assert "FAIL  coating.thickness_cv [polysegment] < 0" in cli.out
    assert "gates: 3 of 4 passed" in cli.out


def test_metrics_json_keys_match_the_metrics_reference(small_run: tuple[Cli, Path], reference_metric_names: list[str]) -> None:
    _, outdir = small_run
    doc = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    assert doc["format"] == "coatsim.metrics/1" and doc["mode"] == "fast" and doc["passed"] is False
    assert doc["scenario"]["name"] == "small_job"
    assert list(doc["variants"]) == list(VARIANTS)
    for groups in doc["variants"].values():
        keys = [f"{g}.{n}" for g, values in groups.items() for n in values]
        assert keys == reference_metric_names
    assert [g["passed"] for g in doc["gates"]] == [True, True, True, False]


def test_the_variants_differ_as_the_controller_model_says(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    v = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))["variants"]
    seg = v["polysegment"]["segmentation"]
    assert seg["n_corners"] == 0 and seg["max_tangent_break_deg"] < 1e-6
    assert seg["max_deviation_mm"] <= 0.1 and seg["n_segments"] < v["polyline-stop"]["segmentation"]["n_segments"]
    assert v["polysegment"]["motion"]["stops"] == 0
    assert v["polyline-stop"]["motion"]["stops"] >= v["polyline-stop"]["segmentation"]["n_segments"] - 1
    assert v["polyline-stop"]["motion"]["cycle_time_s"] > v["polysegment"]["motion"]["cycle_time_s"]
    assert v["polyline-stop"]["coating"]["thickness_cv"] > v["polysegment"]["coating"]["thickness_cv"]
    for variant in VARIANTS:
        assert v[variant]["coating"]["mass_balance_error"] < 1e-3


def test_programs_trajectories_and_coats_read_back(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    for variant in VARIANTS:
        text = (outdir / f"{variant}.as").read_text(encoding="ascii")
        assert ("C1MOVE" in text) == (variant == "polysegment")
        assert read_toolpath(outdir / f"{variant}.as").spray_moves
        log = read_trajectory_csv(outdir / f"{variant}.trajectory.csv")
        assert log.spray.any() and len(log) > 100
        assert (outdir / f"{variant}.thickness.ply").read_bytes().startswith(b"ply\nformat binary_little_endian")
    poly = json.loads((outdir / "polysegment.json").read_text(encoding="utf-8"))
    assert poly["format"] == "coatsim.polysegment/1" and len(poly["segments"]) >= 3


def test_report_has_every_section_in_order_and_embeds_everything(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    html = (outdir / "report.html").read_text(encoding="utf-8")
    found = re.findall(r'<section id="([^"]+)">', html)
    assert found == list(SECTION_IDS) == ["verdict", "speed", "thickness-along-track", "maps", "warnings", "view3d",
                                          "program", "metrics", "summary", "gates"]
    images = re.findall(r'<img alt="[^"]*" src="data:image/png;base64,', html)
    # speed, centre line and histograms, maps and difference, events, the curves (polysegment, θ, polyline);
    # the verdict's bars are HTML, one chart per polyline variant
    assert len(images) == 5
    assert html.count('<table class="bars">') == 2
    assert not re.search(r'(src|href)="(?!data:|#)', html)  # nothing outside the file
    assert not re.search(r"<script[^>]+src=", html) and "https://" not in html.split("<script>")[-1]
    assert "FAIL" in html and "coating.thickness_cv [polysegment] &lt; 0" in html


def test_report_and_console_lead_with_the_verdict_from_the_metrics(small_run: tuple[Cli, Path]) -> None:
    cli, outdir = small_run
    html = (outdir / "report.html").read_text(encoding="utf-8")
    doc = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    comparisons = verdict(doc).comparisons
    assert [c.against for c in comparisons] == ["polyline-stop", "polyline-blend"]
    section = html[html.index('<section id="verdict">'):html.index('<section id="speed">')]
    for c in comparisons:
        assert escape(c.headline, quote=True) in section
        assert c.headline in cli.out
    assert "Gates: 3 of 4 passed; FAILED: coating.thickness_cv [polysegment] &lt; 0" in section


def test_metrics_are_shown_with_human_names_and_percent(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    html = (outdir / "report.html").read_text(encoding="utf-8")
    table = html[html.index('<section id="metrics">'):html.index('<section id="summary">')]
    doc = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    at_speed = doc["variants"]["polysegment"]["motion"]["fraction_at_speed"]
    row = re.search(r'>length at speed \(≥ 95 %\)</td><td class="l">%</td><td>([^<]+)</td>', table)
    assert row and float(row.group(1)) == pytest.approx(100 * at_speed, rel=1e-3)
    breaks = re.search(r">largest tangent break</td><td class=\"l\">deg</td>(.*?)</tr>", table).group(1)
    assert breaks.endswith("<td>–</td><td>–</td>")  # no ratio to a tangent break of 0
    assert ">motion.fraction_at_speed<" not in table and "e+1" not in table


def test_run_finds_the_roi_border_and_the_polyline_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Three variants on one surface: the edge band's border distance and the polyline (with
    its deviation) are computed once and shared, not per variant."""
    import coatsim.run.pipeline
    import coatsim.path.build
    import coatsim.spray.coating_metrics

    calls = {"border_distance": 0, "polyline_of": 0}

    def counted(module, name):
        real = getattr(module, name)

        def wrapper(*args, **kwargs):
            calls[name] += 1
            return real(*args, **kwargs)
        monkeypatch.setattr(module, name, wrapper)

    counted(coatsim.spray.coating_metrics, "border_distance")
    for module in (coatsim.run.pipeline, coatsim.path.build):
        counted(module, "polyline_of")
    scenario = tmp_path / "three.yaml"
    scenario.write_text(SMALL.replace('  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}\n', ""), encoding="utf-8")
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert cli.code == 0, cli.out + cli.err
    document = json.loads((tmp_path / "out" / "metrics.json").read_text(encoding="utf-8"))
    assert set(document["variants"]) == set(VARIANTS)
    assert calls == {"border_distance": 1, "polyline_of": 1}
    stop, blend = (document["variants"][v]["segmentation"] for v in ("polyline-stop", "polyline-blend"))
    assert stop == blend  # the same polyline, measured once


def test_a_scenario_that_cannot_execute_exits_3(tmp_path: Path) -> None:
    far = SMALL.replace("{kind: plate, size_mm: [130.0, 90.0]}",
                        "{kind: plate, size_mm: [130.0, 90.0], pose: {position_mm: [4000.0, 0.0, 200.0]}}")
    scenario = tmp_path / "far.yaml"
    scenario.write_text(far, encoding="utf-8")
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert cli.code == 3, cli.err
    assert cli.err.startswith("coatsim: error: polysegment: ") and cli.err.count("\n") == 1


@pytest.mark.parametrize("workpiece", [
    "{kind: cylinder, radius_mm: 80.0, length_mm: 80.0, axis: y}",
    "{kind: mesh, file: panel.stl}",
])
def test_cylinder_and_mesh_workpieces_are_coated(tmp_path: Path, workpiece: str) -> None:
    import trimesh

    corners = np.array([[-65.0, -45.0, 0.0], [65.0, -45.0, 0.0], [65.0, 45.0, 0.0], [-65.0, 45.0, 0.0]])
    trimesh.Trimesh(corners, [[0, 1, 2], [0, 2, 3]]).export(tmp_path / "panel.stl")
    text = SMALL.replace("{kind: plate, size_mm: [130.0, 90.0]}", workpiece)
    text = text.replace("gates:", "variants: [polysegment]\ngates:").replace(
        '  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}\n', "")
    scenario = tmp_path / "part.yaml"
    scenario.write_text(text, encoding="utf-8")
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert cli.code == 0, cli.out + cli.err
    coating = json.loads((tmp_path / "out" / "metrics.json").read_text(encoding="utf-8"))["variants"]["polysegment"]["coating"]
    assert coating["mass_balance_error"] < 1e-3 and coating["thickness_mean_um"] > 5.0


@pytest.mark.parametrize("edit,line,fragment", [
    (("speed_mm_s: 200.0", "speed_mm_s: -1.0"), 9, "motion.speed_mm_s"),
    (("metric: motion.stops", "metric: motion.n_stops"), 15, "unknown metric 'motion.n_stops'; did you mean 'motion.stops'?"),
    (("metric: motion.stops", "metric: cost.total"), 15, "unknown metric 'cost.total'; known: segmentation.n_segments"),
])
def test_invalid_scenarios_exit_2_naming_the_line(tmp_path: Path, edit: tuple[str, str], line: int, fragment: str) -> None:
    scenario = tmp_path / "bad.yaml"
    scenario.write_text(SMALL.replace(*edit), encoding="utf-8")
    cli = run_cli("run", str(scenario), "-o", str(tmp_path / "out"))
    assert cli.code == 2
    assert cli.err.startswith(f"coatsim: error: {scenario}:{line}: ") and fragment in cli.err, cli.err
    assert not (tmp_path / "out").exists()


def test_schema_command_prints_the_json_schema() -> None:
    cli = run_cli("schema")
    assert cli.code == 0
    assert json.loads(cli.out)["title"] == "coatsim scenario"


def test_run_thickness_ply_carries_exposure_like_coat(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    header = (outdir / "polysegment.thickness.ply").read_bytes().split(b"end_header")[0].decode("ascii")
    assert "property float thickness\nproperty float exposure\n" in header


def test_run_writes_the_cells_tool_and_reports_no_mismatch(small_run: tuple[Cli, Path]) -> None:
    cli, outdir = small_run
    assert "TOOL TRANS(0.00000000,0.00000000,250.00000000,0.000000,0.000000,0.000000)" in (
        outdir / "polysegment.as").read_text(encoding="ascii")
    doc = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    assert not [w for w in doc["warnings"] if "(TOOL)" in w["message"]]
    assert '<section id="warnings"><h2>Warnings and events</h2>' in (outdir / "report.html").read_text(encoding="utf-8")


def test_a_missing_robot_model_names_its_yaml_line(tmp_path: Path) -> None:
    scenario = tmp_path / "job.yaml"
    scenario.write_text(SMALL.replace("gates:", "robot:\n  model: cells/missing.xml\ngates:"), encoding="utf-8")
    line = SMALL.replace("gates:", "robot:\n  model: cells/missing.xml\ngates:").splitlines().index(
        "  model: cells/missing.xml") + 1
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert cli.code == 2
    assert cli.err.startswith(f"coatsim: error: {scenario}:{line}: robot.model: {tmp_path / 'cells' / 'missing.xml'}: "
                              "model file not found"), cli.err
    assert not (tmp_path / "out").exists()  # checked before anything is written
    cli = run_cli("run", str(scenario), "--fast", "--model", str(tmp_path / "other.xml"), "-o", str(tmp_path / "out"))
    assert cli.code == 2 and cli.err.startswith(f"coatsim: error: --model: {tmp_path / 'other.xml'}: model file not found")


def test_run_uses_the_scenarios_model_file_or_the_override(tmp_path: Path) -> None:
    """A copy of the shipped cell whose gun is 20 mm longer: the programs get its TOOL, the run
    needs no other change; with --model the shipped cell is used again."""
    from coatsim.robot.cell import MODELS

    cells = tmp_path / "cells"
    cells.mkdir()
    for name in ("coating_cell.xml", "rs013n_arm.xml"):
        (cells / name).write_text((MODELS / name).read_text(encoding="utf-8"), encoding="utf-8")
    gun = (MODELS / "plasma_gun.xml").read_text(encoding="utf-8").replace('<site name="tcp" pos="0.25 0 0"',
                                                                           '<site name="tcp" pos="0.27 0 0"')
    (cells / "plasma_gun.xml").write_text(gun, encoding="utf-8")
    text = SMALL.replace("gates:", "variants: [polysegment]\nrobot: {model: cells/coating_cell.xml}\ngates:")
    scenario = tmp_path / "job.yaml"
    scenario.write_text(text.replace('  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}\n', ""), encoding="utf-8")
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "own"))
    assert cli.code == 0, cli.err
    assert "TOOL TRANS(0.00000000,0.00000000,270.00000000," in (tmp_path / "own" / "polysegment.as").read_text()
    cli = run_cli("run", str(scenario), "--fast", "--model", str(MODELS / "coating_cell.xml"), "-o", str(tmp_path / "shipped"))
    assert cli.code == 0, cli.err
    assert "TOOL TRANS(0.00000000,0.00000000,250.00000000," in (tmp_path / "shipped" / "polysegment.as").read_text()


SHIPPED = sorted((Path(__file__).resolve().parents[1] / "scenarios").glob("*.yaml"))


@pytest.mark.slow
@pytest.mark.parametrize("scenario", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_shipped_scenario_passes_its_gates_in_fast_mode(scenario: Path, tmp_path: Path) -> None:
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path))
    assert cli.code == 0, cli.out + cli.err


@pytest.mark.slow
def test_a_users_program_against_coatsims(tmp_path):
    """A user's polyline program as a variant: the curve is its sprayed path, coatsim's arc
    program of the same path is compared with it in metrics.json and the report."""
    sys.path.insert(0, str(Path(__file__).parent / "languages" / "kawasaki_as"))
    from as_samples import rounded_rectangle_points, user_contour

    (tmp_path / "cell.as").write_bytes(user_contour(rounded_rectangle_points(), z=300.0))
    scenario = tmp_path / "mine.yaml"
    scenario.write_text(
        "name: mine_vs_arcs\nworkpiece: {kind: plate, size_mm: [200.0, 120.0]}\n"
        "gun: {standoff_mm: 100.0, target_thickness_um: 16.0}\nmotion: {speed_mm_s: 150.0}\n"
        "variants:\n  - {name: mine, program: cell.as}\n  - polysegment\n  - polyline-blend\n"
        "fast: {coating_spacing_mm: 4.0, sample_step_mm: 2.0}\n"
        "gates:\n  - {metric: segmentation.n_segments, variant: polysegment, op: '<', compare_to: mine, factor: 0.1}\n")
    result = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert result.code == 0, result.err
    doc = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert list(doc["variants"]) == ["mine", "polysegment", "polyline-blend"]
    mine, arcs = doc["variants"]["mine"], doc["variants"]["polysegment"]
    assert mine["segmentation"]["n_segments"] == len(rounded_rectangle_points()) - 1
    assert arcs["segmentation"]["n_segments"] < 20
    assert mine["segmentation"]["max_deviation_mm"] < 1e-6
    assert mine["motion"]["curve_length_mm"] == pytest.approx(arcs["segmentation"]["curve_length_mm"], rel=0.01)
    assert (tmp_path / "out" / "mine.as").read_text().startswith(".PROGRAM trace()")
    assert "sprayed path of program variant mine" in (tmp_path / "out" / "report.html").read_text()


def test_a_users_program_with_a_defect_is_one_line(tmp_path):
    (tmp_path / "bad.as").write_text(".PROGRAM x()\n  JMOVE a\n  LMOVE nowhere\n.END\n.TRANS\na 700 0 300 0 180 0\n.END\n")
    scenario = tmp_path / "s.yaml"
    scenario.write_text("name: s\nworkpiece: {kind: plate, size_mm: [100, 100]}\n"
                        "variants:\n  - {name: mine, program: bad.as}\n  - polysegment\n")
    result = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert result.code == 2 and result.err.count("\n") == 1
    assert f"{scenario}:3: variant mine: {tmp_path / 'bad.as'}:3: LMOVE skipped: pose nowhere has no value" \
        in result.err
    (tmp_path / "dry.as").write_text(".PROGRAM dry()\n  JMOVE a\n  LMOVE b\n.END\n.TRANS\na 700 0 300 0 180 0\n"
                                     "b 720 0 300 0 180 0\n.END\n")
    scenario.write_text(scenario.read_text().replace("bad.as", "dry.as"))
    result = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / "out"))
    assert result.code == 2 and result.err.count("\n") == 1
    assert f"{scenario}:3: variant mine: {tmp_path / 'dry.as'}: the gun (output 1) is never on during a motion; " \
        "it switches no output" in result.err

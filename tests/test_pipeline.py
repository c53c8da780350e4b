"""`coatsim run` end to end with the real stack: programs, arm, coat, metrics, report, exit codes."""

from __future__ import annotations

import contextlib
import io
import json
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from coatsim.cli import main
from coatsim.program import read_toolpath
from coatsim.report.document import SECTION_TITLES
from coatsim.robot.trajectory_log import read_trajectory_csv
from coatsim.scenario import VARIANTS

SMALL = """\
name: small_job
description: two 60 mm passes joined by one semicircular turn-around
curve:
  builtin: raster
  params: {width: 60.0, pitch: 20.0, passes: 2}
segmentation: {tolerance_mm: 0.1}
workpiece: {kind: plate, size_mm: [130.0, 90.0]}
gun: {footprint: "gaussian:sigma=5", target_thickness_um: 16.0}
motion: {speed_mm_s: 200.0, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0}
coating: {spacing_mm: 2.0, band_halfwidth_mm: 2.5}
fast: {coating_spacing_mm: 2.5}
gates:
  - {metric: segmentation.max_deviation_mm, op: "<=", threshold: 0.1}
  - {metric: coating.mass_balance_error, op: "<=", threshold: 0.001}
  - {metric: motion.stops, op: "==", threshold: 0}
  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}
"""


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
def small_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Cli, Path]:
    folder = tmp_path_factory.mktemp("small")
    scenario = folder / "small_job.yaml"
    scenario.write_text(SMALL, encoding="utf-8")
    outdir = folder / "out"
    return run_cli("run", str(scenario), "--fast", "-o", str(outdir)), outdir


def test_a_failing_gate_exits_1_after_writing_everything(small_run: tuple[Cli, Path]) -> None:
    cli, outdir = small_run
    assert cli.code == 1, cli.err
    assert cli.err.count("\n") == 1 and "coatsim: error: 1 gate(s) failed: coating.thickness_cv [polysegment] < 0" in cli.err
    expected = {"polysegment.json", "metrics.json", "report.html"}
    expected |= {f"{v}.{ext}" for v in VARIANTS for ext in ("as", "trajectory.csv", "thickness.ply")}
    assert {p.name for p in outdir.iterdir()} == expected
    for variant in VARIANTS:
        assert variant in cli.out.splitlines()[0]
    assert "FAIL  coating.thickness_cv [polysegment] < 0" in cli.out
    assert "gates: 3 of 4 passed" in cli.out


def test_metrics_json_keys_match_the_readme_table(small_run: tuple[Cli, Path], readme_metric_names: list[str]) -> None:
    _, outdir = small_run
    doc = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    assert doc["format"] == "coatsim.metrics/1" and doc["mode"] == "fast" and doc["passed"] is False
    assert doc["scenario"]["name"] == "small_job"
    assert list(doc["variants"]) == list(VARIANTS)
    for groups in doc["variants"].values():
        keys = [f"{g}.{n}" for g, values in groups.items() for n in values]
        assert keys == readme_metric_names
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


def test_report_has_every_section_and_embeds_its_images(small_run: tuple[Cli, Path]) -> None:
    _, outdir = small_run
    html = (outdir / "report.html").read_text(encoding="utf-8")
    for anchor, title in SECTION_TITLES.items():
        assert f'<section id="{anchor}"><h2>{title}</h2>' in html
    images = re.findall(r'<img alt="[^"]*" src="data:image/png;base64,', html)
    assert len(images) == 5  # curve, θ, speed, thickness maps, cross-section
    assert not re.search(r'(src|href)="(?!data:|#)', html)
    assert "<script" not in html.lower()
    assert "FAIL" in html and "coating.thickness_cv [polysegment] &lt; 0" in html


def test_run_finds_the_roi_border_and_the_polyline_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Three variants on one surface: the edge band's border distance and the polyline (with
    its deviation) are computed once and shared, not per variant."""
    import coatsim.pipeline
    import coatsim.program.build
    import coatsim.spray.coating_metrics

    calls = {"border_distance": 0, "polyline_of": 0}

    def counted(module, name):
        real = getattr(module, name)

        def wrapper(*args, **kwargs):
            calls[name] += 1
            return real(*args, **kwargs)
        monkeypatch.setattr(module, name, wrapper)

    counted(coatsim.spray.coating_metrics, "border_distance")
    for module in (coatsim.pipeline, coatsim.program.build):
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


@pytest.mark.slow
def test_same_inputs_give_byte_identical_outputs(tmp_path: Path) -> None:
    scenario = tmp_path / "small_job.yaml"
    scenario.write_text(SMALL, encoding="utf-8")
    for name in ("a", "b"):
        run_cli("run", str(scenario), "--fast", "-o", str(tmp_path / name))
    files = sorted(p.name for p in (tmp_path / "a").iterdir())
    assert files == sorted(p.name for p in (tmp_path / "b").iterdir())
    for name in files:
        a, b = ((tmp_path / d / name).read_bytes() for d in ("a", "b"))
        if name == "polysegment.json":  # its stats record the fitter's wall time
            a, b = (json.loads(x) | {"stats": json.loads(x)["stats"] | {"seconds": 0}} for x in (a, b))
        assert a == b, name


SHIPPED = sorted((Path(__file__).resolve().parents[1] / "scenarios").glob("*.yaml"))


@pytest.mark.slow
@pytest.mark.parametrize("scenario", SHIPPED, ids=[p.stem for p in SHIPPED])
def test_shipped_scenario_passes_its_gates_in_fast_mode(scenario: Path, tmp_path: Path) -> None:
    cli = run_cli("run", str(scenario), "--fast", "-o", str(tmp_path))
    assert cli.code == 0, cli.out + cli.err

"""Resource budgets (issue 14 item 5): each input of the issue that grew without bound is refused
with exit 2 and a budget message *before* the large allocation. Proof without timing: every
command runs in one child process whose address space is capped (RLIMIT_AS, 1.5 GB), so an
allocation the budget did not stop would end in "out of memory" (exit 3), not in exit 2."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from coatsim.core.budgets import MAX_CURVE_FILE_BYTES, MAX_TRAJECTORY_BYTES, MAX_YAML_BYTES
from coatsim.robot.trajectory_log import TrajectoryLog

CAP_BYTES = 1536 << 20
BASE = """\
name: {name}
curve: {{builtin: ellipse, params: {{a: 40.0, b: 20.0}}}}
workpiece: {{kind: plate, size_mm: [120.0, 80.0]}}
variants: [polysegment]
"""

CHILD = r"""
import contextlib, io, json, resource, sys
resource.setrlimit(resource.RLIMIT_AS, (CAP, CAP))
from coatsim.cli import main
results = []
for argv in json.loads(sys.argv[1]):
    err = io.StringIO()
    sys.argv = ["coatsim", *argv]
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            main()
        except SystemExit as exc:
            results.append((exc.code, err.getvalue()))
print(json.dumps(results))
"""


def _sparse(path: Path, size: int) -> Path:
    """A file of ``size`` bytes that takes no disk space."""
    with open(path, "wb") as handle:
        handle.truncate(size)
    return path


def _bomb(levels: int = 9) -> str:
    text = 'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n'
    names = "abcdefghijk"
    for prev, name in zip(names, names[1:levels]):
        text += f"{name}: &{name} [" + ",".join([f"*{prev}"] * 9) + "]\n"
    return text


def _trajectory(path: Path) -> Path:
    t = np.arange(0.0, 0.5, 0.002)
    position = np.column_stack((-50 + 200 * t, np.zeros_like(t), np.full_like(t, 100.0)))
    TrajectoryLog(t=t, position=position, axis=np.tile([0.0, 0.0, -1.0], (len(t), 1)), speed=np.full_like(t, 200.0),
                  spray=np.ones(len(t), bool), progress=200 * t, path_error=np.zeros_like(t),
                  q=np.zeros((len(t), 6))).write_csv(path)
    return path




@pytest.fixture(scope="module")
def results(tmp_path_factory) -> dict[str, tuple[int, str]]:
    """Every case run once in one memory-capped child process."""
    d = tmp_path_factory.mktemp("budgets")

    for name, speed in (("prog", "500"), ("slow", "1e-3")):
        subprocess.run([sys.executable, "-m", "coatsim.cli", "program", "builtin:ellipse:a=40,b=20", "--tol", "0.2",
                        "--speed", speed, "-o", str(d / f"{name}.as")], check=True, capture_output=True)
    traj = _trajectory(d / "traj.csv")

    def scenario(name: str, extra: str) -> str:
        path = d / f"{name}.yaml"
        path.write_text(BASE.format(name=name) + extra)
        return str(path)

    cases = {
        "path samples (--step-mm 1e-4)": ["execute", str(d / "prog.as"), "--step-mm", "1e-4", "-o", str(d / "e1")],
        "path samples (sample_step_mm: 1e-4)": ["run", scenario("fine", "fast: {sample_step_mm: 1.0e-4}\n"), "--fast",
                                                "-o", str(d / "r1")],
        "simulation steps (--speed 1e-3)": ["execute", str(d / "slow.as"), "-o", str(d / "e2")],
        "simulation steps (speed_mm_s: 1e-3)": ["run", scenario("crawl", "motion: {speed_mm_s: 1.0e-3}\n"), "--fast",
                                                "-o", str(d / "r2")],
        "mesh vertices (coat --spacing 0.001)": ["coat", str(traj), "--surface", "plate:300x300@0,0,0", "--spacing",
                                                 "0.001", "-o", str(d / "c1")],
        "mesh vertices (cylinder)": ["coat", str(traj), "--surface", "cylinder:50x300@0,0,0", "--spacing", "0.01",
                                     "-o", str(d / "c2")],
        "mesh vertices (coating.spacing_mm)": ["run", scenario("dense", "coating: {spacing_mm: 0.001}\n"),
                                               "-o", str(d / "r3")],
        "spray sub-steps": ["coat", str(traj), "--surface", "plate:300x300@0,0,0", "--spacing", "5",
                            "--footprint", "gaussian:sigma=1e-5", "-o", str(d / "c3")],
        "trajectory size": ["coat", str(_sparse(d / "huge.csv", MAX_TRAJECTORY_BYTES + 1)), "--surface",
                            "plate:100x100@0,0,0", "-o", str(d / "c4")],
        "curve points (builtin)": ["segment", "builtin:ellipse:points=1e9", "--tol", "0.1"],
        "curve counts (polygon sides)": ["segment", "builtin:polygon:sides=1e12", "--tol", "0.1"],
        "curve file size": ["segment", str(_sparse(d / "huge_curve.csv", MAX_CURVE_FILE_BYTES + 1)), "--tol", "0.1"],
        "YAML size": ["run", str(_sparse(d / "huge.yaml", MAX_YAML_BYTES + 1))],
        "YAML nesting depth": ["run", str(d / "deep.yaml")],
        "YAML alias expansion": ["run", str(d / "bomb.yaml")],
        "YAML alias uses": ["run", str(d / "aliases.yaml")],
    }
    (d / "deep.yaml").write_text("a: " + "[" * 100_000 + "]" * 100_000 + "\n")
    (d / "bomb.yaml").write_text(_bomb())
    (d / "aliases.yaml").write_text("a: &a 1\nb: [" + ",".join(["*a"] * 500) + "]\n")
    names = list(cases)
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
    child = subprocess.run([sys.executable, "-c", CHILD.replace("CAP", str(CAP_BYTES)), json.dumps(list(cases.values()))],
                           capture_output=True, text=True, env=env, timeout=600)
    assert child.returncode == 0, child.stderr
    return dict(zip(names, (tuple(r) for r in json.loads(child.stdout))))


EXPECTED = {
    "path samples (--step-mm 1e-4)": "IK samples of the path",
    "path samples (sample_step_mm: 1e-4)": "IK samples of the path",
    "simulation steps (--speed 1e-3)": "simulation steps of 2 ms",
    "simulation steps (speed_mm_s: 1e-3)": "simulation steps of 2 ms",
    "mesh vertices (coat --spacing 0.001)": "plate 300 x 300 mm meshed every 0.001 mm: vertices: 90,000,600,001 needed",
    "mesh vertices (cylinder)": "cylinder R 50 x 300 mm meshed every 0.01 mm: vertices",
    "mesh vertices (coating.spacing_mm)": "meshed every 0.001 mm: vertices",
    "spray sub-steps": "coating sub-steps",
    "trajectory size": "bytes of the trajectory",
    "curve points (builtin)": "builtin:ellipse: points: 1,000,000,000 needed",
    "curve counts (polygon sides)": "builtin:polygon: sides: 1,000,000,000,000 needed",
    "curve file size": "bytes of the curve file",
    "YAML size": "bytes of the YAML file",
    "YAML nesting depth": "deep.yaml:1: nested deeper than 32 levels",
    "YAML alias expansion": "aliases expand to more than 100,000 values",
    "YAML alias uses": "aliases.yaml:2: more than 100 alias uses",
}


@pytest.mark.parametrize("case", list(EXPECTED))
def test_budget_refuses_before_allocating(results, case):
    code, err = results[case]
    assert code == 2, err
    assert err.startswith("coatsim: error: ") and err.count("\n") == 1, err
    assert EXPECTED[case] in err, err
    if "YAML" not in case:
        assert "over the budget of" in err, err

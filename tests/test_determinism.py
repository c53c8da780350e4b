"""Same inputs, same bytes: every output file of run (a shipped scenario), segment, program,
execute and coat; timings only on request, on stderr."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.golden

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "scenarios" / "airfoil_edge.yaml"  # the quickest shipped scenario

# Each stage once, on small inputs; {out} is the output folder.
COMMANDS = [
    ["segment", "builtin:ellipse:points=600", "--tol", "0.2", "-o", "{out}/poly.json", "--plot", "{out}/poly.png"],
    ["program", "builtin:polygon:sides=3,radius=25", "--tol", "0.5", "--speed", "400", "-o", "{out}/prog.as"],
    ["execute", "{out}/prog.as", "-o", "{out}/exec"],
    ["coat", "{out}/exec/trajectory.csv", "--surface", "plate:120x120@700,0,200", "--spacing", "3", "-o", "{out}/coat"],
    ["run", str(SHIPPED), "--fast", "-o", "{out}/run"],
]
DRIVER = """
import sys
from coatsim.cli import main
for argv in {commands!r}:
    sys.argv = ["coatsim", *argv]
    try:
        main()
    except SystemExit as exc:
        if exc.code:
            raise SystemExit(f"{{argv[0]}} exited {{exc.code}}")
"""


def files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_every_output_is_byte_identical_across_runs(tmp_path: Path) -> None:
    """Two fresh interpreters with different hash seeds, side by side, each in its own folder
    (the outputs name the relative paths they were given, which are the same)."""
    commands = [[a.replace("{out}", "out") for a in cmd] for cmd in COMMANDS]
    procs = []
    for name, seed in (("a", "1"), ("b", "2")):
        (tmp_path / name).mkdir()
        env = {**os.environ, "PYTHONHASHSEED": seed, "MPLBACKEND": "Agg"}
        procs.append(subprocess.Popen([sys.executable, "-c", DRIVER.format(commands=commands)], cwd=tmp_path / name,
                                      env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    for proc in procs:
        _, err = proc.communicate(timeout=900)
        assert proc.returncode == 0, err
    first, second = files(tmp_path / "a"), files(tmp_path / "b")
    assert sorted(first) == sorted(second)
    expected = {"poly.json", "poly.png", "prog.as", "exec/trajectory.csv", "exec/motion.json", "exec/speed.png",
                "coat/thickness.ply", "coat/coating.json", "coat/heatmap.png", "coat/section.png",
                "run/polysegment.json", "run/metrics.json", "run/report.html"}
    assert {f"out/{name}" for name in expected} <= set(first), sorted(first)
    assert [name for name in first if first[name] != second[name]] == []


@pytest.mark.parametrize("argv", [["segment", "builtin:ellipse:points=600", "--tol", "0.2", "--timings"]])
def test_timings_go_to_stderr_on_request_only(argv, run_cli) -> None:
    code, out, err = run_cli(argv)
    assert code == 0 and err.startswith("timings: fitter ") and " s" in err
    assert "time" not in out
    code, out, err = run_cli(argv[:-1])
    assert code == 0 and err == ""

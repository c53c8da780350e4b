"""A real install: the wheel, built from this checkout, installed into a fresh virtual
environment, runs `coatsim program` and `coatsim execute` from a folder outside the checkout
with the robot model it carries as package data."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(argv: list[str], cwd: Path, timeout: float = 900) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    return subprocess.run(argv, cwd=cwd, capture_output=True, text=True, timeout=timeout, env=env | {"MPLBACKEND": "Agg"})


@pytest.mark.slow
def test_the_wheel_installed_in_a_fresh_venv_executes_a_written_program(tmp_path: Path) -> None:
    wheels = tmp_path / "wheels"
    built = run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(wheels), str(ROOT)], tmp_path)
    assert built.returncode == 0, built.stderr
    (wheel,) = wheels.glob("coatsim-*.whl")

    # A fresh environment; the dependencies (numpy, mujoco, ...) are this interpreter's, made
    # visible after the environment's own site-packages, so the coatsim found is the wheel's.
    env_dir = tmp_path / "env"
    venv.EnvBuilder(with_pip=True).create(env_dir)
    python = env_dir / "bin" / "python"
    purelib = run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], tmp_path).stdout.strip()
    deps = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"], *sys.path[1:]}
    (Path(purelib) / "_deps_of_the_test_environment.pth").write_text(
        "\n".join(p for p in deps if p and Path(p).is_dir() and Path(p).resolve() != ROOT) + "\n")
    installed = run([str(python), "-m", "pip", "install", "--no-deps", "-q", str(wheel)], tmp_path)
    assert installed.returncode == 0, installed.stderr

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    where = run([str(python), "-c", "import coatsim, coatsim.robot.cell as c; print(coatsim.__file__); "
                 "print(c.DEFAULT_MODEL)"], elsewhere)
    assert where.returncode == 0, where.stderr
    package, model = where.stdout.split()
    assert Path(package).resolve().is_relative_to(env_dir.resolve()), package
    assert Path(model).resolve().is_relative_to(env_dir.resolve()) and Path(model).is_file(), model

    coatsim = str(env_dir / "bin" / "coatsim")
    version = run([coatsim, "--version"], elsewhere)
    assert version.returncode == 0 and version.stdout.startswith("coatsim ")
    program = run([coatsim, "program", "builtin:rounded-rectangle:width=80,height=50", "--tol", "0.1", "-o", "job.as"],
                  elsewhere)
    assert program.returncode == 0, program.stderr
    executed = run([coatsim, "execute", "job.as", "-o", "out"], elsewhere)
    assert executed.returncode == 0, executed.stderr
    doc = json.loads((elsewhere / "out" / "motion.json").read_text(encoding="utf-8"))
    assert doc["model"] == "default" and doc["motion"]["stops"] == 0 and doc["events"] == []
    assert (elsewhere / "out" / "trajectory.csv").stat().st_size > 10_000

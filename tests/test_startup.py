"""Start-up: importing a stage loads only what the stage needs (checked in fresh interpreters)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

PLOTTING = ("matplotlib", "toppra")  # toppra imports matplotlib.pyplot at import


def loaded(modules: list[str], watch: tuple[str, ...]) -> list[str]:
    code = (f"import sys, json\nfor m in {modules!r}: __import__(m)\n"
            f"print(json.dumps([w for w in {list(watch)!r} if w in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


@pytest.mark.parametrize("modules", [
    ["coatsim.geometry", "coatsim.geometry.segment", "coatsim.geometry.builtin_curves", "coatsim.geometry.polysegment_json"],
    ["coatsim.path", "coatsim.path.check", "coatsim.path.build", "coatsim.cli.program"],
    ["coatsim.robot.execute", "coatsim.robot.ik", "coatsim.robot.sampling", "coatsim.robot.playback",
     "coatsim.robot.cell", "coatsim.robot.motion_metrics", "coatsim.robot.reference", "coatsim.robot.timing"],
])
def test_geometry_program_and_robot_stages_load_no_plotting_library(modules):
    assert loaded(modules, PLOTTING) == []


def test_the_program_stage_and_the_cli_load_no_scipy_and_no_simulator():
    heavy = ("scipy.optimize", "scipy.special", "scipy.spatial", "mujoco", "mink", "trimesh", "pydantic", "dask")
    assert loaded(["coatsim.path", "coatsim.path.check", "coatsim.cli.program"], heavy) == []
    assert loaded(["coatsim.cli.app"], heavy + ("numpy",) + PLOTTING) == []


def test_a_sweep_client_loads_no_simulator_until_it_runs_points():
    assert loaded(["coatsim.sweep.run", "coatsim.sweep.points"], ("mujoco", "mink", "toppra", "trimesh", "dask")) == []


INTERPRETERS = tuple(f"coatsim.languages.{name}.interpreter"
                     for name in ("abb_rapid", "kuka_krl", "fanuc_tp", "urscript", "gcode"))


def test_a_run_loads_the_interpreter_of_a_language_only_when_it_reads_a_program_in_it():
    assert loaded(["coatsim.languages.registry", "coatsim.run.pipeline"], INTERPRETERS) == []

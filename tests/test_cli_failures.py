"""Every failure is one line with the right exit code (issue 14 items 6 and 7), with the exact
inputs the reliability audit used."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from cli_helpers import cli

from coatsim.core.outputs_guard import LOCK_NAME

PLATE = "workpiece: {kind: plate, size_mm: [120.0, 80.0]}\nvariants: [polysegment]\n"




def one_line(result: tuple[int, str, str], code: int, *fragments: str) -> str:
    got, _, err = result
    assert got == code, err
    assert err.count("\n") == 1 and err.startswith("coatsim: "), err
    for fragment in fragments:
        assert fragment in err, err
    return err


def child_env() -> dict[str, str]:
    return {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}


# --- item 6: no traceback ever ------------------------------------------------------------------

def test_coordinates_past_1e154_are_an_input_error(tmp_path):
    curve = tmp_path / "big.csv"
    curve.write_text("0,0\n1e154,1\n2e154,0\n")
    one_line(cli("segment", curve, "--tol", "0.1"), 2, "point 2 lies beyond 1e+09 mm")
    np.save(tmp_path / "big.npy", np.array([[0.0, 0.0], [1e300, 1.0], [2.0, 0.0]]))
    one_line(cli("program", tmp_path / "big.npy", "--tol", "0.1"), 2, "point 2 lies beyond")


def test_deeply_nested_yaml_is_one_line(tmp_path):
    deep = tmp_path / "deep.yaml"
    deep.write_text("name: x\ncurve: " + "{a: " * 3000 + "1" + "}" * 3000 + "\n")
    one_line(cli("run", deep), 2, "deep.yaml:2: nested deeper than 32 levels")
    recursive = tmp_path / "recursive.yaml"
    recursive.write_text("name: &n [*n]\n")
    one_line(cli("run", recursive), 2, "recursive alias")


def test_out_of_memory_under_a_memory_cap_is_one_line(tmp_path):
    """1.4 M vertices are within the budget but not within 700 MB of address space."""
    cap = 700 << 20
    code = ("import resource, sys; resource.setrlimit(resource.RLIMIT_AS, (%d, %d)); from coatsim.cli import main; "
            "sys.argv = ['coatsim'] + sys.argv[1:]; main()" % (cap, cap))
    child = subprocess.run([sys.executable, "-c", code, "coat", str(_trajectory(tmp_path)), "--surface",
                            "plate:300x300@0,0,0", "--spacing", "0.25", "-o", str(tmp_path / "out")],
                           capture_output=True, text=True, env=child_env(), timeout=300)
    assert child.returncode == 3, child.stderr
    assert child.stderr.startswith("coatsim: error: out of memory;") and child.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_an_unexpected_exception_is_one_line_exit_70(tmp_path, monkeypatch):
    import coatsim.geometry

    def broken(*args, **kwargs):
        raise ValueError("Invalid input for linprog: A_ub must not contain values inf, nan, or None\nmore lines")

    monkeypatch.setattr(coatsim.geometry, "segment_curve", broken)
    one_line(cli("segment", "builtin:ellipse", "--tol", "0.1"), 70,
             "coatsim: internal error: ValueError: Invalid input for linprog", "COATSIM_TRACEBACK=1")


def _trajectory(folder: Path, seconds: float = 0.5) -> Path:
    from coatsim.robot.trajectory_log import TrajectoryLog

    t = np.arange(0.0, seconds, 0.002)
    position = np.column_stack((-50 + 200 * t, np.zeros_like(t), np.full_like(t, 100.0)))
    path = folder / "traj.csv"
    TrajectoryLog(t=t, position=position, axis=np.tile([0.0, 0.0, -1.0], (len(t), 1)), speed=np.full_like(t, 200.0),
                  spray=np.ones(len(t), bool), progress=200 * t, path_error=np.zeros_like(t),
                  q=np.zeros((len(t), 6))).write_csv(path)
    return path


@pytest.mark.parametrize(("signum", "status", "word"), [(signal.SIGINT, 130, "interrupted"),
                                                       (signal.SIGTERM, 143, "terminated")])
def test_a_signal_prints_one_line_and_cleans_up(tmp_path, signum, status, word):
    out = tmp_path / "out"
    child = subprocess.Popen([sys.executable, "-m", "coatsim.cli", "coat", str(_trajectory(tmp_path, 2.0)), "--surface",
                              "plate:400x300@0,0,0", "--spacing", "0.4", "-o", str(out)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=child_env())
    deadline = time.monotonic() + 120
    while not (out / LOCK_NAME).exists() and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert child.poll() is None, child.communicate()[1]
    child.send_signal(signum)
    _, err = child.communicate(timeout=120)
    assert child.returncode == status, err
    assert err == f"coatsim: {word}\n"
    assert not out.exists()  # lock removed, no temporary file left, the folder it created is gone


def test_an_error_never_echoes_a_file_that_is_not_a_curve(tmp_path):
    secret = tmp_path / "secrets.txt"
    secret.write_text("user:x:1000:1000:Jane Doe,,,:/home/jane:/bin/bash\napi_token:s3cr3t-Value-1234\n")
    deep_passwd = "../" * 40 + "etc/passwd"
    for target in [str(secret), deep_passwd] if Path("/etc/passwd").is_file() else [str(secret)]:
        scenario = tmp_path / "leak.yaml"
        scenario.write_text(f"name: leak\ncurve: {{file: '{target}'}}\n{PLATE}")
        err = one_line(cli("run", scenario), 2, "is not a number")
        assert not any(word in err for word in ("Jane", "s3cr3t", "/bin/bash", "/home/jane", "daemon", "nologin")), err
    table = tmp_path / "table.yaml"
    table.write_text(f"name: leak\ncurve: {{builtin: ellipse}}\ngun: {{footprint: 'table:{secret}'}}\n{PLATE}")
    err = one_line(cli("run", table), 2, "footprint table header must be 'u_mm,v_mm,rate'")
    assert "Jane" not in err and "home" not in err, err
    err = one_line(cli("coat", secret, "--surface", "plate:10x10@0,0,0", "-o", tmp_path / "o"), 2)
    assert "Jane" not in err and "s3cr3t" not in err, err


def test_a_typo_in_a_number_is_still_shown(tmp_path):
    curve = tmp_path / "c.csv"
    curve.write_text("0,0\n1,1\n2mm,2\n")
    one_line(cli("segment", curve, "--tol", "0.1"), 2, "c.csv:3: field 1 is not a number: '2mm'")


# --- item 7 -----------------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["..", ".", "1abc", "-x", "a/b", "", "x" * 65])
def test_a_scenario_name_is_a_safe_file_stem(tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    scenario = tmp_path / "job.yaml"
    scenario.write_text(f"name: '{name}'\ncurve: {{builtin: ellipse}}\n{PLATE}")
    one_line(cli("run", scenario), 2, "job.yaml:1: name:", "is not a safe file stem")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["job.yaml"]  # nothing written anywhere


def test_a_scenario_name_becomes_a_valid_program_name(tmp_path):
    scenario = tmp_path / "job.yaml"
    scenario.write_text("name: Job-2024.v2_with_a_long_name\ncurve: {builtin: ellipse, params: {a: 30.0, b: 20.0}}\n"
                        + PLATE + "fast: {coating_spacing_mm: 4.0, sample_step_mm: 2.0}\n")
    code, _, err = cli("run", scenario, "--fast", "-o", tmp_path / "out")
    assert code == 0, err
    assert ".PROGRAM job_2024_v2_wit(" in (tmp_path / "out" / "polysegment.as").read_text()


def test_roll_nan_leaves_no_program_on_disk(tmp_path):
    out = tmp_path / "nan.as"
    one_line(cli("program", "builtin:ellipse", "--tol", "0.1", "--roll-deg", "nan", "-o", out), 2, "roll_deg = nan")
    assert not out.exists()


def test_execute_step_zero_is_invalid_input(tmp_path):
    prog = tmp_path / "p.as"
    assert cli("program", "builtin:ellipse:a=40,b=20", "--tol", "0.2", "-o", prog)[0] == 0
    for step in ("0", "-1", "nan", "inf"):
        one_line(cli("execute", prog, "--step-mm", step, "-o", tmp_path / "x"), 2, "sampling step (--step-mm)")
    assert not (tmp_path / "x").exists()


def test_coat_edge_band_nan_is_rejected(tmp_path):
    one_line(cli("coat", _trajectory(tmp_path), "--surface", "plate:100x100@0,0,0", "--edge-band", "nan",
                 "-o", tmp_path / "o"), 2, "--edge-band nan")


def test_huge_parameters_print_no_numpy_warnings(tmp_path):
    """`a,b: 1e300` once printed RuntimeWarnings before the error."""
    child = subprocess.run([sys.executable, "-W", "default", "-m", "coatsim.cli", "segment",
                            "builtin:ellipse:a=1e300,b=1e300", "--tol", "0.1"],
                           capture_output=True, text=True, env=child_env(), timeout=120)
    assert child.returncode == 2 and child.stderr.count("\n") == 1, child.stderr
    scenario = tmp_path / "huge.yaml"
    scenario.write_text(f"name: huge\ncurve: {{builtin: ellipse, params: {{a: 1.0e300, b: 1.0e300}}}}\n{PLATE}")
    child = subprocess.run([sys.executable, "-W", "default", "-m", "coatsim.cli", "run", str(scenario)],
                           capture_output=True, text=True, env=child_env(), timeout=120)
    assert child.returncode == 2 and child.stderr.count("\n") == 1, child.stderr
    assert "Warning" not in child.stderr


def test_unreachable_speed_and_accuracy_are_warned(tmp_path):
    prog = tmp_path / "fast.as"
    code, _, err = cli("program", "builtin:ellipse:a=40,b=20", "--tol", "0.2", "--speed", "1e6", "--accuracy", "1e6",
                       "-o", prog)
    assert code == 0
    assert "coatsim: warning: --accuracy 1e+06 mm is longer than every move" in err
    code, out, err = cli("execute", prog, "-o", tmp_path / "x", "--step-mm", "2")
    assert code == 0, err
    assert "warning: a_40_b_20: ACCURACY 1e+06 mm is longer than every move (the longest is 50 mm)" in err
    assert "SPEED 1e+06 mm/s is beyond the arm, whose joint speed and tool acceleration limits allow at most" in err
    ordinary = tmp_path / "ok.as"
    assert cli("program", "builtin:ellipse:a=40,b=20", "--tol", "0.2", "-o", ordinary)[0] == 0
    code, out, err = cli("execute", ordinary, "-o", tmp_path / "y", "--step-mm", "2")
    assert code == 0 and "beyond the arm" not in err and "ACCURACY" not in err, err


@pytest.mark.parametrize(("args", "words"), [
    (["--spacing", "1e-300"], "vertices: an unbounded number needed"),
    (["--footprint", "gaussian:sigma=1e-300"], "over the budget"),
    (["--footprint", "beta:radius=1e-300,beta=2"], "over the budget"),
    (["--section", "0,0,1e300,1"], "--section must be x0,y0,x1,y1"),
    (["--rate", "1e154"], "spray rate must be positive and at most 1e+12"),
    (["--standoff", "1e154"], "spray stand-off must be positive and at most 1e+09"),
    (["--surface", "plate:1e-9x300@700,0,100"], "plate size must be between 0.001 and 1e+09 mm"),
    (["--surface", "cylinder:1e-300x300@700,0,100"], "cylinder size must be between"),
])
def test_extreme_coat_values_are_input_errors_without_warnings(tmp_path, args, words):
    """Found by fuzzing every numeric option with nan, inf, 0, -1, 1e-300, 1e300, 1e154 and 1e-9."""
    base = ["coat", _trajectory(tmp_path), "--surface", "plate:300x300@700,0,100", "-o", tmp_path / "o"]
    if args[0] == "--surface":
        base = base[:2] + base[4:]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a numpy RuntimeWarning would fail the test
        one_line(cli(*base, *args), 2, words)


def test_a_curve_of_no_size_is_an_input_error():
    one_line(cli("segment", "builtin:polygon:radius=1e-300", "--tol", "0.1"), 2, "the curve is", "at least 1e-06 mm")


def test_an_empty_region_of_interest_names_each_commands_own_settings(tmp_path):
    """The library names edge_band_mm; `coat` adds its flags, `run` the scenario's keys and line."""
    code, _, err = cli("coat", _trajectory(tmp_path), "--surface", "plate:120x80@0,0,0", "--spacing", "2",
                       "--edge-band", "45", "-o", tmp_path / "coat")
    assert code == 2 and err.count("\n") == 1, err
    assert "region of interest is empty" in err and "try --roi part or a smaller --edge-band" in err
    from small_scenario import SMALL

    scenario = tmp_path / "banded.yaml"
    scenario.write_text(SMALL.replace("coating: {spacing_mm: 2.0, band_halfwidth_mm: 2.5}",
                                      "coating: {spacing_mm: 2.0, band_halfwidth_mm: 2.5, edge_band_mm: 50.0}"))
    code, _, err = cli("run", scenario, "--fast", "-o", tmp_path / "run")
    assert code == 2 and err.count("\n") == 1, err
    assert "banded.yaml:" in err and "coating.edge_band_mm" in err and "--roi" not in err and "--edge-band" not in err


def test_coatsim_alone_shows_the_help_exit_2() -> None:
    done = subprocess.run([sys.executable, "-m", "coatsim.cli"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr.startswith("Usage: ") and "\nCommands:" in done.stderr and "\\n" not in done.stderr
    assert "coatsim: error" not in done.stderr

"""`coatsim execute` on a real AS program file (parsed by the programs stage)."""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from coatsim.robot.trajectory_log import read_trajectory_csv

PROGRAM = Path(__file__).resolve().parents[1] / "path" / "data" / "roundrect_polysegment.as"
KEYS = {"cycle_time_s", "ideal_time_s", "mean_speed_mm_s", "min_speed_mm_s", "speed_cv", "fraction_at_speed",
        "stops", "max_path_error_mm", "rms_path_error_mm", "max_joint_speed_ratio", "max_joint_accel_ratio",
        "programmed_speed_mm_s", "curve_length_mm"}


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "coatsim.cli", "execute", *args], capture_output=True, text=True)


def test_execute_writes_log_metrics_and_plot(tmp_path):
    done = run(str(PROGRAM), "-o", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert "cycle" in done.stdout and "stops" in done.stdout
    doc = json.loads((tmp_path / "motion.json").read_text())
    assert KEYS <= set(doc["motion"])
    m = doc["motion"]
    # the header says curve_length_mm=442.8318531 (lead-in and lead-out excluded)
    assert m["curve_length_mm"] == pytest.approx(442.8318531, abs=1e-3)
    assert m["stops"] == 0 and m["max_path_error_mm"] < 0.5
    log = read_trajectory_csv(tmp_path / "trajectory.csv")
    assert log.spray.any() and not log.spray[0] and len(log) > 100
    assert (tmp_path / "speed.png").read_bytes()[:4] == b"\x89PNG"


def test_unreachable_program_exits_3_naming_the_line(tmp_path):
    text = PROGRAM.read_text()
    text = re.sub(r"^p0005 775\.0000000", "p0005 2775.0000000", text, flags=re.M)
    bad = tmp_path / "far.as"
    bad.write_text(text)
    done = run(str(bad), "-o", str(tmp_path / "out"))
    assert done.returncode == 3
    err = done.stderr.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    line = next(i for i, l in enumerate(text.splitlines(), 1) if l.strip().startswith("LMOVE p0005"))
    assert f"line {line}" in err


def test_speed_png_shows_the_sprayed_stretch_not_the_approach():
    """The window of speed.png: the gun-open stretch and the curve proper, a small margin around."""
    import numpy as np

    from coatsim.robot.plots import sprayed_window
    from coatsim.robot.trajectory_log import TrajectoryLog

    progress = np.linspace(0.0, 1000.0, 1001)  # 600 mm approach from home, then 300 mm sprayed, 100 mm away
    spray = (progress >= 600.0) & (progress <= 900.0)
    log = TrajectoryLog(t=progress / 100, position=np.zeros((1001, 3)), axis=np.tile([0, 0, -1.0], (1001, 1)),
                        speed=np.full(1001, 100.0), spray=spray, progress=progress, path_error=np.zeros(1001),
                        q=np.zeros((1001, 6)))
    lo, hi = sprayed_window(log, (610.0, 890.0))
    assert 570.0 < lo < 600.0 and 900.0 < hi < 930.0

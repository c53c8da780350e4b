"""Same drawing, same bytes: the part JSON, its plot and the part program, in two fresh
interpreters with different hash seeds."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from cad_helpers import write_dxf

pytestmark = pytest.mark.golden

DRIVER = """
import sys
from coatsim.cli import main
for argv in ([["segment", "../part.dxf", "-o", "part.json", "--plot", "part.png"],
              ["program", "../part.dxf", "--tol", "0.1", "--order", "nearest", "-o", "part.as"]]):
    sys.argv = ["coatsim", *argv]
    try:
        main()
    except SystemExit as exc:
        if exc.code:
            raise SystemExit(f"{argv[0]} exited {exc.code}")
"""


def drawing(msp, doc) -> None:
    msp.add_lwpolyline([(0, 0, 0, 0, 0.3), (60, 0), (60, 40), (0, 40)], format="xyseb", close=True)
    msp.add_circle((45, 20), 6)
    msp.add_spline(fit_points=[(5, 5), (15, 15), (25, 5), (35, 15)])
    msp.add_line((35, 15), (40, 30))
    msp.add_ellipse((20, 30), major_axis=(8, 0), ratio=0.4)


def test_drawing_outputs_are_byte_identical_across_runs(tmp_path: Path) -> None:
    write_dxf(tmp_path, drawing)
    procs = []
    for name, seed in (("a", "3"), ("b", "4")):
        (tmp_path / name).mkdir()
        env = {**os.environ, "PYTHONHASHSEED": seed, "MPLBACKEND": "Agg"}
        procs.append(subprocess.Popen([sys.executable, "-c", DRIVER], cwd=tmp_path / name, env=env,
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    for proc in procs:
        _, err = proc.communicate(timeout=600)
        assert proc.returncode == 0, err
    for name in ("part.json", "part.png", "part.as"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name

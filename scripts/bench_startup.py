"""Benchmark of start-up: CPU time of short commands and what importing each stage loads.

1. CPU time (user + system, best of N fresh processes) of `coatsim --help`, `coatsim check-program`
   on a small program, `coatsim schema`, and of importing each stage's entry module.
2. Which heavy libraries each stage's import pulls in (matplotlib, toppra, mujoco, mink, scipy
   submodules, dask, pyarrow): robot and geometry must load no plotting library.
3. The exponent of `coatsim check-program` against the program's size (N and 10 N moves): near 0
   while start-up is what it costs.
Figures only; never asserts. Usage: python scripts/bench_startup.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

HEAVY = ("matplotlib", "toppra", "mujoco", "mink", "scipy.optimize", "scipy.special", "scipy.spatial", "trimesh",
         "dask", "distributed", "pyarrow", "pandas", "pydantic", "rich")
STAGES = ("coatsim.cli.app", "coatsim.geometry", "coatsim.geometry.segment", "coatsim.path", "coatsim.robot.execute",
          "coatsim.spray.coat", "coatsim.report.document", "coatsim.run.pipeline", "coatsim.sweep.run")


def cpu_of(argv: list[str], repeat: int) -> float:
    """Best user + system CPU seconds of ``argv`` over ``repeat`` fresh processes."""
    best = float("inf")
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        best = min(best, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
    return best


def loaded_by(module: str) -> list[str]:
    code = (f"import sys, json; import {module}; "
            f"print(json.dumps([m for m in {list(HEAVY)!r} if m in sys.modules]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    os.environ.setdefault("MPLBACKEND", "Agg")
    coatsim = [sys.executable, "-m", "coatsim.cli"]
    with tempfile.TemporaryDirectory() as tmp:
        program = Path(tmp) / "ellipse.as"
        subprocess.run([*coatsim, "program", "builtin:ellipse", "--tol", "0.1", "-o", str(program)],
                       capture_output=True, check=True)
        print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; best of {args.repeat}")
        print(f"{'command':<44} {'CPU s':>7}")
        for label, argv in (("python -c pass (interpreter alone)", [sys.executable, "-c", "pass"]),
                            ("coatsim --help", [*coatsim, "--help"]),
                            ("coatsim check-program ellipse.as", [*coatsim, "check-program", str(program)]),
                            ("coatsim schema", [*coatsim, "schema"])):
            print(f"{label:<44} {cpu_of(argv, args.repeat):>7.3f}")
        print(f"\n{'import':<28} {'CPU s':>7}  heavy libraries loaded")
        for module in STAGES:
            cpu = cpu_of([sys.executable, "-c", f"import {module}"], args.repeat)
            print(f"{module:<28} {cpu:>7.3f}  {', '.join(loaded_by(module)) or '-'}")
        from bench_as_reader import contour  # scripts/bench_as_reader.py: an AS contour of N moves

        times = {}
        for n in (200, 2000):
            program = Path(tmp) / f"contour{n}.as"
            program.write_text(contour(n), encoding="ascii")
            times[n] = cpu_of([*coatsim, "check-program", str(program)], args.repeat)
        print(f"\ncoatsim check-program, 200 moves {times[200]:.3f} s, 2000 moves {times[2000]:.3f} s CPU: exponent "
              f"{math.log(times[2000] / times[200]) / math.log(10):.2f} against the number of moves")


if __name__ == "__main__":
    main()

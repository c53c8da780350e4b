"""What the resource budgets of coatsim/core/budgets.py cost: CPU time and peak memory per unit of
each bounded quantity, measured on a moderate case in a fresh process, and extrapolated to the
budget, with the exponent of the CPU time against the quantity (the case and one of about half
its size: the extrapolation is honest where it is near 1); then how fast an over-budget input
is refused.

Prints figures only (never asserts). Run: python scripts/bench_budgets.py
"""

from __future__ import annotations

import math
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

from coatsim.core import budgets

CHILD = r"""
import resource, sys, time
t0 = time.perf_counter()
from coatsim.cli import main
sys.argv = ["coatsim", *sys.argv[1:]]
try:
    main()
except SystemExit as exc:
    code = exc.code
usage = resource.getrusage(resource.RUSAGE_SELF)
print(f"RESULT {code} {time.perf_counter() - t0:.3f} {usage.ru_maxrss} {usage.ru_utime + usage.ru_stime:.3f}",
      file=sys.stderr)
"""


def measure(*args: str) -> tuple[int, float, float, str, float]:
    """Exit code, wall time (s), peak RSS (MB), first line of stderr and CPU seconds of one
    coatsim command in a fresh process."""
    child = subprocess.run([sys.executable, "-c", CHILD, *args], capture_output=True, text=True)
    lines = child.stderr.strip().splitlines()
    _, code, wall, rss, cpu = lines[-1].split()
    return int(code), float(wall), int(rss) / 1024, (lines[0] if len(lines) > 1 else ""), float(cpu)


def _random_curve(d: Path, n: int) -> str:
    import numpy as np

    path = d / f"random{n}.csv"
    np.savetxt(path, np.random.default_rng(1).uniform(0, 100, (n, 2)), delimiter=",")
    return str(path)


def number_reader() -> None:
    """CPU seconds of coatsim.core.number_text.read_rows per million rows of a trajectory (17
    columns) and of a curve (x;y with decimal commas), and the exponent against the row count."""
    import time

    import numpy as np

    from coatsim.core.number_text import read_rows

    def trajectory(rows: int) -> str:
        i = np.arange(rows)
        return "t_s,x_mm\n" + "".join(f"{k * 0.01:.4f},{k * 2.0:.4f},0,100,0,0,-1,200,1,{k * 2.0:.4f},0,0,0,0,0,0,0\n"
                                       for k in i.tolist())

    def curve(rows: int) -> str:
        xy = np.random.default_rng(0).normal(size=(rows, 2)) * 100
        return "".join(f"{x:.4f};{y:.4f}\n".replace(".", ",") for x, y in xy.tolist())

    print("\nreading numeric tables (CPU s per million rows, exponent from 250 000 to 1 000 000 rows):")
    for label, make in (("trajectory, 17 columns", trajectory), ("curve, x;y decimal commas", curve)):
        seconds = []
        for rows in (250_000, 1_000_000):
            text = make(rows)
            started = time.process_time()
            read_rows(text, "bench", "numbers")
            seconds.append(time.process_time() - started)
        exponent = math.log(seconds[1] / seconds[0]) / math.log(4.0)
        print(f"  {label}: {seconds[1]:.2f} s per 1M rows ({len(text) / 1e6:.0f} MB), exponent {exponent:.2f}")


def main() -> None:
    d = Path(tempfile.mkdtemp(prefix="bench_budgets."))
    subprocess.run([sys.executable, "-m", "coatsim.cli", "program", "builtin:ellipse:a=40,b=20", "--tol", "0.2",
                    "-o", str(d / "p.as")], check=True, capture_output=True)
    subprocess.run([sys.executable, "-m", "coatsim.cli", "program", "builtin:ellipse:a=40,b=20", "--tol", "0.2",
                    "--speed", "2", "-o", str(d / "slow.as")], check=True, capture_output=True)
    subprocess.run([sys.executable, "-m", "coatsim.cli", "program", "builtin:ellipse:a=40,b=20", "--tol", "0.2",
                    "--speed", "4", "-o", str(d / "slow_half.as")], check=True, capture_output=True)
    subprocess.run([sys.executable, "-m", "coatsim.cli", "program", "builtin:ellipse:a=40,b=20", "--tol", "0.2",
                    "--speed", "1e-3", "-o", str(d / "crawl.as")], check=True, capture_output=True)
    subprocess.run([sys.executable, "-m", "coatsim.cli", "execute", str(d / "p.as"), "-o", str(d / "e0")],
                   check=True, capture_output=True)
    _, _, base_mb, _, base_cpu = measure("segment", "builtin:ellipse:points=3", "--tol", "1")
    print(f"baseline (import + tiny segment): {base_cpu:.2f} s CPU, {base_mb:.0f} MB peak RSS\n")
    print("| quantity | measured on | CPU | peak RSS | per unit | at the budget | exponent (half size) |")
    print("|---|---|---|---|---|---|---|")
    from coatsim.languages.kawasaki_as.files import read_toolpath
    from coatsim.robot.sampling import CartesianPiece, plan_pieces

    samples = sum(len(p.s) for p in plan_pieces(read_toolpath(d / "p.as"), 0.01) if isinstance(p, CartesianPiece))
    # (quantity, budget, units (None: counted from the log), command, the command at about half the size)
    rows = [
        ("IK samples", budgets.MAX_PATH_SAMPLES, samples,
         ("execute", str(d / "p.as"), "--step-mm", "0.01", "-o", str(d / "e1")),
         ("execute", str(d / "p.as"), "--step-mm", "0.02", "-o", str(d / "h1"))),
        ("simulation steps", budgets.MAX_SIM_STEPS, None, ("execute", str(d / "slow.as"), "-o", str(d / "e2")),
         ("execute", str(d / "slow_half.as"), "-o", str(d / "h2"))),
        ("mesh vertices", budgets.MAX_MESH_VERTICES, 601 * 601,
         ("coat", str(d / "e0" / "trajectory.csv"), "--surface", "plate:300x300@700,0,100", "--spacing", "0.5",
          "-o", str(d / "c1")),
         ("coat", str(d / "e0" / "trajectory.csv"), "--surface", "plate:300x300@700,0,100", "--spacing", "0.7071",
          "-o", str(d / "h3"))),
        ("curve points", budgets.MAX_CURVE_POINTS, 200_000, ("segment", "builtin:ellipse:points=200000", "--tol", "0.05"),
         ("segment", "builtin:ellipse:points=100000", "--tol", "0.05")),
    ]
    halves = {"IK samples": 0.5, "simulation steps": None, "mesh vertices": (426 * 426) / (601 * 601), "curve points": 0.5}
    for name, budget, units, args, half in rows:
        code, _, rss, _, cpu = measure(*args)
        _, _, _, _, half_cpu = measure(*half)
        if units is None:  # simulation steps: read the log lengths
            units = sum(1 for _ in open(d / "e2" / "trajectory.csv")) - 1
            halves[name] = (sum(1 for _ in open(d / "h2" / "trajectory.csv")) - 1) / units
        per_ms = 1e3 * (cpu - base_cpu) / units
        per_kb = 1024 * max(rss - base_mb, 0.0) / units
        exponent = math.log(max(cpu - base_cpu, 1e-3) / max(half_cpu - base_cpu, 1e-3)) / math.log(1.0 / halves[name])
        print(f"| {name} | {units:,.0f} (exit {code}) | {cpu:.1f} s | {rss:.0f} MB | {per_ms:.3f} ms, {per_kb:.2f} kB "
              f"| {per_ms * budget / 1e3:.0f} s, {per_kb * budget / 1024**2:.2f} GB | {exponent:.2f} |")
    print("\nrefusals (exit code, wall time including the import, peak RSS):")
    bomb = d / "bomb.yaml"
    text = 'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n'
    for prev, new in zip("abcdefgh", "bcdefghi"):
        text += f"{new}: &{new} [" + ",".join([f"*{prev}"] * 9) + "]\n"
    bomb.write_text(text)
    for label, args in (("--step-mm 1e-4", ("execute", str(d / "p.as"), "--step-mm", "1e-4", "-o", str(d / "r1"))),
                        ("--speed 1e-3", ("execute", str(d / "crawl.as"), "-o", str(d / "r2"))),
                        ("coat --spacing 0.001", ("coat", str(d / "e0" / "trajectory.csv"), "--surface",
                                                  "plate:300x300@700,0,100", "--spacing", "0.001", "-o", str(d / "r3"))),
                        ("YAML alias bomb", ("run", str(bomb)))):
        code, wall, rss, message, _ = measure(*args)
        print(f"  {label}: exit {code}, {wall:.2f} s, {rss:.0f} MB  {message[:110]}")
    for label, args in (("3 000 random points", ("segment", _random_curve(d, 3000), "--tol", "0.1")),
                        ("sine, wavelength 1e-6", ("segment", "builtin:sine:wavelength=1e-6", "--tol", "0.1")),
                        ("paper spiral, 1e6 turns", ("segment", "builtin:paper-spiral:turns=1e6", "--tol", "0.1"))):
        code, wall, rss, message, cpu = measure(*args)
        print(f"  {label}: exit {code}, {cpu:.2f} s CPU, {rss:.0f} MB  {message[:110]}")
    number_reader()
    print(f"\n(children's total CPU {resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime:.0f} s; files in {d})")


if __name__ == "__main__":
    main()

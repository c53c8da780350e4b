"""Benchmark of `coatsim sweep`: wall time of the same sweep on 1 and on 2 (or more) local workers.

Runs the sweep (default: sweeps/contour_speed_tolerance.yaml, 12 fast points) into a fresh folder
for each worker count, cluster start-up and sweep.html included, and prints the wall and CPU time,
the speed-up over one worker, the per-point run time and CPU time on the workers, and the
machine's load (the figure means little when other work shares the cores); then, on one worker,
the exponent of the points' CPU time and of the wall time against the number of points (the
sweep, and the sweep with its first axis halved). Figures only; never asserts.

Usage: python scripts/bench_sweep.py [SWEEP.yaml] [--workers 1 2] [--repeat 1]
"""

from __future__ import annotations

import argparse
import math
import os
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep", nargs="?", type=Path, default=ROOT / "sweeps" / "contour_speed_tolerance.yaml")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--repeat", type=int, default=1, help="best of N runs per worker count")
    args = parser.parse_args()
    from coatsim.core.runtime import single_threaded_numerics

    single_threaded_numerics()  # as `coatsim` does (the workers get it from Dask's nanny)
    from coatsim.sweep.run import run_sweep

    print(f"sweep {args.sweep.name}; {os.cpu_count()} cores")
    print(f"{'workers':>7} {'points':>6} {'wall_s':>7} {'speedup':>7} {'point_s':>8} {'pt_cpu_s':>8} {'client_cpu':>10} "
          f"{'load_1m':>7}")
    first = None
    for n in args.workers:
        best = None
        for _ in range(max(1, args.repeat)):
            with tempfile.TemporaryDirectory() as tmp:
                load = os.getloadavg()[0]
                t0, c0 = time.perf_counter(), time.process_time()
                result = run_sweep(args.sweep, Path(tmp) / "out", workers=n, progress=False)
                wall, client = time.perf_counter() - t0, time.process_time() - c0
            if best is None or wall < best[0]:
                best = (wall, result, load, client)
        wall, result, load, client = best
        first = first or wall
        ran = [result.outcomes[p] for p in result.ran]
        point_wall = sum(o.seconds for o in ran) / max(1, len(ran))
        point_cpu = sum(o.cpu_seconds for o in ran) / max(1, len(ran))
        print(f"{n:>7} {len(ran):>6} {wall:>7.1f} {first / wall:>7.2f} {point_wall:>8.2f} {point_cpu:>8.2f} {client:>10.2f} "
              f"{load:>7.2f}", flush=True)
        if n == 1:
            # what two free cores would give: the points' CPU split over two workers, the rest serial
            work = point_cpu * len(ran)
            serial = wall - point_wall * len(ran)
            print(f"        with free cores (estimate from CPU time): 1 worker {serial + work:.1f} s, "
                  f"2 workers {serial + work / 2:.1f} s -> {(serial + work) / (serial + work / 2):.2f}x")
    with tempfile.TemporaryDirectory() as tmp:
        sizes = {}
        for label, sweep in (("half", halved(args.sweep, Path(tmp))), ("all", args.sweep)):
            t0 = time.perf_counter()
            result = run_sweep(sweep, Path(tmp) / f"out-{label}", workers=1, progress=False)
            ran = [result.outcomes[p] for p in result.ran]
            sizes[label] = (len(ran), sum(o.cpu_seconds for o in ran), time.perf_counter() - t0)
    (n1, c1, w1), (n2, c2, w2) = sizes["half"], sizes["all"]
    print(f"one worker, {n1} and {n2} points: points' CPU {c1:.1f} and {c2:.1f} s (exponent "
          f"{math.log(c2 / c1) / math.log(n2 / n1):.2f}), wall {w1:.1f} and {w2:.1f} s (exponent "
          f"{math.log(w2 / w1) / math.log(n2 / n1):.2f}) against the number of points")
    print(f"load average now {os.getloadavg()[0]:.2f}")


def halved(sweep: Path, folder: Path) -> Path:
    """The sweep with the first half of its first grid axis, its base scenario by absolute path."""
    document = yaml.safe_load(sweep.read_text(encoding="utf-8"))
    document["base"] = str((sweep.parent / document["base"]).resolve())
    axis = next(iter(document["grid"]))
    values = document["grid"][axis]
    document["grid"][axis] = values[: max(1, len(values) // 2)]
    path = folder / f"half-{sweep.name}"
    path.write_text(yaml.safe_dump(document, sort_keys=False), encoding="utf-8")
    return path


if __name__ == "__main__":
    main()

"""Benchmark of `coatsim sweep`: wall time of the same sweep on 1 and on 2 (or more) local workers.

Runs the sweep (default: sweeps/contour_speed_tolerance.yaml, 12 fast points) into a fresh folder
for each worker count, cluster start-up and sweep.html included, and prints the wall and CPU time,
the speed-up over one worker, the per-point run time on the workers, and the machine's load
(the figure means little when other work shares the cores). Figures only; never asserts.

Usage: python scripts/bench_sweep.py [SWEEP.yaml] [--workers 1 2] [--repeat 1]
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sweep", nargs="?", type=Path, default=ROOT / "sweeps" / "contour_speed_tolerance.yaml")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--repeat", type=int, default=1, help="best of N runs per worker count")
    args = parser.parse_args()
    from coatsim.runtime import single_threaded_numerics

    single_threaded_numerics()  # as `coatsim` does (the workers get it from Dask's nanny)
    from coatsim.sweep.run import run_sweep

    print(f"sweep {args.sweep.name}; {os.cpu_count()} cores")
    print(f"{'workers':>7} {'points':>6} {'wall_s':>7} {'speedup':>7} {'point_s':>8} {'load_1m':>7}")
    first = None
    for n in args.workers:
        best = None
        for _ in range(max(1, args.repeat)):
            with tempfile.TemporaryDirectory() as tmp:
                load = os.getloadavg()[0]
                t0 = time.perf_counter()
                result = run_sweep(args.sweep, Path(tmp) / "out", workers=n, progress=False)
                wall = time.perf_counter() - t0
            if best is None or wall < best[0]:
                best = (wall, result, load)
        wall, result, load = best
        first = first or wall
        per_point = sum(o.seconds for o in result.outcomes.values()) / max(1, len(result.ran))
        print(f"{n:>7} {len(result.ran):>6} {wall:>7.1f} {first / wall:>7.2f} {per_point:>8.2f} {load:>7.2f}", flush=True)
    usage = resource.getrusage(resource.RUSAGE_SELF)
    print(f"client CPU {usage.ru_utime + usage.ru_stime:.1f} s; load average now {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()

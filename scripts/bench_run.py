"""Benchmark of `coatsim run`: every shipped scenario, its comparison table and wall time.

Usage: python scripts/bench_run.py [--fast] [--outdir runs/bench] [SCENARIO.yaml ...]
Prints figures only; never asserts. Exits non-zero when a scenario file is missing or a run fails.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from coatsim.runtime import single_threaded_numerics

single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load

from coatsim.errors import CoatsimError  # noqa: E402
from coatsim.pipeline import run_scenario  # noqa: E402
from coatsim.report.summary import summary_text  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", type=Path, help="scenario files [default: scenarios/*.yaml]")
    parser.add_argument("--fast", action="store_true", help="use each scenario's fast settings")
    parser.add_argument("--outdir", type=Path, default=ROOT / "runs" / "bench")
    args = parser.parse_args()
    files = args.scenarios or sorted((ROOT / "scenarios").glob("*.yaml"))
    missing = [str(p) for p in files if not p.is_file()]
    if missing or not files:
        sys.exit(f"bench_run: scenario file(s) not found: {', '.join(missing) or 'scenarios/*.yaml'}")
    totals = []
    for path in files:
        started = time.perf_counter()
        try:
            result = run_scenario(path, args.outdir / path.stem, fast=args.fast, progress=False)
        except CoatsimError as exc:
            totals.append((path.stem, time.perf_counter() - started, f"error (exit {exc.exit_code})"))
            print(f"== {path.stem}: error: {exc}\n")
            continue
        wall = time.perf_counter() - started
        totals.append((path.stem, wall, "pass" if result.passed else "FAIL"))
        print(f"== {path.stem} ({'fast' if args.fast else 'full'} mode): wall time {wall:.1f} s")
        print(summary_text(result.document))
        print()
    print(f"{'scenario':<18} {'wall (s)':>9}  gates")
    for name, wall, verdict in totals:
        print(f"{name:<18} {wall:>9.1f}  {verdict}")
    print(f"{'total':<18} {sum(w for _, w, _ in totals):>9.1f}")
    if any(verdict.startswith("error") for _, _, verdict in totals):
        sys.exit(1)


if __name__ == "__main__":
    main()

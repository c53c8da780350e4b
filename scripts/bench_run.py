"""Benchmark of `coatsim run`: every shipped scenario, its comparison table and wall time, then
the lowest speed on the curve proper per variant and the polysegment against each polyline
(min speed ratio, fraction at speed, thickness CV) over all scenarios.

Usage: python scripts/bench_run.py [--fast] [--outdir runs/bench] [SCENARIO.yaml ...]
Prints figures only; never asserts. Exits non-zero when a scenario file is missing or a run fails.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load

from coatsim.core.errors import CoatsimError  # noqa: E402
from coatsim.run.pipeline import run_scenario  # noqa: E402
from coatsim.report.summary import summary_text  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def _num(value, spec: str) -> str:
    return "-" if value is None else format(value, spec)


def print_comparison(documents: dict[str, dict]) -> None:
    """The lowest speed where the curve allows the programmed speed, per variant (mm/s), and the
    polysegment against each polyline."""
    print("lowest speed on the curve proper, where the curve allows the programmed speed (mm/s)")
    names = ("polysegment", "polyline-stop", "polyline-blend")
    print(f"{'scenario':<18} {'programmed':>10} " + " ".join(f"{n:>14}" for n in names))
    for scenario, doc in documents.items():
        variants = doc["variants"]
        speed = next(iter(variants.values()))["motion"]["programmed_speed_mm_s"]
        low = [None if n not in variants or variants[n]["motion"]["min_speed_ratio"] is None
               else variants[n]["motion"]["min_speed_ratio"] * speed for n in names]
        print(f"{scenario:<18} {speed:>10.0f} " + " ".join(f"{_num(v, '.1f'):>14}" for v in low))
    print()
    print("polysegment vs each polyline: min speed ratio, fraction at speed, thickness CV (polysegment / polyline)")
    print(f"{'scenario':<18} {'against':<15} {'min speed ratio':>17} {'fraction at speed':>19} {'thickness CV':>17}")
    for scenario, doc in documents.items():
        variants = doc["variants"]
        if "polysegment" not in variants:
            continue
        mine = variants["polysegment"]
        for other in (n for n in names[1:] if n in variants):
            cells = []
            for group, key, spec in (("motion", "min_speed_ratio", ".3f"), ("motion", "fraction_at_speed", ".3f"),
                                     ("coating", "thickness_cv", ".4f")):
                cells.append(f"{_num(mine[group][key], spec)} / {_num(variants[other][group][key], spec)}")
            print(f"{scenario:<18} {other:<15} {cells[0]:>17} {cells[1]:>19} {cells[2]:>17}")
    print()


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
    documents: dict[str, dict] = {}
    for path in files:
        started = time.perf_counter()
        try:
            result = run_scenario(path, args.outdir / path.stem, fast=args.fast, progress=False)
        except CoatsimError as exc:
            totals.append((path.stem, time.perf_counter() - started, f"error (exit {exc.exit_code})"))
            print(f"== {path.stem}: error: {exc}\n")
            continue
        wall = time.perf_counter() - started
        documents[path.stem] = result.document
        totals.append((path.stem, wall, "pass" if result.passed else "FAIL"))
        print(f"== {path.stem} ({'fast' if args.fast else 'full'} mode): wall time {wall:.1f} s")
        print(summary_text(result.document))
        print()
    print_comparison(documents)
    print(f"{'scenario':<18} {'wall (s)':>9}  gates")
    for name, wall, verdict in totals:
        print(f"{name:<18} {wall:>9.1f}  {verdict}")
    print(f"{'total':<18} {sum(w for _, w, _ in totals):>9.1f}")
    if any(verdict.startswith("error") for _, _, verdict in totals):
        sys.exit(1)


if __name__ == "__main__":
    main()

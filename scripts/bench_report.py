"""Benchmark of the report stage: what report.html (with its pictures, the viewer and the GLB/PLY
files) costs on top of a fast run, per section, in CPU seconds (process time: the machine's load
does not count) and wall seconds. Prints only; never asserts.

    python scripts/bench_report.py [SCENARIO ...]   (default: rounded_contour, paper_spiral)
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    import coatsim.run.pipeline as pipeline
    from coatsim.report import document
    from coatsim.report.sections import (
        maps,
        program,
        speed,
        tables,
        track,
        verdict,
        view3d,
        warnings,
    )

    figures: dict[str, list[float]] = {}

    def timed(name, function):
        def run(*args, **kwargs):
            cpu, wall = time.process_time(), time.perf_counter()
            out = function(*args, **kwargs)
            figures.setdefault(name, [0.0, 0.0])
            figures[name][0] += time.process_time() - cpu
            figures[name][1] += time.perf_counter() - wall
            return out
        return run

    for module in (verdict, speed, track, maps, warnings, view3d, program):
        module.section = timed(module.__name__.rsplit(".", 1)[1], module.section)
    for name in ("metrics_section", "summary_section", "gates_section"):
        setattr(tables, name, timed("tables", getattr(tables, name)))
    pipeline.write_thickness_files = timed("ply+glb", pipeline.write_thickness_files)
    document.write_report = timed("report.html", document.write_report)
    scenarios = [Path(a) for a in sys.argv[1:]] or [ROOT / "scenarios" / n for n in ("rounded_contour.yaml", "paper_spiral.yaml")]
    for scenario in scenarios:
        figures.clear()
        with tempfile.TemporaryDirectory() as out:
            cpu, wall = time.process_time(), time.perf_counter()
            result = pipeline.run_scenario(scenario, out, fast=True, progress=False)
            total = (time.process_time() - cpu, time.perf_counter() - wall)
            size = (Path(out) / "report.html").stat().st_size
        print(f"\n{scenario.name} (fast): run {total[0]:.2f} s CPU, {total[1]:.2f} s wall; report.html {size / 1e6:.2f} MB")
        print(f"{'part':>16} {'CPU s':>7} {'wall s':>7}")
        for name, (c, w) in figures.items():
            print(f"{name:>16} {c:7.2f} {w:7.2f}")
        print(f"report share of the run's CPU: {(figures['report.html'][0] + figures['ply+glb'][0]) / total[0]:.0%}")
        del result


if __name__ == "__main__":
    main()

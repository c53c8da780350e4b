"""Benchmark of the report stage: CPU seconds of report.html per section (and of what the
sections share, computed once), of the PLY and GLB files, and of importing the plotting library
the report is the first to need, for every shipped scenario (or those given) in full mode; then
the exponent of the report's CPU time against the coating mesh's vertices, between the
scenario's fast and full runs. CPU seconds are this process's (load on the machine counts less
than in wall time). Prints only; never asserts.

    python scripts/bench_report.py [--fast-too] [SCENARIO.yaml ...]   (default: every shipped scenario)
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHARED = ("raster", "_located", "coarse", "numbers")  # what several sections draw from (ReportData)


def plotting_import_s() -> float:
    """CPU seconds of importing matplotlib's figure and Agg canvas (paid by the first report of a
    process; left out of the figures below)."""
    started = time.process_time()
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.figure  # noqa: F401

    return time.process_time() - started


class Clock:
    """CPU seconds of each report section and of the shared data, by wrapping them; a call's
    time goes to its part less that of the wrapped calls inside it (report.html: what the
    sections leave, the page itself)."""

    def __init__(self) -> None:
        import coatsim.report.document as document
        import coatsim.run.pipeline as pipeline
        from coatsim.report import data
        from coatsim.report.sections import maps, program, speed, tables, track, verdict, view3d, warnings

        self.seconds: dict[str, float] = {}
        self.inner: list[float] = []
        for module in (verdict, speed, track, maps, warnings, view3d, program):
            module.section = self.wrap(module.__name__.rsplit(".", 1)[1], module.section)
        for name in ("metrics_section", "summary_section", "gates_section"):
            setattr(tables, name, self.wrap("tables", getattr(tables, name)))
        for name in SHARED:
            prop = getattr(data.ReportData, name, None)  # (older versions of the report lack some)
            if prop is not None:
                prop.func = self.wrap(f"shared: {name.strip('_')}", prop.func)
        pipeline.write_thickness_files = self.wrap("PLY + GLB files", pipeline.write_thickness_files)
        document.write_report = self.wrap("page", document.write_report)

    def wrap(self, name: str, function):
        def timed(*args, **kwargs):
            self.inner.append(0.0)
            started = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                elapsed = time.process_time() - started
                self.seconds[name] = self.seconds.get(name, 0.0) + elapsed - self.inner.pop()
                if self.inner:
                    self.inner[-1] += elapsed
        return timed


def run(clock: Clock, scenario: Path, fast: bool) -> tuple[dict[str, float], int, int]:
    """CPU seconds by part, mesh vertices, report.html bytes of one run."""
    from coatsim.run.pipeline import run_scenario

    clock.seconds = {}
    with tempfile.TemporaryDirectory() as out:
        result = run_scenario(scenario, out, fast=fast, progress=False)
        size = (Path(out) / "report.html").stat().st_size
    seconds = dict(clock.seconds)
    seconds["report.html"] = sum(t for name, t in seconds.items() if name != "PLY + GLB files")
    return seconds, result.variants[0].coating.surface.n_vertices, size


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", type=Path, help="scenario files [default: scenarios/*.yaml]")
    parser.add_argument("--fast-too", action="store_true", help="also run fast mode, for the exponent")
    args = parser.parse_args()
    from coatsim.core.runtime import long_lived_imports, single_threaded_numerics

    single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load
    files = args.scenarios or sorted((ROOT / "scenarios").glob("*.yaml"))
    with long_lived_imports():  # as `coatsim run` does: frozen out of the collector's passes
        plotting_s = plotting_import_s()
        clock = Clock()
    print(f"importing matplotlib.figure and the Agg canvas: {plotting_s:.2f} s CPU (once per process; "
          "not in the figures below)")
    run(clock, files[0], fast=True)  # first-use costs of the libraries (fonts, caches) left out
    summary = []
    for scenario in files:
        full, vertices, size = run(clock, scenario, fast=False)
        print(f"\n{scenario.stem} (full mode, {vertices} mesh vertices): report.html {size / 1e6:.2f} MB")
        print(f"  {'part':<22} {'CPU s':>7}")
        for name, seconds in sorted(full.items(), key=lambda item: -item[1]):
            print(f"  {name:<22} {seconds:>7.2f}")
        exponent = "-"
        if args.fast_too:
            fast, fast_vertices, _ = run(clock, scenario, fast=True)
            t1, t2 = fast["report.html"], full["report.html"]
            if fast_vertices != vertices and t1 > 0:
                exponent = f"{math.log(t2 / t1) / math.log(vertices / fast_vertices):.2f}"
            print(f"  fast mode: {fast_vertices} vertices, report.html {t1:.2f} s; exponent against vertices {exponent}")
        summary.append((scenario.stem, full["report.html"], full.get("PLY + GLB files", 0.0), vertices, exponent))
    print(f"\n{'scenario':<18} {'report.html s':>13} {'PLY+GLB s':>10} {'vertices':>9} {'exponent':>9}")
    for name, report_s, files_s, vertices, exponent in summary:
        print(f"{name:<18} {report_s:>13.2f} {files_s:>10.2f} {vertices:>9} {exponent:>9}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()

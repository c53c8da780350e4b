"""Benchmark of `coatsim run`: CPU seconds per stage of every shipped scenario (or those given),
each stage's exponent against its size, then the comparison the runs lead with.

Stages: start-up (importing coatsim, before the run), segmentation, meshing (the coating mesh
and its edge distances), programs (written and read back), execution (the simulated arm and
its trajectory file), coat, metrics (deviations, the shared region of interest, gates,
metrics.json), thickness files (PLY and GLB; the first to import matplotlib, for its colour
map) and report (report.html, with the plotting it imports), and what is left (other: the
scenario and the arm model loaded, the output folder held). CPU seconds are this process's (load on the machine
counts less than in wall time). The exponent of a stage is log(t_full / t_fast) / log(n_full /
n_fast) between the scenario's fast and full runs, n the stage's own size: trajectory rows for
the execution, coating-mesh vertices for meshing, coat, thickness files and report; a stage
whose size is the same in both modes has none (scripts/bench_segment.py and bench_program.py
give theirs).

Usage: python scripts/bench_run.py [--full-only] [--outdir runs/bench] [SCENARIO.yaml ...]
Prints figures only; never asserts. Exits non-zero when a scenario file is missing or a run fails.
"""

from __future__ import annotations

import time

STARTED = time.process_time()

import argparse  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

from coatsim.core.runtime import long_lived_imports, single_threaded_numerics  # noqa: E402

single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load

with long_lived_imports():  # as `coatsim run` does: frozen out of the collector's passes
    import coatsim.report.document as document
    import coatsim.run.pipeline as pipeline
    from coatsim.core.errors import CoatsimError
    from coatsim.report.summary import summary_text

ROOT = Path(__file__).resolve().parents[1]
STARTUP_S = time.process_time() - STARTED
# stage -> the functions of coatsim.run.pipeline whose CPU it is, less that of the stages they call
STAGES = {
    "segmentation": ("segment_input", "segment_curve"),
    "meshing": ("build_surface", "away_from_border"),
    "programs": ("run_variant", "run_program_variant"),
    "execution": ("simulate_variant",),
    "coat": ("coat",),
    "metrics": ("_segmentation_groups", "polyline_of", "hausdorff", "on_common_roi", "evaluate_gates", "assemble",
                "to_json"),
    "thickness files": ("write_thickness_files",),
}
SIZE = {"execution": "rows", "meshing": "vertices", "coat": "vertices", "thickness files": "vertices",
        "report": "vertices"}


class Clock:
    """CPU seconds per stage, by wrapping the pipeline's functions; a call's time goes to its
    stage less the time of the wrapped calls inside it."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {}
        self.inner: list[float] = []  # per open call: CPU seconds of the wrapped calls inside it
        for stage, names in STAGES.items():
            for name in names:
                setattr(pipeline, name, self.wrap(stage, getattr(pipeline, name)))
        document.write_report = self.wrap("report", document.write_report)

    def wrap(self, stage: str, function):
        def timed(*args, **kwargs):
            self.inner.append(0.0)
            started = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                elapsed = time.process_time() - started
                own = elapsed - self.inner.pop()
                self.seconds[stage] = self.seconds.get(stage, 0.0) + own
                if self.inner:
                    self.inner[-1] += elapsed
        return timed


def run(clock: Clock, path: Path, outdir: Path, fast: bool) -> tuple[dict[str, float], dict[str, int], dict]:
    """One run: CPU seconds per stage (with "other" and "total"), sizes, metrics document."""
    clock.seconds = {}
    started = time.process_time()
    result = pipeline.run_scenario(path, outdir, fast=fast, progress=False, force=True)
    total = time.process_time() - started
    seconds = dict(clock.seconds)
    seconds["other"] = total - sum(seconds.values())
    seconds["total"] = total
    sizes = {"rows": sum(len(v.execution.log.t) for v in result.variants),
             "vertices": result.variants[0].coating.surface.n_vertices if result.variants else 0}
    return seconds, sizes, result.document


def exponent(t1: float, t2: float, n1: int, n2: int) -> str:
    if n1 <= 0 or n2 <= 0 or n1 == n2 or t1 <= 0 or t2 <= 0:
        return "-"
    return f"{math.log(t2 / t1) / math.log(n2 / n1):.2f}"


def print_split(name: str, full: dict[str, float], fast: dict[str, float] | None, sizes: tuple[dict, dict] | None) -> None:
    order = ["segmentation", "meshing", "programs", "execution", "coat", "metrics", "thickness files", "report", "other",
             "total"]
    print(f"== {name}: CPU seconds per stage (start-up, importing coatsim: {STARTUP_S:.2f} s)")
    print(f"  {'stage':<16} {'full':>7} {'share':>6}" + (f" {'fast':>7} {'size':>9} {'exponent':>9}" if fast else ""))
    for stage in order:
        t = full.get(stage, 0.0)
        line = f"  {stage:<16} {t:>7.2f} {t / full['total']:>6.0%}"
        if fast is not None and sizes is not None:
            unit = SIZE.get(stage)
            e = "-" if unit is None else exponent(fast.get(stage, 0.0), t, sizes[0][unit], sizes[1][unit])
            line += f" {fast.get(stage, 0.0):>7.2f} {unit or '':>9} {e:>9}"
        print(line)
    if sizes is not None:
        print(f"  sizes fast > full: {sizes[0]['rows']} > {sizes[1]['rows']} trajectory rows, "
              f"{sizes[0]['vertices']} > {sizes[1]['vertices']} mesh vertices")


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
    parser.add_argument("--full-only", action="store_true", help="skip the fast runs (and the exponents)")
    parser.add_argument("--outdir", type=Path, default=ROOT / "runs" / "bench")
    args = parser.parse_args()
    files = args.scenarios or sorted((ROOT / "scenarios").glob("*.yaml"))
    missing = [str(p) for p in files if not p.is_file()]
    if missing or not files:
        sys.exit(f"bench_run: scenario file(s) not found: {', '.join(missing) or 'scenarios/*.yaml'}")
    clock = Clock()
    documents: dict[str, dict] = {}
    totals: list[tuple[str, float, str]] = []
    failed = False
    for path in files:
        try:
            full, full_sizes, doc = run(clock, path, args.outdir / path.stem, fast=False)
            fast = fast_sizes = None
            if not args.full_only:
                fast, fast_sizes, _ = run(clock, path, args.outdir / f"{path.stem}-fast", fast=True)
        except CoatsimError as exc:
            print(f"== {path.stem}: error (exit {exc.exit_code}): {exc}\n")
            totals.append((path.stem, math.nan, "error"))
            failed = True
            continue
        documents[path.stem] = doc
        print_split(path.stem, full, fast, None if fast is None else (fast_sizes, full_sizes))
        print(summary_text(doc))
        print()
        totals.append((path.stem, full["total"], f"{full.get('report', 0.0):.2f}"))
    print_comparison(documents)
    print(f"{'scenario':<18} {'run CPU s':>9} {'report CPU s':>13}")
    for name, total, report in totals:
        print(f"{name:<18} {total:>9.2f} {report:>13}")
    if failed:
        sys.exit(1)


if __name__ == "__main__":
    main()

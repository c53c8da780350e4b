"""Benchmark of the programs stage: write, parse and interpret AS programs of the benchmark curves.

Prints, per curve and variant: moves, program steps, poses, text size, and the best of
``REPEATS`` wall times for writing, parsing and interpreting. Never asserts.
The curves are the benchmark curves (coatsim.geometry.benchmark), or the CSV files of a folder
given as the argument (exit non-zero when it has none); the polysegment comes from
coatsim.geometry.segment_curve at TOL mm.

    python scripts/bench_program.py [DIR]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from coatsim.geometry import load_curve, segment_curve
from coatsim.geometry.benchmark import NAMES, bench_curve
from coatsim.program import interpret, parse_as
from coatsim.program.build import VARIANTS, ProgramOptions, build_program
from coatsim.program.placement import Placement, centering_offset

TOL = 0.1
REPEATS = 5


def best(fn):
    times, result = [], None
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), result


def polysegment_of(curve):
    t0 = time.perf_counter()
    seg = segment_curve(curve, TOL)
    return seg.polysegment, f"segment_curve, {time.perf_counter() - t0:.2f} s"


def main() -> None:
    if len(sys.argv) > 1:
        files = sorted(Path(sys.argv[1]).glob("*.csv"))
        if not files:
            sys.exit(f"bench_program: no curve files (*.csv) in {sys.argv[1]}")
        curves = {path.stem: load_curve(str(path)) for path in files}
    else:
        curves = {name: bench_curve(name) for name in NAMES}
    print(f"tolerance {TOL} mm, best of {REPEATS}")
    print(f"{'curve':10} {'variant':15} {'moves':>6} {'steps':>6} {'poses':>6} {'bytes':>7} "
          f"{'write ms':>9} {'parse ms':>9} {'interp ms':>10} {'lines/s':>9}")
    for name, curve in curves.items():
        poly, how = polysegment_of(curve)
        print(f"# {name}: {poly.n_segments} segments ({poly.n_arcs} arcs) from {how}")
        placement = Placement(offset_xy=centering_offset(poly))
        for variant in VARIANTS:
            options = ProgramOptions(variant=variant)
            t_write, built = best(lambda: build_program(poly, placement, options, tolerance_mm=TOL,
                                                        source=name, points=curve.points))
            t_parse, parsed = best(lambda: parse_as(built.text))
            t_interp, toolpath = best(lambda: interpret(parsed))
            n_lines = built.text.count("\n")
            print(f"{name:10} {variant:15} {len(toolpath.moves):6d} {len(parsed.programs[0].statements):6d} "
                  f"{len(parsed.trans):6d} {len(built.text):7d} {1e3 * t_write:9.2f} {1e3 * t_parse:9.2f} "
                  f"{1e3 * t_interp:10.2f} {n_lines / t_parse:9.0f}")


if __name__ == "__main__":
    main()

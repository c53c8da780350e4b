"""Benchmark of the programs stage: write, parse and interpret AS programs.

Part 1, per benchmark curve and variant: moves, program steps, poses, text size, and the best
of ``REPEATS`` CPU times for writing, parsing and interpreting. Part 2: parse and interpret
speed (lines/s, statements executed/s) on 5 000-line programs in a user's style: a contour of
LMOVEs to a pose array, and one that computes its poses in loops, CASEs and CALLs. Part 3: the
scaling exponent of writing, parsing and interpreting (scripts/scaling.py, N and 10 N moves).
Never asserts. The curves are the benchmark curves (coatsim.geometry.benchmark), or the CSV
files of a folder given as the argument (exit non-zero when it has none); the polysegment comes
from coatsim.geometry.segment_curve at TOL mm. Given a surface paths file
(coatsim.surfacepaths/1, ``coatsim plan -o``) instead, it times the program of its passes
(coatsim.path.surface_program) on the first 1/4, 1/2 and all of them: CPU seconds in all and
per pass, and the share spent fitting and orienting. Times are CPU seconds (``time.process_time``).

    python scripts/bench_program.py [DIR | PATHS.json]
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

from coatsim.geometry import load_curve, segment_curve
from coatsim.geometry.benchmark import NAMES, bench_curve
from coatsim.languages.kawasaki_as import interpret, interpret_run, parse_as
from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.path.build import VARIANTS, ProgramOptions, build_program
from coatsim.path.placement import Placement, centering_offset

TOL = 0.1
REPEATS = 5


def best(fn):
    times, result = [], None
    for _ in range(REPEATS):
        t0 = time.process_time()
        result = fn()
        times.append(time.process_time() - t0)
    return min(times), result


def polysegment_of(curve):
    t0 = time.process_time()
    seg = segment_curve(curve, TOL)
    return seg.polysegment, f"segment_curve, {time.process_time() - t0:.2f} s"


def contour_program(lines: int) -> str:
    """A hand-written style contour: step numbers, lower case, a gun routine, LMOVEs to c[i]."""
    n = lines // 2 - 12
    body = [".PROGRAM trace()", "  speed 150 mm/s always", "  accuracy 1 always", "  jmove c[0]", "  call gun_on"]
    body += [f"  {100 + i} lmove c[{i}]  ; point {i}" for i in range(1, n)]
    body += ["  break", "  signal -1", ".END", ".PROGRAM gun_on()", "  break", "  signal 1", ".END", ".TRANS"]
    body += [f"c[{i}] {700 + 80 * math.cos(i / n * 2 * math.pi):.3f} {40 * math.sin(i / n * 2 * math.pi):.3f} "
             "300.000 0 180 0" for i in range(n)]
    return "\n".join(body + [".END"]) + "\n"


def logic_program(lines: int) -> str:
    """Poses computed in loops, CASEs, string functions and CALLs (many statements per motion)."""
    block = ["  FOR .k = 1 TO 3", "    .x = .x + SIN(.k * 10) * 2", "    IF .x > 50 THEN", "      .x = .x - 100",
             "    ELSE", "      .y = .y + 1", "    END", "  END", "  CASE .y MOD 3 OF", "    VALUE 0:",
             "      $s = $ENCODE(/F6.2, .x)", "    ANY :", "      $s = $MID(\"abcdef\", 2, 3)", "  END",
             "  CALL step(.x, .&y)", "  LMOVE SHIFT(org BY .x, .y MOD 50, 0)"]
    body = [".PROGRAM logic()", "  .x = 0", "  .y = 0", "  JMOVE org"]
    while len(body) + len(block) < lines - 8:
        body += block
    body += [".END", ".PROGRAM step(.a, .&b)", "  .b = .b + INT(.a / 10)", ".END", ".TRANS", "org 650 0 300 0 180 0",
             ".END"]
    return "\n".join(body) + "\n"


def bench_language() -> None:
    print("\n# parse and interpret speed on 5 000-line programs, best of", REPEATS)
    print(f"{'program':10} {'lines':>6} {'parse ms':>9} {'lines/s':>9} {'interp ms':>10} {'steps':>7} {'steps/s':>9} "
          f"{'moves':>6}")
    for name, text in (("contour", contour_program(5000)), ("logic", logic_program(5000))):
        n_lines = text.count("\n")
        t_parse, parsed = best(lambda: parse_as(text))
        t_run, run = best(lambda: interpret_run(parsed))
        steps = sum(run.executions.values())
        print(f"{name:10} {n_lines:6d} {1e3 * t_parse:9.1f} {n_lines / t_parse:9.0f} {1e3 * t_run:10.1f} {steps:7d} "
              f"{steps / t_run:9.0f} {len(run.toolpath.moves):6d}")


def bench_surface(spec: str) -> None:
    """CPU of the polysegment program of the first 1/4, 1/2 and all passes of a surfacepaths file."""
    from dataclasses import replace

    import coatsim.path.surface_program as surface_program
    from coatsim.core import defaults
    from coatsim.path.surfacepaths import read_surfacepaths

    paths = read_surfacepaths(spec)
    spent = {"fit": 0.0, "orient": 0.0}

    def timed(stage, fn):
        def run(*args, **kwargs):
            t0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[stage] += time.process_time() - t0
        return run

    surface_program.fit_passes = timed("fit", surface_program.fit_passes)
    surface_program.oriented_pieces = timed("orient", surface_program.oriented_pieces)
    print(f"{spec}: {len(paths.passes)} passes, tolerance {defaults.TOLERANCE_MM} mm")
    print(f"{'passes':>6} {'points':>7} {'moves':>6} {'CPU s':>8} {'s/pass':>7} {'fit %':>6} {'orient %':>8}")
    for share in (4, 2, 1):
        part = replace(paths, passes=paths.passes[: max(1, len(paths.passes) // share)])
        spent.update(fit=0.0, orient=0.0)
        t0 = time.process_time()
        built = surface_program.build_surface_program(part, ProgramOptions(), surface_program.SurfaceOptions(),
                                                      KAWASAKI_AS)
        total = time.process_time() - t0
        n = len(part.passes)
        print(f"{n:6d} {sum(len(p.points) for p in part.passes):7d} {sum(a + b for a, b in built.counts):6d} "
              f"{total:8.2f} {total / n:7.3f} {100 * spent['fit'] / total:6.1f} {100 * spent['orient'] / total:8.1f}")


def main() -> None:
    if len(sys.argv) > 1 and sys.argv[1].endswith(".json"):
        bench_surface(sys.argv[1])
        return
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
            t_write, built = best(lambda: build_program(poly, placement, options, language=KAWASAKI_AS,
                                                        tolerance_mm=TOL, source=name, points=curve.points))
            t_parse, parsed = best(lambda: parse_as(built.text))
            t_interp, toolpath = best(lambda: interpret(parsed))
            n_lines = built.text.count("\n")
            print(f"{name:10} {variant:15} {len(toolpath.moves):6d} {len(parsed.programs[0].body):6d} "
                  f"{len(parsed.trans):6d} {len(built.text):7d} {1e3 * t_write:9.2f} {1e3 * t_parse:9.2f} "
                  f"{1e3 * t_interp:10.2f} {n_lines / t_parse:9.0f}")
    bench_language()
    import scaling  # scripts/scaling.py: the exponent of writing, parsing and interpreting

    scaling.program()


if __name__ == "__main__":
    main()

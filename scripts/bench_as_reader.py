"""Benchmark of the AS reader: parse and interpret CPU seconds against program size.

Two programs of N moves each: ``contour``, a controller-backup style contour (LMOVEs to a pose
array in .TRANS, step numbers, a CALLed gun routine), and ``field``, the way cells write them
(abbreviated keywords, variables from the controller's memory, a whole array passed to a
subprogram, AVE_TRANS, a joint pose from a transformation, a long flat expression). For N and
10 N moves: CPU seconds of parsing and of interpreting, and the exponent of each against N
(1 = linear). Never asserts.

    python scripts/bench_as_reader.py [N]      (default N = 500, so 5 000 moves at 10 N)
"""

from __future__ import annotations

import math
import sys
import time

from coatsim.languages.kawasaki_as import interpret_run, parse_as

REPEATS = 3


def cpu(fn):
    best, result = math.inf, None
    for _ in range(REPEATS):
        t0 = time.process_time()
        result = fn()
        best = min(best, time.process_time() - t0)
    return best, result


def contour(n: int) -> str:
    body = [".PROGRAM trace()", "  SPEED 150 MM/S ALWAYS", "  ACCURACY 1 ALWAYS", "  JMOVE c[0]", "  CALL gun.on"]
    body += [f"  {100 + i} LMOVE c[{i}]  ; point {i}" for i in range(1, n)]
    body += ["  BREAK", "  SIGNAL -1", ".END", ".PROGRAM gun.on()", "  BREAK", "  SIGNAL 1", ".END", ".TRANS"]
    body += [f"c[{i}] {700 + 80 * math.cos(i / n * 2 * math.pi):.3f} {40 * math.sin(i / n * 2 * math.pi):.3f} "
             "300.000 0 180 0" for i in range(n)]
    return "\n".join(body + [".END"]) + "\n"


def field(n: int) -> str:
    body = [".PROGRAM trace() ; K-IDE", "  spe 150 mm/s always", "  accu 1 always", "  tw 0.1",
            "  point .mid = ave_trans(c[0], c[1])", "  .chk = " + "+".join(["1"] * 300),
            "  if mode == 2 then", "    ty \"mode 2\"", "  end", "  jm c[0]", "  call gun.on(.$msg[], 1)"]
    body += [f"  lm c[{i}]" for i in range(1, n)]
    body += ["  bre", "  signal -1", ".END", ".PROGRAM gun.on(.$m[], .k)", "  bre", "  signal 1", ".END", ".TRANS"]
    body += [f"c[{i}] {700 + 80 * math.cos(i / n * 2 * math.pi):.3f} {40 * math.sin(i / n * 2 * math.pi):.3f} "
             "300.000 0 180 0" for i in range(n)]
    return "\n".join(body + [".END"]) + "\n"


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 500
    print(f"CPU seconds, best of {REPEATS}")
    print(f"{'program':8} {'moves':>6} {'parse s':>8} {'interp s':>9} {'moves/s':>9}")
    for name, make in (("contour", contour), ("field", field)):
        rows = []
        for size in (n, 10 * n):
            text = make(size)
            try:
                t_parse, parsed = cpu(lambda: parse_as(text))
                t_run, run = cpu(lambda: interpret_run(parsed))
            except Exception as exc:  # an older reader may refuse the field style
                print(f"{name:8} {size:6d} refused: {type(exc).__name__}: {str(exc)[:90]}")
                break
            rows.append((size, t_parse, t_run))
            moves = len(run.toolpath.moves)
            print(f"{name:8} {moves:6d} {t_parse:8.3f} {t_run:9.3f} {moves / (t_parse + t_run):9.0f}")
        if len(rows) == 2:
            (n1, p1, r1), (n2, p2, r2) = rows
            k = math.log(n2 / n1)
            print(f"{name:8} exponent: parse {math.log(p2 / p1) / k:.2f}, interpret {math.log(r2 / r1) / k:.2f}")


if __name__ == "__main__":
    main()

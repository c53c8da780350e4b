"""Benchmark of the execute stage (robot twin): prints figures, asserts nothing.

1. Speed: a 1 m straight LMOVE at 200 mm/s (5 s of robot time) through IK, timing, playback
   and logging, best of 3 (interpreter start-up and imports excluded).
2. The paper's spiral (the benchmark curve of coatsim.geometry.benchmark, or a curve file given with
   --curve, which must exist; sigma = 0.1 mm, 200 mm/s) as a polysegment program,
   an exact-stop polyline program and a blended polyline program (ACCURACY 1 mm), each written
   as AS text, parsed back and executed.
3. The scaling exponent of every execute phase on exact-stop polygons of N and 10 N sides, and
   the CPU per robot second of every variant on the spiral (scripts/scaling.py).
Usage: python scripts/bench_twin.py [--curve PATH] [--tol MM] [--speed MM_S]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load

import numpy as np  # noqa: E402

from coatsim.path.toolpath import JointMove, LinearMove, MotionSettings, Pose, ToolPath  # noqa: E402
from coatsim.robot.cell import load_cell  # noqa: E402
from coatsim.robot.execute import execute  # noqa: E402

DOWN = np.diag([-1.0, 1.0, -1.0])


def straight_metre(speed: float) -> ToolPath:
    def pose(y: float) -> Pose:
        return Pose(DOWN, np.array([700.0, y, 300.0]))

    s = MotionSettings(speed, 1.0, True, False)
    stop = MotionSettings(speed, 1.0, True, True)
    return ToolPath("metre", (
        JointMove(None, pose(-530.0), MotionSettings(1000.0, 10.0, True, True), False, 1),
        LinearMove(pose(-530.0), pose(-500.0), s, True, 2),
        LinearMove(pose(-500.0), pose(500.0), s, True, 3),
        LinearMove(pose(500.0), pose(530.0), stop, True, 4),
    ), {"lead_in_mm": "30", "lead_out_mm": "30"})


def bench_speed(cell, speed: float) -> None:
    best = None
    for _ in range(3):
        t0, c0 = time.perf_counter(), time.process_time()
        result = execute(straight_metre(speed), cell)
        result.log.to_csv_text()
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        if best is None or cpu < best[1]:
            best = (wall, cpu, result)
    wall, cpu, result = best
    robot = float(result.log.t[-1])
    m = result.metrics
    print(f"1 m line at {speed:g} mm/s: robot time {robot:.3f} s (curve {m.cycle_time_s:.3f} s), wall {wall:.3f} s "
          f"-> {robot / wall:.1f}x real time, CPU {cpu:.3f} s; rows {len(result.log)}")
    print("  wall by phase (s): " + ", ".join(f"{k} {v:.3f}" for k, v in result.wall.items()))
    print(f"  IK samples {int(round(m.curve_length_mm)) + 60}, max IK residual {m.max_ik_residual_mm:.2e} mm "
          f"/ {m.max_ik_residual_deg:.2e} deg; path error max {m.max_path_error_mm:.4f} mm")


def bench_spiral(cell, curve: Path | None, tol: float, speed: float) -> None:
    from coatsim.geometry.benchmark import bench_points
    from coatsim.languages.kawasaki_as.files import read_toolpath
    from coatsim.path.build import ProgramOptions
    from coatsim.cli.program import run_program

    print(f"\nspiral {curve.name if curve else 'benchmark spiral'}, sigma {tol} mm, {speed:g} mm/s, tool acceleration limit "
          f"{cell.tool_accel_mm_s2 / 1000:g} m/s^2")
    header = ("variant", "moves", "cycle_s", "ideal_s", "min_v", "cv", "at_speed", "feasible", "stops",
              "max_err", "rms_err", "jacc", "wall_s", "cpu_s")
    print(" ".join(f"{h:>10}" for h in header))
    with tempfile.TemporaryDirectory() as tmp:
        if curve is None:
            curve = Path(tmp) / "spiral.csv"
            np.savetxt(curve, bench_points("spiral"), delimiter=",", fmt="%.9f")
        for variant in ("polysegment", "polyline-stop", "polyline-blend"):
            path = Path(tmp) / f"{variant}.as"
            options = ProgramOptions(variant=variant, speed_mm_s=speed, accuracy_mm=1.0)
            run_program(str(curve), tol, options, frame="700,0,200,0,0,0", standoff_mm=100.0, lead_in_mm=30.0,
                        lead_out_mm=30.0, roll_deg=0.0, follow_tangent=False, center=True, output=path)
            toolpath = read_toolpath(path)
            t0, c0 = time.perf_counter(), time.process_time()
            result = execute(toolpath, cell)
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            m = result.metrics
            row = (variant, len(toolpath.moves), f"{m.cycle_time_s:.3f}", f"{m.ideal_time_s:.3f}",
                   f"{m.min_speed_mm_s:.1f}", f"{m.speed_cv:.4f}", f"{m.fraction_at_speed:.4f}",
                   f"{m.fraction_at_speed_feasible:.4f}", m.stops, f"{m.max_path_error_mm:.3f}",
                   f"{m.rms_path_error_mm:.3f}", f"{m.max_joint_accel_ratio:.3f}", f"{wall:.2f}", f"{cpu:.2f}")
            print(" ".join(f"{str(v):>10}" for v in row))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--curve", type=Path, help="curve file [default: the benchmark spiral]")
    parser.add_argument("--tol", type=float, default=0.1)
    parser.add_argument("--speed", type=float, default=200.0)
    args = parser.parse_args()
    if args.curve is not None and not args.curve.is_file():
        sys.exit(f"bench_twin: curve file {args.curve} not found")
    cell = load_cell()
    bench_speed(cell, args.speed)
    bench_spiral(cell, args.curve, args.tol, args.speed)
    import scaling  # scripts/scaling.py: the exponent of every execute phase, compute per robot second

    scaling.execute()


if __name__ == "__main__":
    main()

"""Benchmark of the execute stage on every shipped scenario: real-time factor and accuracy.

For each scenario and program variant: the program is built as the pipeline builds it, written as
AS text, parsed back and executed (start-up, imports and the first cell load excluded). Prints the
robot time (duration of the simulated program), the wall time of ``execute`` by phase, the
real-time factors robot time / wall time and robot time / CPU time (``time.process_time``; the
machine is shared, so CPU time is the figure to compare; best of ``--repeat`` runs by CPU), the
largest IK residual and the path error; then robot time / CPU time per scenario (all its
variants); then the exponent of every execute phase against the number of pieces
(scripts/scaling.py). Figures only; never asserts.

Usage: python scripts/bench_execute.py [--fast] [--repeat N] [SCENARIO.yaml ...]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def programs(path: Path, fast: bool, cell):
    """(variant, ToolPath, sample step mm) of every variant of the scenario at ``path``, built
    as ``coatsim run`` builds them (a drawing's contours as one part program, the polylines
    shared, the cell's gun as TOOL; a user's program read as given)."""
    import tempfile

    import numpy as np

    from coatsim.geometry import make_curve, segment_curve
    from coatsim.languages.kawasaki_as.files import read_toolpath
    from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
    from coatsim.languages.kawasaki_as.names import program_name
    from coatsim.path.build import ProgramOptions, polyline_of
    from coatsim.path.part_program import build_part_program, part_centering_offset
    from coatsim.path.placement import Placement
    from coatsim.path.user import user_program
    from coatsim.robot.kinematics import CellKinematics
    from coatsim.robot.tooling import gun_tool
    from coatsim.run.pipeline import FULL_SAMPLE_STEP_MM
    from coatsim.run.scenario import load_scenario
    from coatsim.run.scenario_inputs import curve_frame, read_user_program, segment_input

    loaded = load_scenario(path)
    spec = loaded.spec
    step = spec.fast.sample_step_mm if fast else FULL_SAMPLE_STEP_MM
    if spec.curve is None:  # the sprayed path of the first program variant, as run does
        entry = spec.programs[0]
        user = user_program(read_user_program(loaded, entry, cell)[0], curve_frame(spec), "")
        contours = (segment_curve(make_curve(user.points, entry.name, "auto"), spec.segmentation.tolerance_mm,
                                  method=spec.segmentation.method, corner_deg=spec.segmentation.corner_deg,
                                  speed_mm_s=spec.motion.speed_mm_s, tool_accel_mm_s2=cell.tool_accel_mm_s2),)
        offset = (0.0, 0.0)
    else:
        contours = segment_input(loaded, cell)[0]
        polys = [c.polysegment for c in contours]
        offset = np.add(part_centering_offset(polys) if spec.curve.center else (0.0, 0.0), spec.curve.offset_mm)
    placement = Placement(frame=curve_frame(spec), standoff_mm=spec.gun.standoff_mm, roll_deg=spec.gun.roll_deg,
                          follow_tangent=spec.gun.follow_tangent, lead_in_mm=spec.motion.lead_in_mm,
                          lead_out_mm=spec.motion.lead_out_mm, offset_xy=(float(offset[0]), float(offset[1])))
    polylines = tuple(polyline_of(c.curve.points, c.polysegment.closed, spec.segmentation.tolerance_mm)
                      for c in contours)
    for entry in spec.variants:
        if not isinstance(entry, str):
            yield entry.name, read_user_program(loaded, entry, cell)[0], step
            continue
        options = ProgramOptions(variant=entry, speed_mm_s=spec.motion.speed_mm_s, accuracy_mm=spec.motion.accuracy_mm,
                                 gun_signal=spec.gun.signal, tool=gun_tool(cell), name=program_name(spec.name))
        built = build_part_program([c.polysegment for c in contours], placement, options,
                                   language=KAWASAKI_AS, tolerance_mm=spec.segmentation.tolerance_mm,
                                   source=f"scenario:{spec.name}", points=[c.curve.points for c in contours],
                                   order=spec.motion.contour_order, polylines=polylines)
        with tempfile.TemporaryDirectory() as tmp:
            program = Path(tmp) / f"{entry}.as"
            program.write_text(built.text, encoding="utf-8")
            toolpath = read_toolpath(program, gun_signal=spec.gun.signal, kinematics=CellKinematics(cell))
        yield entry, toolpath, step


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", type=Path, help="scenario files [default: scenarios/*.yaml]")
    parser.add_argument("--fast", action="store_true", help="the scenarios' fast path sampling")
    parser.add_argument("--repeat", type=int, default=3, help="best of N executions per program (by CPU time)")
    args = parser.parse_args()
    from coatsim.core.runtime import single_threaded_numerics

    single_threaded_numerics()  # as `coatsim` does, before the numerical libraries load
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute

    cell = load_cell()
    files = args.scenarios or sorted((ROOT / "scenarios").glob("*.yaml"))
    warm = next(programs(files[0], args.fast, cell))  # first-run costs (lazy imports, caches) left out
    execute(warm[1], cell, step_mm=warm[2])
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; {'fast' if args.fast else 'full'} mode")
    header = ("scenario", "variant", "robot_s", "wall_s", "ik_s", "timing_s", "play_s", "metr_s", "x_real",
              "cpu_s", "x_cpu", "ik_mm", "ik_deg", "max_err", "rms_err")
    print(" ".join(f"{h:>14}" if i < 2 else f"{h:>9}" for i, h in enumerate(header)))
    robot_total = wall_total = cpu_total = 0.0
    per_scenario = []
    for path in files:
        robot_before, cpu_before = robot_total, cpu_total
        for name, toolpath, step in programs(path, args.fast, cell):
            best = None
            for _ in range(max(1, args.repeat)):
                t0, c0 = time.perf_counter(), time.process_time()
                result = execute(toolpath, cell, step_mm=step)
                wall, cpu = time.perf_counter() - t0, time.process_time() - c0
                if best is None or cpu < best[1]:
                    best = (wall, cpu, result)
            wall, cpu, result = best
            robot = float(result.log.t[-1])
            robot_total += robot
            wall_total += wall
            cpu_total += cpu
            m, w = result.metrics, result.wall
            row = (path.stem, name, f"{robot:.2f}", f"{wall:.2f}", f"{w.get('ik_s', 0):.2f}",
                   f"{w.get('timing_s', 0):.2f}", f"{w.get('playback_s', 0):.2f}", f"{w.get('metrics_s', 0):.2f}",
                   f"{robot / wall:.1f}", f"{cpu:.2f}", f"{robot / cpu:.1f}", f"{m.max_ik_residual_mm:.1e}", f"{m.max_ik_residual_deg:.1e}",
                   f"{m.max_path_error_mm:.4f}", f"{m.rms_path_error_mm:.4f}")
            print(" ".join(f"{v:>14}" if i < 2 else f"{v:>9}" for i, v in enumerate(row)), flush=True)
        per_scenario.append((path.stem, (robot_total - robot_before) / (cpu_total - cpu_before)))
    print("per scenario, robot s / CPU s: " + ", ".join(f"{name} {x:.1f}x" for name, x in per_scenario))
    print(f"all: robot {robot_total:.1f} s, wall {wall_total:.1f} s -> {robot_total / wall_total:.1f}x real time "
          f"(CPU {cpu_total:.1f} s -> {robot_total / cpu_total:.1f}x); load average now {os.getloadavg()[0]:.2f}")
    import scaling  # scripts/scaling.py: the exponent of every execute phase against size

    scaling.execute()


if __name__ == "__main__":
    main()

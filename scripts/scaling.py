"""Scaling exponents of every stage, for the bench scripts: each stage is timed (CPU seconds
of this process, best of a few, so other load on the machine matters less than in wall
time) at a size N and at k·N, and the exponent log(t(kN) / t(N)) / log(k) printed: 1 is
linear, a regression shows as a larger number. Prints only; never asserts.

    python scripts/scaling.py [segment|coat|execute|program ...]
"""

from __future__ import annotations

import math
import sys
import tempfile
import time
from pathlib import Path
from typing import Callable

import numpy as np


def cpu(fn: Callable, repeat: int = 1):
    """(best CPU seconds, last result) of ``fn()``."""
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def exponent(n1: float, t1: float, n2: float, t2: float) -> float:
    return math.log(max(t2, 1e-9) / max(t1, 1e-9)) / math.log(n2 / n1)


def report(title: str, rows: list[tuple[str, float, float, float, float]], unit: str = "N") -> None:
    """rows: (stage, n1, t1, n2, t2)."""
    print(f"\n# scaling: {title} (CPU s; exponent = log(t2/t1) / log(n2/n1), 1 = linear)")
    print(f"  {'stage':<34} {unit + '1':>10} {'t1':>8} {unit + '2':>10} {'t2':>8} {'exponent':>9}")
    for stage, n1, t1, n2, t2 in rows:
        print(f"  {stage:<34} {n1:>10.0f} {t1:>8.3f} {n2:>10.0f} {t2:>8.3f} {exponent(n1, t1, n2, t2):>9.2f}")


def segment(n: int = 100_000, factor: int = 10) -> None:
    """Built-in curve generation, the exact deviation check and the whole fit at N and 10 N points."""
    from coatsim.geometry import builtin_curve, segment_curve
    from coatsim.geometry.deviation import hausdorff

    rows = []
    for name in ("ellipse", "paper-spiral"):
        timed = {}
        for size in (n, factor * n):
            t_build, curve = cpu(lambda: builtin_curve(name, points=size), 2)
            t_fit, seg = cpu(lambda: segment_curve(curve, 0.05), 2 if size == n else 1)
            t_dev, _ = cpu(lambda: hausdorff(curve.points, seg.polysegment), 2)
            timed[size] = (t_build, t_dev, t_fit)
        for k, stage in enumerate(("built-in curve", "exact deviation check", "segment_curve (whole fit)")):
            rows.append((f"{name}: {stage}", n, timed[n][k], factor * n, timed[factor * n][k]))
    report(f"geometry, sigma 0.05 mm, {n} and {factor * n} points", rows)


def coat(spacing: float = 1.0) -> None:
    """Every stage of `coatsim coat` on the 320 mm plate at ``spacing`` and spacing / 2 (4 N vertices)."""
    from coatsim.robot.trajectory_log import TrajectoryLog
    from coatsim.spray.coat import CoatingResult, write_coating
    from coatsim.spray.coating_metrics import coating_metrics, region_of_interest
    from coatsim.spray.deposition import SprayModel, deposit
    from coatsim.spray.footprints import Gaussian
    from coatsim.spray.surfaces import parse_surface_spec

    speed, dt = 200.0, 0.002
    length = 2 * math.pi * math.sqrt((120**2 + 60**2) / 2)
    t = np.arange(0.0, length / speed, dt)
    phase = 2 * math.pi * t / (length / speed)
    n = len(t)
    log = TrajectoryLog(t=t, position=np.column_stack((120 * np.cos(phase), 60 * np.sin(phase), np.full(n, 100.0))),
                        axis=np.tile([0.0, 0.0, -1.0], (n, 1)), speed=np.full(n, speed), spray=np.ones(n, bool),
                        progress=np.zeros(n), path_error=np.zeros(n), q=np.zeros((n, 6)))
    model = SprayModel(Gaussian(5.0), 40.0, 100.0)
    timed = {}
    for s in (spacing, spacing / 2):
        t_mesh, surface = cpu(lambda: parse_surface_spec("plate:320x320@0,0,0", s))
        t_dep, result = cpu(lambda: deposit(surface, log, model))
        t_roi, roi = cpu(lambda: region_of_interest(surface, result, model, "band", spacing=s))
        t_met, metrics = cpu(lambda: coating_metrics(surface, result, model, roi))
        with tempfile.TemporaryDirectory() as tmp:
            t_out, _ = cpu(lambda: write_coating(CoatingResult(surface, model, result, roi, "band", metrics), tmp, {}))
        timed[s] = (surface.n_vertices, (t_mesh, t_dep, t_roi, t_met, t_out))
    (n1, a), (n2, b) = timed[spacing], timed[spacing / 2]
    stages = ("surface mesh", "deposition", "region of interest", "coating metrics", "files (ply, json, png)")
    rows = [(stage, n1, a[k], n2, b[k]) for k, stage in enumerate(stages)]
    rows.append(("coat (all stages)", n1, sum(a), n2, sum(b)))
    report(f"coating, 320 mm plate at {spacing:g} and {spacing / 2:g} mm, an ellipse at 200 mm/s", rows, "verts")


def _polygon(sides: int, radius: float = 80.0, speed: float = 200.0):
    """An exact-stop polygon program: a joint move to the start, then one LMOVE per side."""
    from coatsim.geometry.space.pose import Pose
    from coatsim.path.toolpath import JointMove, LinearMove, MotionSettings, ToolPath

    down = np.diag([-1.0, 1.0, -1.0])
    a = np.linspace(0.0, 2 * math.pi, sides + 1)
    poses = [Pose(down, np.array([700 + radius * math.cos(t), radius * math.sin(t), 300.0])) for t in a]
    stop = MotionSettings(speed, 1.0, False, True)
    moves = [JointMove(None, poses[0], MotionSettings(1000.0, 10.0, True, True), False, 1)]
    moves += [LinearMove(p, q, stop, True, k + 2) for k, (p, q) in enumerate(zip(poses[:-1], poses[1:]))]
    return ToolPath(f"polygon{sides}", tuple(moves), {})


def execute(n: int = 20, factor: int = 10) -> None:
    """The arm simulation per phase on an exact-stop polygon of N and 10 N sides (as many
    rest-to-rest pieces, the same perimeter); then the compute per robot second of the
    exact-stop polyline against the polysegment on the paper's spiral."""
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute as run

    cell = load_cell()
    rows, timed = [], {}
    for sides in (n, factor * n):
        t_all, result = cpu(lambda: run(_polygon(sides), cell))
        timed[sides] = (t_all, result.wall)
    for phase in ("ik_s", "timing_s", "playback_s", "metrics_s"):
        rows.append((f"exact stop: {phase[:-2]} (wall s)", n, timed[n][1][phase], factor * n, timed[factor * n][1][phase]))
    rows.append(("exact stop: execute (CPU)", n, timed[n][0], factor * n, timed[factor * n][0]))
    report(f"execute, exact-stop polygon of {n} and {factor * n} sides (r 80 mm, 200 mm/s)", rows, "pieces")
    spiral_per_robot_second(cell)


def spiral_per_robot_second(cell=None) -> None:
    """CPU per robot second of each variant on the paper's spiral (sigma 0.1 mm, 200 mm/s)."""
    from coatsim.geometry.benchmark import bench_curve
    from coatsim.languages.kawasaki_as.files import read_toolpath
    from coatsim.path.build import ProgramOptions
    from coatsim.cli.program import run_program
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute as run

    cell = cell or load_cell()
    print("\n# execute: CPU per robot second, paper spiral, sigma 0.1 mm, 200 mm/s (best of 3)")
    per = {}
    with tempfile.TemporaryDirectory() as tmp:
        csv = Path(tmp) / "spiral.csv"
        np.savetxt(csv, bench_curve("spiral").points, delimiter=",")
        for variant in ("polysegment", "polyline-stop", "polyline-blend"):
            path = Path(tmp) / f"{variant}.as"
            run_program(str(csv), 0.1, ProgramOptions(variant=variant, speed_mm_s=200.0, accuracy_mm=1.0),
                        frame="700,0,200,0,0,0", standoff_mm=100.0, lead_in_mm=30.0, lead_out_mm=30.0, roll_deg=0.0,
                        follow_tangent=False, center=True, output=path)
            toolpath = read_toolpath(path)
            seconds, result = cpu(lambda: run(toolpath, cell), 3)
            robot = float(result.log.t[-1])
            per[variant] = seconds / robot
            print(f"  {variant:15} pieces {len(toolpath.moves):4d}  robot {robot:6.2f} s  CPU {seconds:6.3f} s  "
                  f"-> {per[variant]:.4f} CPU s per robot s")
    print(f"  exact-stop polyline / polysegment: {per['polyline-stop'] / per['polysegment']:.2f}x (issue 15 target <= 1.3x)")


def program(n: int = 500, factor: int = 10) -> None:
    """Writing, parsing and interpreting a polyline program of N and 10 N moves."""
    from coatsim.geometry import make_curve
    from coatsim.languages.kawasaki_as import interpret, parse_as
    from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
    from coatsim.path.build import ProgramOptions, build_program, polyline_of
    from coatsim.path.placement import Placement

    timed = {}
    for size in (n, factor * n):
        a = np.linspace(0.0, 2 * math.pi, size + 1)
        curve = make_curve(np.column_stack((80 * np.cos(a), 80 * np.sin(a))), "circle")
        poly = polyline_of(curve.points, curve.closed, 1e-9)
        options = ProgramOptions(variant="polyline-blend")
        t_write, built = cpu(lambda: build_program(poly, Placement(), options, language=KAWASAKI_AS, tolerance_mm=1e-9,
                                                   source="circle", points=curve.points), 3)
        t_parse, parsed = cpu(lambda: parse_as(built.text), 3)
        t_interp, _ = cpu(lambda: interpret(parsed), 3)
        timed[size] = (t_write, t_parse, t_interp)
    rows = [(stage, n, timed[n][k], factor * n, timed[factor * n][k])
            for k, stage in enumerate(("write (build_program)", "parse", "interpret"))]
    report(f"programs, polyline of {n} and {factor * n} moves", rows, "moves")


STAGES = {"segment": segment, "coat": coat, "execute": execute, "program": program}

if __name__ == "__main__":
    for name in sys.argv[1:] or list(STAGES):
        if name not in STAGES:
            sys.exit(f"scaling: unknown stage {name!r}; choose from {', '.join(STAGES)}")
        STAGES[name]()

"""Benchmark of the twin on 3-D parts: prints figures, asserts nothing.

Per analytic test part (tests/surface_parts.py: a cylinder, a torus section, a saddle, a
blade-like twisted sheet; each placed in the shipped cell, passes 100 mm off the surface) and per
program variant (the 3-D fit, the blended and the exact-stop polyline of the same passes; speed
300 mm/s on the tool, roll fixed): the program's moves, the reachable fraction of its poses,
collisions with the part (its mesh in the cell), the cycle time over the sprayed passes, the
lowest speed ratio where the curve allows the speed, the spray spot's lowest speed ratio, the
largest angle between the simulated spray axis and the surface normal (at the nearest point of
the pass sampled 20 times more densely), and CPU seconds of writing and of executing the
program. Then the exponent of the program's CPU time against the points per pass
(scripts/scaling.py).

    python scripts/bench_twin3d.py [--speed 300] [--parts cylinder,torus_section,saddle,blade]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
sys.path.insert(0, str(ROOT / "tests"))

from scaling import cpu, report  # noqa: E402
from surface_parts import PARTS, write_surfacepaths  # noqa: E402

from coatsim.core.errors import ExecutionError  # noqa: E402
from coatsim.geometry.space.xyzoat import pose_from_xyzoat  # noqa: E402
from coatsim.languages.kawasaki_as.files import read_toolpath  # noqa: E402
from coatsim.languages.registry import language  # noqa: E402
from coatsim.path.build import ProgramOptions  # noqa: E402
from coatsim.path.surface_program import SurfaceOptions, build_surface_program  # noqa: E402
from coatsim.path.surfacepaths import read_surfacepaths  # noqa: E402
from coatsim.robot.cell import load_cell  # noqa: E402
from coatsim.robot.collisions import load_part, with_part  # noqa: E402
from coatsim.robot.execute import execute  # noqa: E402
from coatsim.robot.reachability import reachable_fraction  # noqa: E402

VARIANTS = ("polysegment", "polyline-blend", "polyline-stop")


def axis_error_deg(part, result) -> float:
    """Largest angle between the simulated spray axis and minus the surface normal at the nearest
    point of the densely sampled passes, over the rows of the passes proper (the leads run past
    the sampled surface)."""
    from scipy.spatial import cKDTree

    pose = pose_from_xyzoat(part.pose)
    dense = part.passes(points_per_pass=5000, lead_mm=0.0)
    tcp = np.vstack([pose.apply(np.array(p["points"]) + 100.0 * np.array(p["normals"])) for p in dense])
    axes = -np.vstack([pose.apply_vectors(np.array(p["normals"])) for p in dense])
    log = result.log
    rows = np.zeros(len(log.t), dtype=bool)
    for a, b in result.curves:
        rows |= (log.progress >= a) & (log.progress <= b) & log.spray
    _, near = cKDTree(tcp).query(log.position[rows])
    cos = np.einsum("ij,ij->i", log.axis[rows], axes[near])
    return float(np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))).max())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=300.0)
    parser.add_argument("--parts", default=",".join(PARTS))
    args = parser.parse_args()
    lang = language("kawasaki-as")
    base = load_cell()
    print(f"# twin in 3-D: {args.speed:g} mm/s on the tool, stand-off 100 mm, tolerance 0.1 mm, axis within 2 deg")
    print(f"{'part':<14} {'variant':<15} {'moves':>6} {'reach':>6} {'collision':>10} {'cycle s':>8} "
          f"{'min v':>6} {'spot':>6} {'axis deg':>9} {'prog s':>7} {'exec s':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        scaling = []
        for name in args.parts.split(","):
            part = PARTS[name]()
            source, mesh = write_surfacepaths(folder, part, points_per_pass=400)
            cell = with_part(base, load_part(mesh, pose_from_xyzoat(part.pose)))
            paths = read_surfacepaths(source)
            for variant in VARIANTS:
                t_prog, prog = cpu(lambda: build_surface_program(paths, ProgramOptions(variant=variant, speed_mm_s=args.speed),
                                                                 SurfaceOptions(), lang))
                file = folder / f"{name}_{variant}.as"
                file.write_text(prog.text, encoding="ascii")
                toolpath = read_toolpath(file)
                reach = reachable_fraction(toolpath, cell).fraction
                moves = sum(a + b for a, b in prog.counts)
                try:
                    t_exec, result = cpu(lambda: execute(toolpath, cell))
                except ExecutionError as exc:
                    kind = "yes" if "touches" in str(exc) else "-"
                    print(f"{name:<14} {variant:<15} {moves:>6} {reach:>6.3f} {kind:>10}  failed: {exc}")
                    continue
                m, tr = result.metrics, result.trace
                ratio = "-" if m.min_speed_ratio is None else f"{m.min_speed_ratio:.3f}"
                spot = "-" if tr.min_ratio is None else f"{tr.min_ratio:.3f}"
                print(f"{name:<14} {variant:<15} {moves:>6} {reach:>6.3f} {'none':>10} {m.cycle_time_s:>8.3f} "
                      f"{ratio:>6} {spot:>6} {axis_error_deg(part, result):>9.3f} {t_prog:>7.2f} {t_exec:>7.2f}")
            small = write_surfacepaths(folder / "n", part, points_per_pass=250)[0]
            large = write_surfacepaths(folder / "4n", part, points_per_pass=1000)[0]
            t1, _ = cpu(lambda: build_surface_program(read_surfacepaths(small), ProgramOptions(), SurfaceOptions(), lang))
            t2, _ = cpu(lambda: build_surface_program(read_surfacepaths(large), ProgramOptions(), SurfaceOptions(), lang))
            scaling.append((f"{name}: program (3-D fit)", 250, t1, 1000, t2))
        report("programs of 3-D passes against points per pass", scaling, "points")


if __name__ == "__main__":
    main()

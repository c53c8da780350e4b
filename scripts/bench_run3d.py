"""Benchmark of runs on 3-D parts: per shipped 3-D scenario (fast mode unless --full) the three
variants side by side (moves, cycle time, lowest speed ratio, thickness CV, share within the
specification), the CPU seconds of every stage (plan, programs, execution, coating, report) and of
the whole run; then the coating stage's CPU seconds against the coating mesh's vertices on the
tube (the polysegment's trajectory sprayed onto the part meshed at two spacings) and its exponent.
Prints figures only (never asserts).

    python scripts/bench_run3d.py [--full] [--scenarios cylinder_3d,blade_3d,...]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))

from scaling import cpu, report  # noqa: E402

import coatsim.run.part_run as part_run  # noqa: E402
from coatsim.run.pipeline import run_scenario  # noqa: E402

SCENARIOS = ("cylinder_3d", "blade_3d", "wear_plate_3d", "scan_patch_3d")
STAGES = {"plan_part": "plan", "fit_passes": "programs", "build_surface_program": "programs", "execute": "execution",
          "coat": "coating", "write_part_report": "report", "write_thickness_files": "report"}


def timed(spent: dict, stage: str, fn):
    def wrapper(*args, **kwargs):
        t0 = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            spent[stage] += time.process_time() - t0
    return wrapper


def instrument(spent: dict) -> None:
    import coatsim.report.part_document as document

    for name, stage in STAGES.items():
        module = document if name == "write_part_report" else part_run
        setattr(module, name, timed(spent, stage, getattr(module, name)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="the scenarios' full settings instead of fast mode")
    parser.add_argument("--scenarios", default=",".join(SCENARIOS))
    args = parser.parse_args()
    spent: dict = defaultdict(float)
    instrument(spent)
    print(f"# runs on 3-D parts ({'full' if args.full else 'fast'} mode), CPU seconds of this process")
    head = f"{'scenario':<15} {'variant':<15} {'moves':>6} {'cycle s':>8} {'min v':>7} {'CV':>7} {'in spec':>8}"
    rows, last = [], None
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.scenarios.split(","):
            spent.clear()
            t, result = cpu(lambda: run_scenario(ROOT / "scenarios" / f"{name}.yaml", Path(tmp) / Path(name).name,
                                                 fast=not args.full, progress=False,
                                                 keep_going=True))
            print(head)
            for v, groups in result.document["variants"].items():
                m, c, s = groups["motion"], groups["coating"], groups["segmentation"]
                ratio = "-" if m["min_speed_ratio"] is None else f"{m['min_speed_ratio']:.3f}"
                print(f"{name:<15} {v:<15} {s['n_segments']:>6} {m['cycle_time_s']:>8.3f} {ratio:>7} "
                      f"{c['thickness_cv']:>7.4f} {100 * c['within_spec_fraction']:>7.1f}%")
            for v, why in result.failures.items():
                print(f"{name:<15} {v:<15} failed: {why}")
            gates = result.document["gates"]
            print(f"  gates: {sum(g['passed'] for g in gates)} of {len(gates)} passed"
                  + "".join(f"; FAILED {g['label']}" for g in gates if not g["passed"]))
            stages = ", ".join(f"{k} {spent[k]:.1f}" for k in ("plan", "programs", "execution", "coating", "report"))
            vertices = result.variants[0].coating.surface.n_vertices
            print(f"  CPU {t:.1f} s in all ({stages}); coating mesh {vertices} vertices, "
                  f"{result.document['plan']['passes']} passes\n")
            rows.append((name, t))
            last = result if name == "cylinder_3d" else last
        if last is not None:
            coat_scaling(last)


def coat_scaling(result) -> None:
    """The tube's polysegment trajectory sprayed onto the part at two mesh spacings."""
    from coatsim.geometry.surface import load_part
    from coatsim.spray.coat import coat
    from coatsim.spray.surfaces import mesh_surface

    import numpy as np

    from coatsim.geometry.space.xyzoat import pose_from_xyzoat

    run = result.variants[0]
    part = load_part(ROOT / "scenarios" / "parts" / "tube.stl", "mm")
    pose = pose_from_xyzoat(tuple(result.document["scenario"]["part"]["pose"]))
    matrix = np.eye(4)
    matrix[:3, :3], matrix[:3, 3] = pose.rotation, pose.translation_mm
    sizes = []
    for spacing in (3.0, 1.5):
        surface = mesh_surface(part.vertices_mm, part.faces, spacing, matrix, "tube")
        t, _ = cpu(lambda: coat(run.execution.log, surface, run.coating.model, roi="field"))
        sizes.append((surface.n_vertices, t))
    report("coating on the tube against the mesh's vertices (shadows on)",
           [("coat (deposit + ROI + metrics)", sizes[0][0], sizes[0][1], sizes[1][0], sizes[1][1])], "vertices")


if __name__ == "__main__":
    main()

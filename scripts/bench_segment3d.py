"""Benchmark of the 3-D fit: the six space-curve families and five held-out ones
(coatsim.geometry.space.families: FAMILIES, HELD_OUT) at σ = 0.05 / 0.1 / 0.5 mm, against a
greedy 3-D arc fitter that ignores tangency.

Per curve and σ: segments of coatsim's G1 chain (arcs, lines) and of the greedy fitter and
their ratio, the certified deviation, the largest tangent break, the largest orientation
error of the orientation-aware fit of the same points as a surface pass (``--axes``), CPU
seconds; then the totals and the exponent of the fit's CPU time against the input size
(scripts/scaling.py). The greedy baseline (coatsim.geometry.space.greedy): from the current
input point, the longest run of input points whose arc through its first, middle and last
point keeps every point of the run within σ, then the next run starts where that one ends:
kinks at every junction. Prints only; never asserts.

    python scripts/bench_segment3d.py [--sigmas 0.05,0.1,0.5] [--points 1500] [--only helix,trefoil] [--axes]
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from scaling import cpu, report  # noqa: E402

from coatsim.geometry.space.curve import make_space_curve  # noqa: E402
from coatsim.geometry.space.families import FAMILIES, HELD_OUT, TOLERANCES_MM  # noqa: E402
from coatsim.geometry.space.greedy import greedy_knots  # noqa: E402
from coatsim.geometry.space.segment import segment_space_curve  # noqa: E402


def surface_axes(points: np.ndarray) -> np.ndarray:
    """A spray axis per point for the orientation benchmark: the curve's principal normal
    direction smoothed (toward the centre of curvature), as a gun inside a bend would point."""
    d = np.gradient(points, axis=0)
    dd = np.gradient(d, axis=0)
    t = d / np.linalg.norm(d, axis=1)[:, None]
    n = dd - np.einsum("ij,ij->i", dd, t)[:, None] * t
    return n / np.linalg.norm(n, axis=1)[:, None]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sigmas", default=",".join(str(s) for s in TOLERANCES_MM))
    parser.add_argument("--points", type=int, default=1500)
    parser.add_argument("--only", default="", help="comma-separated family names (default: all)")
    parser.add_argument("--axes", action="store_true", help="also fit each curve with spray axes (orientation error)")
    args = parser.parse_args()
    sigmas = [float(s) for s in args.sigmas.split(",")]
    families = {**FAMILIES, **HELD_OUT}
    names = [n for n in families if not args.only or n in args.only.split(",")]
    print(f"# 3-D fit: {args.points} points per curve; segments ours / greedy (3-point arcs, no tangency); "
          f"held out: {', '.join(HELD_OUT)}")
    print(f"  {'curve':<10} {'σ mm':>6} {'ours':>5} {'arcs':>5} {'lines':>5} {'greedy':>6} {'ratio':>6} {'dev mm':>9} "
          f"{'break°':>8} {'axis err°':>9} {'CPU s':>7}")
    total = [0, 0, 0.0]
    for name in names:
        points = families[name](args.points)
        curve = make_space_curve(points, name)
        for tol in sigmas:
            seconds, fit = cpu(lambda: segment_space_curve(curve, tol))
            greedy = len(greedy_knots(points, tol)) - 1
            axis_err = ""
            if args.axes:
                from coatsim.geometry.space.orient import fit_surface_pass

                axis_err = f"{math.degrees(fit_surface_pass(points, surface_axes(points), tol).max_axis_error_rad):9.3f}"
            print(f"  {name:<10} {tol:>6g} {fit.chain.n_segments:>5} {fit.chain.n_arcs:>5} {fit.chain.n_lines:>5} "
                  f"{greedy:>6} {fit.chain.n_segments / greedy:>6.2f} {fit.max_deviation_mm:>9.5f} "
                  f"{math.degrees(fit.chain.max_tangent_break()):>8.1e} {axis_err:>9} {seconds:>7.2f}")
            total = [total[0] + fit.chain.n_segments, total[1] + greedy, total[2] + seconds]
    print(f"  {'total':<17} {total[0]:>5} {'':>11} {total[1]:>6} {total[0] / max(total[1], 1):>6.2f} {'':>28} {total[2]:>7.2f}")
    rows = []
    for name in ("helix", "blade"):
        t1, _ = cpu(lambda: segment_space_curve(make_space_curve(FAMILIES[name](2000), name), 0.1))
        t2, _ = cpu(lambda: segment_space_curve(make_space_curve(FAMILIES[name](20000), name), 0.1))
        rows.append((f"segment_space_curve {name} σ 0.1", 2000, t1, 20000, t2))
    report("3-D fit against input points", rows)


if __name__ == "__main__":
    main()

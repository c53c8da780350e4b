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

Where the G1 chain has more pieces than the greedy's kinked arcs (at 1500 points: torus σ 0.1
and 0.5, blade and saddle σ 0.05, freeform and trefoil σ 0.5), one piece fewer was measured out
of the fit's reach: from every start (knots spread as the greedy's, evenly, every junction of a
chain that fits merged away) it stalls with the same miss on every piece, no curvature cap or
minimum length holding it (torus 8 pieces 0.125 mm at σ 0.1, 5 pieces 0.68 mm at σ 0.5; blade 10
pieces 0.053 mm; saddle 19 pieces 0.056 mm; freeform 6 pieces 0.527 mm; trefoil 14 pieces
0.5007 mm, 13 pieces 0.56 mm). A kinked chain turns its plane freely at every junction; the next
arc of a G1 chain must contain the tangent it arrives with, so a fast twist costs it pieces.

``--arc-planes``: instead, the section on ``arc_planes="principal"`` (every arc in a plane normal to
X, Y or Z): per curve (the families and three curves in principal planes: a pass around a cylinder
whose axis is X, a contour at z = 30, a stepped curve from z = const to x = const) and σ, segments,
arcs and corners with ``any`` and with ``principal``, the corners the option added, the certified
deviation and CPU seconds of each; then the exponent of the principal fit's CPU time.

    python scripts/bench_segment3d.py [--sigmas 0.05,0.1,0.5] [--points 1500] [--only helix,trefoil] [--axes]
    python scripts/bench_segment3d.py --arc-planes [--sigmas ...] [--points ...] [--only ...]
    python scripts/bench_segment3d.py --taught [--only ...]

``--taught``: instead, each family taught with 15, 30 and 60 of its own points at σ = 1 and 0.7 ×
the polygon's chordal deviation (coatsim.geometry.space.taught): segments against moves and
against the greedy fitter on the same vertices, corners, deviation, CPU seconds.
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


def cylinder_pass(n: int) -> np.ndarray:
    """Around a cylinder whose axis is X (radius 60 mm), three quarters of a turn at x = 20 (G19)."""
    t = np.linspace(0.0, 1.5 * math.pi, n)
    return np.column_stack((20 + 0 * t, 60 * np.cos(t), 60 * np.sin(t)))


def contour_z30(n: int) -> np.ndarray:
    """A closed lobed contour at z = 30 (G17)."""
    t = np.linspace(0, 2 * math.pi, n)
    r = 40 + 6 * np.cos(3 * t)
    return np.column_stack((r * np.cos(t), 0.7 * r * np.sin(t), 30 + 0 * t))


def stepped(n: int) -> np.ndarray:
    """A quarter circle at z = 30 running on along +Y, then turning up in the plane x = 0."""
    k = n // 3
    a, y, b = np.linspace(-math.pi / 2, 0, k), np.linspace(0, 30, k)[1:], np.linspace(0, math.pi / 2, n - 2 * k + 2)[1:]
    return np.vstack((np.column_stack((40 * np.cos(a) - 40, 40 * np.sin(a), 30 + 0 * a)),
                      np.column_stack((0 * y, y, 30 + 0 * y)),
                      np.column_stack((0 * b, 30 + 25 * np.sin(b), 55 - 25 * np.cos(b)))))


PRINCIPAL_CURVES = {"cyl-x": cylinder_pass, "z30": contour_z30, "stepped": stepped}


def arc_planes_section(families: dict, names: list[str], sigmas: list[float], n_points: int) -> None:
    """Segments, arcs and corners with arc_planes any and principal, the corners added, the
    certified deviation and CPU seconds of each."""
    print(f"# arc_planes: {n_points} points per curve; any -> principal")
    print(f"  {'curve':<10} {'σ mm':>6} {'segs':>9} {'arcs':>9} {'corners':>9} {'added':>5} {'dev mm':>17} "
          f"{'CPU s':>13}")
    total = [0, 0, 0, 0, 0.0, 0.0]
    for name in names:
        curve = make_space_curve(families[name](n_points), name)
        for tol in sigmas:
            t_any, fit_any = cpu(lambda: segment_space_curve(curve, tol))
            t_pr, fit_pr = cpu(lambda: segment_space_curve(curve, tol, arc_planes="principal"))
            a, p = fit_any.chain, fit_pr.chain
            added = len(set(p.corners)) - len(set(a.corners))
            print(f"  {name:<10} {tol:>6g} {a.n_segments:>4}>{p.n_segments:<4} {a.n_arcs:>4}>{p.n_arcs:<4} "
                  f"{len(a.corners):>4}>{len(p.corners):<4} {added:>5} {fit_any.max_deviation_mm:>8.5f}>"
                  f"{fit_pr.max_deviation_mm:<8.5f} {t_any:>6.2f}>{t_pr:<6.2f}")
            total = [total[0] + a.n_segments, total[1] + p.n_segments, total[2] + len(a.corners),
                     total[3] + len(p.corners), total[4] + t_any, total[5] + t_pr]
    print(f"  {'total':<17} {total[0]:>4}>{total[1]:<4} {'':>9} {total[2]:>4}>{total[3]:<4} {'':>23} "
          f"{total[4]:>6.2f}>{total[5]:<6.2f}")
    rows = []
    for name in ("helix", "stepped"):
        make = families[name]
        t1, _ = cpu(lambda: segment_space_curve(make_space_curve(make(2000), name), 0.1, arc_planes="principal"))
        t2, _ = cpu(lambda: segment_space_curve(make_space_curve(make(20000), name), 0.1, arc_planes="principal"))
        rows.append((f"segment_space_curve {name} σ 0.1 principal", 2000, t1, 20000, t2))
    report("principal-plane fit against input points", rows)


def taught_section(families: dict, names: list[str], vertices: tuple[int, ...] = (15, 30, 60)) -> None:
    """Each family taught with a few vertices (its own points at that count), σ a share of the
    polygon's chordal deviation (the densely sampled curve's largest distance from it): moves
    in, segments out against the greedy fitter's on the same vertices, corners, the certified
    deviation and CPU seconds."""
    from coatsim.geometry.space.nearest import polyline_index

    print("# taught (sparse) space polylines: σ = share × chordal deviation")
    print(f"  {'curve':<10} {'moves':>5} {'share':>5} {'σ mm':>7} {'segs':>5} {'segs/moves':>10} {'greedy':>6} "
          f"{'corners':>7} {'dev mm':>9} {'CPU s':>7}")
    total = [0, 0, 0.0]
    for name in names:
        dense = families[name](20000)
        for n in vertices:
            poly = families[name](n)
            sag = float(polyline_index(poly)[0].distance(dense)[0].max())
            for share in (1.0, 0.7):
                tol = share * sag
                closed = "yes" if np.array_equal(poly[0], poly[-1]) else "no"
                seconds, fit = cpu(lambda: segment_space_curve(make_space_curve(poly, name, closed), tol))
                moves = len(poly) - 1
                greedy = len(greedy_knots(poly, tol)) - 1
                print(f"  {name:<10} {moves:>5} {share:>5g} {tol:>7.3f} {fit.chain.n_segments:>5} "
                      f"{fit.chain.n_segments / moves:>10.2f} {greedy:>6} {len(fit.chain.corners):>7} "
                      f"{fit.max_deviation_mm:>9.4f} {seconds:>7.2f}")
                total = [total[0] + moves, total[1] + fit.chain.n_segments, total[2] + seconds]
    print(f"  moves {total[0]}, segments {total[1]} ({total[1] / max(total[0], 1):.2f}), CPU {total[2]:.1f} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sigmas", default=",".join(str(s) for s in TOLERANCES_MM))
    parser.add_argument("--points", type=int, default=1500)
    parser.add_argument("--only", default="", help="comma-separated family names (default: all)")
    parser.add_argument("--axes", action="store_true", help="also fit each curve with spray axes (orientation error)")
    parser.add_argument("--arc-planes", action="store_true", help="only the section on arc_planes='principal'")
    parser.add_argument("--taught", action="store_true", help="only the section on taught (sparse) polylines")
    args = parser.parse_args()
    sigmas = [float(s) for s in args.sigmas.split(",")]
    families = {**FAMILIES, **HELD_OUT}
    if args.arc_planes:
        families = {**PRINCIPAL_CURVES, **families}
    names = [n for n in families if not args.only or n in args.only.split(",")]
    if args.arc_planes:
        arc_planes_section(families, names, sigmas, args.points)
        return
    if args.taught:
        taught_section(families, names)
        return
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

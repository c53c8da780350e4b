"""Benchmark of the geometry stage: segment the five benchmark curves with the paper's method and
the default fitter, next to the reference counts (coatsim.geometry.benchmark: the curves are
generated from their formulas; ``--curves DIR`` reads NAME.csv files instead and exits non-zero
when one is missing).

For every curve and σ in SIGMAS, per method: segments (arcs, lines), the deviation reported
by segment_curve, an independent check of it by dense sampling of both curves (KD-tree,
step σ/20, within step/2 of the true value), the largest tangent break at a junction that is
not a listed corner, and the wall time. Then the time to segment 100 000-point curves at
σ = 0.05 mm. Prints only; never asserts.

    python scripts/bench_segment.py [--no-paper] [--sigmas 0.05,0.5] [--curves DIR]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from coatsim.errors import CoatsimError
from coatsim.geometry import load_curve, segment_curve
from coatsim.geometry.benchmark import NAMES, TOLERANCES_MM, bench_curve, reference_count

SIGMAS = TOLERANCES_MM
LARGE = ("builtin:paper-spiral:points=100000", "builtin:ellipse:points=100000")
LARGE_SIGMA = 0.05


def dense(points: np.ndarray, step: float) -> np.ndarray:
    out = [points[:1]]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, int(math.ceil(np.linalg.norm(b - a) / step)))
        out.append(a + np.linspace(0.0, 1.0, n + 1)[1:, None] * (b - a))
    return np.vstack(out)


def dense_poly(poly, step: float) -> np.ndarray:
    out = []
    for seg in poly.segments:
        n = max(1, int(math.ceil(seg.length / step)))
        s = np.linspace(0.0, seg.length, n + 1)
        if seg.kind == "arc":
            a0 = math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0])
            phi = a0 + math.copysign(1.0, seg.sweep) * s / seg.radius
            out.append(np.asarray(seg.center) + seg.radius * np.column_stack((np.cos(phi), np.sin(phi))))
        else:
            a, b = np.asarray(seg.start), np.asarray(seg.end)
            out.append(a + (s / max(seg.length, 1e-300))[:, None] * (b - a))
    return np.vstack(out)


def sampled_deviation(points: np.ndarray, poly, step: float) -> float:
    """Two-sided Hausdorff distance by dense sampling (independent of coatsim's check)."""
    a, b = dense(points, step), dense_poly(poly, step)
    return float(max(cKDTree(b).query(a)[0].max(), cKDTree(a).query(b)[0].max()))


def max_break_deg(poly) -> float:
    """Largest heading change at a junction that is not a listed corner (end tangents from
    the end points and centres, not from the stored headings)."""
    def tangent(seg, at_end: bool):
        if seg.kind == "arc":
            r = np.subtract(seg.end if at_end else seg.start, seg.center)
            t = np.array([-r[1], r[0]]) * math.copysign(1.0, seg.sweep)
        else:
            t = np.subtract(seg.end, seg.start)
        return t / np.linalg.norm(t)

    segs = poly.segments
    pairs = list(zip(segs[:-1], segs[1:])) + ([(segs[-1], segs[0])] if poly.closed else [])
    worst = 0.0
    for k, (a, b) in enumerate(pairs):
        if k in poly.corners:
            continue
        ta, tb = tangent(a, True), tangent(b, False)
        worst = max(worst, abs(math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb)))
    return math.degrees(worst)


def reference(kind: str, name: str, sigma: float) -> int | str:
    return (reference_count(kind, name, sigma) or "") if sigma in TOLERANCES_MM else ""


def row(name: str, sigma: float, method: str, curve) -> str:
    greedy, literal = reference("greedy", name, sigma), reference("paper", name, sigma)
    head = f"{name:10} {sigma:6g} {method:8}"
    tail = f"{greedy!s:>7} {literal!s:>7}"
    t0 = time.perf_counter()
    try:
        seg = segment_curve(curve, sigma, method=method)
    except CoatsimError as exc:
        return f"{head} failed after {time.perf_counter() - t0:.2f} s: {exc}"[:150] + f"  | refs {greedy} {literal}"
    seconds = time.perf_counter() - t0
    poly = seg.polysegment
    check = sampled_deviation(curve.points, poly, sigma / 20)
    flag = " !" if check > sigma * 1.025 else ""
    gap = "" if not curve.closed or poly.end == poly.start else " (open seam)"
    return (f"{head} {poly.n_segments:5d} {poly.n_arcs:5d} {poly.n_lines:5d} {seg.max_deviation_mm:10.5f} "
            f"{check:10.5f}{flag:2} {max_break_deg(poly):9.2e} {seconds:8.2f} {tail}{gap}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-paper", action="store_true", help="skip the paper's method")
    parser.add_argument("--sigmas", default=",".join(map(str, SIGMAS)), help="comma-separated tolerances, mm")
    parser.add_argument("--no-large", action="store_true", help="skip the 100 000-point timings")
    parser.add_argument("--curves", type=Path, help="read the benchmark curves from DIR/NAME.csv")
    args = parser.parse_args()
    sigmas = tuple(float(s) for s in args.sigmas.split(","))
    methods = ("optimal",) if args.no_paper else ("paper", "optimal")
    curves = {}
    for name in NAMES:
        if args.curves is None:
            curves[name] = bench_curve(name)
            continue
        path = args.curves / f"{name}.csv"
        if not path.is_file():
            sys.exit(f"bench_segment: benchmark curve {path} not found")
        curves[name] = load_curve(str(path))
    print(f"bench curves: {args.curves or 'generated from their formulas (coatsim.geometry.benchmark)'}")
    print("dev = reported by segment_curve; check = dense-sampling Hausdorff (step sigma/20; '!' above 1.025 sigma);")
    print("break = largest tangent break at a non-corner junction; refs = greedy free-arc / paper literally")
    print(f"{'curve':10} {'sigma':>6} {'method':8} {'segs':>5} {'arcs':>5} {'lines':>5} {'dev mm':>10} "
          f"{'check mm':>10}   {'break deg':>9} {'seconds':>8} {'greedy':>7} {'paper':>7}")
    for name, curve in curves.items():
        for sigma in sigmas:
            for method in methods:
                print(row(name, sigma, method, curve), flush=True)
    if args.no_large:
        return
    print(f"\nlarge inputs at sigma = {LARGE_SIGMA} mm (default method)")
    for spec in LARGE:
        curve = load_curve(spec)
        t0 = time.perf_counter()
        try:
            seg = segment_curve(curve, LARGE_SIGMA)
        except CoatsimError as exc:
            print(f"{spec}: failed after {time.perf_counter() - t0:.2f} s: {exc}")
            continue
        seconds = time.perf_counter() - t0
        poly = seg.polysegment
        print(f"{spec}: {len(curve.points)} points -> {poly.n_segments} segments ({poly.n_arcs} arcs), "
              f"deviation {seg.max_deviation_mm:.5f} mm, {seconds:.2f} s", flush=True)


if __name__ == "__main__":
    main()

"""Benchmark of the geometry stage: segment the five bench curves, the built-ins and curves the
fitter was not tuned on (scripts/heldout_curves.py), next to the reference counts
(coatsim.geometry.benchmark: the bench curves are generated from their formulas; ``--curves DIR``
reads NAME.csv files instead and exits non-zero when one is missing).

For every curve and σ, per method: segments (arcs, lines), the deviation reported by
segment_curve, an independent check of it by dense sampling of both curves (KD-tree, step σ/20,
within step/2 of the true value), the largest tangent break at a junction that is not a listed
corner, the tightest arc over the curve's tightest radius (``R ratio``: below 1 the fit turns
tighter than the curve anywhere does), the shortest segment, the largest curvature jump at a
tangent junction (1/mm) and the CPU seconds (``time.process_time``). Then the held-out curves fitted for 300 mm/s at
5 m/s² (tightest arc against v²/a = 18 mm, speed-limited stretches), the time to segment
100 000-point curves at σ = 0.05 mm, and the scaling exponent of the built-in curves, the exact
deviation check and the whole fit from 100 000 to 1 000 000 points (scripts/scaling.py). Prints
only; never asserts. The figures come from the polysegment alone, so the script also measures
older versions of the fitter (PYTHONPATH=<their checkout>).

    python scripts/bench_segment.py [--paper] [--sigmas 0.05,0.5] [--only bench,builtin,heldout,speed,large] [--curves DIR]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.errors import CoatsimError
from coatsim.geometry import load_curve, make_curve, segment_curve
from coatsim.geometry.benchmark import NAMES, TOLERANCES_MM, bench_curve, reference_count

from heldout_curves import CURVES, heldout_points, tightest_radius_mm

SIGMAS = TOLERANCES_MM
BUILTINS = ("paper-spiral", "ellipse", "ellipse:a=80,b=50", "naca", "cam", "epitrochoid", "sine", "clothoid",
            "rounded-rectangle", "polygon", "d-shape", "raster")
BUILTIN_SIGMAS = (0.05, 0.5)
HELDOUT_SIGMAS = (0.05, 0.1, 0.5)
SPEED_MM_S, TOOL_ACCEL_MM_S2, SPEED_SIGMA = 300.0, 5000.0, 0.1  # the speed table: v²/a = 18 mm
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


def _tangent(seg, at_end: bool) -> np.ndarray:
    if seg.kind == "arc":
        r = np.subtract(seg.end if at_end else seg.start, seg.center)
        t = np.array([-r[1], r[0]]) * math.copysign(1.0, seg.sweep)
    else:
        t = np.subtract(seg.end, seg.start)
    return t / np.linalg.norm(t)


def _pairs(poly) -> list[tuple[int, object, object]]:
    """(junction index, segment before, segment after) for every junction, seam last."""
    segs = poly.segments
    pairs = list(zip(segs[:-1], segs[1:])) + ([(segs[-1], segs[0])] if poly.closed else [])
    return [(k, a, b) for k, (a, b) in enumerate(pairs)]


def max_break_deg(poly) -> float:
    """Largest heading change at a junction that is not a listed corner (end tangents from
    the end points and centres, not from the stored headings)."""
    worst = 0.0
    for k, a, b in _pairs(poly):
        if k not in poly.corners:
            ta, tb = _tangent(a, True), _tangent(b, False)
            worst = max(worst, abs(math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb)))
    return math.degrees(worst)


def _curvature(seg) -> float:
    return math.copysign(1.0 / seg.radius, seg.sweep) if seg.kind == "arc" else 0.0


def max_curvature_jump(poly) -> float:
    """Largest |Δκ| (1/mm) at a junction that is not a listed corner."""
    jumps = [abs(_curvature(b) - _curvature(a)) for k, a, b in _pairs(poly) if k not in poly.corners]
    return max(jumps, default=0.0)


def min_radius(poly) -> float:
    return min((s.radius for s in poly.segments if s.kind == "arc"), default=math.inf)


def input_tightest_radius(points: np.ndarray, poly, spacing: float = 0.5) -> float:
    """Tightest radius of a noise-free input: circles through points ``spacing`` mm apart
    along it, away (3 spacings) from the polysegment's listed corners."""
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))))
    at = np.arange(spacing, s[-1] - spacing, spacing / 4)
    p = lambda u: np.column_stack((np.interp(u, s, points[:, 0]), np.interp(u, s, points[:, 1])))  # noqa: E731
    a, b, c = p(at - spacing), p(at), p(at + spacing)
    cross = (b - a)[:, 0] * (c - b)[:, 1] - (b - a)[:, 1] * (c - b)[:, 0]
    kappa = 2 * np.abs(cross) / (np.linalg.norm(b - a, axis=1) * np.linalg.norm(c - b, axis=1) * np.linalg.norm(c - a, axis=1))
    corners = np.array([poly.segments[k].end for k in poly.corners]).reshape(-1, 2)
    if len(corners):
        near = cKDTree(corners).query(b)[0] < 3 * spacing
        kappa = kappa[~near]
    top = float(kappa.max()) if len(kappa) else 0.0
    return 1.0 / top if top > 0 else math.inf


HEAD = (f"{'segs':>5} {'arcs':>5} {'lines':>5} {'dev mm':>9} {'check mm':>9}   {'break deg':>9} "
        f"{'R ratio':>7} {'short mm':>8} {'jump 1/mm':>9} {'seconds':>7}")


def measure(curve, sigma: float, method: str, tightest: float | None) -> str:
    t0 = time.process_time()
    try:
        seg = segment_curve(curve, sigma, method=method)
    except CoatsimError as exc:
        return f"failed after {time.process_time() - t0:.2f} s: {exc}"[:110]
    seconds = time.process_time() - t0
    poly = seg.polysegment
    check = sampled_deviation(curve.points, poly, sigma / 20)
    flag = " !" if check > sigma * 1.025 else ""
    tight = input_tightest_radius(curve.points, poly) if tightest is None else tightest
    ratio = min_radius(poly) / tight if math.isfinite(tight) else math.inf
    shortest = min(s.length for s in poly.segments)
    gap = "" if not curve.closed or poly.end == poly.start else " (open seam)"
    return (f"{poly.n_segments:5d} {poly.n_arcs:5d} {poly.n_lines:5d} {seg.max_deviation_mm:9.5f} "
            f"{check:9.5f}{flag:2} {max_break_deg(poly):9.2e} {ratio:7.3f} {shortest:8.3f} "
            f"{max_curvature_jump(poly):9.4f} {seconds:7.2f}{gap}")


def bench_curves(folder: Path | None) -> dict:
    """The five bench curves: generated, or read from ``folder``/NAME.csv (exit if one is missing)."""
    if folder is None:
        return {name: bench_curve(name) for name in NAMES}
    curves = {}
    for name in NAMES:
        path = folder / f"{name}.csv"
        if not path.is_file():
            sys.exit(f"bench_segment: benchmark curve {path} not found")
        curves[name] = load_curve(str(path))
    return curves


def bench_table(curves: dict, sigmas, methods) -> None:
    print("\nbench curves; refs = greedy free-arc / paper literally (coatsim.geometry.benchmark)")
    print(f"{'curve':10} {'sigma':>6} {'method':8} {HEAD} {'greedy':>6} {'paper':>6}")
    for name, curve in curves.items():
        for sigma in sigmas:
            for method in methods:
                greedy = reference_count("greedy", name, sigma) or ""
                literal = reference_count("paper", name, sigma) or ""
                print(f"{name:10} {sigma:6g} {method:8} {measure(curve, sigma, method, None)} {greedy!s:>6} {literal!s:>6}",
                      flush=True)


def builtin_table() -> None:
    print("\nbuilt-in curves (default method)")
    print(f"{'curve':22} {'sigma':>6} {HEAD}")
    for name in BUILTINS:
        curve = load_curve(f"builtin:{name}")
        for sigma in BUILTIN_SIGMAS:
            print(f"{name:22} {sigma:6g} {measure(curve, sigma, 'optimal', None)}", flush=True)


def heldout_table() -> None:
    print("\nheld-out curves, 4000 points (scripts/heldout_curves.py; R ratio against the formula's tightest radius)")
    print(f"{'curve':18} {'R min':>7} {'sigma':>6} {HEAD}")
    for name in CURVES:
        pts, closed = heldout_points(name)
        curve = make_curve(pts, name, "yes" if closed else "no")
        tight = tightest_radius_mm(name)
        for sigma in HELDOUT_SIGMAS:
            print(f"{name:18} {tight:7.2f} {sigma:6g} {measure(curve, sigma, 'optimal', tight)}", flush=True)


def speed_table() -> None:
    """Fits that know the speed: the tightest arc against v²/a and the input's tightest radius,
    the speed-limited stretches and the slowest speed on them."""
    limit = SPEED_MM_S**2 / TOOL_ACCEL_MM_S2
    print(f"\nat {SPEED_MM_S:g} mm/s and {TOOL_ACCEL_MM_S2 / 1000:g} m/s² (v²/a = {limit:g} mm), sigma = {SPEED_SIGMA} mm")
    print(f"{'curve':18} {'R min':>7} {'segs':>5} {'tightest arc':>12} {'limited':>7} {'slowest mm/s':>12} {'seconds':>7}")
    for name in CURVES:
        pts, closed = heldout_points(name)
        curve = make_curve(pts, name, "yes" if closed else "no")
        t0 = time.process_time()
        try:
            seg = segment_curve(curve, SPEED_SIGMA, speed_mm_s=SPEED_MM_S, tool_accel_mm_s2=TOOL_ACCEL_MM_S2)
        except TypeError:
            print("this version of segment_curve takes no speed")
            return
        except CoatsimError as exc:
            print(f"{name:18} failed: {exc}"[:110])
            continue
        poly = seg.polysegment
        slowest = min((v for _, _, v in poly.speed_limited), default=math.nan)
        print(f"{name:18} {tightest_radius_mm(name):7.2f} {poly.n_segments:5d} {min_radius(poly):12.2f} "
              f"{len(poly.speed_limited):7d} {slowest:12.1f} {time.process_time() - t0:7.2f}", flush=True)


def large_table() -> None:
    print(f"\nlarge inputs at sigma = {LARGE_SIGMA} mm (default method)")
    for spec in LARGE:
        curve = load_curve(spec)
        t0 = time.process_time()
        try:
            seg = segment_curve(curve, LARGE_SIGMA)
        except CoatsimError as exc:
            print(f"{spec}: failed after {time.process_time() - t0:.2f} s: {exc}")
            continue
        seconds = time.process_time() - t0
        poly = seg.polysegment
        print(f"{spec}: {len(curve.points)} points -> {poly.n_segments} segments ({poly.n_arcs} arcs), "
              f"deviation {seg.max_deviation_mm:.5f} mm, shortest {min(s.length for s in poly.segments):.3f} mm, "
              f"{seconds:.2f} s", flush=True)
    import scaling  # scripts/scaling.py: the exponent of every geometry stage

    scaling.segment()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paper", action="store_true", help="also the paper's method on the bench curves")
    parser.add_argument("--sigmas", default=",".join(map(str, SIGMAS)), help="bench-curve tolerances, mm")
    parser.add_argument("--only", default="bench,builtin,heldout,speed,large", help="tables to print")
    parser.add_argument("--curves", type=Path, help="read the bench curves from DIR/NAME.csv")
    args = parser.parse_args()
    tables = set(args.only.split(","))
    print("dev = reported by segment_curve; check = dense-sampling Hausdorff (step sigma/20; '!' above 1.025 sigma);")
    print("break = largest tangent break at a non-corner junction; R ratio = tightest arc / tightest radius of the "
          "input; short = shortest segment; jump = largest curvature change at a tangent junction")
    if "bench" in tables:
        bench_table(bench_curves(args.curves), tuple(float(s) for s in args.sigmas.split(",")), ("paper", "optimal") if args.paper else ("optimal",))
    if "builtin" in tables:
        builtin_table()
    if "heldout" in tables:
        heldout_table()
    if "speed" in tables:
        speed_table()
    if "large" in tables:
        large_table()


if __name__ == "__main__":
    main()

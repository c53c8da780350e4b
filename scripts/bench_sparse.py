"""Benchmark of the fitter on taught (sparse) polylines and on the curvature cap of open curves.

1. The field figures: a 36-gon of r 50 mm, an ellipse 100 x 50 mm taught with 31 points, the
   paper's spiral simplified to 69 points, a sine taught with 50 moves (σ 0.1 mm).
2. Taught polygons of smooth curves the fitter was not tuned on (circle, ellipses,
   superellipse, limaçon, spirals, clothoid, open Lissajous, harmonics): vertices evenly
   spaced along the curve, σ a share of the polygon's own chordal deviation (the largest
   sagitta of an edge against the curve), clean and with hand-like jitter of the vertices.
3. Open 3:2 Lissajous figures with a phase offset (4 000 points, evenly spaced along their
   length), where the tightest arc must not be tighter than the curve.

Per row: points in, segments out (arcs, lines), the deviation reported, the tightest arc over
the polygon's own tightest turning (the circle through three consecutive vertices; for dense
curves the formula's tightest radius), CPU seconds (``time.process_time``). Prints only;
the figures come from the polysegment alone, so ``PYTHONPATH=<another checkout>`` measures
another version of the fitter.

    python scripts/bench_sparse.py [--only field,taught,lissajous] [--vertices 12,24,48]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from coatsim.core.errors import CoatsimError
from coatsim.geometry import make_curve, segment_curve
from coatsim.geometry.builtin_curves import paper_spiral
from coatsim.geometry.rdp import rdp_indices

TAU = 2 * math.pi


def _polar(r):
    return lambda t: np.column_stack((r(t) * np.cos(t), r(t) * np.sin(t)))


def _superellipse(a: float, b: float, n: float):
    def f(t):
        c, s = np.cos(t), np.sin(t)
        return np.column_stack((a * np.sign(c) * np.abs(c) ** (2 / n), b * np.sign(s) * np.abs(s) ** (2 / n)))
    return f


def _clothoid(t):
    """Euler spiral of scale 60 mm, by cumulative trapezoids of cos/sin(t²)."""
    dt = np.diff(t, prepend=t[0])
    c, s = np.cos(t ** 2), np.sin(t ** 2)
    x = np.cumsum((c + np.roll(c, 1)) / 2 * dt)
    y = np.cumsum((s + np.roll(s, 1)) / 2 * dt)
    return 60 * np.column_stack((x - x[0], y - y[0]))


def lissajous(a: float, b: float, phase: float):
    return lambda t: np.column_stack((a * np.sin(3 * t + phase), b * np.sin(2 * t)))


# name -> (function of t, t0, t1, closed)
FAMILIES = {
    "circle-50": (_polar(lambda t: 50 + 0 * t), 0.0, TAU, True),
    "ellipse-100x50": (lambda t: np.column_stack((100 * np.cos(t), 50 * np.sin(t))), 0.0, TAU, True),
    "ellipse-70x60": (lambda t: np.column_stack((70 * np.cos(t), 60 * np.sin(t))), 0.0, TAU, True),
    "superellipse-3": (_superellipse(80.0, 50.0, 3.0), 0.0, TAU, True),
    "limacon": (_polar(lambda t: 50 + 20 * np.cos(t)), 0.0, TAU, True),
    "archimedes": (_polar(lambda t: 10 + 6 * t), 0.0, 5 * math.pi, False),
    "log-spiral": (_polar(lambda t: 12 * np.exp(0.12 * t)), 0.0, 5 * math.pi, False),
    "clothoid": (_clothoid, 0.2, 1.9, False),
    "lissajous-open": (lissajous(200.0, 150.0, 1.47), 0.0, 0.9 * TAU, False),
    "harmonics": (_polar(lambda t: 60 + 6 * np.cos(3 * t) + 4 * np.sin(5 * t + 0.3)), 0.0, TAU, True),
}
VERTICES = (12, 24, 48)  # --vertices 8,15,30,60,120,200 for the long table (about 15 CPU minutes)
SIGMA_SHARES = (1.0, 0.7)  # σ as a share of the polygon's chordal deviation
JITTER = 0.2  # hand-like jitter: std of the vertices' offset, as a share of σ
LISSAJOUS = ((200.0, 150.0, 1.47, 0.9), (120.0, 120.0, 0.1, 0.85), (150.0, 100.0, 1.5, 0.95),
             (100.0, 100.0, 1.65, 0.8), (180.0, 120.0, 0.2, 0.9))  # (a, b, phase, share of the period)


def dense(f, t0: float, t1: float, n: int = 40_001) -> tuple[np.ndarray, np.ndarray]:
    """Points of the formula and their arc length."""
    p = f(np.linspace(t0, t1, n))
    return p, np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))


def along(p: np.ndarray, s: np.ndarray, at: np.ndarray) -> np.ndarray:
    return np.column_stack((np.interp(at, s, p[:, 0]), np.interp(at, s, p[:, 1])))


def taught(name: str, vertices: int) -> tuple[np.ndarray, bool, float]:
    """The polygon of ``vertices`` points evenly along the curve (a closed one repeats its
    first), whether it is closed, and its chordal deviation (mm)."""
    f, t0, t1, closed = FAMILIES[name]
    p, s = dense(f, t0, t1)
    knots = np.linspace(0.0, s[-1], vertices + 1 if closed else vertices)
    poly = along(p, s, knots)
    if closed:
        poly[-1] = poly[0]
    sag = 0.0
    for a, b, lo, hi in zip(poly[:-1], poly[1:], knots[:-1], knots[1:]):
        inner = p[(s >= lo) & (s <= hi)]
        d = b - a
        sag = max(sag, float(np.abs((inner - a) @ np.array([-d[1], d[0]]) / np.linalg.norm(d)).max(initial=0.0)))
    return poly, closed, sag


def own_radius(points: np.ndarray, closed: bool) -> float:
    """The tightest circle through three consecutive vertices (mm)."""
    pts = points[:-1] if closed else points
    a, b, c = (np.roll(pts, 1, axis=0), pts, np.roll(pts, -1, axis=0)) if closed else (pts[:-2], pts[1:-1], pts[2:])
    ab, bc, ca = (np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1), np.linalg.norm(a - c, axis=1))
    cross = np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    with np.errstate(divide="ignore"):
        return float((ab * bc * ca / (2 * cross)).min())


def measure(points: np.ndarray, closed: bool, tol: float, radius_mm: float) -> dict:
    curve = make_curve(points, "bench", "yes" if closed else "no")
    started = time.process_time()
    try:
        seg = segment_curve(curve, tol)
    except CoatsimError as exc:
        return {"error": str(exc)[:60], "cpu": time.process_time() - started}
    cpu = time.process_time() - started
    poly = seg.polysegment
    radii = [s.radius for s in poly.segments if hasattr(s, "radius")]
    return {"segments": poly.n_segments, "arcs": poly.n_arcs, "lines": poly.n_lines, "dev": seg.max_deviation_mm,
            "ratio": min(radii) / radius_mm if radii else math.inf, "cpu": cpu,
            "notes": len(getattr(seg, "notes", ()))}


def row(label: str, n_in: int, tol: float, m: dict) -> str:
    if "error" in m:
        return f"{label:<30} {n_in:>5} {tol:>7.3f}  refused: {m['error']}  ({m['cpu']:.2f} s)"
    return (f"{label:<30} {n_in:>5} {tol:>7.3f} {m['segments']:>5} {m['arcs']:>4} {m['lines']:>5} "
            f"{m['dev']:>8.4f} {m['ratio']:>7.2f} {m['notes']:>5} {m['cpu']:>7.2f}")


HEADER = f"{'curve':<30} {'in':>5} {'σ mm':>7} {'segs':>5} {'arcs':>4} {'lines':>5} {'dev mm':>8} {'R ratio':>7} {'notes':>5} {'cpu s':>7}"


def field() -> None:
    print("\n# the field figures (σ 0.1 mm)\n" + HEADER)
    tol = 0.1
    t = np.linspace(0.0, TAU, 37)
    gon = np.column_stack((50 * np.cos(t), 50 * np.sin(t)))
    gon[-1] = gon[0]
    t = np.linspace(0.0, TAU, 31)
    ell = np.column_stack((100 * np.cos(t), 50 * np.sin(t)))
    ell[-1] = ell[0]
    spiral = paper_spiral()
    spiral = spiral[rdp_indices(spiral, _spiral_eps(spiral, 69))]
    x = np.linspace(0.0, 200.0, 50)
    sine = np.column_stack((x, 20 * np.sin(TAU * x / 100)))
    for label, pts, closed in (("36-gon r 50", gon, True), ("ellipse 100x50, 31 points", ell, True),
                               ("spiral, 69 points", spiral, False), ("sine, 50 moves", sine, False)):
        print(row(label, len(pts), tol, measure(pts, closed, tol, own_radius(pts, closed))), flush=True)


def _spiral_eps(points: np.ndarray, count: int) -> float:
    """The RDP tolerance that keeps ``count`` points (bisection)."""
    lo, hi = 1e-4, 50.0
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if len(rdp_indices(points, mid)) > count else (lo, mid)
    return hi


def taught_polygons(vertices: tuple[int, ...], seed: int = 0) -> None:
    print("\n# taught polygons (σ = share × chordal deviation; jitter: σ·0.2 std)\n" + HEADER)
    rng = np.random.default_rng(seed)
    totals = {"in": 0, "out": 0, "worst_share": 0.0, "worst_ratio": math.inf, "cpu": 0.0, "refused": 0}
    for name in FAMILIES:
        for n in vertices:
            poly, closed, sag = taught(name, n)
            if sag < 0.02 or sag > 10.0:
                continue
            for share in SIGMA_SHARES:
                tol = share * sag
                for jitter in (False, True):
                    pts = poly.copy()
                    if jitter:
                        pts[:-1] += rng.normal(0.0, JITTER * tol, (len(pts) - 1, 2))
                        if closed:
                            pts[-1] = pts[0]
                    m = measure(pts, closed, tol, own_radius(pts, closed))
                    label = f"{name} n{n} s{share:g}{' j' if jitter else ''}"
                    print(row(label, len(pts), tol, m), flush=True)
                    totals["cpu"] += m["cpu"]
                    if "error" in m:
                        totals["refused"] += 1
                        continue
                    totals["in"] += len(pts) - 1
                    totals["out"] += m["segments"]
                    totals["worst_share"] = max(totals["worst_share"], m["segments"] / (len(pts) - 1))
                    totals["worst_ratio"] = min(totals["worst_ratio"], m["ratio"])
    print(f"moves in {totals['in']}, segments out {totals['out']} ({totals['out'] / max(totals['in'], 1):.2f}), "
          f"worst segments/moves {totals['worst_share']:.2f}, worst R ratio {totals['worst_ratio']:.2f}, "
          f"refused {totals['refused']}, CPU {totals['cpu']:.1f} s")


def lissajous_open() -> None:
    print("\n# open 3:2 Lissajous figures, 4000 points (R ratio against the formula's tightest radius)\n" + HEADER)
    for a, b, phase, stop in LISSAJOUS:
        f = lissajous(a, b, phase)
        p, s = dense(f, 0.0, stop * TAU, 400_001)
        pts = along(p, s, np.linspace(0.0, s[-1], 4000))
        t = np.linspace(0.0, stop * TAU, 400_001)
        d1 = np.gradient(f(t), t, axis=0)
        d2 = np.gradient(d1, t, axis=0)
        kappa = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
        radius = float(1.0 / kappa[2:-2].max())
        for tol in (0.05, 0.1):
            label = f"{a:g}x{b:g} φ{phase:.2f} {stop:g} R{radius:.1f}"
            print(row(label, len(pts), tol, measure(pts, False, tol, radius)), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="field,taught,lissajous")
    parser.add_argument("--vertices", default=",".join(map(str, VERTICES)), help="vertices of the taught polygons")
    args = parser.parse_args()
    only = args.only.split(",")
    if "field" in only:
        field()
    if "taught" in only:
        taught_polygons(tuple(int(v) for v in args.vertices.split(",")))
    if "lissajous" in only:
        lissajous_open()


if __name__ == "__main__":
    main()

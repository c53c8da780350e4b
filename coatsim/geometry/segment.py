"""segment_curve: a curve and a tolerance in, a verified polysegment out."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np

from coatsim.errors import InputError
from coatsim.geometry.corners import detect_corners
from coatsim.geometry.curves import Curve
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fit import fit_run
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.theta import ThetaFunction, paper_polysegment, theta_of_polyline

Method = Literal["optimal", "paper"]
METHODS = ("optimal", "paper")


@dataclass(frozen=True, eq=False)
class Segmentation:
    """A fitted polysegment with its verified deviation and provenance; ``seconds`` is the
    fitter's wall time (reported on request, never written to a file: outputs depend on the
    inputs alone)."""

    curve: Curve
    polysegment: Polysegment
    method: str
    tolerance_mm: float
    max_deviation_mm: float
    seconds: float
    theta: ThetaFunction
    theta_approx: ThetaFunction | None = None
    theta_tolerance: float | None = None

    def summary(self) -> str:
        """One screen of text: counts, verified deviation, tangency."""
        st = self.stats()
        lines = [
            f"{self.curve.name}: {st['input_points']} points, length {self.curve.length:.3f} mm, "
            f"{'closed' if self.curve.closed else 'open'}",
            f"method {self.method}, tolerance {self.tolerance_mm:g} mm"
            + (f", θ tolerance {self.theta_tolerance:.4g}" if self.theta_tolerance is not None else ""),
            f"segments {st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines), "
            f"corners {len(self.polysegment.corners)}",
            f"max deviation {st['max_deviation_mm']:.6f} mm (exact two-sided Hausdorff), "
            f"max tangent break {st['max_tangent_break_deg']:.3g} deg",
        ]
        return "\n".join(lines)

    def stats(self) -> dict:
        poly = self.polysegment
        return {
            "n_segments": poly.n_segments,
            "n_arcs": poly.n_arcs,
            "n_lines": poly.n_lines,
            "max_deviation_mm": self.max_deviation_mm,
            "max_tangent_break_deg": math.degrees(poly.max_tangent_break()),
            "input_points": len(self.curve.points),
        }


def _runs(points: np.ndarray, corners: np.ndarray, closed: bool) -> tuple[np.ndarray, list[np.ndarray]]:
    """Split at corners. Returns (points rotated so a closed curve starts at its first corner,
    list of runs each sharing its end point with the next run's start)."""
    if closed and len(corners):
        first = int(corners[0])
        body = points[:-1]
        points = np.vstack((body[first:], body[:first], body[first:first + 1]))
        corners = (corners - first) % len(body)
        cuts = [0, *sorted(int(c) for c in corners if c != 0), len(points) - 1]
    else:
        cuts = [0, *(int(c) for c in corners), len(points) - 1]
    return points, [points[a : b + 1] for a, b in zip(cuts[:-1], cuts[1:])]


def _corner_junctions(counts: list[int], closed: bool, has_corners: bool) -> tuple[int, ...]:
    """Junction indices (end of segment k) that sit on corners: the ends of all runs but the
    last, and the seam of a closed curve that starts at a corner."""
    ends = np.cumsum(counts) - 1
    junctions = [int(k) for k in ends[:-1]]
    if closed and has_corners:
        junctions.append(int(ends[-1]))
    return tuple(junctions)


def segment_curve(
    curve: Curve,
    tol: float,
    method: Method = "optimal",
    corner_deg: float = 20.0,
    theta_tolerance: float | None = None,
) -> Segmentation:
    """Approximate ``curve`` by a G1 chain of arcs and lines within ``tol`` mm.

    ``optimal`` guarantees the two-sided Hausdorff distance <= tol (verified exactly), keeps
    every junction tangent-continuous except at detected true corners, and uses few segments.
    ``paper`` is the paper's literal method: RDP on θ with ``theta_tolerance`` if given,
    otherwise the largest θ tolerance (by bisection) whose result stays within ``tol``.
    """
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise InputError(f"--tol: the tolerance must be a positive number of mm, got {tol}")
    if method not in METHODS:
        raise InputError(f"--method: unknown method {method!r}; choose one of {', '.join(METHODS)}")
    if not (math.isfinite(corner_deg) and 0 < corner_deg < 180):
        raise InputError(f"--corner-deg: must be between 0 and 180 degrees, got {corner_deg}")
    started = time.perf_counter()
    pts = curve.points
    theta = theta_of_polyline(pts)
    if method == "paper":
        poly, approx, eps = _paper(curve, tol, theta_tolerance)
        dev = hausdorff(pts, poly).hausdorff
        return Segmentation(curve, poly, method, tol, dev, time.perf_counter() - started, theta, approx, eps)
    corners = detect_corners(pts, curve.closed, corner_deg, tol)
    rotated, runs = _runs(pts, corners, curve.closed)
    closed_loop = curve.closed and len(corners) == 0
    fitted = [fit_run(run, tol, closed_loop) for run in runs]
    pieces = [segs for segs, _ in fitted]
    segments = tuple(seg for piece in pieces for seg in piece)
    poly = Polysegment(segments, closed=curve.closed, corners=_corner_junctions([len(p) for p in pieces], curve.closed, len(corners) > 0))
    dev = fitted[0][1] if len(fitted) == 1 else hausdorff(rotated, poly).hausdorff
    return Segmentation(curve, poly, method, tol, dev, time.perf_counter() - started, theta)


def _paper(curve: Curve, tol: float, theta_tolerance: float | None) -> tuple[Polysegment, ThetaFunction, float]:
    pts = curve.points
    if theta_tolerance is not None:
        if not theta_tolerance > 0:
            raise InputError(f"--theta-tol: must be positive, got {theta_tolerance}")
        poly, _, approx = paper_polysegment(pts, theta_tolerance, curve.closed)
        return poly, approx, theta_tolerance

    def attempt(eps: float):
        poly, _, approx = paper_polysegment(pts, eps, curve.closed)
        return hausdorff(pts, poly).hausdorff <= tol, poly, approx

    # Shrink the θ tolerance until the deviation holds, then bisect between the last
    # failing and the first passing value (the deviation is not monotone in it).
    eps, fail = 1.0, None
    ok, poly, approx = attempt(eps)
    while not ok and eps > 1e-9:
        fail, eps = eps, eps / 2
        ok, poly, approx = attempt(eps)
    if not ok:
        raise InputError(f"{curve.name}: the paper method cannot reach {tol} mm")
    best = (poly, approx, eps)
    lo, hi = eps, fail
    for _ in range(12 if hi is not None else 0):
        mid = math.sqrt(lo * hi)
        ok, poly, approx = attempt(mid)
        if ok:
            lo = mid
            if poly.n_segments <= best[0].n_segments:
                best = (poly, approx, mid)
        else:
            hi = mid
    return best

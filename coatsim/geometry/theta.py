"""The angular characteristic function θ of a polyline and the paper's literal method.

Section IV of the paper: θ is the cumulative signed turning angle against arc length
normalised to [0, 1]; a polysegment has a piecewise-linear θ, so simplifying θ with RDP and
rebuilding the curve from the simplified θ (eq. 16) yields a polysegment, which a similarity
transform then maps onto the input's end points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.geometry.rdp import rdp_indices


@dataclass(frozen=True, eq=False)
class ThetaFunction:
    """θ sampled at knots ``t`` (n,) in [0, 1] with values ``theta`` (n,) radians.

    ``length`` is the curve length L (mm) and ``start_heading`` the absolute heading (rad)
    that θ = 0 stands for.
    """

    t: np.ndarray
    theta: np.ndarray
    length: float
    start_heading: float


def edge_headings(points: np.ndarray) -> np.ndarray:
    """Unwrapped heading (rad) of every edge of a polyline, shape (n - 1,)."""
    d = np.diff(points, axis=0)
    return np.unwrap(np.arctan2(d[:, 1], d[:, 0]))


def theta_of_polyline(points: np.ndarray) -> ThetaFunction:
    """Sampled θ of a polyline: θ_k (turning accumulated up to edge k) at the middle of edge k,
    plus the end knots θ(0) = 0 and θ(1) = θ of the last edge."""
    pts = np.asarray(points, dtype=float)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate(([0.0], np.cumsum(seg)))
    length = float(s[-1])
    heading = edge_headings(pts)
    theta = heading - heading[0]
    mid = (s[:-1] + s[1:]) / 2 / length
    t = np.concatenate(([0.0], mid, [1.0]))
    values = np.concatenate(([0.0], theta, [theta[-1]]))
    return ThetaFunction(t, values, length, float(heading[0]))


def simplify_theta(theta: ThetaFunction, tolerance: float) -> ThetaFunction:
    """RDP on the (t, θ) graph with ``tolerance`` (distance in that plane)."""
    keep = rdp_indices(np.column_stack((theta.t, theta.theta)), tolerance)
    return ThetaFunction(theta.t[keep], theta.theta[keep], theta.length, theta.start_heading)


def rebuild_unit(theta: ThetaFunction) -> Polysegment:
    """Unit-length polysegment whose θ is the piecewise-linear ``theta`` (paper eq. 16):
    each θ piece of slope Δφ/Δt is an arc of curvature Δφ/Δt and length Δt (a line if Δφ = 0),
    starting at the origin with heading 0."""
    dt = np.diff(theta.t)
    dphi = np.diff(theta.theta)
    good = dt > 0
    return Polysegment(chain((0.0, 0.0), 0.0, dphi[good] / dt[good], dt[good]))


def similarity_onto(poly: Polysegment, start: np.ndarray, end: np.ndarray | None,
                    length: float, heading: float) -> Polysegment:
    """Map ``poly`` (starting at the origin with heading 0) onto the curve.

    Open curves: the similarity that sends the chain's end points onto ``start`` and ``end``.
    Closed curves (``end`` None, or start == end): scale by ``length`` and rotate by the
    curve's start ``heading``, since end points give no scale or direction there.
    """
    chord = np.asarray(poly.end, dtype=float)
    if end is not None and np.linalg.norm(end - start) > 0 and np.linalg.norm(chord) > 0:
        target = np.asarray(end, float) - np.asarray(start, float)
        scale = float(np.linalg.norm(target) / np.linalg.norm(chord))
        angle = math.atan2(target[1], target[0]) - math.atan2(chord[1], chord[0])
    else:
        scale, angle = length, heading
    c, s = math.cos(angle), math.sin(angle)
    return poly.transformed(np.array([[c, -s], [s, c]]), start, scale)


def paper_polysegment(points: np.ndarray, theta_tolerance: float, closed: bool) -> tuple[Polysegment, ThetaFunction, ThetaFunction]:
    """The paper's method with a fixed RDP tolerance on θ.

    Returns (polysegment, θ of the input, simplified θ).
    """
    pts = np.asarray(points, dtype=float)
    theta = theta_of_polyline(pts)
    approx = simplify_theta(theta, theta_tolerance)
    unit = rebuild_unit(approx)
    poly = similarity_onto(unit, pts[0], None if closed else pts[-1], theta.length, theta.start_heading)
    if not closed:
        return Polysegment(poly.segments), theta, approx
    segments, corners = _closed_up(poly.segments)
    return Polysegment(segments, closed=True, corners=corners), theta, approx


def _closed_up(segments: tuple) -> tuple[tuple, tuple[int, ...]]:
    """Close a loop the paper's rebuild leaves slightly open (the paper has no step for this;
    a closed polysegment must end on its start). Least-norm Newton steps on the last
    segments first try to close it with the start tangent, then with the position only (the
    seam becomes a listed corner); if neither converges, a closing line is appended and both
    of its junctions are corners."""
    from coatsim.geometry.primitives import Line, snap_end
    from coatsim.geometry.refine import ChainParams, close_exactly

    kappa = np.array([s.curvature for s in segments])
    length = np.array([s.length for s in segments])
    start = np.asarray(segments[0].start, dtype=float)
    params = ChainParams(segments[0].start_heading, kappa, length)
    n = len(segments)
    for turn in (2 * math.pi * round(float(np.sum(kappa * length)) / (2 * math.pi)), None):
        closed = close_exactly(start, params, start, turn)
        chained = chain(segments[0].start, closed.heading, closed.kappa, closed.length)
        if math.dist(chained[-1].end, segments[0].start) <= 1e-9 * float(length.sum()):
            return snap_end(chained, segments[0].start), (() if turn is not None else (n - 1,))
    closing = Line(segments[-1].end, segments[0].start)
    return tuple(segments) + (closing,), (n - 1, n)

def theta_of_polysegment(poly: Polysegment) -> ThetaFunction:
    """θ of a polysegment: linear on every segment, with a knot at every junction and a jump
    at every corner (two knots at the same t there)."""
    t, theta = [0.0], [0.0]
    s, angle = 0.0, 0.0
    total = poly.length
    for k, seg in enumerate(poly.segments):
        if k > 0:
            jump = math.remainder(seg.start_heading - poly.segments[k - 1].end_heading, 2 * math.pi)
            if jump != 0.0:
                angle += jump
                t.append(s / total)
                theta.append(angle)
        s += seg.length
        angle += seg.end_heading - seg.start_heading
        t.append(s / total)
        theta.append(angle)
    return ThetaFunction(np.array(t), np.array(theta), total, poly.segments[0].start_heading)


def paper_within(pts: np.ndarray, closed: bool, name: str, tol: float,
                 theta_tolerance: float | None) -> tuple[Polysegment, ThetaFunction, float]:
    """The paper's method within ``tol`` (mm) of the points: its θ tolerance shrunk until the
    deviation holds, then bisected towards the fewest segments (or ``theta_tolerance`` as given)."""
    if theta_tolerance is not None:
        if not theta_tolerance > 0:
            raise InputError(f"theta_tolerance: must be positive, got {theta_tolerance}", parameters=("theta_tolerance",))
        poly, _, approx = paper_polysegment(pts, theta_tolerance, closed)
        return poly, approx, theta_tolerance

    def attempt(eps: float):
        poly, _, approx = paper_polysegment(pts, eps, closed)
        return hausdorff(pts, poly).hausdorff <= tol, poly, approx

    # Shrink the θ tolerance until the deviation holds, then bisect between the last
    # failing and the first passing value (the deviation is not monotone in it).
    eps, fail = 1.0, None
    ok, poly, approx = attempt(eps)
    while not ok and eps > 1e-9:
        fail, eps = eps, eps / 2
        ok, poly, approx = attempt(eps)
    if not ok:
        raise InputError(f"{name}: the paper method cannot reach {tol} mm")
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

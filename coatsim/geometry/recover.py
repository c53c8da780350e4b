"""Recovery of curves that are exactly chains of lines and arcs (up to round-off).

A rounded rectangle, a slot or a raster sampled from exact primitives should come back as
exactly those primitives, at any tolerance, rather than as a fitted approximation. We cut
the run where the discrete curvature jumps, fit a line or a circle to every stretch, and
accept the result only if every stretch fits to round-off, neighbours are tangent, and the
chain they form covers the whole run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from coatsim.geometry.polysegment import chain
from coatsim.geometry.primitives import Segment, snap_end

KAPPA_JUMP = 1e-3  # curvature change x run length that ends a stretch
DISTINCT = 10.0  # neighbouring primitives differ in curvature by this many KAPPA_JUMP at least
MIN_VERTICES = 4
MAX_PRIMITIVES = 200


def _curvature(points: np.ndarray) -> np.ndarray:
    d = np.diff(points, axis=0)
    ell = np.linalg.norm(d, axis=1)
    h = np.arctan2(d[:, 1], d[:, 0])
    turn = np.remainder(np.diff(h) + math.pi, 2 * math.pi) - math.pi
    return 2 * turn / (ell[:-1] + ell[1:])


def _stretches(kappa: np.ndarray, length: float) -> list[tuple[int, int]]:
    """Maximal runs of interior vertices (indices into points) with constant curvature; a
    run ends at the first curvature that differs from the run's first by the jump. The end
    is searched in windows that double (a long run costs one vectorised pass), and the search
    stops once there are more runs than a chain may have primitives."""
    out, first, n = [], 0, len(kappa)
    while first < n:
        end, lo, window = n, first + 1, 64
        while lo < n:
            hi = min(n, lo + window)
            hit = np.flatnonzero(np.abs(kappa[lo:hi] - kappa[first]) * length > KAPPA_JUMP)
            if len(hit):
                end = lo + int(hit[0])
                break
            lo, window = hi, 2 * window
        if end - first >= MIN_VERTICES:
            out.append((first + 1, end))  # vertex indices: kappa[j] belongs to vertex j + 1
            if len(out) > MAX_PRIMITIVES:
                break
        first = end
    return out


@dataclass(frozen=True, eq=False)
class _Prim:
    """A fitted line (kappa 0: ``ref`` a point on it, ``direction`` along the input) or
    circle (``ref`` its centre, signed ``kappa``)."""

    kappa: float
    ref: np.ndarray
    direction: np.ndarray


def _fit(points: np.ndarray, mean_kappa: float, length: float) -> tuple[_Prim, float]:
    """Line or circle through ``points`` and its max residual."""
    if abs(mean_kappa) * length < KAPPA_JUMP:
        c = points.mean(axis=0)
        _, _, vt = np.linalg.svd(points - c)
        u = vt[0] if vt[0] @ (points[-1] - points[0]) > 0 else -vt[0]
        return _Prim(0.0, c, u), float(np.abs((points - c) @ vt[1]).max())
    a = np.column_stack((2 * points, np.ones(len(points))))
    sol = np.linalg.lstsq(a, (points**2).sum(axis=1), rcond=None)[0]
    center = sol[:2]
    radius = math.sqrt(sol[2] + center @ center)
    res = np.abs(np.linalg.norm(points - center, axis=1) - radius)
    return _Prim(math.copysign(1.0 / radius, mean_kappa), center, np.zeros(2)), float(res.max())


def recover_exact(points: np.ndarray, closed_loop: bool, tolerance: float) -> tuple[Segment, ...] | None:
    """The exact line/arc chain through ``points`` if there is one, else None.

    Open runs start at the first and end at the last point; a closed loop starts at the
    junction before its first stretch, so its seam is a tangent junction.
    """
    pts = np.asarray(points, dtype=float)
    if len(pts) < MIN_VERTICES + 2:
        return None
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    slack = min(tolerance / 20, 1e-6 * length)
    kappa = _curvature(pts)
    stretches = _stretches(kappa, length)
    if not stretches or len(stretches) > MAX_PRIMITIVES:
        return None  # a smooth free-form curve: many tiny stretches, not a few primitives
    prims = []
    for a, b in stretches:
        prim, res = _fit(pts[a - 1 : b + 2], float(kappa[a - 1 : b].mean()), length)
        if res > slack:
            return None
        prims.append(prim)
    if closed_loop and len(prims) > 1 and _same(prims[0], prims[-1], slack, length):
        prims = prims[:-1]
    if not prims or (closed_loop and len(prims) < 2):
        return None
    pairs = zip(prims, prims[1:] + (prims[:1] if closed_loop else []))
    if any(abs(p.kappa - q.kappa) * length <= DISTINCT * KAPPA_JUMP for p, q in pairs):
        return None  # neighbours barely differ: a smooth curve cut into near-circles, not primitives
    segs = _assemble(pts, prims, closed_loop, slack)
    if segs is None:
        return None
    from coatsim.geometry.deviation import hausdorff
    from coatsim.geometry.polysegment import Polysegment

    poly = Polysegment(segs, closed=closed_loop)
    if poly.max_tangent_break() > 1e-9 or hausdorff(pts, poly).hausdorff > tolerance:
        return None
    return segs


def _same(p: _Prim, q: _Prim, slack: float, length: float) -> bool:
    if p.kappa == 0.0 or q.kappa == 0.0:
        return p.kappa == q.kappa and abs((q.ref - p.ref) @ np.array([-p.direction[1], p.direction[0]])) <= slack
    return abs(p.kappa - q.kappa) * length < KAPPA_JUMP and float(np.linalg.norm(p.ref - q.ref)) <= slack


def _tangent_point(p: _Prim, q: _Prim, slack: float) -> np.ndarray | None:
    """Where p and q touch tangentially, or None if they do not."""
    if p.kappa == 0.0 and q.kappa == 0.0:
        return None
    if p.kappa == 0.0 or q.kappa == 0.0:
        line, circle = (p, q) if p.kappa == 0.0 else (q, p)
        foot = line.ref + ((circle.ref - line.ref) @ line.direction) * line.direction
        return foot if abs(np.linalg.norm(circle.ref - foot) - 1 / abs(circle.kappa)) <= slack else None
    d = q.ref - p.ref
    dist = float(np.linalg.norm(d))
    r1, r2 = 1 / abs(p.kappa), 1 / abs(q.kappa)
    if dist > slack and abs(dist - abs(r1 - r2)) <= slack:
        return p.ref + d / dist * (r1 if r1 >= r2 else -r1)
    if abs(dist - (r1 + r2)) <= slack:
        return p.ref + d / dist * r1
    return None


def _assemble(pts: np.ndarray, prims: list[_Prim], closed_loop: bool, slack: float) -> tuple[Segment, ...] | None:
    """Chain the primitives between their tangent points."""
    n = len(prims)
    joints = []
    for i in range(n - 1 + closed_loop):
        point = _tangent_point(prims[i], prims[(i + 1) % n], slack)
        if point is None:
            return None
        joints.append(point)
    if closed_loop:
        starts, ends = [joints[-1]] + joints[:-1], joints
    else:
        starts, ends = [pts[0]] + joints, joints + [pts[-1]]
    kappas, lengths, heading = [], [], None
    for prim, a, b in zip(prims, starts, ends):
        if prim.kappa == 0.0:
            tangent, seg_len = prim.direction, float((b - a) @ prim.direction)
        else:
            sign = math.copysign(1.0, prim.kappa)
            ra, rb = a - prim.ref, b - prim.ref
            tangent = sign * np.array([-ra[1], ra[0]]) * abs(prim.kappa)
            sweep = math.atan2(rb[1], rb[0]) - math.atan2(ra[1], ra[0])
            seg_len = (sign * sweep) % (2 * math.pi) / abs(prim.kappa)
        if seg_len <= 0:
            return None
        heading = math.atan2(tangent[1], tangent[0]) if heading is None else heading
        kappas.append(prim.kappa)
        lengths.append(seg_len)
    segs = chain((float(starts[0][0]), float(starts[0][1])), heading, kappas, lengths)
    target = segs[0].start if closed_loop else (float(ends[-1][0]), float(ends[-1][1]))
    return snap_end(segs, target) if np.linalg.norm(np.asarray(segs[-1].end) - target) <= slack else None

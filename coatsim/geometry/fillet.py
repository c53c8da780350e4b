"""The fallback chain: the input polyline with a tangent arc rounding every vertex.

Always G1 and always within the tolerance (each fillet stays within σ of its vertex and the
lines lie on the input's edges), but with up to two segments per vertex, so the fitter uses
it only where its own method cannot reach the tolerance (very sparse or kinked input).
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.polysegment import chain
from coatsim.geometry.primitives import Segment, snap_end

SAFETY = 0.999  # fillets keep this fraction of σ, so round-off cannot push them past it


def fillet_chain(points: np.ndarray, tolerance: float, closed_loop: bool) -> tuple[Segment, ...]:
    """Lines along the input's edges joined by fillets of radius at most
    σ·cos(α/2)/(1 − cos(α/2)) (so a fillet passes within σ of its vertex) and no longer than
    half of either neighbouring edge."""
    pts = np.asarray(points, dtype=float)
    edge = np.diff(pts, axis=0)
    ell = np.linalg.norm(edge, axis=1)
    heading = np.arctan2(edge[:, 1], edge[:, 0])
    n = len(ell)
    # turn[i] is the turn at the vertex between edge i - 1 and edge i (cyclic for a loop)
    turn = np.remainder(heading - np.roll(heading, 1) + math.pi, 2 * math.pi) - math.pi
    if not closed_loop:
        turn[0] = 0.0
    half = np.abs(turn) / 2
    with np.errstate(divide="ignore", invalid="ignore"):
        r_tol = np.where(half > 0, SAFETY * tolerance * np.cos(half) / (1 - np.cos(half)), np.inf)
        shorter = np.minimum(ell, np.roll(ell, 1)) if closed_loop else np.minimum(ell, np.concatenate(([ell[0]], ell[:-1])))
        r_len = np.where(half > 0, 0.5 * shorter / np.tan(half), np.inf)
        radius = np.minimum(r_tol, r_len)
        trim = np.where(half > 0, radius * np.tan(half), 0.0)
    kappas, lengths = [], []
    for i in range(n):
        out_trim = trim[i + 1] if i + 1 < n else (trim[0] if closed_loop else 0.0)
        line = ell[i] - trim[i] - out_trim
        if line > 1e-12 * ell.sum():
            kappas.append(0.0)
            lengths.append(line)
        j = i + 1 if i + 1 < n else (0 if closed_loop else None)
        if j is not None and half[j] > 0:
            kappas.append(math.copysign(1.0 / radius[j], turn[j]))
            lengths.append(radius[j] * abs(turn[j]))
    start = pts[0] + trim[0] * np.array([math.cos(heading[0]), math.sin(heading[0])])
    segs = chain((float(start[0]), float(start[1])), float(heading[0]), kappas, lengths)
    return snap_end(segs, segs[0].start if closed_loop else (float(pts[-1][0]), float(pts[-1][1])))

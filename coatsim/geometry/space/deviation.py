"""The exact two-sided Hausdorff distance between an input polyline and a 3-D chain.

Both directions are measured exactly (closed-form point-to-line, point-to-arc and
point-to-edge distances, coatsim.geometry.space.nearest) at a set of points, then
certified between them, as the planar check does (coatsim.geometry.certify):

- polyline -> chain: at every vertex; along an edge the distance to the chain is
  1-Lipschitz, so (d_a + d_b + length) / 2 bounds it, and it is at most the distance to the
  segment nearest either end, which along a straight edge is convex (a line) or has a second
  derivative of at least −1 / (r − d) (an arc of radius r: a torus tube), so
  max(f_a, f_b) + c·length² / 8 bounds it too; edges whose bound exceeds the maximum found are
  halved and their midpoints measured;
- chain -> polyline: at points every ``tolerance / 4`` along the chain, or every median input
  edge if that is longer, and every segment end;
  between two of them the same two bounds hold with the input edge nearest either end (the
  distance to an edge is convex in space, so along an arc of radius r it bends by at least
  −1 / r); stretches in doubt are halved.

The result is the largest distance measured, unless stretches are still in doubt after
``MAX_HALVINGS`` rounds: then it is the largest bound left, so the reported value is never
below the true distance (and above it by at most ``CERTIFY_SLACK`` relative in practice).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.nearest import SegmentTable, chain_index, edge_distance, polyline_index

CERTIFY_SLACK = 1e-9  # certified to this fraction of (1 + the distance), mm
MAX_HALVINGS = 60
CHAIN_SAMPLES_PER_SIGMA = 4


@dataclass(frozen=True)
class Deviation3:
    """The two directed parts (mm) of the Hausdorff distance."""

    input_to_output: float
    output_to_input: float

    @property
    def hausdorff(self) -> float:
        return max(self.input_to_output, self.output_to_input)


def hausdorff3(polyline: np.ndarray, chain: SpaceChain, tolerance: float) -> Deviation3:
    """Certified two-sided Hausdorff distance between ``polyline`` (n, 3), n >= 2, and
    ``chain``; ``tolerance`` (mm) sets the sampling step along the chain (any positive value
    gives the same result, up to the certification slack)."""
    verts = np.asarray(polyline, dtype=float)
    if verts.ndim != 2 or verts.shape[1] != 3 or len(verts) < 2:
        raise ValueError(f"hausdorff3 needs a polyline of at least two 3-D points, got shape {verts.shape}")
    table = SegmentTable.of(chain)
    step = tolerance / CHAIN_SAMPLES_PER_SIGMA
    # the chain is measured at about the input's own spacing (or finer): between two such
    # points the bounds certify it, halving where they do not
    edge = float(np.median(np.linalg.norm(np.diff(verts, axis=0), axis=1)))
    return Deviation3(_input_to_chain(verts, table, step), _chain_to_input(verts, table, max(step, edge)))


def distance_to_chain(points: np.ndarray, chain: SpaceChain, tolerance: float) -> np.ndarray:
    """Exact distance (n,) from points (n, 3) to the chain."""
    return chain_index(SegmentTable.of(chain), tolerance / CHAIN_SAMPLES_PER_SIGMA).distance(points)[0]


def _semiconvex_bound(fa: np.ndarray, fb: np.ndarray, length: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Largest value over an interval of a function with f'' >= -c: max(f(a), f(b)) + c L² / 8."""
    with np.errstate(invalid="ignore"):
        return np.maximum(fa, fb) + np.where(c > 0, c * length**2 / 8, 0.0)


def _arc_concavity(table: SegmentTable, seg: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """How concave the distance to segment ``seg`` can be along a straight line where it stays
    below ``upper``: 0 for a line (a convex set), 1 / (r − upper) for an arc of radius r (its
    distance function is that of a torus tube of radius at most ``upper``), inf beyond."""
    r = table.radius[seg]
    with np.errstate(divide="ignore"):
        return np.where(~table.is_arc[seg], 0.0, np.where(upper < r, 1.0 / (r - upper), np.inf))


def _input_to_chain(verts: np.ndarray, table: SegmentTable, step: float) -> float:
    """Vertices exactly; each edge stretch bounded by the Lipschitz bound and by the
    semiconvex bound of the distance to the segment nearest either end."""
    index = chain_index(table, step)
    d, who = index.distance(verts)
    best = float(d.max())
    a, b = verts[:-1], verts[1:]
    da, db, ja, jb = d[:-1], d[1:], who[:-1], who[1:]
    for _ in range(MAX_HALVINGS):
        slack = CERTIFY_SLACK * (1 + best)
        length = np.linalg.norm(b - a, axis=1)
        bound = (da + db + length) / 2
        for j in (ja, jb):
            fa, fb = table.distance(a, j)[0], table.distance(b, j)[0]
            bound = np.minimum(bound, _semiconvex_bound(fa, fb, length, _arc_concavity(table, j, bound)))
        live = bound > best + slack
        if not live.any():
            return best
        a, b, da, db, ja, jb = (x[live] for x in (a, b, da, db, ja, jb))
        mid = (a + b) / 2
        dm, jm = index.distance(mid)
        best = max(best, float(dm.max()))
        a, b = np.vstack((a, mid)), np.vstack((mid, b))
        da, db = np.concatenate((da, dm)), np.concatenate((dm, db))
        ja, jb = np.concatenate((ja, jm)), np.concatenate((jm, jb))
    return max(best, float(bound.max()))


def _chain_to_input(verts: np.ndarray, table: SegmentTable, step: float) -> float:
    """Points along the chain exactly; each stretch bounded by the Lipschitz bound and by the
    semiconvex bound of the distance to the input edge nearest either end (the distance to an
    edge, a convex set, is convex in space; along an arc of radius r its second derivative is
    at least −1/r)."""
    index, _ = polyline_index(verts)
    count = np.maximum(1, np.ceil(table.length / step).astype(np.int64))
    seg = np.repeat(np.arange(len(count)), count)
    first = np.repeat(np.cumsum(count) - count, count)
    k = np.arange(len(seg)) - first
    s0 = k / count[seg] * table.length[seg]
    s1 = (k + 1) / count[seg] * table.length[seg]
    p0, p1 = table.point_at(seg, s0), table.point_at(seg, s1)
    d0, e0 = index.distance(p0)
    d1, e1 = index.distance(p1)
    best = float(max(d0.max(), d1.max()))
    for _ in range(MAX_HALVINGS):
        length = s1 - s0
        bound = (d0 + d1 + length) / 2
        c = np.where(table.is_arc[seg], 1.0 / table.radius[seg], 0.0)
        for e in (e0, e1):
            bound = np.minimum(bound, _semiconvex_bound(edge_distance(p0, verts, e), edge_distance(p1, verts, e), length, c))
        live = bound > best + CERTIFY_SLACK * (1 + best)
        if not live.any():
            return best
        seg, s0, s1, p0, p1, d0, d1, e0, e1 = (x[live] for x in (seg, s0, s1, p0, p1, d0, d1, e0, e1))
        sm = (s0 + s1) / 2
        pm = table.point_at(seg, sm)
        dm, em = index.distance(pm)
        best = max(best, float(dm.max()))
        seg = np.concatenate((seg, seg))
        s0, s1 = np.concatenate((s0, sm)), np.concatenate((sm, s1))
        p0, p1 = np.vstack((p0, pm)), np.vstack((pm, p1))
        d0, d1 = np.concatenate((d0, dm)), np.concatenate((dm, d1))
        e0, e1 = np.concatenate((e0, em)), np.concatenate((em, e1))
    return max(best, float(bound.max()))

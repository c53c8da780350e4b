"""Exact nearest-feature distances with KD-trees: to a polysegment's segments or to a
polyline's edges, and the largest such distance over many points.

Each index holds sample points, each sample owning a contiguous range of features, such that
every point of every feature lies within ``reach`` of a sample that owns it. A bound uses the
features owned by the nearest sample (an upper bound, exact nearly everywhere); an exact
value takes every feature owned by a sample within bound + reach (the nearest feature's
closest point has such a sample). ``max_distance`` measures exactly only the points whose
bound can still exceed the maximum found so far.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.budgets import check_budget
from coatsim.geometry.segment_table import SegmentTable

SEGMENT_SAMPLES = 1024  # samples along a polysegment (at least one per segment)


def expand_ranges(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(row, item) pairs for the integer ranges [lo, hi) of every row."""
    counts = hi - lo
    row = np.repeat(np.arange(len(lo)), counts)
    item = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts - lo, counts)
    return row, item


def edge_distance(points: np.ndarray, verts: np.ndarray, edge: np.ndarray) -> np.ndarray:
    a = verts[edge]
    ab = verts[edge + 1] - a
    ap = points - a
    den = ab[:, 0] ** 2 + ab[:, 1] ** 2
    u = np.clip((ap[:, 0] * ab[:, 0] + ap[:, 1] * ab[:, 1]) / np.where(den > 0, den, 1.0), 0.0, 1.0)
    return np.hypot(ap[:, 0] - u * ab[:, 0], ap[:, 1] - u * ab[:, 1])


def _check_pairs(count: int) -> None:
    """The exact deviation check compares each point with every feature near it: a chain that
    crosses itself everywhere (random or aliased input) puts nearly all of them near each point."""
    check_budget("the exact deviation check: point-feature pairs at once", count, "deviation_pairs",
                 "the curve has no structure at this tolerance (random or aliased points): smooth or resample it, "
                 "or raise tolerance_mm", parameters=("tolerance_mm",))


class _Layer:
    """Samples (k, 2) in a KD-tree, sample i owning features [lo[i], hi[i]); every point of
    every feature lies within ``reach`` of a sample that owns it."""

    def __init__(self, samples: np.ndarray, lo: np.ndarray, hi: np.ndarray, reach: float):
        self.tree = cKDTree(samples) if len(samples) else None
        self.lo, self.hi, self.reach = lo, hi, reach

    def nearest(self, points: np.ndarray, pad: int, n_features: int) -> tuple[np.ndarray, np.ndarray]:
        """(row, feature) pairs: the features of each point's nearest sample, widened by ``pad``."""
        if self.tree is None:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        _, s = self.tree.query(points)
        return expand_ranges(np.maximum(self.lo[s] - pad, 0), np.minimum(self.hi[s] + pad, n_features))

    def within(self, points: np.ndarray, upper: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(row, feature) pairs: every feature owned by a sample within upper + reach."""
        if self.tree is None:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        radius = upper * (1 + 1e-9) + self.reach * (1 + 1e-9) + 1e-12
        _check_pairs(int(np.sum(self.tree.query_ball_point(points, radius, return_length=True))))
        hits = self.tree.query_ball_point(points, radius, return_sorted=False)
        counts = np.fromiter((len(h) for h in hits), dtype=np.int64, count=len(points))
        sample = np.fromiter((i for h in hits for i in h), dtype=np.int64, count=int(counts.sum()))
        owner = np.repeat(np.arange(len(points)), counts)
        _check_pairs(int((self.hi[sample] - self.lo[sample]).sum()))
        pair_row, feature = expand_ranges(self.lo[sample], self.hi[sample])
        return owner[pair_row], feature


class _Index:
    """Nearest features over one or more sample layers; subclasses measure one feature."""

    def __init__(self, layers: list[_Layer], n_features: int):
        self.layers, self.n_features = layers, n_features
        self.reach = max(layer.reach for layer in layers)

    def measure(self, points: np.ndarray, feature: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(distance, nearest point) from points[i] to feature[i]."""
        raise NotImplementedError

    def _best(self, points: np.ndarray, pairs: list[tuple[np.ndarray, np.ndarray]]):
        """Smallest distance per point over its (row, feature) pairs (every row present)."""
        row = np.concatenate([r for r, _ in pairs])
        feature = np.concatenate([f for _, f in pairs])
        if len(pairs) > 1:
            key = np.unique(row * self.n_features + feature)
            row, feature = key // self.n_features, key % self.n_features
        d, foot = self.measure(points[row], feature)
        order = np.lexsort((d, row))
        first = order[np.searchsorted(row[order], np.arange(len(points)))]
        return d[first], feature[first], foot[first]

    def bound(self, points: np.ndarray, pad: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Upper bound on the distance (the features of the nearest sample of every layer,
        widened by ``pad``): (distance, feature, nearest point)."""
        pts = np.asarray(points, dtype=float)
        return self._best(pts, [layer.nearest(pts, pad, self.n_features) for layer in self.layers])

    def exact(self, points: np.ndarray, upper: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Exact distance of points whose distance is at most ``upper``: every feature owned
        by a sample within upper + reach. Returns (distance, feature, nearest point)."""
        pts = np.asarray(points, dtype=float)
        pairs = [layer.within(pts, upper) for layer in self.layers]
        missing = np.setdiff1d(np.arange(len(pts)), np.concatenate([r for r, _ in pairs]))
        if len(missing):  # an upper bound that rounding made too tight: the nearest samples' features too
            for layer in self.layers:
                r, f = layer.nearest(pts[missing], 0, self.n_features)
                pairs.append((missing[r], f))
        row = np.concatenate([r for r, _ in pairs])
        feature = np.concatenate([f for _, f in pairs])
        key = np.unique(row * self.n_features + feature)
        return self._best(pts, [(key // self.n_features, key % self.n_features)])


class PolysegmentIndex(_Index):
    """Nearest segment of a polysegment: samples spread along each segment by arc length."""

    def __init__(self, table: SegmentTable, n_samples: int = SEGMENT_SAMPLES):
        self.table = table
        spacing = float(table.length.sum()) / n_samples
        count = np.maximum(1, np.ceil(table.length / spacing if spacing > 0 else 0).astype(np.int64))
        seg, k = expand_ranges(np.zeros(len(table), dtype=np.int64), count)
        s = (k + 0.5) * (table.length / count)[seg]
        self.samples = _Layer(table.point_at(seg, s), seg, seg + 1, float(np.max(table.length / (2 * count))))
        super().__init__([self.samples], len(table))

    def measure(self, points, feature):
        d, foot, _ = self.table.distance(points, feature)
        return d, foot

    def bound(self, points, pad=0):
        return self.nearest(points)[:3]

    def nearest(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Bound from the segment of the nearest sample, or the next one where that
        segment's nearest point is its end (the fitter's input: one segment per vertex,
        rarely two). Returns (distance, segment, nearest point, where: -1 at the segment's
        start, +1 at its end, 0 inside)."""
        pts = np.asarray(points, dtype=float)
        _, s = self.samples.tree.query(pts)
        seg = self.samples.lo[s]
        d, foot, where = self.table.distance(pts, seg)
        ends = np.flatnonzero(where != 0)
        other = np.where(where[ends] < 0, self.table.neighbour(seg[ends], -1), self.table.neighbour(seg[ends], 1))
        ok = other >= 0
        ends, other = ends[ok], other[ok]
        d2, foot2, where2 = self.table.distance(pts[ends], other)
        better = d2 < d[ends]
        upd = ends[better]
        d[upd], seg[upd], foot[upd], where[upd] = d2[better], other[better], foot2[better], where2[better]
        return d, seg, foot, where


class PolylineIndex(_Index):
    """Nearest edge of a polyline. Where the polyline runs on smoothly, runs of consecutive
    edges (a few median edges long) share one sample, their middle vertex; elsewhere (a
    scribble, a sharp turn) and on long edges, every edge has samples at most two median
    edges apart. Two layers, so neither reach inflates the other's searches."""

    RUN = 8  # median edges per run

    def __init__(self, vertices: np.ndarray):
        self.vertices = v = np.asarray(vertices, dtype=float)
        n_edges = len(v) - 1
        self.length = length = np.hypot(*np.diff(v, axis=0).T)
        self.median = float(np.median(length))
        piece = max(2 * self.median, float(length.sum()) / max(n_edges, 1), 1e-300)
        run_length = self.RUN * piece / 2
        s = np.concatenate(([0.0], np.cumsum(length)))
        short = np.flatnonzero(length <= piece)
        # runs of short edges by the arc length of their middles
        run = np.floor((s[short] + s[short + 1]) / 2 / run_length).astype(np.int64)
        first = np.flatnonzero(np.r_[True, run[1:] != run[:-1]]) if len(run) else run
        lo = short[first]
        hi = np.r_[short[first[1:] - 1], short[-1]] + 1 if len(first) else lo
        contiguous = hi - lo == np.diff(np.r_[first, len(short)])
        mid = v[(lo + hi) // 2]
        row, vertex = expand_ranges(lo, hi + 1)  # vertices lo..hi of every run, run after run
        gap = np.hypot(*(v[vertex] - mid[row]).T)
        far = np.maximum.reduceat(gap, np.cumsum(hi + 1 - lo) - (hi + 1 - lo)) if len(lo) else gap
        good = contiguous & (far <= run_length)
        runs = _Layer(mid[good], lo[good], hi[good], float(far[good].max(initial=0.0)))
        # every other edge: pieces of at most `piece`, a sample at each piece's middle
        single = np.ones(n_edges, dtype=bool)
        single[expand_ranges(lo[good], hi[good])[1]] = False
        edge = np.flatnonzero(single)
        count = np.maximum(1, np.ceil(length[edge] / piece).astype(np.int64))
        which, k = expand_ranges(np.zeros(len(edge), dtype=np.int64), count)
        e = edge[which]
        pieces = v[e] + ((k + 0.5) / count[which])[:, None] * (v[e + 1] - v[e])
        singles = _Layer(pieces, e, e + 1, float(np.max(length[edge] / (2 * count), initial=0.0)))
        super().__init__([layer for layer in (runs, singles) if layer.tree is not None], n_edges)

    def bound(self, points, pad=2):
        """The edges of the nearest sample of each layer, widened by ``pad`` edges."""
        return super().bound(points, pad)

    def measure(self, points, feature):
        d = edge_distance(points, self.vertices, feature)
        return d, points  # the nearest point on the polyline is not needed


def max_distance(index: _Index, points: np.ndarray, upper: np.ndarray, lower: float = 0.0,
                 bounded: bool = False) -> float:
    """Largest exact distance from ``points`` to the index's features, at least ``lower``.

    ``upper`` (n,) bounds each distance from above (inf if unknown; ``bounded`` when it
    already comes from ``index.bound``). Points are taken in order of decreasing bound; a
    point is measured exactly only while its bound exceeds the largest exact distance so far.
    """
    best = float(lower)
    pts = np.asarray(points, dtype=float)
    upper = np.array(upper, dtype=float)
    live = np.flatnonzero(upper > best)
    batch = 64
    while len(live):
        if len(live) > batch:
            live = live[np.argpartition(-upper[live], batch - 1)[:batch]]
        u = upper[live]
        if not bounded:
            u = np.minimum(u, index.bound(pts[live])[0])
        upper[live] = -np.inf  # measured (or shown not to matter) below
        order = np.argsort(-u, kind="stable")
        take, u = live[order], u[order]
        for i in range(0, len(take), 16):
            if u[i] <= best:
                break
            keep = u[i : i + 16] > best
            d = index.exact(pts[take[i : i + 16]][keep], u[i : i + 16][keep])[0]
            best = max(best, float(d.max(initial=best)))
        live = np.flatnonzero(upper > best)
        batch *= 4
    return best


def distance_per_point(index: _Index, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact (distance, feature, nearest point) for every point."""
    pts = np.asarray(points, dtype=float)
    d, feature, foot = index.bound(pts)
    if not len(pts):
        return d, feature, foot
    return index.exact(pts, d)

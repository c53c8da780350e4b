"""The deposition model's terms per (sub-step, vertex) pair, evaluated a KD-tree leaf at a time.

The culling search (coatsim.spray.culling) yields (sub-step, leaf) pairs. Each leaf's vertices
sit side by side in blocks (positions and normals; one width for all, a large leaf in several,
the last padded), so a pass reads a block's rows in one take and a sub-step's once per block,
not once per vertex. Every pair gets
its reference-plane radius; only the pairs within the footprint's cut-off radius (``near``)
get the density, rate and distance: every footprint is zero beyond that radius, so the others
receive nothing. The arithmetic per pair is that of the model in coatsim.spray.deposition, dot
products summed in one fixed order, so a pair's terms do not depend on its pass or block.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.core.numeric import ROUND_OFF, TINY
from coatsim.spray.culling import LeafPairs, VertexTree
from coatsim.spray.footprints import Footprint

_PAIRS_PER_PASS = 8192  # pairs whose terms are computed at once (their arrays stay in cache)
_BLOCK_SLOTS = 8  # the fixed work of a block (a take of its rows), in pair slots: an estimate


@dataclass(frozen=True, eq=False)
class LeafBlocks:
    """Each leaf's vertices side by side in blocks of one ``width`` (a leaf of more vertices takes
    several, ``blocks`` from its ``first`` one): ``rows`` (6, B, width) their x, y, z, nx, ny, nz
    (padding: zero normals, never seen), ``vertex`` (B, width) their ids (padding: the leaf's first
    vertex)."""

    rows: np.ndarray
    vertex: np.ndarray
    first: np.ndarray
    blocks: np.ndarray

    @property
    def width(self) -> int:
        return self.rows.shape[2]


def _block_width(count: np.ndarray) -> int:
    """The width that costs least over leaves of ``count`` vertices: the padding slots against
    the fixed work of a block (a take of its rows)."""
    widths = np.arange(1, int(count.max()) + 1)
    blocks = -(-count[None, :] // widths[:, None])
    return int(widths[np.argmin(blocks.sum(axis=1) * (widths + _BLOCK_SLOTS))])


def leaf_blocks(tree: VertexTree, vertices: np.ndarray, normals: np.ndarray) -> LeafBlocks:
    """The blocks of the leaves of ``tree`` over ``vertices`` and unit ``normals`` (n, 3)."""
    width = _block_width(tree.count)
    blocks = -(-tree.count // width)
    first = np.cumsum(blocks) - blocks
    leaf = np.repeat(np.arange(tree.n_leaves), blocks)
    place = (np.arange(len(leaf)) - first[leaf])[:, None] * width + np.arange(width)  # in the leaf
    real = place < tree.count[leaf, None]
    vertex = tree.order[tree.start[leaf, None] + np.where(real, place, 0)]
    rows = np.hstack([vertices, normals]).astype(float)[vertex].transpose(2, 0, 1)
    rows[3:] = np.where(real, rows[3:], 0.0)
    return LeafBlocks(np.ascontiguousarray(rows), vertex, first, blocks)


@dataclass(frozen=True, eq=False)
class NearPairs:
    """The pairs within the cut-off radius, in pair order (sub-step, leaf, place in the leaf), all
    (m,): sub-step ``step`` and ``slot`` (into the vertices touched), axial distance ``da`` = d·a
    (mm), ``facing`` = −d·n (mm), ``dist`` = |d| (mm) and thickness ``rate`` before deposition
    efficiency (mm/s), d = x − p the nozzle-to-vertex offset; where shadows are cast, also the
    ``vertex`` and the squared reference-plane radius ``r2`` (mm²; None without shadows)."""

    step: np.ndarray
    slot: np.ndarray
    da: np.ndarray
    facing: np.ndarray
    dist: np.ndarray
    rate: np.ndarray
    vertex: np.ndarray | None
    r2: np.ndarray | None


class PairBuffer:
    """Columns that near_pairs writes its pairs to, reused by every batch of a deposit (their
    pages are mapped once, not per batch) and grown when a batch needs more."""

    def __init__(self) -> None:
        self.indices = np.empty((3, 0), dtype=np.int64)
        self.values = np.empty((5, 0))

    def columns(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Room for ``n`` pairs: (3, n) integers and (5, n) floats."""
        if self.indices.shape[1] < n:
            self.indices, self.values = np.empty((3, n), dtype=np.int64), np.empty((5, n))
        return self.indices[:, :n], self.values[:, :n]


def _dot(d: np.ndarray, c: np.ndarray, out: np.ndarray) -> np.ndarray:
    """d·c of the (3, n) ``d`` and ``c``, summed as (d0 c0 + d2 c2) + d1 c1 (the order of numpy's
    einsum over three terms); ``out`` (3, n) is overwritten (it may be ``c``)."""
    np.multiply(d, c, out=out)
    out[0] += out[2]
    out[0] += out[1]
    return out[0]


def near_pairs(leaves: LeafBlocks, step_columns: np.ndarray, pairs: LeafPairs, span: tuple[int, int],
               gun: tuple[Footprint, float, float], hideable: np.ndarray | None, r2_min: np.ndarray,
               buffer: PairBuffer) -> NearPairs:
    """The near pairs among the pairs numbered ``span`` = [start, end) of ``pairs``, in ``buffer``;
    ``step_columns`` (12, m) holds each sub-step's position, unit axis and footprint axes e1, e2;
    ``gun`` is the footprint, deposited rate Q (mm³/s) and reference stand-off h0 (mm).
    The squared radii go into ``r2_min`` (per vertex, in place; inf where unseen), but for the
    near pairs of the vertices a shadow may hide (``hideable``; None: no shadows), whose rays
    are yet to be cast."""
    (footprint, rate, h0), width = gun, leaves.width
    start, end = span
    first, last = np.searchsorted(pairs.first, start, "right") - 1, np.searchsorted(pairs.first, end)
    leaf = pairs.leaf[first:last]
    # each (sub-step, leaf) pair as (sub-step, block) pairs, those that hold pairs of the span
    blocks = leaves.blocks.take(leaf)
    j = np.arange(int(blocks.sum())) - np.repeat(np.cumsum(blocks) - blocks, blocks)
    number = np.repeat(pairs.first[first:last], blocks) + j * width
    within = slice(np.searchsorted(number, start, "right") - 1, np.searchsorted(number, end))
    block = (np.repeat(leaves.first.take(leaf), blocks) + j)[within]
    step = np.repeat(pairs.step[first:last], blocks)[within]
    base = (np.repeat(pairs.base[first:last], blocks) + j * width)[within]
    # the first block pair's places before ``head`` and the last's from ``tail`` on are outside the span
    head, tail = start - number[within][0], end - number[within][-1]
    limit = footprint.cutoff_mm**2 * (1 + ROUND_OFF)  # past it, a radius is beyond the cut-off whatever its rounding
    per = max(1, _PAIRS_PER_PASS // width)
    indices, values = buffer.columns(len(step) * width)
    filled = 0
    for lo in range(0, len(step), per):
        hi = min(lo + per, len(step))
        x = leaves.rows.take(block[lo:hi], axis=1).reshape(6, -1)
        p = np.repeat(step_columns.take(step[lo:hi], axis=1), width).reshape(12, -1)
        d = x[:3]
        d -= p[:3]
        da = _dot(d, p[3:6], p[3:6])
        dn = np.negative(_dot(d, x[3:6], x[3:6]))
        seen = (da > TINY) & (dn > 0)
        scale = np.divide(h0, da, out=np.zeros_like(da), where=seen)
        u = _dot(d, p[6:9], p[6:9])
        u *= scale
        v = _dot(d, p[9:12], p[9:12])
        v *= scale
        r2 = np.where(seen, u * u + v * v, np.inf)
        near = r2 <= limit
        vertex = leaves.vertex.take(block[lo:hi], axis=0).ravel()
        np.minimum.at(r2_min, vertex, r2 if hideable is None else np.where(near & hideable[vertex], np.inf, r2))
        if lo == 0:
            near[:head] = False
        if hi == len(step):
            near[(hi - 1 - lo) * width + tail:] = False
        k = np.flatnonzero(near)
        pair, place = np.divmod(k, width)
        pair += lo
        u, v, scale, facing, near_d = u.take(k), v.take(k), scale.take(k), dn.take(k), d.take(k, axis=1)
        g = footprint.density(u, v)
        into = slice(filled, filled + len(k))
        indices[0, into], indices[1, into] = step.take(pair), base.take(pair) + place
        values[0, into], values[1, into] = da.take(k), facing
        values[2, into] = np.sqrt(_dot(near_d, near_d, near_d))
        values[3, into] = rate * g * scale**3 * facing / h0
        if hideable is not None:
            indices[2, into], values[4, into] = vertex.take(k), r2.take(k)
        filled += len(k)
    shadowed = (indices[2, :filled], values[4, :filled]) if hideable is not None else (None, None)
    return NearPairs(indices[0, :filled], indices[1, :filled], *values[:4, :filled], *shadowed)

"""Which vertices a sprayed sub-step can reach: a KD-tree over the surface vertices whose nodes
carry bounding spheres, searched top-down for the spheres that may meet the footprint's cut-off
cone (apex at the nozzle, half-angle atan(cut-off radius / h0)).

The search visits a node only when its parent's sphere meets the cone, so its work per sub-step
grows with the vertices in reach and the depth of the tree, not with the size of the mesh. Every
node's sphere encloses its children's spheres and the cone test never gets stricter for a larger
sphere (it bounds a 1-Lipschitz distance), so the search returns exactly the leaves that testing
every leaf would return. Pairs come out sub-step by sub-step, leaf by leaf in tree order, so the
order in which a vertex's contributions are summed does not depend on the search.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

LEAF_SIZE = 48
_SLACK = 1e-9  # relative and absolute growth of every sphere: rounding never drops a leaf


@dataclass(frozen=True, eq=False)
class VertexTree:
    """Nodes 0..L-1 are the leaves in the order of ``start`` (contiguous ranges of ``order``, the
    vertex ids); the others are inner nodes with two ``children`` each (-1 for a leaf). Every node
    has a bounding sphere ``centre`` (k, 3) mm, ``radius`` (k,) mm."""

    order: np.ndarray
    start: np.ndarray
    count: np.ndarray
    centre: np.ndarray
    radius: np.ndarray
    children: np.ndarray
    root: int

    @property
    def n_leaves(self) -> int:
        return len(self.start)


def _enclosing(c1: np.ndarray, r1: np.ndarray, c2: np.ndarray, r2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest spheres enclosing pairs of spheres (row by row), grown by the slack."""
    d = np.linalg.norm(c2 - c1, axis=1)
    radius = 0.5 * (d + r1 + r2)
    t = np.where(d > 0, (radius - r1) / np.where(d > 0, d, 1.0), 0.0)[:, None]
    centre = c1 + t * (c2 - c1)
    first, second = d + r2 <= r1, d + r1 <= r2
    centre = np.where(first[:, None], c1, np.where(second[:, None], c2, centre))
    radius = np.where(first, r1, np.where(second, r2, radius))
    return centre, radius * (1 + _SLACK) + _SLACK


def vertex_tree(points: np.ndarray) -> VertexTree:
    """The tree of ``points`` (n, 3): scipy's KD-tree split, spheres fitted bottom-up."""
    tree = cKDTree(points, leafsize=LEAF_SIZE, balanced_tree=False, compact_nodes=False)
    nodes, links, stack = [], [], [(tree.tree, -1)]
    while stack:  # pre-order: a parent before its children
        node, parent = stack.pop()
        nodes.append(node)
        links.append(parent)
        if node.split_dim != -1:
            me = len(nodes) - 1
            stack.extend(((node.greater, me), (node.lesser, me)))
    is_leaf = np.array([n.split_dim == -1 for n in nodes])
    span = np.array([(n.start_idx, n.end_idx) for n in nodes], dtype=np.int64)
    leaf_rank = np.flatnonzero(is_leaf)[np.lexsort((span[is_leaf, 1], span[is_leaf, 0]))]
    ids = np.empty(len(nodes), dtype=np.int64)  # pre-order position -> node id (leaves first)
    ids[leaf_rank] = np.arange(len(leaf_rank))
    ids[~is_leaf] = len(leaf_rank) + np.arange(int((~is_leaf).sum()))
    start, count = span[leaf_rank, 0], span[leaf_rank, 1] - span[leaf_rank, 0]
    order = np.asarray(tree.indices, dtype=np.int64)
    leaf = np.repeat(np.arange(len(start)), count)
    pts = points[order]  # leaf by leaf: each leaf a contiguous run from its start
    centre = np.zeros((len(nodes), 3))
    radius = np.zeros(len(nodes))
    centre[: len(start)] = 0.5 * (np.minimum.reduceat(pts, start) + np.maximum.reduceat(pts, start))
    radius[: len(start)] = np.maximum.reduceat(np.linalg.norm(pts - centre[leaf], axis=1), start) * (1 + _SLACK) + _SLACK
    children = np.full((len(nodes), 2), -1, dtype=np.int64)
    parent = np.asarray(links[1:], dtype=np.int64)
    child = ids[np.arange(1, len(nodes))]
    slot = np.zeros(len(nodes), dtype=np.int64)
    for c, p in zip(child, ids[parent]):  # lesser first (pushed last, popped first)
        children[p, slot[p]] = c
        slot[p] += 1
    depth = np.zeros(len(nodes), dtype=np.int64)  # pre-order: a parent's depth is known first
    for k in range(1, len(nodes)):
        depth[ids[k]] = depth[ids[parent[k - 1]]] + 1
    inner = np.flatnonzero(children[:, 0] >= 0)
    for level in range(int(depth.max(initial=0)), -1, -1):  # children before parents
        at = inner[depth[inner] == level]
        if len(at):
            a, b = children[at, 0], children[at, 1]
            centre[at], radius[at] = _enclosing(centre[a], radius[a], centre[b], radius[b])
    return VertexTree(order, start, count, centre, radius, children, int(ids[0]))


def meets_cone(centre: np.ndarray, radius: np.ndarray, apex: np.ndarray, axis: np.ndarray,
               slope: float) -> np.ndarray:
    """True where the sphere (centre, radius) may meet the cone (apex, unit axis, lateral/axial =
    ``slope``). Conservative: the distance from a centre at axial w, lateral l to the cone's
    boundary line, (l - slope w) / sqrt(1 + slope^2), never exceeds its distance to the cone."""
    v = centre - apex
    w = np.einsum("nk,nk->n", v, axis)
    lateral = np.sqrt(np.maximum(np.einsum("nk,nk->n", v, v) - w * w, 0.0))
    return (w >= -radius) & (lateral - slope * w <= radius * math.sqrt(1 + slope * slope))


def cone_leaves(tree: VertexTree, position: np.ndarray, axis: np.ndarray, slope: float,
                steps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(sub-step, leaf) pairs whose leaf sphere may meet the cut-off cone of each of ``steps``
    (indices into ``position`` and ``axis``), ordered by sub-step, then leaf."""
    node = np.full(len(steps), tree.root, dtype=np.int64)
    step = np.asarray(steps, dtype=np.int64)
    found_step, found_leaf = [], []
    while len(step):
        keep = meets_cone(tree.centre.take(node, axis=0), tree.radius.take(node), position.take(step, axis=0),
                          axis.take(step, axis=0), slope)
        step, node = step[keep], node[keep]
        leaf = node < tree.n_leaves
        found_step.append(step[leaf])
        found_leaf.append(node[leaf])
        step, node = np.repeat(step[~leaf], 2), tree.children.take(node[~leaf], axis=0).ravel()
    key = np.sort(np.concatenate(found_step) * tree.n_leaves + np.concatenate(found_leaf))  # by sub-step, then leaf
    return key // tree.n_leaves, key % tree.n_leaves


@dataclass(frozen=True, eq=False)
class LeafPairs:
    """(sub-step, leaf) pairs whose leaf sphere may meet the sub-step's cone, ordered by sub-step,
    then leaf; each stands for the pairs of its sub-step with its leaf's vertices, ``size`` in
    all, the first of them numbered ``first``. The vertices of the leaves met, each once
    (``touched``), and where each pair's leaf starts in it (``base``; a vertex's slot is its
    leaf's base plus its place in the leaf), so sums per vertex take work in proportion to the
    pairs, not to the mesh."""

    step: np.ndarray
    leaf: np.ndarray
    first: np.ndarray
    base: np.ndarray
    touched: np.ndarray
    size: int


def cone_pairs(tree: VertexTree, position: np.ndarray, axis: np.ndarray, slope: float, steps: np.ndarray) -> LeafPairs:
    """The pairs of ``steps`` (indices into ``position`` and ``axis``), ordered by sub-step, then
    leaf, then the vertex's place in its leaf."""
    step, leaf = cone_leaves(tree, position, axis, slope, steps)
    counts = tree.count[leaf]
    hit = np.unique(leaf)
    size = tree.count[hit]
    base = np.zeros(tree.n_leaves, dtype=np.int64)
    base[hit] = np.cumsum(size) - size
    touched = tree.order[np.repeat(tree.start[hit] - base[hit], size) + np.arange(int(size.sum()))]
    return LeafPairs(step, leaf, np.cumsum(counts) - counts, base[leaf], touched, int(counts.sum()))

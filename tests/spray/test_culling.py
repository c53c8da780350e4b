"""The culling tree's top-down search returns exactly the leaves a test of every leaf returns, and
the pairs index the vertices they touch."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.spray.culling import cone_leaves, cone_pairs, meets_cone, vertex_tree


def every_leaf(tree, position, axis, slope):
    """The oracle: each sub-step against each leaf sphere."""
    leaves = np.arange(tree.n_leaves)
    step = np.repeat(np.arange(len(position)), tree.n_leaves)
    leaf = np.tile(leaves, len(position))
    hit = meets_cone(tree.centre[leaf], tree.radius[leaf], position[step], axis[step], slope)
    return step[hit], leaf[hit]


@given(st.integers(0, 2**31 - 1), st.integers(1, 3000), st.floats(0.05, 2.0))
@settings(max_examples=40, deadline=None)
def test_the_search_finds_exactly_the_leaves_that_meet_the_cone(seed, n, slope):
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 3)) * rng.uniform(1, 100, 3)
    tree = vertex_tree(points)
    position = rng.normal(size=(30, 3)) * 150
    axis = rng.normal(size=(30, 3))
    axis /= np.linalg.norm(axis, axis=1)[:, None]
    found = cone_leaves(tree, position, axis, slope, np.arange(30))
    expected = every_leaf(tree, position, axis, slope)
    np.testing.assert_array_equal(found[0], expected[0])
    np.testing.assert_array_equal(found[1], expected[1])
    pairs = cone_pairs(tree, position, axis, slope, np.arange(30))
    np.testing.assert_array_equal(pairs.step, found[0])
    np.testing.assert_array_equal(pairs.leaf, found[1])
    counts = tree.count[pairs.leaf]
    assert pairs.size == counts.sum() and np.array_equal(pairs.first, np.cumsum(counts) - counts)
    place = np.arange(pairs.size) - np.repeat(pairs.first, counts)
    step = np.repeat(pairs.step, counts)
    vertex = tree.order[np.repeat(tree.start[pairs.leaf], counts) + place]
    slot = np.repeat(pairs.base, counts) + place
    np.testing.assert_array_equal(pairs.touched[slot], vertex)  # every touched vertex once
    assert len(np.unique(pairs.touched)) == len(pairs.touched) and set(pairs.touched) == set(vertex)
    for s in range(30):  # every vertex strictly inside a cone is among its pairs
        d_all = points - position[s]
        w_all = d_all @ axis[s]
        lateral = np.sqrt(np.maximum(np.einsum("ij,ij->i", d_all, d_all) - w_all**2, 0))
        assert set(np.flatnonzero((w_all > 0) & (lateral < slope * w_all))) <= set(vertex[step == s])


def test_every_sphere_encloses_its_childrens():
    points = np.random.default_rng(1).uniform(-100, 100, (5000, 3))
    tree = vertex_tree(points)
    inner = np.flatnonzero(tree.children[:, 0] >= 0)
    for k in (0, 1):
        child = tree.children[inner, k]
        gap = np.linalg.norm(tree.centre[child] - tree.centre[inner], axis=1) + tree.radius[child]
        assert np.all(gap <= tree.radius[inner])
    leaf = np.repeat(np.arange(tree.n_leaves), tree.count)
    assert np.all(np.linalg.norm(points[tree.order] - tree.centre[leaf], axis=1) <= tree.radius[leaf])
    assert sorted(tree.order.tolist()) == list(range(5000))

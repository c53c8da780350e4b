"""The pair terms evaluated leaf block by leaf block: the model's terms for every pair within the
cut-off radius, the far pairs left out without changing any result, and batches that split a
leaf's pairs counting every pair once."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.spray import deposition, pair_terms
from coatsim.spray.culling import cone_pairs, vertex_tree
from coatsim.spray.deposition import deposit, substeps
from coatsim.spray.efficiency import parse_efficiency_spec
from coatsim.spray.footprints import Beta
from coatsim.spray.pair_terms import PairBuffer, leaf_blocks, near_pairs
from spray_helpers import H0, gun, line_log, make_log, shelf_over_floor, volume

FIELDS = ("thickness_mm", "exposure_s", "track_distance_mm", "shadowed_mm", "lost_mm", "spray_angle_deg",
          "standoff_mm")


def tilted_shelf_pass():
    """A tilted pass along the shelf's edge: shadows, grazing incidence and far pairs."""
    log = line_log((6.0, -40, H0), (6.0, 40, H0), step_mm=1.0)
    tilt = math.radians(15)
    return make_log(log.t, log.position, (-math.sin(tilt), 0.0, -math.cos(tilt)))


@pytest.fixture(scope="module")
def shelf():
    return shelf_over_floor(1.0)[0], tilted_shelf_pass()


@pytest.mark.parametrize("model", [gun(), gun(efficiency=parse_efficiency_spec("angle")), gun(Beta(12.0, 1.5)),
                                   gun(shadows="off")], ids=["shadows", "efficiency", "beta", "no-shadows"])
def test_leaving_out_the_pairs_past_the_cut_off_changes_nothing(shelf, model, monkeypatch):
    surface, log = shelf
    culled = deposit(surface, log, model)
    seen_far = np.isfinite(culled.track_distance_mm) & (culled.track_distance_mm > model.footprint.cutoff_mm)
    assert seen_far.any()  # some pairs were past the cut-off radius, so the reject was exercised
    monkeypatch.setattr(pair_terms, "ROUND_OFF", 1e300)  # no seen pair is past so wide a cut-off
    every = deposit(surface, log, model)
    for field in FIELDS:
        np.testing.assert_array_equal(getattr(culled, field), getattr(every, field), err_msg=field)
    assert (culled.rays, culled.evaluations) == (every.rays, every.evaluations)


def test_batches_that_split_a_leaf_count_every_pair_once(shelf, monkeypatch):
    # (the shelf's largest leaves take two blocks: batches split blocks and leaves alike)
    surface, log = shelf
    whole = deposit(surface, log, gun())
    monkeypatch.setattr(deposition, "_PAIRS_PER_BATCH", 997)  # not a multiple of any leaf's size
    split = deposit(surface, log, gun())
    for field in FIELDS:
        np.testing.assert_allclose(getattr(split, field), getattr(whole, field), rtol=1e-12, atol=0, err_msg=field)
    np.testing.assert_array_equal(split.track_distance_mm, whole.track_distance_mm)
    assert volume(surface, split.thickness_mm) == pytest.approx(volume(surface, whole.thickness_mm), rel=1e-12)
    assert split.evaluations == whole.evaluations


@given(st.integers(0, 2**31 - 1))
@settings(max_examples=15, deadline=None)
def test_near_pairs_hold_the_model_terms_of_every_pair_that_gets_spray(seed):
    rng = np.random.default_rng(seed)
    points = rng.uniform(-40, 40, (int(rng.integers(50, 800)), 3)) * (1, 1, 0.3)
    normals = rng.normal(size=points.shape) + (0, 0, 2)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    log = make_log([0.0, 0.1, 0.2], [[-20, 0, H0], [0, 10, H0], [20, -5, 90]], [[0.1, 0, -1], [0, 0.1, -1], [0, 0, -1]])
    model = gun(Beta(25.0, 2.0))
    steps = substeps(log, model)
    tree = vertex_tree(points)
    pairs = cone_pairs(tree, steps.position, steps.axis, model.footprint.cutoff_mm / H0, np.arange(len(steps)))
    r2_min = np.full(len(points), np.inf)
    near = near_pairs(leaf_blocks(tree, points, normals), steps.columns, pairs, (0, pairs.size),
                      (model.footprint, model.rate_mm3_s, H0),
                      np.ones(len(points), bool), r2_min, PairBuffer())
    vertex = pairs.touched[near.slot]
    np.testing.assert_array_equal(vertex, near.vertex)
    # the model of coatsim.spray.deposition, pair by pair
    d = points[vertex] - steps.position[near.step]
    da = np.einsum("ij,ij->i", d, steps.axis[near.step])
    facing = -np.einsum("ij,ij->i", d, normals[vertex])
    u = np.einsum("ij,ij->i", d, steps.e1[near.step]) * H0 / da
    v = np.einsum("ij,ij->i", d, steps.e2[near.step]) * H0 / da
    rate = model.rate_mm3_s * model.footprint.density(u, v) * H0**2 * facing / da**3
    assert np.all((da > 0) & (facing > 0))
    np.testing.assert_allclose(near.da, da, rtol=1e-12)
    np.testing.assert_allclose(near.facing, facing, rtol=1e-12)
    np.testing.assert_allclose(near.dist, np.linalg.norm(d, axis=1), rtol=1e-12)
    np.testing.assert_allclose(near.rate, rate, rtol=1e-9, atol=1e-12 * rate.max(initial=0))
    np.testing.assert_allclose(near.r2, u * u + v * v, rtol=1e-12)
    # every pair with spray is near; every vertex is in one leaf block once
    every = points[None, :, :] - steps.position[:, None, :]
    along = np.einsum("sij,sj->si", every, steps.axis)
    lateral2 = np.einsum("sij,sij->si", every, every) - along**2
    sprayed = (along > 0) & (lateral2 * (H0 / np.where(along > 0, along, 1)) ** 2 < (0.99 * 25.0) ** 2)
    sprayed &= np.einsum("sij,ij->si", every, normals) < 0
    got = set(zip(near.step.tolist(), vertex.tolist()))
    assert {(int(s), int(i)) for s, i in zip(*np.nonzero(sprayed))} <= got


@pytest.mark.parametrize("spread", [0.0, 1.0], ids=["even-leaves", "uneven-leaves"])
def test_leaf_blocks_hold_every_vertex_once_and_padding_never_seen(spread):
    rng = np.random.default_rng(3)
    points = rng.uniform(-50, 50, (3000, 3)) * np.exp(spread * rng.normal(size=(3000, 1)))
    normals = np.tile([0.0, 0.0, 1.0], (3000, 1))
    tree = vertex_tree(points)
    blocks = leaf_blocks(tree, points, normals)
    leaf = np.repeat(np.arange(tree.n_leaves), blocks.blocks)
    place = (np.arange(len(leaf)) - blocks.first[leaf])[:, None] * blocks.width + np.arange(blocks.width)
    real = place < tree.count[leaf, None]
    assert sorted(blocks.vertex[real].tolist()) == list(range(3000))
    np.testing.assert_array_equal(blocks.vertex[real], tree.order[(tree.start[leaf, None] + place)[real]])
    np.testing.assert_array_equal(blocks.rows[:3][:, real].T, points[blocks.vertex[real]])
    assert np.all(blocks.rows[3:][:, ~real] == 0)
    assert real.mean() > 0.6  # the width suits the leaves: padding stays a minority
    assert (blocks.blocks > 1).any() == bool(spread)  # uneven leaves: the large ones take several blocks

"""Parts like users bring (heldout_parts.py): CAD edges, fillets, a through-hole, a noisy scan
with a hole, a narrow arm, metres, flipped triangles; what a thermal-spray engineer relies on."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from heldout_parts import domed_flange, filleted_slab, l_bracket, noisy_dome, plate_with_arm
from scipy.spatial.transform import Rotation
from surface_helpers import SPACING, options

from coatsim.geometry.surface import Facing, FromPlane, Pass, SurfacePaths, part_from_arrays, plan
from coatsim.geometry.surface.verify import PlanCheckFailed, verify

BRACKET = l_bracket()


@pytest.mark.parametrize("pattern", ["raster", "geodesic", "boundary"])
def test_on_a_cad_bracket_every_normal_is_its_face_normal(pattern):
    # flat faces meeting at sharp edges: the gun's axis is the face's own normal everywhere,
    # never an average across an edge, and no pass runs over an edge
    vertices, faces = BRACKET
    paths = plan(part_from_arrays(vertices, faces), options(pattern=pattern, region=Facing((0.6, 0, 0.8), 60.0)))
    for p in paths.passes:
        n = p.normals
        assert np.allclose(n, n[0], atol=1e-9), "a pass crosses a sharp edge"
        assert np.isclose(np.abs(n[0]).max(), 1.0, atol=1e-9)
    assert paths.stats.normal_max_angle_deg < 1e-6 and paths.stats.normal_off_faces_deg < 1e-6
    assert any("sharp edges" in note for note in paths.notes)
    assert paths.stats.coverage > 0.94


def test_the_check_refuses_a_normal_averaged_across_a_sharp_edge():
    vertices, faces = BRACKET
    part = part_from_arrays(vertices, faces)
    paths = plan(part, options(region=Facing((0.6, 0, 0.8), 60.0)))
    assert verify(part, paths) < 1e-6
    # the point of the base's top face nearest the upright, its normal tilted halfway to the
    # upright's (what smoothing across the edge gives): 45 deg off the face it lies on
    points = np.concatenate([p.points for p in paths.passes])
    k = int(np.argmin(np.where(points[:, 2] > 7.9, points[:, 0], np.inf)))
    bad = [Pass(p.points, p.normals.copy(), p.closed, p.lead_in, p.lead_out) for p in paths.passes]
    sizes = np.cumsum([len(p.points) for p in bad])
    which = int(np.searchsorted(sizes, k, side="right"))
    bad[which].normals[k - (sizes[which - 1] if which else 0)] = [math.sqrt(0.5), 0.0, math.sqrt(0.5)]
    tilted = SurfacePaths(paths.mesh, paths.pattern, paths.spacing_mm, paths.standoff_mm, paths.ripple_pct,
                          tuple(bad), paths.stats)
    with pytest.raises(PlanCheckFailed, match="outside the faces around it"):
        verify(part, tilted)


@pytest.mark.parametrize("pattern", ["raster", "geodesic", "boundary"])
def test_a_dome_on_a_flange_plans_across_its_crease(pattern):
    # a lathe part: the cap meets the flat ring at a 53 deg crease; a raster point lifted onto the
    # cap's smooth surface right at the crease lies as near the ring's facet as the cap's, and
    # takes the cap's normal: the check accepts either side of a sharp edge (it refused the plan)
    vertices, faces = domed_flange()
    part = part_from_arrays(vertices, faces)
    paths = plan(part, options(pattern=pattern))
    assert verify(part, paths) < 5.0 and paths.stats.coverage > 0.95
    for p in paths.passes:
        on_ring = p.points[:, 2] < 1e-6
        assert np.all(p.normals[on_ring, 2] > 0.999) or not on_ring.any()


def test_a_flat_rings_ridge_gives_no_sliver_passes():
    # the distance from a ring's border peaks along its middle circle: the level just below the
    # peak broke into 141 loops under 5 mm, each a pass; level curves that short are left out
    t = np.linspace(0, 2 * math.pi, 72, endpoint=False)
    rings = np.linspace(70.0, 100.0, 5)
    vertices = np.vstack([np.column_stack([r * np.cos(t), r * np.sin(t), np.zeros_like(t)]) for r in rings])
    k = np.arange(72)
    faces = np.vstack([np.column_stack([j * 72 + k, (j + 1) * 72 + k, (j + 1) * 72 + (k + 1) % 72]) for j in range(4)]
                      + [np.column_stack([j * 72 + k, (j + 1) * 72 + (k + 1) % 72, j * 72 + (k + 1) % 72]) for j in range(4)])
    paths = plan(part_from_arrays(vertices, faces), options(pattern="boundary"))
    lengths = [float(np.linalg.norm(np.diff(p.points, axis=0), axis=1).sum()) for p in paths.passes]
    assert min(lengths) >= SPACING / 2 and len(lengths) <= 6 and paths.stats.coverage > 0.97
    assert any("level curves shorter than half a spacing" in n for n in paths.notes)


def test_passes_inside_the_part_are_named_in_a_note():
    # an L of two boxes saved as one file without their union (an assembly's bodies): the base's
    # top face runs on under the upright, and the gun 100 mm over it would stand in the upright;
    # the one solid bracket is clear
    import trimesh

    base = trimesh.creation.box(extents=(127.0, 76.0, 10.0))
    upright = trimesh.creation.box(extents=(10.0, 76.0, 63.0))
    upright.apply_translation((58.0, 0.0, 36.5))
    both = trimesh.util.concatenate([base, upright])
    paths = plan(part_from_arrays(np.asarray(both.vertices), np.asarray(both.faces)),
                 options(region=Facing((0, 0, 1), 30.0)))
    note = next(n for n in paths.notes if "within the stand-off (100 mm)" in n)
    assert 55.0 < float(re.search(r"the part ([\d.]+) mm out", note).group(1)) < 65.0  # the upright's top, 63 over
    vertices, faces = BRACKET
    clear = plan(part_from_arrays(vertices, faces), options(region=Facing((0, 0, 1), 30.0)))
    assert not [n for n in clear.notes if "stand-off" in n]
    # facing obliquely, the region takes the walls of the base's hole (20 mm across in x): from
    # them the gun would stand in the opposite wall
    hole = plan(part_from_arrays(vertices, faces), options(region=Facing((0.6, 0, 0.8), 60.0)))
    note = next(n for n in hole.notes if "within the stand-off (100 mm)" in n)
    assert abs(float(re.search(r"the part ([\d.]+) mm out", note).group(1)) - 20.0) < 0.5


def test_fillets_are_followed_and_the_flat_top_keeps_its_normal():
    vertices, faces = filleted_slab(n_profile=96, n_along=40)
    paths = plan(part_from_arrays(vertices, faces), options(region=Facing((0, 0, 1)), step_direction=(1, 0, 0)))
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    # the top face is flat 2 smoothing lengths in from its fillets: the normal there is +z
    flat = np.abs(points[:, 0]) < 40.0 - 2 * 5.0
    # (the smoothing's tail reaches past two lengths: a fraction of a degree)
    tilt = np.degrees(np.arccos(np.clip(normals[flat, 2], -1, 1)))
    assert flat.any() and tilt.max() < 1.0
    # on the fillets the normal turns with the surface, within the cone of the faces near it
    assert paths.stats.normal_off_faces_deg < 1.0
    # the fillets' sections are part of the passes (the planes run across them, no sharp edge)
    assert points[:, 0].max() > 45.0 and points[:, 0].min() < -45.0
    assert paths.stats.coverage > 0.99
    assert paths.stats.spacing_max_mm <= 1.01 * SPACING


@pytest.mark.parametrize("pattern", ["raster", "geodesic"])
def test_a_noisy_scanned_dome_with_a_hole(pattern):
    vertices, faces = noisy_dome()
    paths = plan(part_from_arrays(vertices, faces), options(pattern=pattern))
    points = np.concatenate([p.points for p in paths.passes])
    normals = np.concatenate([p.normals for p in paths.passes])
    # the noise (0.1 mm on 1.7 mm triangles, faces tilted by several degrees) does not wobble the
    # gun: within 1.5 deg of the sphere's true normal, except near the open borders
    radial = points / np.linalg.norm(points, axis=1)[:, None]
    off = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals, radial), -1, 1)))
    inner = (np.hypot(points[:, 0], points[:, 1]) < 65.0) & (np.hypot(points[:, 0] - 25, points[:, 1] - 10) > 20)
    assert np.percentile(off[inner], 99) < 1.5
    s = paths.stats
    assert s.coverage > 0.97 and s.spacing_max_mm < 1.1 * SPACING and s.spacing_median_mm == pytest.approx(
        SPACING, rel=0.03)


@pytest.mark.parametrize("pattern", ["raster", "geodesic", "boundary"])
def test_an_arm_narrower_than_a_spacing_gets_a_pass(pattern):
    vertices, faces = plate_with_arm()
    paths = plan(part_from_arrays(vertices, faces), options(pattern=pattern, region=Facing((0, 0, 1))))
    points = np.concatenate([p.points for p in paths.passes])
    on_arm = points[points[:, 0] > 105.0]
    assert len(on_arm) and np.abs(on_arm[:, 1] - 30.0).max() < 4.0
    assert paths.stats.coverage > 0.96
    assert paths.stats.spacing_max_mm < 1.1 * SPACING  # no gap measured across the arm's length
    if pattern == "raster":
        assert any("added" in note for note in paths.notes)


def _moved(paths: SurfacePaths, rotation: np.ndarray, shift: np.ndarray) -> list[np.ndarray]:
    return [p.points @ rotation.T + shift for p in paths.passes]


def test_the_bracket_moved_rigidly_carries_its_passes():
    vertices, faces = BRACKET
    rotation = Rotation.from_euler("xyz", [23.0, -41.0, 67.0], degrees=True).as_matrix()
    shift = np.array([120.0, -35.0, 410.0])
    gun = np.array([0.6, 0.0, 0.8])
    base = plan(part_from_arrays(vertices, faces), options(region=Facing(tuple(gun), 60.0), step_direction=(0, 1, 0)))
    moved = plan(part_from_arrays(vertices @ rotation.T + shift, faces),
                 options(region=Facing(tuple(rotation @ gun), 60.0), step_direction=tuple(rotation @ [0, 1.0, 0])))
    assert len(moved.passes) == len(base.passes)
    # the same passes: the same ends and length (pieces of equal area, such as the upright's top
    # and the base's end, may swap their turn in the spraying order; the triangles the planner
    # refines a flat face into may differ, and with them the points along a straight pass)
    for a, p in zip(_moved(base, rotation, shift), base.passes):
        ends = np.array([a[0], a[-1]])
        match = [b for b in moved.passes if abs(b.length_mm - p.length_mm) < 1e-6
                 and min(np.abs(ends - b.points[[0, -1]]).max(), np.abs(ends[::-1] - b.points[[0, -1]]).max()) < 1e-6]
        assert len(match) == 1
        assert np.allclose(p.normals[0] @ rotation.T, match[0].normals[0], atol=1e-6)


def test_a_finer_bracket_moves_the_passes_far_less_than_the_spacing():
    coarse = plan(part_from_arrays(*l_bracket(2.0)), options(region=Facing((0.6, 0, 0.8), 60.0)))
    fine = plan(part_from_arrays(*l_bracket(1.0)), options(region=Facing((0.6, 0, 0.8), 60.0)))
    assert len(coarse.passes) == len(fine.passes)
    for a, b in zip(coarse.passes, fine.passes):
        gap = np.min(np.linalg.norm(a.points[:, None] - b.points[None], axis=2), axis=1)
        assert gap.max() < 0.05 * SPACING


def test_a_bracket_in_metres_with_flipped_triangles_plans_as_in_millimetres():
    vertices, faces = BRACKET
    reference = plan(part_from_arrays(vertices, faces), options(region=Facing((0.6, 0, 0.8), 60.0)))
    flipped = faces.copy()
    turn = np.random.default_rng(5).random(len(faces)) < 0.3
    flipped[turn] = flipped[turn][:, ::-1]
    metres = plan(part_from_arrays(vertices / 1000.0, flipped, units="m"), options(region=Facing((0.6, 0, 0.8), 60.0)))
    assert any("turned" in note for note in metres.notes)
    assert len(metres.passes) == len(reference.passes)
    for a, b in zip(reference.passes, metres.passes):
        assert np.abs(a.points - b.points).max() < 1e-6 and np.allclose(a.normals, b.normals, atol=1e-9)


def test_faces_a_start_plane_does_not_reach_take_passes_from_their_border():
    # the plane x = 60 cuts the base's top; the upright's face lies beyond a sharp edge
    vertices, faces = BRACKET
    paths = plan(part_from_arrays(vertices, faces), options(pattern="geodesic", start=FromPlane((60, 0, 0), (1, 0, 0)),
                                                            region=Facing((0.6, 0, 0.8), 60.0)))
    points = np.concatenate([p.points for p in paths.passes])
    assert np.any(np.isclose(points[:, 0], 8.0) & (points[:, 2] > 20.0))  # passes on the upright's face
    assert any("take passes from their own border" in note for note in paths.notes)
    assert paths.stats.coverage > 0.95


@pytest.mark.slow  # a minute: the strips are refined to the planning mesh's edge
def test_a_filleted_box_of_long_thin_facets_keeps_its_passes_on_the_part():
    """A CAD export of a box with rounded edges: the hull of its corner spheres, each straight
    fillet one strip of triangles the length of a side. The strips' corner normals turn along
    their length where the surface does not; the lift onto the smooth surface is capped by each
    facet's width (it threw points 4.7 mm off the part; the facets sag 0.3 mm)."""
    import trimesh

    ball = trimesh.creation.icosphere(subdivisions=3, radius=15.0).vertices
    corners = [ball + [sx * 85.0, sy * 60.0, sz * 15.0] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    hull = trimesh.convex.convex_hull(np.vstack(corners))
    paths = plan(part_from_arrays(hull.vertices, hull.faces),
                 options(region=Facing((0, 0, 1), 45.0), step_direction=(0, 1, 0)))
    points = np.concatenate([p.points for p in paths.passes])
    q = np.abs(points) - [85.0, 60.0, 15.0]
    exact = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0) - 15.0  # signed distance
    assert np.abs(exact).max() < 0.2 and len(points) > 100 and np.abs(points[:, 0]).max() > 86.0  # on the fillets


@pytest.mark.parametrize("seed", [0, 3])
def test_a_scans_folded_slivers_do_not_turn_a_pass_normal(seed):
    """A dome scanned as random points with 0.2 mm of noise: a few triangles fold over. A pass
    point on one was judged to lean into the part and its normal turned to the mean of the faces
    there, 160-174 degrees off its neighbours'; folded and sliver faces judge nothing now."""
    from scipy.spatial import Delaunay

    rng = np.random.default_rng(seed)
    uv = rng.uniform(-120, 120, (2500, 2))
    uv = uv[np.hypot(*uv.T) <= 120]
    rim = np.linspace(0, 2 * math.pi, 120, endpoint=False)
    uv = np.vstack((uv, 120 * np.column_stack((np.cos(rim), np.sin(rim)))))
    faces = Delaunay(uv).simplices
    z = np.sqrt(200**2 - (uv**2).sum(axis=1)) - math.sqrt(200**2 - 120**2)
    vertices = np.column_stack((uv, z)) + rng.normal(0, 0.2, (len(uv), 3))
    paths = plan(part_from_arrays(vertices, faces), options(region=Facing((0, 0, 1), 60.0), step_direction=(0, 1, 0)))
    turns = [np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", p.normals[1:], p.normals[:-1]), -1, 1))).max()
             for p in paths.passes]
    assert max(turns) < 10.0 and len(paths.passes) > 5

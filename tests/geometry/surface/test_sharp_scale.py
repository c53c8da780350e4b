"""Sharp edges judged at a gun's scale (features.sharp_at_scale): a scan on uniformly random
points has slivers whose noise tilts them far apart, yet plans like the clean sheet; a thin
plate's rim and a box's edges stay sharp; slivers that nothing near tilts are settled without
growing their patches."""

from __future__ import annotations

import re

import numpy as np
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import Delaunay
from surface_helpers import SPACING, options

from coatsim.geometry.surface import part_from_arrays, plan
from coatsim.geometry.surface.features import SHARP_EDGE_DEG


def random_scan(noise_mm: float, seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """A wavy 140 x 90 mm sheet on uniformly random points (about 4 mm apart, as a scanner's
    Delaunay triangulation: slivers of all shapes) with ``noise_mm`` of noise in z."""
    rng = np.random.default_rng(seed)
    points = rng.uniform([-70, -45], [70, 45], size=(900, 2))
    z = 8 * np.sin(points[:, 0] / 40) * np.cos(points[:, 1] / 50) + rng.normal(0, noise_mm, len(points))
    return np.column_stack([points, z]), Delaunay(points).simplices


def test_a_noisy_scan_on_random_points_plans_like_the_clean_sheet():
    vertices, faces = random_scan(0.3)
    normals = trimesh.Trimesh(vertices, faces, process=False).face_normals
    pairs = trimesh.Trimesh(vertices, faces, process=False).face_adjacency
    cos = np.abs(np.einsum("ij,ij->i", normals[pairs[:, 0]], normals[pairs[:, 1]]))
    assert (cos < np.cos(np.radians(SHARP_EDGE_DEG))).sum() > 20  # slivers meeting like a box's edges
    noisy = plan(part_from_arrays(vertices, faces, "scan"), options(step_direction=(0, 1, 0)))
    clean = plan(part_from_arrays(*random_scan(0.0), "clean"), options(step_direction=(0, 1, 0)))
    # judged by the faces' own normals: 903 mm of "sharp" edges cutting the sheet into islands;
    # at the smoothing length a few slivers along the border are left
    sharp = [float(re.search(r"has ([\d.]+) mm of sharp edges", n).group(1)) for n in noisy.notes if "sharp edges" in n]
    assert sum(sharp) < 50.0 and not [n for n in noisy.notes if "island" in n]
    # as many passes a spacing or longer; the noise may leave a patch at the region's end that
    # a short pass fills (a level curve there was a loop of 0.1 mm, left out)
    spans = lambda paths: [float(np.linalg.norm(np.diff(p.points, axis=0), axis=1).sum()) for p in paths.passes]  # noqa: E731
    assert abs(sum(x >= SPACING for x in spans(noisy)) - sum(x >= SPACING for x in spans(clean))) <= 1
    assert sum(x for x in spans(noisy) if x < SPACING) < 2 * SPACING
    assert noisy.stats.coverage > 0.98 and noisy.stats.normal_off_faces_deg < 5.0


def test_a_thin_plates_rim_and_a_boxs_edges_stay_sharp():
    from coatsim.geometry.surface.features import sharp_at_scale

    for size in ((100.0, 60.0, 2.0), (40.0, 40.0, 40.0)):
        box = trimesh.creation.box(size).subdivide().subdivide()
        vertices, faces = np.asarray(box.vertices), np.asarray(box.faces)
        pairs, sharp = sharp_at_scale(vertices, faces, 5.0)
        normals = box.face_normals
        crease = np.einsum("ij,ij->i", normals[pairs[:, 0]], normals[pairs[:, 1]]) < 0.5
        assert crease.sum() > 0 and np.array_equal(sharp, crease)


def sliver_d_prism(radius_mm: float, step_mm: float, height_mm: float = 20.0) -> tuple[np.ndarray, np.ndarray]:
    """An open prism on a D (half a circle closed by its diameter) in slivers, as the planner
    refines a CAD part cut in many narrow facets: profile points 0.15 of ``step_mm`` apart,
    rings ``step_mm`` apart; the flat meets the round at two sharp edges."""
    gap = 0.15 * step_mm
    arc = np.linspace(0.0, np.pi, round(np.pi * radius_mm / gap) + 1)
    flat = np.linspace(-radius_mm, radius_mm, round(2 * radius_mm / gap) + 1)[1:-1]
    profile = np.vstack([np.column_stack([radius_mm * np.cos(arc), radius_mm * np.sin(arc)]),
                         np.column_stack([flat, np.zeros_like(flat)])])
    n = len(profile)
    heights = np.linspace(0.0, height_mm, round(height_mm / step_mm) + 1)
    vertices = np.vstack([np.column_stack([profile, np.full(n, z)]) for z in heights])
    k = np.arange(n)
    quads = np.vstack([np.column_stack([r + k, r + (k + 1) % n, r + n + (k + 1) % n, r + n + k])
                       for r in n * np.arange(len(heights) - 1)])
    return vertices, np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])


@settings(max_examples=15, deadline=None)
@given(st.floats(30.0, 60.0), st.floats(2.0, 4.0), st.floats(1.0, 5.0), st.integers(0, 2**16))
def test_a_settled_sliver_has_every_face_near_it_within_the_persistent_angle(radius_mm, step_mm, ball_mm, seed):
    """features._settled is a proof, not an estimate: a part of narrow facets with sharp edges,
    turned at random, checked against every face of the mesh for the settled slivers nearest
    the edges and some others."""
    from scipy.spatial.transform import Rotation

    from coatsim.geometry.surface.features import PERSISTENT_SHARP_DEG, _settled, _slivers

    vertices, faces = sliver_d_prism(radius_mm, step_mm)
    turn = Rotation.random(random_state=seed).as_matrix()
    vertices = vertices @ turn.T
    normals = trimesh.Trimesh(vertices, faces, process=False).face_normals
    seeds = np.flatnonzero(_slivers(vertices, faces))
    settled = _settled(vertices, faces, normals, seeds, ball_mm)
    assert settled.any() and not settled.all()  # the middle of the round or the flat settles, never an edge
    triangles = vertices[faces]
    centres = triangles[seeds[settled]].mean(axis=1) @ turn  # in the prism's own frame
    edge = np.argsort(np.minimum(np.hypot(centres[:, 0] - radius_mm, centres[:, 1]),
                                 np.hypot(centres[:, 0] + radius_mm, centres[:, 1])))
    for k in seeds[settled][np.concatenate([edge[:40], np.random.default_rng(seed).permutation(edge)[:20]])]:
        centre = triangles[k].mean(axis=0)
        gap = trimesh.triangles.closest_point(triangles, np.repeat(centre[None], len(faces), axis=0)) - centre
        near = np.linalg.norm(gap, axis=1) <= ball_mm
        assert (normals[near] @ normals[k] >= np.cos(np.radians(PERSISTENT_SHARP_DEG)) - 1e-12).all()


def test_one_tilted_sliver_in_a_flat_sheet_unsettles_the_slivers_round_it():
    """A cube's mean normal hides one tilted face among hundreds; its cone does not."""
    from coatsim.geometry.surface.features import _settled, _slivers

    x, y = np.meshgrid(np.arange(0.0, 60.0, 0.3), np.arange(0.0, 40.0, 4.0))
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    n = x.shape[1]
    k = np.arange(n - 1)
    quads = np.vstack([np.column_stack([r + k, r + k + 1, r + n + k + 1, r + n + k])
                       for r in n * np.arange(x.shape[0] - 1)])
    faces = np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    bump = np.argmin(np.linalg.norm(vertices[:, :2] - [30.0, 20.0], axis=1))
    vertices[bump, 2] = 1.0  # its faces tilt 73 deg
    normals = trimesh.Trimesh(vertices, faces, process=False).face_normals
    seeds = np.flatnonzero(_slivers(vertices, faces))
    settled = _settled(vertices, faces, normals, seeds, 3.0)
    centres = vertices[faces[seeds]].mean(axis=1)
    assert not settled[np.linalg.norm(centres[:, :2] - [30.0, 20.0], axis=1) < 3.0].any()
    assert settled[np.linalg.norm(centres[:, :2] - [30.0, 20.0], axis=1) > 30.0].all()

"""Sharp edges judged at a gun's scale (features.sharp_at_scale): a scan on uniformly random
points has slivers whose noise tilts them far apart, yet plans like the clean sheet; a thin
plate's rim and a box's edges stay sharp."""

from __future__ import annotations

import re

import numpy as np
import trimesh
from scipy.spatial import Delaunay
from surface_helpers import options

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
    assert abs(len(noisy.passes) - len(clean.passes)) <= 1
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

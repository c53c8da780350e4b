"""Sharp edges and the feature regions they bound.

A CAD part's faces meet at sharp edges (the edge of a plate, a chamfer); a gun cannot follow
its normal round one, and averaging normals across one gives an axis that is off both faces
(45 deg at a right-angled edge). An edge is sharp when the normals of its two faces differ by
more than ``SHARP_EDGE_DEG``: more than a scan's noise or the facets of a curved surface
tessellated finely enough to plan on (a cylinder in 10 facets or more), less than the edges
of a box or a plate. Feature regions are the pieces of the surface joined by edges that are
not sharp; normals are smoothed within a region and passes stay in one.

At a gun's scale (``sharp_at_scale``): on a scan of random points two slivers of a flat sheet
meet at 60 deg or more while the sheet around them is flat to a degree, and such edges chain
up into "creases" that cut the sheet into islands. So an edge is sharp there only if its sides
still meet at more than ``PERSISTENT_SHARP_DEG`` when each side's face normals are averaged
(by area) over the faces within a smoothing length of the edge's midpoint, reached from the
edge without leaving that ball, on that side of the plane through the edge between the two
faces' normals, and facing the way the two faces do (not the far skin of a thin plate). A
mean normal over a patch is set by the patch's border, so the noise shrinks with the length
while a box's, a bracket's or an icosahedron's edge keeps its whole angle. A sliver's normal
is its noise: a side's mean leaves out its faces narrower than ``FRINGE_FRACTION`` of the
length (twice the area over the longest edge) unless it has no other. A side of such faces
only that covers less than ``FRINGE_FRACTION`` of its half of the ball and reaches the mesh's
border is a fringe (the slivers a Delaunay triangulation leaves along a scan's convex border, a
lip the footprint does not resolve), not a face, and its edge is not sharp; a thin plate's rim,
not on a border, stays sharp. For the same reason a sliver (narrower than ``SLIVER_ASPECT`` of
its longest edge) whose normal is more than ``PERSISTENT_SHARP_DEG`` off the mean normal around
it is chosen for the region by that mean (``selection_normals``).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from coatsim.geometry.surface.topology import face_components, face_pairs, manifold_split, mesh_edges

if TYPE_CHECKING:
    from scipy.sparse import csr_matrix

#: an edge whose faces' normals differ by more than this is sharp (at the faces' own scale) ...
SHARP_EDGE_DEG = 40.0
#: ... and stays sharp at a gun's scale while its two sides' mean normals differ by more than this
PERSISTENT_SHARP_DEG = 20.0
#: a face narrower (twice its area over its longest edge) than this fraction of its longest edge is a sliver
SLIVER_ASPECT = 0.2
#: a face narrower than this fraction of the length is left out of a side's mean normal; a side of
#: such faces covering less than this fraction of its half ball, at the mesh's border, is a fringe
FRINGE_FRACTION = 0.5
#: a face's share within a ball is counted on a barycentric grid of this many steps
SHARE_STEPS = 8
#: sharp edges judged at once at a gun's scale (bounds the memory of the edge-face pairs)
SHARP_CHUNK = 2048


def smooth_pairs(faces: np.ndarray, face_n: np.ndarray) -> np.ndarray:
    """Pairs of faces (K, 2) sharing a manifold edge whose own normals (``face_n``, unit,
    faces wound consistently) differ by at most ``SHARP_EDGE_DEG``."""
    pairs, _ = face_pairs(faces, mesh_edges(faces))
    cos = np.einsum("ij,ij->i", face_n[pairs[:, 0]], face_n[pairs[:, 1]])
    return pairs[cos >= math.cos(math.radians(SHARP_EDGE_DEG))]


def feature_split(faces: np.ndarray, face_n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Faces on vertices split along sharp edges (``smooth_pairs``): each vertex gets one copy
    per fan of its faces joined by edges that are neither sharp nor non-manifold, so a sharp
    edge becomes a border on both sides. Returns (new faces, original vertex of each new vertex)."""
    return manifold_split(faces, smooth_pairs(faces, face_n))


def shared_corners(faces: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """The two vertices (K, 2) that each pair of faces ``pairs`` (K, 2) shares."""
    first, second = faces[pairs[:, 0]], faces[pairs[:, 1]]
    on_both = np.column_stack([(second == first[:, [k]]).any(axis=1) for k in range(3)])
    return np.sort(np.where(on_both, first, -1), axis=1)[:, 1:]  # the third corner is -1


def edge_length_mm(vertices: np.ndarray, faces: np.ndarray, pairs: np.ndarray) -> float:
    """The total length of the edges shared by the pairs of faces ``pairs`` (K, 2), mm."""
    ends = shared_corners(faces, pairs)
    return float(np.linalg.norm(vertices[ends[:, 0]] - vertices[ends[:, 1]], axis=1).sum())


def sharp_at_scale(vertices: np.ndarray, faces: np.ndarray, scale_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of faces (K, 2) sharing a manifold edge, and whether each edge is sharp at the
    scale ``scale_mm`` (K,) bool (see the module docstring). The faces may be wound
    inconsistently (a file as read): each piece is judged as if wound alike."""
    edges = mesh_edges(faces)
    pairs, consistent = face_pairs(faces, edges)
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a) * _winding(len(faces), pairs, consistent)[:, None]
    area = 0.5 * np.linalg.norm(cross, axis=1)
    face_n = cross / np.maximum(2 * area, 1e-300)[:, None]
    cos = np.einsum("ij,ij->i", face_n[pairs[:, 0]], face_n[pairs[:, 1]])
    sharp = cos < math.cos(math.radians(SHARP_EDGE_DEG))
    candidates = np.flatnonzero(sharp)
    if len(candidates) and scale_mm > 0:
        adjacency = _adjacency(len(faces), pairs)
        longest = np.linalg.norm(np.stack([b - a, c - b, a - c]), axis=2).max(axis=0)
        narrow = 2 * area < FRINGE_FRACTION * scale_mm * longest
        kinds = (narrow, (edges.face_count[edges.of_face] != 2).any(axis=1))
        for chunk in np.array_split(candidates, math.ceil(len(candidates) / SHARP_CHUNK)):
            sharp[chunk] = _persists(vertices, faces, face_n, area, kinds, adjacency, pairs[chunk], scale_mm)
    return pairs, sharp


def feature_labels(vertices: np.ndarray, faces: np.ndarray, scale_mm: float) -> np.ndarray:
    """The feature region of each face at the scale ``scale_mm``, (m,) int (``sharp_at_scale``)."""
    pairs, sharp = sharp_at_scale(vertices, faces, scale_mm)
    return face_components(len(faces), pairs[~sharp])[1]


def selection_normals(vertices: np.ndarray, faces: np.ndarray, scale_mm: float) -> np.ndarray:
    """Unit face normals (m, 3) (faces wound consistently) for choosing the faces a gun sees: a
    sliver's own normal is its noise (a tilted sliver would leave a pinhole in the region that
    splits the passes), so a sliver more than ``PERSISTENT_SHARP_DEG`` off the area-weighted
    mean normal of the faces within ``scale_mm`` of its centre (reached without crossing an edge
    sharp at that scale) takes that mean; every other face keeps its own."""
    cross = np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]], vertices[faces[:, 2]] - vertices[faces[:, 0]])
    face_n = cross / np.maximum(np.linalg.norm(cross, axis=1), 1e-300)[:, None]
    sliver = np.flatnonzero(_slivers(vertices, faces))
    if len(sliver) and scale_mm > 0:
        sliver = sliver[~_settled(vertices, faces, face_n, sliver, scale_mm)]
    if not len(sliver) or scale_mm <= 0:
        return face_n
    pairs, sharp = sharp_at_scale(vertices, faces, scale_mm)
    rows, cols = _patches(vertices, faces, _adjacency(len(faces), pairs[~sharp]), np.arange(len(sliver)), sliver,
                          vertices[faces[sliver]].mean(axis=1), scale_mm)
    summed = np.zeros((len(sliver), 3))
    np.add.at(summed, rows, cross[cols])  # twice the area times the unit normal
    mean = summed / np.maximum(np.linalg.norm(summed, axis=1), 1e-300)[:, None]
    off = np.einsum("ij,ij->i", mean, face_n[sliver]) < math.cos(math.radians(PERSISTENT_SHARP_DEG))
    out = face_n.copy()
    out[sliver[off]] = mean[off]
    return out


def _slivers(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Whether each face is narrower than ``SLIVER_ASPECT`` of its longest edge, (m,) bool."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    longest = np.linalg.norm(np.stack([b - a, c - b, a - c]), axis=2).max(axis=0)
    return np.linalg.norm(np.cross(b - a, c - a), axis=1) < SLIVER_ASPECT * longest**2


def _settled(vertices: np.ndarray, faces: np.ndarray, face_n: np.ndarray, seeds: np.ndarray,
             radius_mm: float) -> np.ndarray:
    """Whether every face within ``radius_mm`` of each seed face's centre has its normal within
    ``PERSISTENT_SHARP_DEG`` of the seed's (so any mean of them is too), (k,) bool; proven, not
    measured face by face: such a face has its corners within the radius plus the longest edge,
    so in the 27 cubes of that size round the centre's, and each cube's faces (those with a
    corner in it) lie in a cone of normals about their mean."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    size = radius_mm + float(np.linalg.norm(np.stack([b - a, c - b, a - c]), axis=2).max())
    cells, at = np.unique(np.floor(vertices / size).astype(np.int64), axis=0, return_inverse=True)
    corner_cell, corner_face = at.ravel()[faces.ravel()], np.repeat(np.arange(len(faces)), 3)
    mean = np.zeros((len(cells), 3))
    np.add.at(mean, corner_cell, face_n[corner_face])
    mean /= np.maximum(np.linalg.norm(mean, axis=1), 1e-300)[:, None]
    widest = np.zeros(len(cells))  # each cube's cone half-angle, rad
    np.maximum.at(widest, corner_cell,
                  np.arccos(np.clip(np.einsum("ij,ij->i", mean[corner_cell], face_n[corner_face]), -1.0, 1.0)))
    centre_cell = np.floor(vertices[faces[seeds]].mean(axis=1) / size).astype(np.int64)
    low = cells.min(axis=0) - 1
    span = cells.max(axis=0) - low + 2

    def scalar(cell: np.ndarray) -> np.ndarray:  # a cube's index in the order np.unique sorts them
        return ((cell[:, 0] - low[0]) * span[1] + cell[:, 1] - low[1]) * span[2] + cell[:, 2] - low[2]

    known, settled = scalar(cells), np.ones(len(seeds), dtype=bool)
    for step in np.array(np.meshgrid(*[(-1, 0, 1)] * 3)).reshape(3, -1).T:
        key = scalar(centre_cell + step)
        at_key = np.minimum(np.searchsorted(known, key), len(cells) - 1)
        there = known[at_key] == key
        off = np.arccos(np.clip(np.einsum("ij,ij->i", mean[at_key], face_n[seeds]), -1.0, 1.0)) + widest[at_key]
        settled &= ~there | (off <= math.radians(PERSISTENT_SHARP_DEG))
    return settled


def _adjacency(n_faces: int, pairs: np.ndarray) -> csr_matrix:
    """The faces' adjacency, a symmetric (m, m) CSR matrix of ones at the ``pairs`` (K, 2)."""
    from scipy.sparse import coo_matrix

    ends = np.concatenate([pairs, pairs[:, ::-1]])
    return coo_matrix((np.ones(len(ends)), (ends[:, 0], ends[:, 1])), shape=(n_faces,) * 2).tocsr()


def _share_inside(triangles: np.ndarray, centres: np.ndarray, radius_mm: float) -> np.ndarray:
    """About which share of each triangle (k, 3, 3) lies within ``radius_mm`` of its centre
    (k, 3): the share of the points of a barycentric grid of ``SHARE_STEPS`` steps inside."""
    i, j = np.meshgrid(np.arange(SHARE_STEPS + 1), np.arange(SHARE_STEPS + 1))
    keep = i + j <= SHARE_STEPS
    weights = np.column_stack([i[keep], j[keep], SHARE_STEPS - i[keep] - j[keep]]) / SHARE_STEPS
    inside = np.zeros(len(triangles))
    for w in weights:
        inside += np.linalg.norm(np.einsum("k,ikl->il", w, triangles) - centres, axis=1) <= radius_mm
    return inside / len(weights)


def _winding(n_faces: int, pairs: np.ndarray, consistent: np.ndarray) -> np.ndarray:
    """+1 or -1 per face (m,): turning the faces at -1 winds each orientable piece alike (a face
    of a piece that cannot be oriented keeps +1)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    # a face as read (f) or turned (f + m): consistent neighbours share a state (as normals.orient)
    f, g = pairs[:, 0], pairs[:, 1]
    rows = np.concatenate([f, f + n_faces])
    cols = np.concatenate([np.where(consistent, g, g + n_faces), np.where(consistent, g + n_faces, g)])
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(2 * n_faces,) * 2)
    label = connected_components(graph, directed=False)[1]
    return np.where(label[:n_faces] <= label[n_faces:], 1.0, -1.0)


def _persists(vertices: np.ndarray, faces: np.ndarray, face_n: np.ndarray, area: np.ndarray,
              kinds: tuple[np.ndarray, np.ndarray], adjacency: csr_matrix, pairs: np.ndarray,
              scale_mm: float) -> np.ndarray:
    """Whether the sides of each edge shared by ``pairs`` (K, 2) (sharp at the faces' scale)
    meet at more than ``PERSISTENT_SHARP_DEG`` at the scale ``scale_mm`` with neither side a
    fringe (module docstring); ``kinds``: whether each face is narrow, and on the mesh's border."""
    ends = shared_corners(faces, pairs)
    middle = vertices[ends].mean(axis=1)
    between = face_n[pairs[:, 0]] + face_n[pairs[:, 1]]
    splitter = np.cross(vertices[ends[:, 1]] - vertices[ends[:, 0]], between)
    side_of_first = np.sign(np.einsum("ij,ij->i", vertices[faces[pairs[:, 0]]].mean(axis=1) - middle, splitter))
    rows, cols = _patches(vertices, faces, adjacency, np.repeat(np.arange(len(pairs)), 2), pairs.ravel(), middle,
                          scale_mm)
    normal = face_n[cols]
    side = np.sign(np.einsum("ij,ij->i", vertices[faces[cols]].mean(axis=1) - middle[rows], splitter[rows]))
    weight = area[cols] * (np.einsum("ij,ij->i", normal, between[rows]) > 0)  # not a thin part's far skin
    narrow, on_border = kinds[0][cols], kinds[1][cols]
    inside = area[cols] * _share_inside(vertices[faces[cols]], middle[rows], scale_mm)
    means, fringe = [], np.zeros(len(pairs), dtype=bool)
    for wanted in (side_of_first, -side_of_first):
        on = side == wanted[rows]
        wide = np.bincount(rows[on & ~narrow], minlength=len(pairs))
        covered = np.bincount(rows[on], weights=inside[on], minlength=len(pairs))
        touching = np.bincount(rows[on & on_border], minlength=len(pairs)) > 0
        fringe |= (wide == 0) & touching & (covered < FRINGE_FRACTION * 0.5 * math.pi * scale_mm**2)
        counted = on & (~narrow | (wide[rows] == 0))
        summed = np.zeros((len(pairs), 3))
        np.add.at(summed, rows[counted], normal[counted] * weight[counted, None])
        means.append(summed / np.maximum(np.linalg.norm(summed, axis=1), 1e-300)[:, None])
    cos = np.einsum("ij,ij->i", *means)
    folded = np.linalg.norm(between, axis=1) < 1e-9  # faces back to back: a fold at any scale
    return folded | ((cos < math.cos(math.radians(PERSISTENT_SHARP_DEG))) & ~fringe)


def _patches(vertices: np.ndarray, faces: np.ndarray, adjacency: csr_matrix, rows: np.ndarray, cols: np.ndarray,
             centres: np.ndarray, radius_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (patch ``rows``, face ``cols``): the seed faces of each patch grown ring by ring
    through ``adjacency`` (faces sharing an edge) by the faces within ``radius_mm`` of the
    patch's centre, ``centres[row]``."""
    from scipy.sparse import coo_matrix

    n = len(faces)
    kept = np.sort(rows.astype(np.int64) * n + cols)
    tried, frontier = kept, kept
    while len(frontier):
        ring = coo_matrix((np.ones(len(frontier)), (frontier // n, frontier % n)), shape=(len(centres), n))
        touched = (ring.tocsr() @ adjacency).tocoo()  # no pair twice
        new = np.sort(touched.row.astype(np.int64) * n + touched.col)
        at = np.minimum(np.searchsorted(tried, new), len(tried) - 1)
        new = new[tried[at] != new]
        frontier = new[_within(vertices[faces[new % n]], centres[new // n], radius_mm)]
        # two sorted runs: a stable sort merges them in linear time
        tried, kept = np.sort(np.concatenate([tried, new]), kind="stable"), np.concatenate([kept, frontier])
    return kept // n, kept % n


def _within(triangles: np.ndarray, points: np.ndarray, radius_mm: float) -> np.ndarray:
    """Whether each triangle (k, 3, 3) comes within ``radius_mm`` of its point (k, 3): a corner
    that near, or none farther than the radius past the centroid decides; the rest are measured."""
    import trimesh

    corner = np.linalg.norm(triangles - points[:, None, :], axis=2)
    centroid = triangles.mean(axis=1)
    reach = np.linalg.norm(triangles - centroid[:, None, :], axis=2).max(axis=1)
    near = corner.min(axis=1) <= radius_mm
    unsure = ~near & (np.linalg.norm(centroid - points, axis=1) - reach <= radius_mm)
    if unsure.any():
        gap = trimesh.triangles.closest_point(triangles[unsure], points[unsure]) - points[unsure]
        near[unsure] = np.linalg.norm(gap, axis=1) <= radius_mm
    return near

"""Normals a gun can follow: consistent outward orientation, and smoothing over the footprint.

Orientation: triangles are flipped so that every pair sharing a manifold edge is wound alike
(the file's majority winding wins in each connected piece); then a closed piece is turned
outward (positive volume) and an open piece (a scan) toward the side the gun comes from.

Facets: a part exported from CAD is a sphere or a cylinder in flat facets; the mesh refined to
plan on puts its new vertices on those facets, whose normals step from facet to facet (a dome of
radius 100 mm in 7 mm facets: 0.2-0.3 deg, half a millimetre at a 100 mm stand-off). So the raw
normal at a vertex of the refined mesh is interpolated linearly across the file's own facet that
holds it, from that facet's corner normals; a corner normal is Max's weighting of the faces of its
fan between sharp edges (exact at the vertices of a sphere; N. Max, "Weights for computing vertex
normals from facet normals", 1999). A flat face of the part (a patch of coplanar triangles wider
than the smoothing reaches across, a box's side next to its fillet) keeps its own normal: a
corner shared with a fillet would tilt it across the whole of a long triangle.

Smoothing: the raw vertex normals diffuse over the surface for a time t = L^2/2 (implicit
steps of the heat equation, (M + t/k L) N = M N0 with the cotangent Laplacian L and the lumped
mass M, k = SMOOTHING_STEPS of them), which averages them over about a length L along the
surface (not through the part, so the two skins of a thin part stay apart), and are
normalised. One step damps a wave of the normals of wavenumber w by 1 / (1 + t w^2), k steps by
(1 + t w^2 / k)^-k: alike for the part's shape (w L small), but a scan's noise from vertex to
vertex (w L large) one step leaves at a share that a 100 mm stand-off turns into tenths of a
millimetre of the tool's path (0.2 mm of noise on 1.7 mm facets: its tool points scattered
0.07 mm with one step, 0.04 mm with two). On a cylinder or a sphere the normal field is an
eigenfunction of the Laplacian, so smoothing leaves it exact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.surface.boxes import TriangleBoxes
from coatsim.geometry.surface.features import feature_split
from coatsim.geometry.surface.topology import Edges, face_components, face_pairs, mesh_edges

#: relative residual at which the smoothing solve stops (normals to about 1e-8)
SMOOTHING_RTOL = 1e-9
#: implicit steps the smoothing time is split into (smooth_normals): the part's shape is damped
#: alike by one or more, a scan's noise from vertex to vertex far more by two
SMOOTHING_STEPS = 2
#: an edge shorter than this share of the median edge weighs as that long in Max's corner weights
#: (a sliver's corner would otherwise outweigh its whole fan)
SHORT_EDGE_SHARE = 1e-2
#: a point lies in a facet when nearer than this share of the part's extent (rounding of the refinement)
ON_FACET_SHARE = 1e-9
#: triangles whose normals differ by less than this are one flat patch (flat_faces)
FLAT_PATCH_DEG = 0.05
#: a flat patch wider than this many smoothing lengths is a face of the part, not a facet (flat_faces)
FLAT_FACE_SMOOTHING_LENGTHS = 2.0
#: the share of the way a point is lifted toward its corners' tangent planes (Facets.lifted)
PHONG_SHAPE = 0.5
#: a facet whose longest edge is more than this many times its width is a strip (along_flattened) ...
STRIP_ASPECT = 4.0
#: ... whose normals turn along it by more than this many times the sag they turn across it: no
#: curvature of the part (CAD facets sag about alike)
STRIP_SAG_RATIO = 10.0
#: a probe counts as behind a face when more than this fraction of its step behind it (kept_outward)
BEHIND_FRACTION = 1e-3
#: an open piece whose net facing towards the gun is below this share of its area, ...
FACING_SHARE = 0.05
#: ... and whose volume about its own centre is above this share of (area/2)^1.5, wraps round (_outward)
WRAP_SHARE = 0.01


@dataclass(frozen=True, eq=False)
class Orientation:
    """Triangles wound consistently and outward, how many were flipped, and notes."""

    faces: np.ndarray
    flipped: int
    notes: tuple[str, ...]


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit face normals (m, 3) and face areas (m,) mm^2."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    norm = np.linalg.norm(cross, axis=1)
    return cross / np.maximum(norm, 1e-300)[:, None], 0.5 * norm


def orient(vertices: np.ndarray, faces: np.ndarray, toward: np.ndarray | None) -> Orientation:
    """Wind ``faces`` consistently and outward; open pieces face ``toward`` (a unit vector)
    when given, else keep the file's majority winding."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    m = len(faces)
    edges = mesh_edges(faces)
    pairs, consistent = face_pairs(faces, edges)
    n_pieces, piece = face_components(m, pairs)
    # a face in state 0 (as read) or 1 (flipped): consistent neighbours share a state
    f, g = pairs[:, 0], pairs[:, 1]
    rows = np.concatenate([f, f + m])
    cols = np.concatenate([np.where(consistent, g, g + m), np.where(consistent, g + m, g)])
    _, state_label = connected_components(coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(2 * m, 2 * m)),
                                          directed=False)
    as_read, flipped_label = state_label[:m], state_label[m:]
    orientable = as_read != flipped_label
    # in each piece keep as read the faces of the larger of its two state classes
    key = piece.astype(np.int64) * (2 * m) + as_read
    classes, size = np.unique(key, return_counts=True)
    best = np.full(n_pieces, -1, dtype=np.int64)
    best_size = np.zeros(n_pieces, dtype=np.int64)
    for k, s in zip(classes.tolist(), size.tolist()):
        p = k // (2 * m)
        if s > best_size[p]:
            best[p], best_size[p] = k % (2 * m), s
    flip = orientable & (as_read != best[piece])
    notes = []
    if (~orientable).any():
        notes.append(f"{len(np.unique(piece[~orientable]))} piece(s) of the mesh cannot be oriented "
                     "(a Moebius-like surface); their triangles keep the file's winding")
    faces = np.where(flip[:, None], faces[:, ::-1], faces)
    flip_piece = _outward(vertices, faces, piece, n_pieces, _closed_pieces(edges, piece, n_pieces), toward)
    faces = np.where(flip_piece[piece][:, None], faces[:, ::-1], faces)
    flipped = int(np.count_nonzero(flip ^ flip_piece[piece]))
    return Orientation(faces, flipped, tuple(notes))


def _closed_pieces(edges: Edges, piece: np.ndarray, n_pieces: int) -> np.ndarray:
    """Whether each piece is closed: every edge of its faces has exactly two faces."""
    open_face = (edges.face_count[edges.of_face] != 2).any(axis=1)
    closed = np.ones(n_pieces, dtype=bool)
    closed[np.unique(piece[open_face])] = False
    return closed


def _outward(vertices: np.ndarray, faces: np.ndarray, piece: np.ndarray, n_pieces: int, closed: np.ndarray,
             toward: np.ndarray | None) -> np.ndarray:
    """Which pieces to flip: closed ones with negative volume; open ones facing away from
    ``toward``, or, where they face it and away from it alike but wrap round (a pipe seen from
    its side, whose net facing is nil), with a negative volume about their own centre."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    centre = vertices.mean(axis=0)
    volume = np.bincount(piece, weights=np.einsum("ij,ij->i", a - centre, np.cross(b - centre, c - centre)),
                         minlength=n_pieces)
    flip = closed & (volume < 0)
    if toward is not None:
        area_normal = np.cross(b - a, c - a)
        facing = np.bincount(piece, weights=area_normal @ toward, minlength=n_pieces)
        total = np.bincount(piece, weights=np.linalg.norm(area_normal, axis=1), minlength=n_pieces)
        # about its own centre, an open piece that wraps round (a pipe, a tube without its ends)
        # has the volume sign of the closed part it is most of
        mid = (a + b + c) / 3
        own = np.column_stack([np.bincount(piece, weights=mid[:, k], minlength=n_pieces) for k in range(3)])
        own = (own / np.maximum(np.bincount(piece, minlength=n_pieces), 1)[:, None])[piece]
        wrap = np.bincount(piece, weights=np.einsum("ij,ij->i", a - own, np.cross(b - own, c - own)), minlength=n_pieces)
        wraps = (np.abs(facing) <= FACING_SHARE * total) & (np.abs(wrap) > WRAP_SHARE * (total / 2) ** 1.5)
        flip |= ~closed & np.where(wraps, wrap < 0, facing < -1e-6 * total)
    return flip


def closed_faces(faces: np.ndarray) -> np.ndarray:
    """Whether each face belongs to a closed piece of the mesh, (m,) bool."""
    edges = mesh_edges(faces)
    n_pieces, piece = face_components(len(faces), face_pairs(faces, edges)[0])
    return _closed_pieces(edges, piece, n_pieces)[piece]


def vertex_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Area-weighted vertex normals (n, 3), unit (zero where no face touches a vertex)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    cross = np.cross(b - a, c - a)
    summed = np.zeros_like(vertices)
    for k in range(3):
        np.add.at(summed, faces[:, k], cross)
    return summed / np.maximum(np.linalg.norm(summed, axis=1), 1e-300)[:, None]


def corner_normals(vertices: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals at the corners of ``faces``, one per fan of a vertex's faces between sharp
    edges, weighted after Max (exact at the vertices of a sphere): (faces on the split vertices,
    the split vertices' normals)."""
    split, copies = feature_split(faces, face_normals(vertices, faces)[0])
    at = vertices[copies]
    lengths = np.linalg.norm(at[split] - at[np.roll(split, -1, axis=1)], axis=2)
    floor = SHORT_EDGE_SHARE * float(np.median(lengths)) if lengths.size else 0.0
    summed = np.zeros_like(at)
    for k in range(3):
        e1, e2 = at[split[:, (k + 1) % 3]] - at[split[:, k]], at[split[:, (k + 2) % 3]] - at[split[:, k]]
        square1 = np.maximum(np.einsum("ij,ij->i", e1, e1), floor**2)
        square2 = np.maximum(np.einsum("ij,ij->i", e2, e2), floor**2)
        np.add.at(summed, split[:, k], np.cross(e1, e2) / np.maximum(square1 * square2, 1e-300)[:, None])
    return split, summed / np.maximum(np.linalg.norm(summed, axis=1), 1e-300)[:, None]


def flat_faces(vertices: np.ndarray, faces: np.ndarray, width_mm: float) -> np.ndarray:
    """Which faces (m,) bool lie in a flat patch (triangles joined by edges across which the
    normal turns by less than ``FLAT_PATCH_DEG``) wider than ``width_mm`` (twice its area over
    its perimeter): a face of the part rather than a facet of a curved surface."""
    face_n, area = face_normals(vertices, faces)
    edges = mesh_edges(faces)
    pairs, consistent, slot, _ = face_pairs(faces, edges, slots=True)
    cos = np.einsum("ij,ij->i", face_n[pairs[:, 0]], face_n[pairs[:, 1]])
    joined = consistent & (cos >= np.cos(np.radians(FLAT_PATCH_DEG)))
    count, patch = face_components(len(faces), pairs[joined])
    lengths = np.linalg.norm(vertices[faces] - vertices[np.roll(faces, -1, axis=1)], axis=2)
    # each inner edge of a patch is counted once from either face: take both off the perimeter
    perimeter = np.bincount(patch, weights=lengths.sum(axis=1), minlength=count) - 2.0 * np.bincount(
        patch[pairs[joined, 0]], weights=lengths[pairs[joined, 0], slot[joined]], minlength=count)
    width = 2.0 * np.bincount(patch, weights=area, minlength=count) / np.maximum(perimeter, 1e-300)
    return width[patch] > width_mm


@dataclass(frozen=True, eq=False)
class Facets:
    """The part's own facets (outward-wound) with a normal at each corner: ``corners`` (m, 3, 3)
    (``corner_normals``, or the face's own normal on a flat patch wider than the smoothing,
    ``flat_faces``), and the normals and the smooth surface they give at points on the facets."""

    vertices: np.ndarray
    faces: np.ndarray
    face_n: np.ndarray
    corners: np.ndarray
    boxes: TriangleBoxes
    caps: np.ndarray  # the most each face lets ``lifted`` move a point, mm (face_widths_mm)

    @classmethod
    def of(cls, vertices: np.ndarray, faces: np.ndarray, smoothing_mm: float) -> Facets:
        """The facets ``faces`` (wound consistently) of a part whose normals are smoothed over
        ``smoothing_mm`` (a flat patch wider than ``FLAT_FACE_SMOOTHING_LENGTHS`` of it is a face)."""
        split, corner = corner_normals(vertices, faces)
        face_n = face_normals(vertices, faces)[0]
        flat = flat_faces(vertices, faces, FLAT_FACE_SMOOTHING_LENGTHS * smoothing_mm)
        corners = along_flattened(vertices, faces, np.where(flat[:, None, None], face_n[:, None, :], corner[split]))
        cos = np.clip(np.einsum("ijk,ik->ij", corners, face_n), -1.0, 1.0)
        caps = PHONG_SHAPE * face_widths_mm(vertices, faces) * np.sqrt(1.0 - cos**2).max(axis=1)
        return cls(vertices, faces, face_n, corners, TriangleBoxes(vertices, faces), caps)

    def _holding(self, points: np.ndarray, side: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(points held, their faces, barycentric weights): a point on an edge or a vertex is held
        by the face whose normal is nearest its ``side`` (unit normals from the faces on the
        point's side of a sharp edge); a point on no face, or on a sliver, is left out."""
        import trimesh

        extent = float(np.ptp(self.vertices, axis=0).max()) if len(self.vertices) else 0.0
        owner, face, distance = self.boxes.touching(points, ON_FACET_SHARE * extent)
        on = distance <= ON_FACET_SHARE * extent
        owner, face = owner[on], face[on]
        # per point the face best facing its side: sort by point, then by agreement, keep the last
        order = np.lexsort((np.einsum("ij,ij->i", self.face_n[face], side[owner]), owner))
        last = np.r_[owner[order][1:] != owner[order][:-1], True]
        held, by = owner[order][last], face[order][last]
        weights = np.clip(trimesh.triangles.points_to_barycentric(self.vertices[self.faces[by]], points[held]), 0, None)
        good = np.isfinite(weights).all(axis=1)
        return held[good], by[good], weights[good]

    def folded(self, width_mm: float) -> np.ndarray:
        """Faces (m,) a scan's noise folded over, or that are too narrow to say which way they
        face: narrower than ``width_mm``, or facing against the area-weighted mean of the faces
        sharing their edges (an overhanging wall's faces face with their neighbours)."""
        edges = mesh_edges(self.faces)
        pairs, _ = face_pairs(self.faces, edges)
        _, area = face_normals(self.vertices, self.faces)
        around = np.zeros_like(self.face_n)
        weighted = self.face_n * area[:, None]
        np.add.at(around, pairs[:, 0], weighted[pairs[:, 1]])
        np.add.at(around, pairs[:, 1], weighted[pairs[:, 0]])
        return (face_widths_mm(self.vertices, self.faces) < width_mm) | (np.einsum("ij,ij->i", self.face_n, around) < 0)

    def largest_lift_mm(self) -> float:
        """An upper bound on how far ``lifted`` moves a point (the largest of ``caps``)."""
        return float(self.caps.max()) if len(self.faces) else 0.0

    def normals(self, points: np.ndarray, side: np.ndarray) -> np.ndarray:
        """Unit normals (p, 3) at ``points`` on the facets, interpolated linearly across the face
        holding each from its corners; a point on no face keeps its ``side``."""
        held, by, weights = self._holding(points, side)
        interpolated = np.einsum("ij,ijk->ik", weights, self.corners[by])
        norm = np.linalg.norm(interpolated, axis=1)
        good = norm > 1e-9
        out = side.copy()
        out[held[good]] = interpolated[good] / norm[good, None]
        return out

    def lifted(self, points: np.ndarray, side: np.ndarray) -> np.ndarray:
        """``points`` on the facets moved along their unit normals ``side`` onto the smooth surface
        the corner normals describe (Phong tessellation: halfway to the mean of the point's
        projections onto the corners' tangent planes, weighted as its barycentric coordinates;
        half, ``PHONG_SHAPE``, is exact to second order on a circle or a sphere, where the whole
        way overshoots by the facet's own sagitta). Along the normal, so that the tool point
        stays on the normal's ray (a sphere's passes keep their tool points on the sphere's
        radii); on a flat face a point stays put; a point on no face stays; no point moves more
        than its face's cap (``caps``)."""
        held, by, weights = self._holding(points, side)
        offset = points[held, None, :] - self.vertices[self.faces[by]]
        height = np.einsum("ijk,ijk->ij", offset, self.corners[by])
        move = -PHONG_SHAPE * np.einsum("ij,ijk->ik", weights * height, self.corners[by])
        cap = self.caps[by]
        along = np.clip(np.einsum("ij,ij->i", move, side[held]), -cap, cap)
        out = points.copy()
        out[held] = points[held] + along[:, None] * side[held]
        return out


def along_flattened(vertices: np.ndarray, faces: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Corner normals (m, 3, 3) with the tilt along a strip taken out where no curvature explains
    it. CAD tessellates a surface finely across its curvature and coarsely along the directions it
    barely curves in (a cylinder's rulings, a fillet's length), so that every facet sags about
    alike from the surface: a turn of the normal by a angle along an edge l long means a sag of
    about l a / 8. A strip (longest edge more than ``STRIP_ASPECT`` times its width) whose corner
    normals turn along its longest edge by more than ``STRIP_SAG_RATIO`` times the sag they turn
    across it does not curve that way: its ends are corners shared with another surface (a
    capsule's cap, a box's end), whose facets tilt them by half their own turn. Interpolated along
    160 mm of a capsule's side that tilt put the normal 1.7 deg off 10 mm from the cap (a sag
    along of 1.4 mm against 0.04 mm across: 32 times); a spool's waist in coarse rings, concave
    along its axis, sags 0.19 mm along and 0.034 mm across (5.6 times) and keeps its tilt."""
    triangles = vertices[faces]
    edges = np.roll(triangles, -1, axis=1) - triangles
    lengths = np.linalg.norm(edges, axis=2)
    k = np.argmax(lengths, axis=1)
    rows = np.arange(len(faces))
    longest = lengths[rows, k]
    width = face_widths_mm(vertices, faces)
    along = edges[rows, k] / np.maximum(longest, 1e-300)[:, None]
    start, end, apex = corners[rows, k], corners[rows, (k + 1) % 3], corners[rows, (k + 2) % 3]
    to_apex = triangles[rows, (k + 2) % 3] - triangles[rows, k]
    across = to_apex - np.einsum("ij,ij->i", to_apex, along)[:, None] * along  # in the face, across the edge
    across /= np.maximum(np.linalg.norm(across, axis=1), 1e-300)[:, None]
    sag_along = longest * np.abs(np.einsum("ij,ij->i", end - start, along)) / 8.0
    foot = np.clip(np.einsum("ij,ij->i", to_apex, along) / np.maximum(longest, 1e-300), 0.0, 1.0)[:, None]
    at_foot = (1.0 - foot) * start + foot * end  # the normal on the edge across from the apex
    sag_across = width * np.abs(np.einsum("ij,ij->i", apex - at_foot, across)) / 8.0
    strip = (longest > STRIP_ASPECT * width) & (sag_along > STRIP_SAG_RATIO * sag_across)
    if not strip.any():
        return corners
    kept = corners[strip] - np.einsum("ijk,ik->ij", corners[strip], along[strip])[:, :, None] * along[strip, None, :]
    out = corners.copy()
    out[strip] = kept / np.maximum(np.linalg.norm(kept, axis=2), 1e-300)[:, :, None]
    return out


def face_widths_mm(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Each face's smallest width (m,): twice its area over its longest edge. A point is lifted
    (Facets.lifted) by at most PHONG_SHAPE times its face's width times the largest sine between
    the face's normal and a corner normal: on a well-shaped facet the smooth surface lies within
    that (a sphere's equilateral facet of side a sags a²/6R, the cap is a²/4R); a long thin one
    (a CAD fillet's strip the length of the part) has corner normals turning along its length
    that no curvature there explains, and uncapped, halfway to their tangent planes threw pass
    points 4.7 mm off a filleted box whose facets sag 0.3 mm."""
    triangles = vertices[faces]
    longest = np.linalg.norm(triangles - np.roll(triangles, -1, axis=1), axis=2).max(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1)
    return 2.0 * area / np.maximum(longest, 1e-300)


def smooth_normals(vertices: np.ndarray, faces: np.ndarray, length_mm: float, raw: np.ndarray) -> np.ndarray:
    """Unit vertex normals (n, 3) averaged over about ``length_mm`` along the surface, from the
    unit ``raw`` normals (n, 3) (Facets.normals).

    The system is symmetric positive definite; conjugate gradients with a diagonal
    preconditioner solve it in time about linear in the mesh size (a direct factorisation's
    fill-in grows faster on large scans)."""
    import potpourri3d as pp3d
    from scipy.sparse import diags
    from scipy.sparse.linalg import LinearOperator, cg

    if length_mm <= 0:
        return raw
    laplacian = pp3d.cotan_laplacian(vertices, faces, denom_eps=1e-12)
    mass = pp3d.vertex_areas(vertices, faces)
    system = (diags(mass) + 0.5 * length_mm**2 / SMOOTHING_STEPS * laplacian).tocsr()
    diagonal = system.diagonal()
    jacobi = LinearOperator(system.shape, matvec=lambda x: x / diagonal, dtype=float)
    smoothed = raw
    for _ in range(SMOOTHING_STEPS):
        smoothed = np.column_stack([cg(system, mass * smoothed[:, k], x0=smoothed[:, k], rtol=SMOOTHING_RTOL,
                                       maxiter=10_000, M=jacobi)[0] for k in range(3)])
    norm = np.linalg.norm(smoothed, axis=1)
    bad = ~(norm > 1e-9)
    smoothed[bad], norm[bad] = raw[bad], 1.0
    return smoothed / norm[:, None]


def largest_angle_deg(vertex_normals_: np.ndarray, faces: np.ndarray, normals_of_faces: np.ndarray) -> float:
    """Largest angle between a vertex normal and the normal of a face around that vertex."""
    cos = np.einsum("ijk,ik->ij", vertex_normals_[faces], normals_of_faces)
    return float(np.degrees(np.arccos(np.clip(cos.min(), -1.0, 1.0)))) if len(faces) else 0.0


def kept_outward(points: np.ndarray, normals: np.ndarray, boxes: TriangleBoxes, face_n: np.ndarray,
                 tolerance: float, ignored: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """Unit normals at points made to leave the (outward-wound) part: a normal whose first step
    (``tolerance`` long) goes behind the faces touching its point (the floor's normal at the foot
    of an overhanging wall, smoothing across a concave crease it cannot follow) becomes the mean
    of the touching faces' normals, or failing that the normal of the nearest face to that step.
    ``boxes`` holds the part's faces, ``face_n`` their unit outward normals; faces ``ignored``
    (m,) judge nothing (a scan's slivers, which its noise folds over: a normal "behind" one was
    turned to a mean of the faces there 86-113 deg off its neighbours'). Returns the normals and
    how many were changed."""
    owner, face, distance = boxes.touching(points, tolerance)
    keep = (distance <= tolerance) & (True if ignored is None else ~ignored[face])
    owner, face = owner[keep], face[keep]
    probes = points + tolerance * normals
    bad = np.flatnonzero(_behind(probes, owner, face, boxes.triangles, face_n, len(points), BEHIND_FRACTION * tolerance))
    if not len(bad):
        return normals, 0
    fixed = normals.copy()
    for i in bad.tolist():  # few points: at concave creases and the feet of walls
        touching = face_n[face[owner == i]]
        mean = touching.sum(axis=0)
        mean /= max(float(np.linalg.norm(mean)), 1e-300)
        fixed[i] = mean if (touching @ mean).min() > 0 else touching[np.argmax(touching @ normals[i])]
    return fixed, len(bad)


def _behind(probes: np.ndarray, owner: np.ndarray, face: np.ndarray, triangles: np.ndarray, face_n: np.ndarray,
            count: int, slack: float) -> np.ndarray:
    """Whether each probe lies more than ``slack`` behind the nearest of its faces (ties at an
    edge or a vertex judged by the sum of the tied faces' normals, a pseudo-normal), (count,)
    bool. The slack keeps a probe that runs along a face (a normal at a concave sharp edge
    that is the other face's normal) from counting as behind it by rounding."""
    import trimesh

    closest = trimesh.triangles.closest_point(triangles[face], probes[owner])
    gap = np.linalg.norm(probes[owner] - closest, axis=1)
    best = np.full(count, np.inf)
    np.minimum.at(best, owner, gap)
    tied = gap <= best[owner] * (1 + 1e-6) + 1e-12
    pseudo = np.zeros((count, 3))
    np.add.at(pseudo, owner[tied], face_n[face[tied]])
    foot = np.zeros((count, 3))
    foot[owner[tied]] = closest[tied]
    side = np.einsum("ij,ij->i", probes - foot, pseudo)
    has = np.isfinite(best)
    return has & (side < -slack)

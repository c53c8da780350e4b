"""The part in the cell and collisions with it: a contact between the arm (or its gun) and anything
else in the cell during the run is a failure naming the program step and the two bodies.

MuJoCo collides a mesh geom by its convex hull, so a part mesh is given to it as convex pieces.
coatsim does not decompose the solid (no convex-decomposition library is a dependency); it covers
the part's surface with slabs: the faces are grouped into patches of about ``patch_mm`` (by the
cell of a grid their centroids fall in), and each patch becomes the convex hull of its vertices
and the same vertices moved ``thickness_mm`` against their normals. That hull holds the patch's
surface, so the gun cannot pass through the surface without touching it; it bulges past a curved
patch by at most its sagitta (patch² / 8R: 0.8 mm for 20 mm patches on R = 60 mm) and holds
nothing of a closed part's interior (a gun reaching the interior has crossed the surface first).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import mujoco
import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.robot.cell import MM, Cell, cell_of

PART_BODY = "part"
WORKPIECE_SITE = "workpiece"  # the cell's own workpiece is the body holding this site (the part replaces it)
PATCH_MM = 20.0      # the side of a patch of faces made one convex piece
MAX_PIECES = 600     # larger parts get larger patches (MuJoCo compiles each hull)
THICKNESS_MM = 2.0   # how deep a patch's slab reaches behind the surface


class Collision(ExecutionError):
    """The arm or the gun touches something in the cell: the program ``step`` and the two bodies."""

    def __init__(self, message: str, *, step: str, bodies: tuple[str, str]) -> None:
        super().__init__(message)
        self.step, self.bodies = step, bodies


@dataclass(frozen=True, eq=False)
class PartMesh:
    """A part's surface in the robot base frame: vertices (n, 3) mm, faces (m, 3)."""

    vertices: np.ndarray
    faces: np.ndarray
    notes: tuple[str, ...] = ()


def load_part(path: str | Path, pose: Pose, units: str = defaults.PLAN_UNITS) -> PartMesh:
    """A mesh file (STL, PLY, OBJ, OFF, GLB) read as ``plan`` reads it (in ``units``: mm, cm, m,
    in, or auto from the file, else from its extent, with a note; repaired) and placed by
    ``pose`` (its frame in the base frame, mm). Read in its file's numbers, a part in metres was
    a thousandth of its size in the cell, and no contact with it could be found."""
    from coatsim.geometry.surface.mesh import load_part as read_mesh

    part = read_mesh(path, units)
    return PartMesh(pose.apply(part.vertices_mm), part.faces, part.notes)


def convex_pieces(part: PartMesh, patch_mm: float = PATCH_MM, thickness_mm: float = THICKNESS_MM) -> list[np.ndarray]:
    """The vertex sets (k, 3) mm whose convex hulls together cover the part's surface (module text)."""
    v, f = part.vertices, part.faces
    tri = v[f]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = 0.5 * float(np.linalg.norm(normals, axis=1).sum())
    size = max(patch_mm, math.sqrt(area / MAX_PIECES))
    vertex_normals = np.zeros_like(v)
    np.add.at(vertex_normals, f.ravel(), np.repeat(normals, 3, axis=0))
    length = np.linalg.norm(vertex_normals, axis=1)
    vertex_normals = vertex_normals / np.where(length > 0, length, 1.0)[:, None]
    cells = np.floor((tri.mean(axis=1) - v.min(axis=0)) / size).astype(np.int64)
    _, patch = np.unique(cells, axis=0, return_inverse=True)
    pieces = []
    for k in range(int(patch.max()) + 1):
        ids = np.unique(f[patch.ravel() == k])
        pts = np.vstack((v[ids], v[ids] - thickness_mm * vertex_normals[ids]))
        if np.linalg.matrix_rank(pts - pts.mean(axis=0), tol=1e-6) == 3:
            pieces.append(pts)
    return pieces


def with_part(cell: Cell, part: PartMesh) -> Cell:
    """The cell with the part in it (body ``part``, one mesh geom per convex piece, colliding with
    the arm and the gun as the cell's own fixtures do) in place of the cell's own workpiece (the
    body holding the site ``WORKPIECE_SITE``, the shipped cell's flat plate: a part placed where it
    lies, a bowl sunk through it, had the gun touch a plate the user never asked for)."""
    spec = mujoco.MjSpec.from_file(str(cell.path))
    workpiece = next((site for site in spec.sites if site.name == WORKPIECE_SITE), None)
    if workpiece is not None and workpiece.parent.name != "world":
        spec.delete(workpiece.parent)
    body = spec.worldbody.add_body(name=PART_BODY)
    for k, pts in enumerate(convex_pieces(part)):
        mesh = spec.add_mesh(name=f"{PART_BODY}_piece_{k}")
        mesh.uservert = (pts * MM).ravel().tolist()
        geom = body.add_geom(name=f"{PART_BODY}_{k}", type=mujoco.mjtGeom.mjGEOM_MESH, meshname=mesh.name)
        geom.contype, geom.conaffinity, geom.density = 1, 2, 0.0
        geom.rgba = [0.7, 0.72, 0.76, 1.0]
    try:
        model = spec.compile()
    except ValueError as exc:
        raise InputError(f"the part mesh cannot be added to the cell: {str(exc).strip().splitlines()[0]}") from None
    return cell_of(model, cell.path)


def part_overlaps(cell: Cell) -> tuple[str, ...]:
    """What to tell the user where the part placed in ``cell`` (:func:`with_part`) reaches into a
    body of the cell that is not on the arm (a part centred on the table's top, half of it
    inside the table): one line per such body, with its deepest piece's depth in it. The
    gun meets that body where it sprays the part near it, and the run then stops (Collision)."""
    model = cell.model
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    body_of = model.geom_bodyid
    on_arm = _moving_geoms(model)
    part = [g for g in range(model.ngeom) if model.body(int(body_of[g])).name == PART_BODY]
    fixed = [g for g in range(model.ngeom) if not on_arm[g] and model.body(int(body_of[g])).name != PART_BODY]
    deepest: dict[str, float] = {}
    fromto = np.zeros(6)
    for g in fixed:
        name = model.body(int(body_of[g])).name
        for p in part:
            depth = -mujoco.mj_geomDistance(model, data, g, p, 0.0, fromto)
            if depth > deepest.get(name, 0.0):
                deepest[name] = depth
    return tuple(f"the part overlaps the cell's {name} ({depth / MM:.1f} mm deep): the gun meets the {name} where it "
                 "sprays the part near it; place the part clear of it" for name, depth in deepest.items())


def _moving_geoms(model: mujoco.MjModel) -> np.ndarray:
    """Whether each geom rides on the arm (on a body below its first joint)."""
    first = int(model.jnt_bodyid[0])
    moving = np.zeros(model.nbody, dtype=bool)
    for b in range(model.nbody):
        a = b
        while a > 0 and a != first:
            a = int(model.body_parentid[a])
        moving[b] = a == first
    return moving[model.geom_bodyid]


def check_collisions(cell: Cell, q: np.ndarray, label: Callable[[int], str]) -> None:
    """Collision at the first configuration of ``q`` (n, 6) where a geom on the arm penetrates
    one that is not (the part, the cell's fixtures), naming the step (``label(row)``) and the bodies."""
    model = cell.model
    data = mujoco.MjData(model)
    on_arm = _moving_geoms(model)
    for i in range(len(q)):
        data.qpos[:] = q[i]
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        if not data.ncon:
            continue
        contact = data.contact
        g1, g2, dist = contact.geom1, contact.geom2, contact.dist
        hit = np.flatnonzero((dist < 0) & (on_arm[g1] != on_arm[g2]))
        if len(hit):
            a, b = int(g1[hit[0]]), int(g2[hit[0]])
            arm, other = (a, b) if on_arm[a] else (b, a)
            bodies = (model.body(int(model.geom_bodyid[arm])).name, model.body(int(model.geom_bodyid[other])).name)
            step = label(i)
            raise Collision(f"{step}: the {bodies[0]} touches the {bodies[1]} ({-dist[hit[0]] * 1e3:.1f} mm deep); "
                            "move the path or the part apart, or raise the stand-off", step=step, bodies=bodies)

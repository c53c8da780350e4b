"""Geodesic passes (the seed authors' method): level sets of the heat-method distance from a start.

The start is the region's border (``FromBoundary``), the section of a plane (``FromPlane``) or a
list of points (``FromPoints``). The heat method holds the distance at the vertices next to the
start (the arc to it, distance.NearestOnCurves), so the start need not run along edges and the
mesh is not cut. Passes are the level sets at
(k + 1/2) spacing from a border or points (the first pass half a spacing in, so the start is
covered) and at k spacing on both sides of a plane (its section is a pass; the distance is signed
by the side of the plane). Where holes or a genus split a level set, it has several pieces.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.surface.contours import crossing_edges, edge_points, level_curves
from coatsim.geometry.surface.distance import NearestOnCurves, arc_length, distance_levels, heat_distance
from coatsim.geometry.surface.passes import barycentric
from coatsim.geometry.surface.piece import Piece
from coatsim.geometry.vectors import unit_rows


@dataclass(frozen=True)
class FromBoundary:
    """Start at the region's border."""


@dataclass(frozen=True)
class FromPlane:
    """Start at the section of the plane through ``point_mm`` with normal ``normal`` (part frame)."""

    point_mm: tuple[float, float, float]
    normal: tuple[float, float, float]


@dataclass(frozen=True)
class FromPoints:
    """Start at points on the surface (part frame, mm); each is moved to the nearest surface point."""

    points_mm: tuple[tuple[float, float, float], ...]


Start = Union[FromBoundary, FromPlane, FromPoints]


def geodesic_piece(piece: Piece, start: Start, spacing_mm: float, band_mm: float,
                   points: dict[int, np.ndarray] | None = None) -> Piece | None:
    """The piece with the signed or unsigned heat distance from the start and its levels; None
    when the start does not touch this piece. ``points`` are the start points on this piece
    (face id -> barycentric weights rows), from ``assign_points``."""
    if isinstance(start, FromBoundary):
        sources = np.flatnonzero(piece.on_border)
        if not len(sources):
            raise InputError("geodesic passes from the border need a border: a piece of the region is closed; give a "
                             "plane or points as the start", parameters=("start",))
        distance = heat_distance(piece.vertices, piece.faces, sources)
        return _levelled(piece, distance, band_mm + 0.5 * spacing_mm, spacing_mm, band_mm)
    if isinstance(start, FromPlane):
        side = (piece.vertices - np.asarray(start.point_mm)) @ np.asarray(start.normal)
        section = level_curves(piece.vertices, piece.faces, side, 0.0)
        if not section:
            return None
        edges = crossing_edges(piece.faces, side, 0.0)
        t = edge_points(piece.vertices, side, 0.0, edges)[1]
        heat = np.bincount(edges.ravel(), weights=np.column_stack([1 - t, t]).ravel(), minlength=len(side))
        sources = np.flatnonzero(heat > 0)
        nearest = NearestOnCurves([(c.points, unit_rows(c.sample(piece.faces, piece.normals)), c.closed)
                                   for c in section])
        held = nearest.arc(piece.vertices[sources], piece.normals[sources])
        distance = heat_distance(piece.vertices, piece.faces, sources, held, heat[sources])
        return _levelled(piece, np.where(side < 0, -distance, distance), 0.0, spacing_mm, band_mm)
    if not points:
        return None
    sources, held, heat = _around_points(piece, points)
    distance = heat_distance(piece.vertices, piece.faces, sources, held, heat)
    return _levelled(piece, distance, 0.5 * spacing_mm, spacing_mm, band_mm)


def _around_points(piece: Piece, points: dict[int, np.ndarray]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The corners of the faces holding start points, their distance (the arc) to the nearest
    start point, and each point's heat spread over them by its barycentric weights."""
    faces = np.concatenate([np.full(len(b), f) for f, b in points.items()])
    bary = np.concatenate(list(points.values()))
    corners = piece.faces[faces]
    at = np.einsum("ij,ijk->ik", bary, piece.vertices[corners])
    normal = unit_rows(np.einsum("ij,ijk->ik", bary, piece.normals[corners]))
    sources, where = np.unique(corners, return_inverse=True)
    heat = np.bincount(where.ravel(), weights=bary.ravel(), minlength=len(sources))
    held = np.full(len(sources), np.inf)
    for p, n in zip(at, normal):
        chord = piece.vertices[sources] - p
        held = np.minimum(held, arc_length(chord, piece.normals[sources], np.tile(n, (len(sources), 1))))
    return sources, held, heat


def _levelled(piece: Piece, field: np.ndarray, first: float, spacing_mm: float, band_mm: float) -> Piece:
    inside = piece.inside(band_mm)
    if not inside.any():
        return piece.with_field(field, np.zeros(0))
    levels = distance_levels(float(field[inside].min()), float(field[inside].max()), first, spacing_mm)
    return piece.with_field(field, levels)


def assign_points(pieces: list[Piece], start: FromPoints, tolerance_mm: float) -> list[dict[int, np.ndarray]]:
    """Each start point on its nearest piece: per piece, face id -> barycentric weights (k, 3).
    A point farther than ``tolerance_mm`` from every piece is an InputError."""
    import trimesh

    points = np.asarray(start.points_mm, dtype=float).reshape(-1, 3)
    best = np.full(len(points), np.inf)
    where: list[tuple[int, int]] = [(-1, -1)] * len(points)
    for k, piece in enumerate(pieces):
        mesh = trimesh.Trimesh(piece.vertices, piece.faces, process=False)
        _, distance, face = trimesh.proximity.closest_point(mesh, points)
        for i in np.flatnonzero(distance < best):
            best[i], where[i] = distance[i], (k, int(face[i]))
    assigned: list[dict[int, np.ndarray]] = [{} for _ in pieces]
    for i, (k, face) in enumerate(where):
        if not best[i] <= tolerance_mm:
            raise InputError(f"start point {tuple(round(float(x), 3) for x in points[i])} lies "
                             f"{best[i]:.3g} mm from the region (more than {tolerance_mm:.3g} mm); "
                             "give points on the coated surface", parameters=("start",))
        piece = pieces[k]
        bary = barycentric(piece.vertices, piece.faces, np.array([face]), points[i][None])[0]
        bary = np.clip(bary, 0.0, None)
        bary /= bary.sum()
        rows = assigned[k].get(face)
        assigned[k][face] = bary[None] if rows is None else np.vstack([rows, bary])
    return assigned

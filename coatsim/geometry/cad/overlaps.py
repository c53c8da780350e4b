"""Collinear lines of a drawing that overlap (a part drawn twice over a stretch, an edge
shared by two outlines): each is kept, and sprayed, so the user is told."""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from coatsim.geometry.cad.pieces import NativePiece, Piece
from coatsim.geometry.primitives import Line

PARALLEL_RAD = 1e-6  # lines this close in direction are parallel


def overlapping_lines(pieces: Sequence[Piece], tol: float) -> list[tuple[Piece, Piece]]:
    """Pairs of line pieces on one line (within ``tol``) that share more than ``tol`` of
    their length, in drawing order."""
    lines = [(k, p) for k, p in enumerate(pieces) if isinstance(p, NativePiece) and isinstance(p.segment, Line)]
    if len(lines) < 2:
        return []
    a = np.array([p.start for _, p in lines], float)
    b = np.array([p.end for _, p in lines], float)
    theta = np.mod(np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]), math.pi)
    order = np.argsort(theta, kind="stable")
    cuts = np.flatnonzero(np.diff(theta[order]) > PARALLEL_RAD) + 1
    groups = list(np.split(order, cuts))
    groups.append(np.flatnonzero((theta <= PARALLEL_RAD) | (math.pi - theta <= PARALLEL_RAD)))  # 0 and π: one direction
    found: set[tuple[int, int]] = set()
    for group in groups:
        found |= _overlaps_in(group, a, b, tol)
    return [(lines[i][1], lines[j][1]) for i, j in sorted(found)]


def _overlaps_in(group: np.ndarray, a: np.ndarray, b: np.ndarray, tol: float) -> set[tuple[int, int]]:
    """Overlapping pairs (indices into a, b; smaller first) among parallel lines."""
    if len(group) < 2:
        return set()
    d = b[group[0]] - a[group[0]]
    d = d / np.linalg.norm(d)
    normal = np.array([-d[1], d[0]])
    offset = a[group] @ normal
    lo = np.minimum(a[group] @ d, b[group] @ d)
    hi = np.maximum(a[group] @ d, b[group] @ d)
    by = np.argsort(offset, kind="stable")
    pairs = set()
    for x in range(len(by)):
        for y in range(x + 1, len(by)):
            i, j = by[x], by[y]
            if offset[j] - offset[i] > tol:
                break
            if min(hi[i], hi[j]) - max(lo[i], lo[j]) > tol:
                pairs.add((int(min(group[i], group[j])), int(max(group[i], group[j]))))
    return pairs

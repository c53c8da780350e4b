"""Chaining the pieces of a drawing into contours.

Pieces are joined end to end where their ends lie within the join tolerance of each other
(either direction: a piece drawn backwards is reversed). Zero-length pieces (not longer than
the join tolerance) and duplicates (same ends and middle within it) are dropped first. Where
three or more ends meet, they are paired by tangent continuity (the straightest
continuation first) and what is left over ends a contour; this is noted. A contour whose
last end meets its first is closed. Two open ends closer than ``near_mm`` but farther apart
than the join tolerance are an error: the drawing is almost joined there, and spraying it
either way would be a guess.

At each join the ends are made to coincide exactly: an arc keeps its end point (a line or
free-form piece moves to it), two arcs meet at the first one's end (the second keeps its
radius), otherwise the ends meet half way. A join between native pieces is *tangent* when
their headings agree to ``TANGENT_EXACT_RAD`` (round-off); a join with a free-form piece
is tangent within ``TANGENT_FREE_DEG``, because fitting that piece makes it tangent exactly.
Every other join is a corner.

Contours come out in drawing order (by their first drawn piece); a closed contour starts at
its first drawn piece, in the direction it was drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.errors import InputError
from coatsim.geometry.cad.overlaps import overlapping_lines
from coatsim.geometry.cad.pieces import NativePiece, Piece
from coatsim.geometry.primitives import Arc

TANGENT_EXACT_RAD = 1e-6
TANGENT_FREE_DEG = 0.5


@dataclass(frozen=True, eq=False)
class Contour:
    """Oriented pieces, each starting exactly where the previous one ends; ``tangent[k]``
    tells whether the join after piece k (the seam last, for a closed contour) is tangent,
    ``breaks[k]`` its heading change (rad)."""

    pieces: tuple[Piece, ...]
    closed: bool
    tangent: tuple[bool, ...]
    breaks: tuple[float, ...]

    @property
    def name(self) -> str:
        return self.pieces[0].source

    @property
    def length(self) -> float:
        return float(sum(p.length for p in self.pieces))


@dataclass(frozen=True, eq=False)
class Chaining:
    """The contours of a drawing and notes on what was dropped or paired by choice."""

    contours: tuple[Contour, ...]
    notes: tuple[str, ...]


def _wrap(angle: float) -> float:
    return abs(math.remainder(angle, 2 * math.pi))


def _is_native(piece: Piece) -> bool:
    return isinstance(piece, NativePiece)


def join_is_tangent(a: Piece, b: Piece, heading_break: float) -> bool:
    """Whether the join of ``a`` into ``b`` with that heading change (rad) is tangent."""
    if _is_native(a) and _is_native(b):
        return heading_break <= TANGENT_EXACT_RAD
    return heading_break <= math.radians(TANGENT_FREE_DEG)


class _Sets:
    """Union-find over end indices."""

    def __init__(self, n: int) -> None:
        self.parent = list(range(n))

    def find(self, i: int) -> int:
        while self.parent[i] != i:
            self.parent[i] = self.parent[self.parent[i]]
            i = self.parent[i]
        return i

    def union(self, i: int, j: int) -> None:
        a, b = self.find(i), self.find(j)
        if a != b:
            self.parent[max(a, b)] = min(a, b)


def _drop_degenerate(pieces: Sequence[Piece], tol: float, notes: list[str]) -> list[Piece]:
    """Without zero-length pieces and duplicates (the later copy goes)."""
    kept = [p for p in pieces if p.length > tol]
    if len(kept) < len(pieces):
        first = next(p for p in pieces if p.length <= tol)
        notes.append(f"dropped {len(pieces) - len(kept)} zero-length pieces (first: {first.source})")
    if len(kept) < 2:
        return kept
    mids = np.array([p.midpoint() for p in kept])
    duplicate = set()
    for i, j in sorted(cKDTree(mids).query_pairs(tol)):
        a, b = kept[i], kept[j]
        same = math.dist(a.start, b.start) <= tol and math.dist(a.end, b.end) <= tol
        flipped = math.dist(a.start, b.end) <= tol and math.dist(a.end, b.start) <= tol
        if (same or flipped) and i not in duplicate and abs(a.length - b.length) <= 2 * tol:
            duplicate.add(j)
    if duplicate:
        first = kept[min(duplicate)]
        notes.append(f"dropped {len(duplicate)} duplicate pieces (first: {first.source})")
    return [p for k, p in enumerate(kept) if k not in duplicate]


def _arrive(piece: Piece, side: int) -> float:
    """Heading when arriving at the node through end ``side`` (0 start, 1 end) of ``piece``."""
    return piece.end_heading if side == 1 else piece.start_heading + math.pi


def _leave(piece: Piece, side: int) -> float:
    return piece.start_heading if side == 0 else piece.end_heading + math.pi


def _pair_ends(pieces: list[Piece], tol: float, notes: list[str]) -> dict[tuple[int, int], tuple[int, int]]:
    """Partner of every joined end (piece index, side); unpaired ends are open."""
    ends = np.array([p.start for p in pieces] + [p.end for p in pieces], dtype=float)
    n = len(pieces)
    sets = _Sets(2 * n)
    for i, j in cKDTree(ends).query_pairs(tol):
        sets.union(int(i), int(j))
    nodes: dict[int, list[tuple[int, int]]] = {}
    for k in range(2 * n):
        nodes.setdefault(sets.find(k), []).append((k % n, k // n))
    partner: dict[tuple[int, int], tuple[int, int]] = {}
    branches = []
    for members in nodes.values():
        if len(members) == 2:
            a, b = members
            partner[a], partner[b] = b, a
        elif len(members) > 2:
            branches.append(members)
            options = sorted(
                (_wrap(_leave(pieces[b[0]], b[1]) - _arrive(pieces[a[0]], a[1])), a, b)
                for x, a in enumerate(members) for b in members[x + 1:]
            )
            for _, a, b in options:
                if a not in partner and b not in partner:
                    partner[a], partner[b] = b, a
    if branches:
        where = ends[branches[0][0][1] * n + branches[0][0][0]]
        names = ", ".join(pieces[i].source for i, _ in branches[0][:4])
        notes.append(f"{len(branches)} places where three or more pieces meet, paired by tangent continuity "
                     f"(first at ({where[0]:.4g}, {where[1]:.4g}): {names})")
    return partner


def _walk(start: int, partner: dict, pieces: list[Piece]) -> tuple[list[Piece], list[int], bool]:
    """Oriented pieces of the chain through ``start`` (drawn direction), their indices,
    and whether the chain closes."""
    back: list[tuple[int, bool]] = []
    cur = (start, 0)
    while cur in partner:
        j, side = partner[cur]
        if j == start:
            return _closed_loop(start, back, pieces)
        back.append((j, side == 1))  # entered at its end: forward
        cur = (j, 1 - side)
    chain = [(j, fwd) for j, fwd in reversed(back)] + [(start, True)]
    cur = (start, 1)
    while cur in partner:
        j, side = partner[cur]
        chain.append((j, side == 0))
        cur = (j, 1 - side)
    return [pieces[j] if fwd else pieces[j].reversed() for j, fwd in chain], [j for j, _ in chain], False


def _closed_loop(start: int, back: list[tuple[int, bool]], pieces: list[Piece]) -> tuple[list[Piece], list[int], bool]:
    chain = [(start, True)] + [(j, fwd) for j, fwd in reversed(back)]
    return [pieces[j] if fwd else pieces[j].reversed() for j, fwd in chain], [j for j, _ in chain], True


def _junction(a: Piece, b: Piece) -> tuple[float, float]:
    """The point where ``a`` and ``b`` are made to meet."""
    a_arc = _is_native(a) and isinstance(a.segment, Arc)
    b_arc = _is_native(b) and isinstance(b.segment, Arc)
    if a_arc:
        return a.end
    if b_arc:
        return b.start
    return ((a.end[0] + b.start[0]) / 2, (a.end[1] + b.start[1]) / 2)


def _snap(oriented: list[Piece], closed: bool) -> tuple[Piece, ...]:
    """The pieces with coinciding ends at every join."""
    n = len(oriented)
    joins = [_junction(oriented[k], oriented[k + 1]) for k in range(n - 1)]
    seam = _junction(oriented[-1], oriented[0]) if closed else None
    out = []
    for k, piece in enumerate(oriented):
        start = joins[k - 1] if k > 0 else (seam if closed else piece.start)
        end = joins[k] if k < n - 1 else (seam if closed else piece.end)
        if (start, end) != (piece.start, piece.end):
            piece = piece.with_ends(start, end)
        out.append(piece)
    return tuple(out)


def _contour(pieces: tuple[Piece, ...], closed: bool) -> Contour:
    pairs = list(zip(pieces[:-1], pieces[1:])) + ([(pieces[-1], pieces[0])] if closed else [])
    breaks = tuple(_wrap(b.start_heading - a.end_heading) for a, b in pairs)
    tangent = tuple(join_is_tangent(a, b, brk) for (a, b), brk in zip(pairs, breaks))
    return Contour(pieces, closed, tangent, breaks)


def _near_misses(contours: list[tuple[list[Piece], bool]], tol: float, near_mm: float, source: str) -> None:
    """Raise on two open ends within ``near_mm`` of each other (but not joined)."""
    ends, owners = [], []
    for k, (pieces, closed) in enumerate(contours):
        if not closed:
            ends += [pieces[0].start, pieces[-1].end]
            owners += [(k, pieces[0]), (k, pieces[-1])]
    if len(ends) < 2:
        return
    pts = np.array(ends, dtype=float)
    pairs = sorted(cKDTree(pts).query_pairs(near_mm))
    if not pairs:
        return
    i, j = min(pairs, key=lambda ij: float(np.linalg.norm(pts[ij[0]] - pts[ij[1]])))
    gap = float(np.linalg.norm(pts[i] - pts[j]))
    what = "its own start" if owners[i][0] == owners[j][0] else owners[j][1].source
    raise InputError(
        f"{source}: cannot chain {owners[i][1].source}: its end at ({pts[i][0]:.6g}, {pts[i][1]:.6g}) is "
        f"{gap:.3g} mm from {what}, more than the join tolerance {tol:g} mm (raise the join tolerance, --join-tol, to join them)"
    )


def chain_pieces(pieces: Sequence[Piece], join_tol_mm: float, source: str = "drawing",
                 near_mm: Optional[float] = None) -> Chaining:
    """Contours of ``pieces`` joined within ``join_tol_mm``; see the module docstring."""
    if not (math.isfinite(join_tol_mm) and join_tol_mm > 0):
        raise InputError(f"join tolerance {join_tol_mm} mm (--join-tol): must be a finite number > 0")
    notes: list[str] = []
    kept = _drop_degenerate(pieces, join_tol_mm, notes)
    if not kept:
        raise InputError(f"{source}: every piece is shorter than the join tolerance {join_tol_mm:g} mm")
    overlaps = overlapping_lines(kept, join_tol_mm)
    if overlaps:
        notes.append(f"{len(overlaps)} pairs of lines overlap along one line, kept and sprayed twice there "
                     f"(first: {overlaps[0][0].source} and {overlaps[0][1].source})")
    partner = _pair_ends(kept, join_tol_mm, notes)
    seen = np.zeros(len(kept), dtype=bool)
    chains: list[tuple[list[Piece], bool]] = []
    for i in range(len(kept)):
        if seen[i]:
            continue
        oriented, members, closed = _walk(i, partner, kept)
        seen[members] = True
        chains.append((oriented, closed))
    if near_mm is not None and near_mm > join_tol_mm:
        _near_misses(chains, join_tol_mm, near_mm, source)
    contours = tuple(_contour(_snap(oriented, closed), closed) for oriented, closed in chains)
    return Chaining(contours, tuple(notes))


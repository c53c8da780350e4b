"""Chaining the pieces of a drawing into contours.

Pieces are joined end to end where their ends lie within the join tolerance of each other
(either direction: a piece drawn backwards is reversed). Zero-length pieces (not longer than
the join tolerance) and duplicates (same ends and middle within it, or within ``NEAR_SHARE`` σ
for pieces longer than σ when σ is given) are dropped first; so is a piece no longer than ``NEAR_SHARE`` σ whose
neighbours meet tangentially across it (a path closed a few micrometres short of its start). Where
three or more ends meet, a drawn path's pieces are followed in the order it was drawn (two
closed outlines touching at a corner stay two), the other ends are paired by tangent
continuity (the straightest continuation first), and what is left over ends a contour; this
is noted. A contour whose last end meets its first is closed.

Ends a few micrometres apart are everyday CAD rounding. Two open ends farther apart than the
join tolerance but closer than ``near_mm`` (the fit's tolerance σ) are joined too, nearest
first, where the join moves no drawn point by more than ``NEAR_SHARE`` σ (the contour is then
fitted within what is left of σ); a note gives the largest gap closed. Ends closer than σ
that are not joined stay the ends of their own contours, and a note names them.

At each join the ends are made to coincide exactly: an arc keeps its end point (a line or
free-form piece moves to it), two arcs meet at the first one's end (the second keeps its
radius), otherwise the ends meet half way. A join between native pieces is *tangent* when
their headings agree to ``TANGENT_EXACT_RAD`` (round-off); a join with a free-form piece
is tangent within ``TANGENT_FREE_DEG``, because fitting that piece makes it tangent exactly.
Every other join is a corner. Each contour records how far its joins moved the drawing
(``moved_mm``).

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
NEAR_SHARE = 0.5  # a near-miss join may move the drawing by this share of σ
_MOVE_SAMPLES = 33  # points along an arc at which its move is measured (_moved)


@dataclass(frozen=True, eq=False)
class Contour:
    """Oriented pieces, each starting exactly where the previous one ends; ``tangent[k]``
    tells whether the join after piece k (the seam last, for a closed contour) is tangent,
    ``breaks[k]`` its heading change (rad); ``moved_mm`` bounds how far making the ends meet
    moved any drawn point."""

    pieces: tuple[Piece, ...]
    closed: bool
    tangent: tuple[bool, ...]
    breaks: tuple[float, ...]
    moved_mm: float = 0.0

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


def _drop_degenerate(pieces: Sequence[Piece], tol: float, same_mm: float, notes: list[str]) -> list[Piece]:
    """Without zero-length pieces (not longer than ``tol``) and duplicates (the later copy goes):
    the same within ``tol``, or pieces longer than twice ``same_mm`` the same within it (an
    outline drawn twice, once rounded to 0.01 mm, was sprayed twice; shorter pieces within it
    are a path's own detail, a spike out and back)."""
    kept = [p for p in pieces if p.length > tol]
    if len(kept) < len(pieces):
        first = next(p for p in pieces if p.length <= tol)
        notes.append(f"dropped {len(pieces) - len(kept)} zero-length pieces (first: {first.source})")
    if len(kept) < 2:
        return kept
    duplicate = _duplicates(kept, tol)
    if same_mm > tol:  # within same_mm only pieces longer than twice that: short ones are a path's detail
        long = [k for k, p in enumerate(kept) if p.length > 2.0 * same_mm and k not in duplicate]
        duplicate |= {long[k] for k in _duplicates([kept[k] for k in long], same_mm)}
    if duplicate:
        first = kept[min(duplicate)]
        notes.append(f"dropped {len(duplicate)} duplicate pieces, each within {same_mm:g} mm of one kept "
                     f"(first: {first.source})")
    return [p for k, p in enumerate(kept) if k not in duplicate]


def _duplicates(pieces: Sequence[Piece], tol: float) -> set[int]:
    """Indices of pieces that repeat an earlier kept piece (same or swapped ends within ``tol``,
    lengths within ``2 tol``). Each kept piece looks up its neighbours once, so many copies of
    one piece cost one lookup each, not one per pair of copies."""
    starts = np.array([p.start for p in pieces], dtype=float)
    ends = np.array([p.end for p in pieces], dtype=float)
    lengths = np.array([p.length for p in pieces], dtype=float)
    tree = cKDTree(np.array([p.midpoint() for p in pieces]))
    duplicate = np.zeros(len(pieces), dtype=bool)
    for i in range(len(pieces)):
        if duplicate[i]:
            continue
        near = np.array(tree.query_ball_point(tree.data[i], tol), dtype=int)
        near = near[(near > i) & ~duplicate[near]]
        if not len(near):
            continue
        same = (np.linalg.norm(starts[near] - starts[i], axis=1) <= tol) & (np.linalg.norm(ends[near] - ends[i], axis=1) <= tol)
        flipped = ((np.linalg.norm(starts[near] - ends[i], axis=1) <= tol)
                   & (np.linalg.norm(ends[near] - starts[i], axis=1) <= tol))
        duplicate[near[(same | flipped) & (np.abs(lengths[near] - lengths[i]) <= 2 * tol)]] = True
    return set(np.flatnonzero(duplicate).tolist())


def _arrive(piece: Piece, side: int) -> float:
    """Heading when arriving at the node through end ``side`` (0 start, 1 end) of ``piece``."""
    return piece.end_heading if side == 1 else piece.start_heading + math.pi


def _leave(piece: Piece, side: int) -> float:
    return piece.start_heading if side == 0 else piece.end_heading + math.pi


def _drawn_on(pieces: list[Piece], a: tuple[int, int], b: tuple[int, int]) -> bool:
    """Whether ends ``a`` and ``b`` (piece index, side) are where one piece of a drawn path
    ends and the next one drawn begins."""
    (i, side_i), (j, side_j) = sorted((a, b))
    return (j == i + 1 and side_i == 1 and side_j == 0 and pieces[i].path != ""
            and pieces[i].path == pieces[j].path)


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
                (not _drawn_on(pieces, a, b), _wrap(_leave(pieces[b[0]], b[1]) - _arrive(pieces[a[0]], a[1])), a, b)
                for x, a in enumerate(members) for b in members[x + 1:]
            )
            for _, _, a, b in options:
                if a not in partner and b not in partner:
                    partner[a], partner[b] = b, a
    if branches:
        where = ends[branches[0][0][1] * n + branches[0][0][0]]
        names = ", ".join(pieces[i].source for i, _ in branches[0][:4])
        notes.append(f"{len(branches)} place{'s' if len(branches) != 1 else ''} where three or more pieces meet, "
                     f"paired along their drawn paths, "
                     f"then by tangent continuity "
                     f"(first at ({where[0]:.4g}, {where[1]:.4g}): {names})")
    return partner


def _bridged(kept: list[Piece], partner: dict, limit_mm: float, notes: list[str]) -> tuple[list[Piece], dict]:
    """The pieces without those no longer than ``limit_mm`` whose neighbours meet tangentially
    across them (within ``TANGENT_FREE_DEG``), the neighbours paired instead: a path closed
    0.004 mm short of its start (Z draws that as a line) gave a micro-segment and two corners."""
    dropped = set()
    for i, piece in enumerate(kept):
        a, b = partner.get((i, 0)), partner.get((i, 1))
        if piece.length > limit_mm or a is None or b is None or i in (a[0], b[0]) or a == b:
            continue
        if a[0] in dropped or b[0] in dropped:
            continue
        if _wrap(_leave(kept[b[0]], b[1]) - _arrive(kept[a[0]], a[1])) <= math.radians(TANGENT_FREE_DEG):
            partner[a], partner[b] = b, a
            del partner[(i, 0)], partner[(i, 1)]
            dropped.add(i)
    if not dropped:
        return kept, partner
    first = kept[min(dropped)]
    notes.append(f"dropped {len(dropped)} pieces of {limit_mm:g} mm or less between pieces that meet tangentially "
                 f"across them (rounding where a path closes; first: {first.source}, {first.length:.3g} mm)")
    index = {old: new for new, old in enumerate(k for k in range(len(kept)) if k not in dropped)}
    moved = {(index[i], side): (index[j], other) for (i, side), (j, other) in partner.items()}
    return [p for k, p in enumerate(kept) if k not in dropped], moved


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


def _snap(oriented: list[Piece], closed: bool) -> tuple[tuple[Piece, ...], list[float]]:
    """The pieces with coinciding ends at every join, and how far that moved each one's drawn
    points (mm)."""
    n = len(oriented)
    joins = [_junction(oriented[k], oriented[k + 1]) for k in range(n - 1)]
    seam = _junction(oriented[-1], oriented[0]) if closed else None
    out, moved = [], []
    for k, piece in enumerate(oriented):
        start = joins[k - 1] if k > 0 else (seam if closed else piece.start)
        end = joins[k] if k < n - 1 else (seam if closed else piece.end)
        moved.append(0.0)
        if (start, end) != (piece.start, piece.end):
            snapped = piece.with_ends(start, end)
            moved[-1] = _moved(piece, snapped)
            piece = snapped
        out.append(piece)
    return tuple(out), moved


def _moved(old: Piece, new: Piece) -> float:
    """How far moving a piece's ends moved its points, at most (mm): of an arc, the largest
    distance between its points at the same share of its length before and after (its centre
    moves far more than its points where a long arc's ends move along its chord)."""
    ends = max(math.dist(old.start, new.start), math.dist(old.end, new.end))
    if _is_native(old) and isinstance(old.segment, Arc):
        u = np.linspace(0.0, 1.0, _MOVE_SAMPLES)
        before, after = old.segment.points(u * old.segment.length), new.segment.points(u * new.segment.length)
        return max(ends, float(np.linalg.norm(before - after, axis=1).max()))
    return ends


def _contour(pieces: tuple[Piece, ...], closed: bool, moved: float) -> Contour:
    pairs = list(zip(pieces[:-1], pieces[1:])) + ([(pieces[-1], pieces[0])] if closed else [])
    breaks = tuple(_wrap(b.start_heading - a.end_heading) for a, b in pairs)
    tangent = tuple(join_is_tangent(a, b, brk) for (a, b), brk in zip(pairs, breaks))
    return Contour(pieces, closed, tangent, breaks, moved)


def _chains(kept: list[Piece], partner: dict) -> list[tuple[list[Piece], list[int], bool]]:
    """Every chain of pieces joined through ``partner``, in drawing order."""
    seen = np.zeros(len(kept), dtype=bool)
    chains = []
    for i in range(len(kept)):
        if not seen[i]:
            oriented, members, closed = _walk(i, partner, kept)
            seen[members] = True
            chains.append((oriented, members, closed))
    return chains


def _open_ends(kept: list[Piece], chains: list) -> list[tuple[tuple[int, int], tuple[float, float], int]]:
    """The free ends of open chains: (piece index, side), point, chain index."""
    out = []
    for c, (oriented, members, closed) in enumerate(chains):
        if closed:
            continue
        first, last = members[0], members[-1]
        for index, point in ((first, oriented[0].start), (last, oriented[-1].end)):
            side = 0 if kept[index].start == point else 1
            out.append(((index, side), point, c))
    return out


def _near_joins(kept: list[Piece], partner: dict, tol: float, near_mm: float,
                notes: list[str]) -> list[tuple[tuple[int, int], tuple[int, int]]]:
    """Join open ends farther apart than ``tol`` but within NEAR_SHARE of ``near_mm`` (nearest
    first, each end once), into ``partner``; note what was joined and what was left apart.
    Returns the ends joined."""
    ends = _open_ends(kept, _chains(kept, partner))
    if len(ends) < 2:
        return []
    pts = np.array([p for _, p, _ in ends], dtype=float)
    pairs = sorted(((float(np.linalg.norm(pts[i] - pts[j])), i, j) for i, j in cKDTree(pts).query_pairs(near_mm)))
    joined, apart, used = [], [], set()
    for gap, i, j in pairs:
        if gap <= tol or i in used or j in used:
            continue
        (a, b) = ends[i][0], ends[j][0]
        if gap <= NEAR_SHARE * near_mm and a != b:
            partner[a], partner[b] = b, a
            used |= {i, j}
            joined.append((gap, i, j))
        else:
            apart.append((gap, i, j))
    name = lambda i: kept[ends[i][0][0]].source  # noqa: E731
    if joined:
        gap, i, j = max(joined)
        notes.append(f"joined {_pairs(len(joined))} of ends closer than the tolerance but farther apart than the join "
                     f"tolerance {tol:g} mm; the largest gap closed is {gap:.3g} mm, at ({pts[i][0]:.6g}, {pts[i][1]:.6g}) "
                     f"between {name(i)} and {name(j)}")
    apart = [(g, i, j) for g, i, j in apart if i not in used and j not in used]
    if apart:
        gap, i, j = min(apart)
        what = "its own start" if ends[i][2] == ends[j][2] else name(j)
        notes.append(f"{_pairs(len(apart))} of ends {near_mm:g} mm or less apart not joined (joining them would move "
                     f"the drawing by more than {NEAR_SHARE * near_mm:g} mm): they end contours of their own, first "
                     f"{name(i)} at ({pts[i][0]:.6g}, {pts[i][1]:.6g}), {gap:.3g} mm from {what}")
    return [(ends[i][0], ends[j][0]) for _, i, j in joined]


def _contours(kept: list[Piece], partner: dict, near: list, tol: float, limit: float,
              notes: list[str]) -> tuple[Contour, ...]:
    """The contours with their ends made to meet (moves within the join tolerance ``tol`` are
    round-off, not counted in ``moved_mm``); a near-miss join that would move an arc (its
    centre) by more than ``limit`` is undone, and noted."""
    while True:
        contours, undone = [], False
        for oriented, members, closed in _chains(kept, partner):
            snapped, moves = _snap(oriented, closed)
            moved = max(moves)
            inside = [(a, b) for a, b in near if a[0] in members]
            if moved > limit and inside:
                over = {m for m, mv in zip(members, moves) if mv > limit}
                culprits = [(a, b) for a, b in inside if a[0] in over or b[0] in over] or inside
                for a, b in culprits:
                    partner.pop(a), partner.pop(b)
                    near.remove((a, b))
                notes.append(f"{len(culprits)} near-miss joins in the contour from {kept[members[0]].source} undone: "
                             f"they would move it by {moved:.3g} mm")
                undone = True
                break
            contours.append(_contour(snapped, closed, moved if moved > tol else 0.0))
        if not undone:
            return tuple(contours)


def _pairs(n: int) -> str:
    return f"{n} pair" + ("s" if n != 1 else "")


def chain_pieces(pieces: Sequence[Piece], join_tol_mm: float, source: str = "drawing",
                 near_mm: Optional[float] = None) -> Chaining:
    """Contours of ``pieces`` joined within ``join_tol_mm``, and near misses within
    ``near_mm`` (σ) where that moves the drawing little; see the module docstring."""
    if not (math.isfinite(join_tol_mm) and join_tol_mm > 0):
        raise InputError(f"join tolerance {join_tol_mm} mm (--join-tol): must be a finite number > 0")
    notes: list[str] = []
    near = near_mm is not None and near_mm > join_tol_mm
    kept = _drop_degenerate(pieces, join_tol_mm, NEAR_SHARE * near_mm if near else join_tol_mm, notes)
    if not kept:
        raise InputError(f"{source}: every piece is shorter than the join tolerance {join_tol_mm:g} mm")
    overlaps = overlapping_lines(kept, join_tol_mm)
    if overlaps:
        notes.append(f"{len(overlaps)} pairs of lines overlap along one line, kept and sprayed twice there "
                     f"(first: {overlaps[0][0].source} and {overlaps[0][1].source})")
    partner = _pair_ends(kept, join_tol_mm, notes)
    if near:
        kept, partner = _bridged(kept, partner, NEAR_SHARE * near_mm, notes)
    joins = _near_joins(kept, partner, join_tol_mm, near_mm, notes) if near else []
    limit = NEAR_SHARE * near_mm if near_mm is not None else math.inf
    return Chaining(_contours(kept, partner, joins, join_tol_mm, limit, notes), tuple(notes))

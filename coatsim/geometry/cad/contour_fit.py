"""A chained contour becomes a polysegment: native lines and arcs exactly, free-form
stretches fitted within the tolerance.

- Native pieces go in as they are. Collinear lines and concentric arcs of equal radius that
  meet tangentially are merged into one segment, when the merge moves nothing by more than
  round-off (``MERGE_EPS`` relative), so a drawing of lines and arcs comes back with at most
  as many segments as primitives and zero deviation.
- A free-form stretch is a run of free-form pieces joined tangentially. It is split at its
  true corners (cusps inside a piece, found by the rule of point curves) and fitted by the
  default fitter (``fit_run``) from its first to its last point; where it joins a native
  piece tangentially its end tangent is pinned to that piece's, so the join is G1 exactly.
  A closed contour that is one tangent free-form loop is fitted as a closed point curve.
- Lines and arcs that meet at a tangent broken by rounding only (within ``TANGENT_FREE_DEG``)
  are fitted as free-form pieces, so that join comes out tangent.
- Joins that are not tangent are the polysegment's corners.

The deviation reported is the largest of the merges' and of the fitted stretches' bounds:
each stretch is fitted within σ minus the flattening distance to samples that lie within
that distance of the drawn curves, and reports its verified deviation from the samples plus
the flattening distance. It is 0 for a contour of lines and arcs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from coatsim.geometry.cad.chaining import TANGENT_EXACT_RAD, TANGENT_FREE_DEG, Contour, join_is_tangent
from coatsim.geometry.cad.fit_copies import Fitted, bucket, reuse
from coatsim.geometry.cad.pieces import FreePiece
from coatsim.geometry.corners import detect_corners
from coatsim.geometry.fit import fit_run
from coatsim.geometry.limits import fit_limits
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Line, Segment

MERGE_EPS = 1e-9
DENSE_STEP_SIGMAS = 1.0  # the fitter gets free-form stretches with points at most this many σ apart


@dataclass(frozen=True, eq=False)
class ContourFit:
    """The contour's polysegment, its verified deviation (mm), the dense samples of the drawn
    contour (n, 2) (closed: last = first), and how many pieces went in."""

    polysegment: Polysegment
    deviation_mm: float
    points: np.ndarray
    n_pieces: int


@dataclass
class _Block:
    """Consecutive pieces fitted or copied together: one native piece, or a free stretch."""

    pieces: list
    free: bool


def _blocks(contour: Contour) -> tuple[list[_Block], list[bool], bool]:
    """Blocks in contour order, tangency of the join after each block (seam last when
    closed), and whether the whole contour is one tangent free-form loop."""
    pieces, tangent = list(contour.pieces), list(contour.tangent)
    n = len(pieces)
    free = [isinstance(p, FreePiece) for p in pieces]
    if contour.closed:
        # start at a join that ends a block: a corner, or one with a native piece on either side
        cuts = [k for k in range(n) if not (free[k] and free[(k + 1) % n] and tangent[k])]
        if not cuts:
            return [_Block(pieces, True)], [True], True
        first = (cuts[-1] + 1) % n
        pieces, tangent, free = pieces[first:] + pieces[:first], tangent[first:] + tangent[:first], free[first:] + free[:first]
    blocks: list[_Block] = []
    after: list[bool] = []
    for k, piece in enumerate(pieces):
        if blocks and free[k] and blocks[-1].free and tangent[k - 1]:
            blocks[-1].pieces.append(piece)
            continue
        if blocks:
            after.append(tangent[k - 1])
        blocks.append(_Block([piece], free[k]))
    if contour.closed:
        after.append(tangent[-1])
    return blocks, after, False


def _free_points(block: _Block) -> np.ndarray:
    return np.vstack([block.pieces[0].points[:1]] + [p.points[1:] for p in block.pieces])


def _fit_free(points: np.ndarray, tolerance: float, closed_loop: bool, start_heading: float | None,
              end_heading: float | None, speed_kappa: float | None = None,
              cache: dict | None = None) -> tuple[tuple[Segment, ...], float]:
    """The fitter on one free-form stretch, its end tangents pinned where given (a stretch
    pinned at its end only is fitted backwards with its start pinned); ``speed_kappa`` = a / v²
    caps its arcs for the programmed speed. The fitter gets the stretch's polyline with extra
    points on its chords (``densified``). A stretch that copies one fitted before (``cache``,
    one per drawing) gets that chain moved into place (:mod:`coatsim.geometry.cad.fit_copies`)."""
    originals = cache.setdefault(bucket(points, closed_loop, speed_kappa), []) if cache is not None else None
    if originals:
        reused = reuse(originals, points, tolerance, start_heading, end_heading)
        if reused is not None:
            return reused
    dense = densified(points, DENSE_STEP_SIGMAS * tolerance)
    if start_heading is None and end_heading is not None:
        back = dense[::-1]
        fit = fit_run(back, tolerance, False, fit_limits(back, False, tolerance, None, speed_kappa),
                      start_heading=end_heading + math.pi).reversed()
    else:
        fit = fit_run(dense, tolerance, closed_loop, fit_limits(dense, closed_loop, tolerance, None, speed_kappa),
                      start_heading=start_heading, end_heading=end_heading)
    segments, dev = tuple(fit.segments), fit.deviation_mm
    if originals is not None:
        originals.append(Fitted(points.copy(), start_heading, end_heading, segments, dev))
    return segments, dev


def densified(points: np.ndarray, step_mm: float) -> np.ndarray:
    """The same polyline with points added on its chords, none farther than ``step_mm``
    apart. Flattened curves are sampled sparsely where they are straight and densely where
    they bend; the fitter's curvature estimate (made for evenly sampled curves) misreads
    long sparse chords, fails its caps and retries for seconds, or falls back."""
    edges = np.linalg.norm(np.diff(points, axis=0), axis=1)
    parts = np.maximum(1, np.ceil(edges / step_mm).astype(np.int64))
    if parts.max() == 1:
        return points
    edge = np.repeat(np.arange(len(edges)), parts)
    first = np.repeat(np.cumsum(parts) - parts, parts)
    frac = (np.arange(int(parts.sum())) - first + 1) / np.repeat(parts, parts)
    dense = np.vstack((points[:1], points[edge] + frac[:, None] * (points[edge + 1] - points[edge])))
    dense[np.cumsum(parts)] = points[1:]  # the original vertices exactly
    return dense


def _corner_vertices(points: np.ndarray, tolerance: float, corner_deg: float, closed: bool = False) -> list[int]:
    """Sample indices of the true corners of a stretch (a closed loop repeats its first
    sample last). The samples are denser where the curve bends (flattening), which the corner
    rule (made for evenly sampled input) would read as corners, so it runs on an even
    resampling at σ/2; each corner found is the sample with the sharpest turn within σ."""
    ell = np.linalg.norm(np.diff(points, axis=0), axis=1)
    s = np.concatenate(([0.0], np.cumsum(ell)))
    n = int(np.clip(np.ceil(s[-1] / (tolerance / 2)), 8, 200_000))
    u = np.linspace(0.0, s[-1], n + 1)
    even = np.column_stack((np.interp(u, s, points[:, 0]), np.interp(u, s, points[:, 1])))
    heading = np.arctan2(np.diff(points[:, 1]), np.diff(points[:, 0]))
    wrap = lambda a: np.abs(np.remainder(a + math.pi, 2 * math.pi) - math.pi)  # noqa: E731
    turn = np.concatenate(([wrap(heading[0] - heading[-1]) if closed else 0.0], wrap(np.diff(heading)), [0.0]))
    inner = np.arange(len(s)) < len(s) - 1
    if not closed:
        inner &= np.arange(len(s)) > 0
    found = []
    for c in detect_corners(even, closed, corner_deg, tolerance):
        gap = np.abs(s - u[int(c)])
        if closed:
            gap = np.minimum(gap, s[-1] - gap)
        near = np.flatnonzero((gap <= tolerance) & inner)
        if len(near):
            found.append(int(near[np.argmax(turn[near])]))
    return sorted(set(found))


def _fit_stretch(points: np.ndarray, tolerance: float, corner_deg: float | None, start_heading: float | None,
                 end_heading: float | None, cuts: list[int] | None = None,
                 speed_kappa: float | None = None, cache: dict | None = None) -> tuple[list[Segment], list[bool], float]:
    """An open free-form stretch split at its true corners (cusps inside a piece; the rule of
    point curves, see detect_corners; or at ``cuts``), each run fitted, the stretch's ends
    pinned where given. Returns the segments, the corner flag of every join between them,
    the deviation."""
    inner = _corner_vertices(points, tolerance, corner_deg) if cuts is None else sorted(cuts)
    cuts = [0, *inner, len(points) - 1]
    segments: list[Segment] = []
    corner_after: list[bool] = []
    worst = 0.0
    for k, (a, b) in enumerate(zip(cuts[:-1], cuts[1:])):
        fitted, dev = _fit_free(points[a:b + 1], tolerance, False, start_heading if k == 0 else None,
                                end_heading if b == len(points) - 1 else None, speed_kappa, cache)
        if segments:
            corner_after.append(True)
        segments.extend(fitted)
        corner_after.extend([False] * (len(fitted) - 1))
        worst = max(worst, dev)
    return segments, corner_after, worst


def _free_loop(points: np.ndarray, tolerance: float, corner_deg: float,
               speed_kappa: float | None, cache: dict | None = None) -> tuple[Polysegment, float]:
    """A closed contour that is one free-form loop: fitted as a closed loop, or, where it has
    true corners, from its first corner on, run by run between them."""
    corners = _corner_vertices(points, tolerance, corner_deg, closed=True)
    if not corners:
        segs, dev = _fit_free(points, tolerance, True, None, None, speed_kappa, cache)
        return Polysegment(tuple(segs), closed=True), dev
    body, first = points[:-1], corners[0]
    rotated = np.vstack((body[first:], body[:first], body[first:first + 1]))
    segs, inner, dev = _fit_stretch(rotated, tolerance, None, None, None,
                                    cuts=[(c - first) % len(body) for c in corners[1:]], speed_kappa=speed_kappa, cache=cache)
    flags = inner + [True]  # the seam is the first corner
    return Polysegment(tuple(segs), closed=True, corners=tuple(k for k, c in enumerate(flags) if c)), dev


def _scale(segments: list[Segment]) -> float:
    return max(1.0, max(abs(c) for s in segments for p in (s.start, s.end) for c in p))


def _merged(a: Segment, b: Segment, eps: float) -> tuple[Segment, float] | None:
    """One segment for a tangent pair of collinear lines or concentric equal arcs, and how
    far it moves the pair (mm); None if they are not such a pair."""
    if isinstance(a, Line) and isinstance(b, Line):
        line = Line(a.start, b.end)
        d, e = np.subtract(b.end, a.start), np.subtract(a.end, a.start)
        norm = float(np.linalg.norm(d))
        if norm == 0.0:
            return None
        off = abs(float(d[0] * e[1] - d[1] * e[0])) / norm
        return (line, off) if off <= eps else None
    if isinstance(a, Arc) and isinstance(b, Arc) and (a.sweep > 0) == (b.sweep > 0):
        off = math.dist(a.center, b.center) + abs(a.radius - b.radius)
        if off <= eps and abs(a.sweep + b.sweep) <= 2 * math.pi * (1 + 1e-12):
            return Arc(a.start, b.end, a.center, a.radius, a.sweep + b.sweep), off
    return None


def _merge(segments: list[Segment], corner_after: list[bool], closed: bool) -> tuple[list[Segment], list[bool], float]:
    """Merge tangent collinear lines and concentric equal arcs (across the seam too)."""
    eps = MERGE_EPS * _scale(segments)
    segs, corners, worst = [segments[0]], [], 0.0
    for k in range(1, len(segments)):
        merged = None if corner_after[k - 1] else _merged(segs[-1], segments[k], eps)
        if merged is None:
            segs.append(segments[k])
            corners.append(corner_after[k - 1])
        else:
            segs[-1], worst = merged[0], max(worst, merged[1])
    if closed:
        corners.append(corner_after[-1])
        if len(segs) > 1 and not corners[-1]:
            merged = _merged(segs[-1], segs[0], eps)
            if merged is not None:
                segs = [merged[0]] + segs[1:-1]
                corners = corners[:-1]  # the seam is now the join before the merged segment
                worst = max(worst, merged[1])
    return segs, corners, worst


def _rounded_joins_freed(contour: Contour, flatten_mm: float) -> Contour:
    """The contour with the arcs at a join that breaks tangency by rounding only (more than
    ``TANGENT_EXACT_RAD``, at most ``TANGENT_FREE_DEG``; two lines there: both) made free-form
    pieces (their samples), so that the fit makes those joins tangent within the tolerance, its
    arcs pinned to the lines beside them. A
    CAM program's biarcs with their ends rounded to 0.01 mm meet 0.01-0.1 deg apart: kept as
    drawn, every join was a corner, a stop of the robot (72 on an ellipse)."""
    n = len(contour.pieces)
    rounded = [contour.breaks[k] > TANGENT_EXACT_RAD and contour.breaks[k] <= math.radians(TANGENT_FREE_DEG)
               and not isinstance(contour.pieces[k], FreePiece) and not isinstance(contour.pieces[(k + 1) % n], FreePiece)
               for k in range(len(contour.breaks))]
    if not any(rounded):
        return contour
    freed = set()
    for k in (k for k, r in enumerate(rounded) if r):
        pair = {k, (k + 1) % n}
        arcs = {j for j in pair if isinstance(contour.pieces[j].segment, Arc)}
        freed |= arcs or pair  # a line next to an arc stays: the arc's fit is pinned to it
    pieces = tuple(FreePiece(p.samples(flatten_mm), p.start_heading, p.end_heading, p.source, p.path) if k in freed else p
                   for k, p in enumerate(contour.pieces))
    pairs = list(zip(pieces[:-1], pieces[1:])) + ([(pieces[-1], pieces[0])] if contour.closed else [])
    tangent = tuple(join_is_tangent(a, b, brk) for (a, b), brk in zip(pairs, contour.breaks))
    return replace(contour, pieces=pieces, tangent=tangent)


def _samples(contour: Contour, flatten_mm: float) -> np.ndarray:
    parts = [contour.pieces[0].samples(flatten_mm)[:1]] + [p.samples(flatten_mm)[1:] for p in contour.pieces]
    pts = np.vstack(parts)
    if contour.closed:
        pts[-1] = pts[0]
    return pts


def fit_contour(contour: Contour, tolerance_mm: float, flatten_mm: float, corner_deg: float = 20.0,
                speed_kappa: float | None = None, cache: dict | None = None) -> ContourFit:
    """The polysegment of one contour; see the module docstring. Free-form samples lie
    within ``flatten_mm`` of the drawn curves, so stretches are fitted to them within
    ``tolerance_mm - flatten_mm`` and their deviation is reported plus ``flatten_mm``: an
    upper bound of the distance to the drawn curve, at most ``tolerance_mm``. ``speed_kappa``
    = a / v² keeps fitted arcs no tighter than the programmed speed allows where the drawn
    curve allows it. ``cache`` (a dict kept over the contours of one drawing) lets
    translated copies of a free-form stretch share one fit (:mod:`coatsim.geometry.cad.fit_copies`)."""
    if not 0 < flatten_mm < tolerance_mm:
        raise ValueError("flatten_mm must be between 0 and the tolerance")
    fit_tol = tolerance_mm - flatten_mm
    contour = _rounded_joins_freed(contour, flatten_mm)
    blocks, tangent_after, loop = _blocks(contour)
    if loop:
        poly, dev = _free_loop(_free_points(blocks[0]), fit_tol, corner_deg, speed_kappa, cache)
        return ContourFit(poly, dev + flatten_mm, _samples(contour, flatten_mm), len(contour.pieces))
    segments: list[Segment] = []
    corner_after: list[bool] = []
    worst = 0.0
    n = len(blocks)
    for k, block in enumerate(blocks):
        if block.free:
            before, after = blocks[(k - 1) % n], blocks[(k + 1) % n]
            pin_start = (k > 0 or contour.closed) and not before.free and tangent_after[k - 1]
            pin_end = k < len(tangent_after) and not after.free and tangent_after[k]
            fitted, inner, dev = _fit_stretch(_free_points(block), fit_tol, corner_deg,
                                              before.pieces[-1].end_heading if pin_start else None,
                                              after.pieces[0].start_heading if pin_end else None,
                                              speed_kappa=speed_kappa, cache=cache)
            worst = max(worst, dev + flatten_mm)
        else:
            fitted, inner = [block.pieces[0].segment], []
        segments.extend(fitted)
        corner_after.extend(inner)
        if k < len(tangent_after):
            corner_after.append(not tangent_after[k])
    corner_after = _fitted_breaks(segments, corner_after, contour.closed)
    segs, corners, merge_dev = _merge(segments, corner_after, contour.closed)
    poly = Polysegment(tuple(segs), closed=contour.closed, corners=tuple(k for k, c in enumerate(corners) if c))
    return ContourFit(poly, max(worst, merge_dev), _samples(contour, flatten_mm), len(contour.pieces))


def _fitted_breaks(segments: list[Segment], corner_after: list[bool], closed: bool) -> list[bool]:
    """Corner flags with every join that is not tangent in the result marked as a corner
    (a join the drawing has tangent but a fit could not pin)."""
    out = list(corner_after)
    n = len(segments)
    for k in range(len(out)):
        a, b = segments[k], segments[(k + 1) % n]
        if not out[k] and abs(math.remainder(b.start_heading - a.end_heading, 2 * math.pi)) > TANGENT_EXACT_RAD:
            out[k] = True
    return out


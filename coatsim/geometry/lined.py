"""A planar run with straight stretches: lines where the input is straight, one arc for a bend
between two of them, the other curved stretches fitted with their end headings pinned to the
lines' directions.

The default fit (coatsim.geometry.fit) has lines only where the input is exactly lines and
circles (coatsim.geometry.recover): a rounded rectangle whose corners are a hair off circular
came back as fifteen arcs, its straight sides of radius 5–90 m, that a controller runs as
circles and a user reads as a fault. The straight stretches are found as in space
(coatsim.geometry.space.straight: within σ/2 of a line over at least 50 σ, and unbent); a bend
between two lines is the arc tangent to both with the radius that fits its input best, each line
ending at a tangent point (between lines running opposite ways, a U-turn: the arc tangent to the
first, the second leaving it along its tangent), where that keeps the input of the bend and both
lines within σ. The chain is a candidate where it is G1 at every junction and within σ of the
whole run; the caller takes it over the chain without lines where each straight stretch costs at
most a segment (with_lines).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from coatsim.core.errors import InputError
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fit import fit_free, fit_simple
from coatsim.geometry.limits import fit_limits
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Line, Segment, make_segment
from coatsim.geometry.run_fit import RunFit
from coatsim.geometry.space.straight import Straight, lined_loop_run, straight_stretches
from coatsim.geometry.sparse import is_sparse

G1_RAD = 1e-9  # a junction of the lined chain breaking its tangent by more: the chain is not taken
MIN_TURN_RAD = 1e-3  # lines turning less than this meet in no useful point
MIN_POINTS = 3  # input points inside a bend that its radius is fitted to, at least


def _heading(u: np.ndarray) -> float:
    return math.atan2(float(u[1]), float(u[0]))


def _point(p: np.ndarray) -> tuple[float, float]:
    return float(p[0]), float(p[1])


def lined_run(points: np.ndarray, tol: float, min_segment_mm: float | None,
              speed_kappa: float | None) -> RunFit | None:
    """The lined chain of an open run (n, 2) without corners, or None where the run has no
    straight stretch or the chain is not G1 within σ (see the module text)."""
    lines = straight_stretches(points, tol)
    if not lines:
        return None
    chain = _chain(points, tol, lines, min_segment_mm, speed_kappa)
    return None if chain is None else _checked(points, *chain, False, tol)


def lined_loop(points: np.ndarray, tol: float, min_segment_mm: float | None,
               speed_kappa: float | None) -> RunFit | None:
    """The lined chain of a closed loop (n, 2; last point = first) without corners, fitted
    round it from the start of a straight stretch to that stretch again
    (coatsim.geometry.space.straight.lined_loop_run), or None (as lined_run)."""
    lined = lined_loop_run(points, tol)
    if lined is None:
        return None
    loop = lined.points[: lined.lap + 1]
    for bend_back in (True, False):  # a U-turn re-aims the line after it: one back onto the first line may
        chain = _chain(lined.points, tol, lined.lines, min_segment_mm, speed_kappa,  # miss its direction (a
                       tail=False, bend_back=bend_back)                              # slot): pinned arcs there
        if chain is not None:
            segments, kept = chain
            found = _checked(loop, (Line(segments[-1].start, segments[0].end),) + segments[1:-1], kept, True, tol)
            if found is not None:
                return found
    return None


def with_lines(lined: RunFit | None, plain: RunFit) -> RunFit:
    """The lined chain where its straight stretches cost at most a segment each: fewer segments
    than the chain without lines, or more lines and no more segments than it has plus the lines
    added (a straight side drawn as an arc of metres reads as a fault and runs as a circle; a
    chain of exact lines and circles stays as it is)."""
    if lined is None:
        return plain
    lines = lambda fit: sum(isinstance(s, Line) for s in fit.segments)  # noqa: E731
    extra, added = len(lined.segments) - len(plain.segments), lines(lined) - lines(plain)
    return lined if extra < 0 or 0 < added >= extra else plain


def _checked(points: np.ndarray, segments: tuple[Segment, ...], kept: bool, closed: bool,
             tol: float) -> RunFit | None:
    """The chain as a run's fit where it is G1 at every junction and within σ of ``points``."""
    poly = Polysegment(segments, closed=closed)
    if np.any(poly.junction_breaks() > G1_RAD):
        return None
    dev = hausdorff(points, poly).hausdorff
    return RunFit(segments, dev, limits_kept=kept) if dev <= tol else None


def _chain(run: np.ndarray, tol: float, lines: list[Straight], min_segment_mm: float | None,
           speed_kappa: float | None, tail: bool = True, bend_back: bool = True) -> tuple[tuple[Segment, ...], bool] | None:
    """The segments of ``run`` with ``lines`` for its straight stretches, bends between two
    lines as one arc and the other curved stretches pinned to the lines (``tail``: the stretch
    after the last line too; without ``bend_back`` the stretch before the last line is pinned
    arcs, never one bend), and whether the pinned fits kept their curvature caps; None where a
    pinned fit fails."""
    segments: list[Segment] = []
    kept = True
    after: Straight | None = None  # the line before the curved stretch
    for line in [*lines, None] if tail else lines:
        bend = None if after is None or line is None or (line is lines[-1] and not bend_back) \
            else _bend(after, line, run, tol)
        if bend is not None:
            _, arc, after = bend
            segments[-1] = Line(segments[-1].start, arc.start)
            segments += [arc, Line(arc.end, _point(after.end))]
            continue
        head = run[:1] if after is None else after.end[None]
        body = run[(0 if after is None else after.last) + 1 : (len(run) - 1 if line is None else line.first)]
        tail = run[-1:] if line is None else line.start[None]
        stretch = np.vstack((head, body, tail))
        stretch = stretch[np.r_[True, np.any(np.diff(stretch, axis=0) != 0, axis=1)]]  # a line's end on an input point
        if (after is not None or line.first > 0) and (len(body) or float(np.linalg.norm(tail - head)) > 0):
            start = None if after is None else _heading(after.direction)
            end = None if line is None else _heading(line.direction)
            fitted = _pinned(stretch, tol, start, end, min_segment_mm, speed_kappa)
            if fitted is None:
                return None
            segments.extend(fitted.segments)
            kept = kept and fitted.limits_kept
        if line is not None:
            start = segments[-1].end if segments else _point(line.start)
            segments.append(Line(start, _point(line.end)))
            after = line
    return tuple(segments), kept


def _pinned(stretch: np.ndarray, tol: float, start: float | None, end: float | None, min_segment_mm: float | None,
            speed_kappa: float | None) -> RunFit | None:
    """The fit of a curved stretch leaving along ``start`` and arriving along ``end`` (rad; None:
    free), or None where it misses σ, has a corner or does not keep a pin."""
    if len(stretch) < MIN_POINTS + 2:  # two lines meeting with no input between them: no G1 chain joins them
        return None
    backwards = start is None  # only the end pinned: the reversed stretch with its start pinned
    run = stretch[::-1] if backwards else stretch
    first = (end + math.pi) if backwards else start
    last = None if backwards else end
    if first is None:
        return None
    limits = fit_limits(run, False, tol, min_segment_mm, speed_kappa)
    found = fit_simple(run, tol, False, first, last) or fit_free(run, tol, False, limits, quick=True,
                                                                 start_heading=first, end_heading=last)
    if found is None and not is_sparse(run, False, tol):  # taught points: the halving search is long; the
        try:                                               # chain without lines is the fallback
            found = fit_free(run, tol, False, limits, fillet=False, start_heading=first, end_heading=last)
        except InputError:
            return None
    if found is None:
        return None
    segments = found.segments
    off = lambda a, b: abs(math.remainder(a - b, 2 * math.pi))  # noqa: E731
    if found.corners or found.deviation_mm > tol or off(segments[0].start_heading, first) > G1_RAD \
            or (last is not None and off(segments[-1].end_heading, last) > G1_RAD):
        return None
    return found.reversed() if backwards else found


def _bend(before: Straight, after: Straight, points: np.ndarray, tol: float) -> tuple[Straight, Segment, Straight] | None:
    """The two lines cut at the tangent points of the arc tangent to both whose radius fits the
    bend's input best, and that arc; None where the lines turn too little or too much, the
    bend has too few points, or the lines and the arc miss σ of the input they stand for."""
    u1, u2 = before.direction, after.direction
    cross, dot = float(u1[0] * u2[1] - u1[1] * u2[0]), float(u1 @ u2)
    turn = math.atan2(cross, dot)
    inner = points[before.last + 1 : after.first]
    if abs(turn) <= MIN_TURN_RAD or len(inner) < MIN_POINTS:
        return None
    if abs(turn) >= math.pi - MIN_TURN_RAD:
        return _u_turn(before, after, inner, points, tol)
    w = after.start - before.end  # the lines meet where before.end + a u1 = after.start + b u2
    a = float(w[0] * u2[1] - w[1] * u2[0]) / cross
    corner = before.end + a * u1
    room = min(float((corner - before.start) @ u1), float((after.end - corner) @ u2))
    if not room > 0:
        return None
    inward = math.copysign(1.0, turn) * np.array([-u1[1], u1[0]])
    half = math.tan(abs(turn) / 2)

    def misfit(radius: float) -> float:
        centre = corner - u1 * radius * half + inward * radius
        return float(np.square(np.linalg.norm(inner - centre, axis=1) - radius).sum())

    radius = float(minimize_scalar(misfit, bounds=(1e-6 * room / half, room / half), method="bounded").x)
    t1 = before.start + u1 * float((corner - u1 * radius * half - before.start) @ u1)
    arc = make_segment(_point(t1), _heading(u1), math.copysign(1.0 / radius, turn), radius * abs(turn))
    return _kept(before, after, arc, points, tol)


def _u_turn(before: Straight, after: Straight, inner: np.ndarray, points: np.ndarray,
            tol: float) -> tuple[Straight, Segment, Straight] | None:
    """A bend between lines running (nearly) opposite ways (a slot's end, a raster's turn-around):
    they meet nowhere, so the arc is the one tangent to the line before (where along it, and its
    radius, fitted to the bend's input by least squares) and the line after leaves it along the
    tangent through that line's far end."""
    u1 = before.direction
    left = np.array([-u1[1], u1[0]])
    side = math.copysign(1.0, float((after.start - before.end) @ left))
    inward = side * left

    def misfit(x: np.ndarray) -> np.ndarray:
        centre = before.end + x[0] * u1 + x[1] * inward
        return np.linalg.norm(inner - centre, axis=1) - x[1]

    width = abs(float((after.start - before.end) @ inward))
    guess = np.array([float(((inner - before.end) @ u1).max()) - width / 2, width / 2])
    along, radius = least_squares(misfit, guess, x_scale=max(width, tol)).x
    if not radius > 0:
        return None
    t1 = before.end + along * u1
    rel = after.end - (t1 + radius * inward)
    dist = float(np.linalg.norm(rel))
    if not dist > radius or (t1 - before.start) @ u1 <= 0:
        return None
    tangent = math.atan2(float(rel[1]), float(rel[0])) - side * math.acos(radius / dist)  # radial angle of the tangent point
    start = math.atan2(float(-inward[1]), float(-inward[0]))
    sweep = (side * (tangent - start)) % (2 * math.pi)
    arc = make_segment(_point(t1), _heading(u1), side / radius, radius * sweep)
    return _kept(before, after, arc, points, tol)


def _kept(before: Straight, after: Straight, arc: Segment, points: np.ndarray,
          tol: float) -> tuple[Straight, Segment, Straight] | None:
    """The lines cut at the arc's ends (the line after leaving the arc's end for its own far end:
    G1 to round-off) and the arc, where each line keeps a piece and the lines and the arc keep
    the input from the first point of the line before to the last of the line after within σ."""
    t1, t2 = np.asarray(arc.start), np.asarray(arc.end)
    u1, u2 = before.direction, (after.end - t2) / np.linalg.norm(after.end - t2)
    q1 = t1 - u1 * float((t1 - points[before.first]) @ u1)
    q2 = t2 + u2 * float((points[after.last] - t2) @ u2)
    if not ((t1 - q1) @ u1 > 0 and (q2 - t2) @ u2 > 0 and (t1 - before.start) @ u1 > 0
            and (after.end - t2) @ u2 > 0):
        return None  # the arc would take a whole line
    local = Polysegment((Line(_point(q1), _point(t1)), arc, Line(arc.end, _point(q2))))
    if hausdorff(points[before.first : after.last + 1], local).hausdorff > tol:
        return None
    return replace(before, end=t1), arc, replace(after, start=t2)

"""Straight stretches of a space curve, where a line stands for the input.

The arc spline of a run (coatsim.geometry.space.tube_fit) has no lines: a straight stretch
comes back as an arc of a radius of kilometres, bowing inside σ, that a controller runs as a
circle and a user reads as a fault (a pipe's centreline, line–bend–line–bend–line in two
planes, came back as five arcs). A stretch is straight where the line between two input
points keeps every point between them within LINE_SHARE σ over at least MIN_SIGMAS σ, and the
points do not bend (_unbent: by least squares, the mean curvature over the whole band and the
largest over the points the line stands for each keep a chord of the stretch, or of REF_SIGMAS σ,
the longer, within SAG_SHARE σ; a gently curved stretch uses the whole band, a sine's flank
bends at its ends: arcs keep both). Points (n, 2) or (n, 3): the planar fit finds its lines the
same way (coatsim.geometry.lined). The line is the points' least-squares line, ending where the input leaves it by END_SHARE
σ; the caller fits the curved stretches between lines with their end tangents pinned to the
lines' directions (or one arc tangent to both, coatsim.geometry.space.bend), so the chain stays G1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from coatsim.geometry.space.greedy import farthest
from coatsim.geometry.space.local import arc_length

LINE_SHARE = 0.5  # a straight stretch's line keeps the input within this share of σ, ...
MIN_SIGMAS = 50.0  # ... is at least this many σ long (REF_SIGMAS where the run ends before the band is used up), ...
SAG_SHARE, REF_SIGMAS = 0.25, 100.0  # ... and bends so little that a chord of its length (or of REF_SIGMAS σ,
                                     # the longer: a curved tail is no line) stays within SAG_SHARE σ
SKIP = 4  # where a line from a point is no straight stretch, the next is tried this share of its reach on
END_SHARE = 0.05  # the line ends where the input leaves it by this share of σ: a line drawn on into a bend
                  # leaves the next arc a tangent the curve has already turned from (2 mm into a bend of
                  # r 40 mm, 2.9 degrees: no honest arc then follows within σ)


@dataclass(frozen=True, eq=False)
class Straight:
    """Input points ``first`` to ``last`` (indices) stood for by the line from ``start`` to
    ``end`` (mm; the run's own end point where the stretch reaches it)."""

    first: int
    last: int
    start: np.ndarray
    end: np.ndarray

    @property
    def direction(self) -> np.ndarray:
        d = self.end - self.start
        return d / np.linalg.norm(d)


def straight_stretches(points: np.ndarray, tolerance: float) -> list[Straight]:
    """The straight stretches of a run of input points (n, 2 or 3), in order and not overlapping
    (see the module text)."""
    n, s = len(points), arc_length(points)
    out: list[Straight] = []
    i = 0
    while i < n - 1:
        j = farthest(i, n, lambda a, b: _line_fits(points, a, b, LINE_SHARE * tolerance))
        if s[j] - s[i] >= MIN_SIGMAS * tolerance and j - i >= 2:
            line = _trimmed(points, i, _onwards(points, i, j, END_SHARE * tolerance), END_SHARE * tolerance)
            shortest = (REF_SIGMAS if j == n - 1 else MIN_SIGMAS) * tolerance  # a band cut off by the run's end
            if line is not None and float(np.linalg.norm(line.end - line.start)) >= shortest \
                    and _unbent(points, i, j, line, tolerance):                # says less of a bend
                joined = _joined(points, out[-1], line, tolerance) if out else None
                if joined is not None:
                    out[-1] = joined
                else:
                    out.append(line)
                i = max(j, line.last)
                continue
        i += max(1, (j - i) // SKIP)
    return out


@dataclass(frozen=True, eq=False)
class LinedLoop:
    """A closed loop with straight stretches as an open run round it and a part of a lap
    more: ``points`` start where a stretch starts (not the one the loop's first point may cut
    in two) and go round to the end of that stretch again; ``lines`` are the run's stretches,
    the first one again last (the loop is ``points[:lap + 1]``), so a fit along them has the
    bend back onto the first line as any other and closes on its line."""

    points: np.ndarray
    lines: list[Straight]
    lap: int


def lined_loop_run(loop: np.ndarray, tolerance: float) -> LinedLoop | None:
    """The loop (last point = first) as a LinedLoop, or None where it has no straight stretch."""
    lines = straight_stretches(loop, tolerance)
    if not lines:
        return None
    body, first = loop[:-1], (lines[1] if len(lines) > 1 and lines[0].first == 0 else lines[0]).first
    run = np.vstack((body[first:], body[:first], body[first : first + 1]))
    lines = straight_stretches(run, tolerance)
    if not lines or lines[0].first != 0:
        return None
    head, lap = lines[0], len(run) - 1
    again = Straight(head.first + lap, head.last + lap, head.start, head.end)
    return LinedLoop(np.vstack((run, run[1 : head.last + 1])), [*lines, again], lap)


def _fitted_line(stretch: np.ndarray, through: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A point and the unit direction of the least-squares line of points (k, 3), or of the one
    through the point ``through``."""
    centre = stretch.mean(axis=0) if through is None else through
    return centre, np.linalg.svd(stretch - centre, full_matrices=False)[2][0]


def _offsets(points: np.ndarray, i: int, j: int) -> tuple[np.ndarray, np.ndarray, float]:
    """Points i..j as positions t along their least-squares line, scaled to [-1, 1], their
    offsets from it, and the scale (mm)."""
    stretch = points[i : j + 1]
    centre, u = _fitted_line(stretch)
    t = (stretch - centre) @ u
    scale = max(float(np.abs(t).max()), 1e-300)
    return t / scale, stretch - centre - t[:, None] * u, scale


def _sag(kappa: float, chord: float, tolerance: float) -> bool:
    """Whether a curvature ``kappa`` takes a chord of max(``chord``, REF_SIGMAS σ) no more than
    SAG_SHARE σ off it."""
    chord = max(chord, REF_SIGMAS * tolerance)
    return kappa * chord * chord / 8.0 <= SAG_SHARE * tolerance


def _unbent(points: np.ndarray, i: int, j: int, line: Straight, tolerance: float) -> bool:
    """Whether points i..j (where a line keeps the input within the band) and the stretch
    ``line`` stands for (the points within END_SHARE σ of it) bend by no more than a line
    allows: the mean curvature of the parabola fitted to the offsets of i..j from their
    least-squares line passes _sag over i..j (a gently curved stretch uses the whole band), and
    so does the largest curvature (at an end) of the cubic fitted to those of the line's own
    points over its length (across an inflection, a sine's flank, the parabola has no bend).
    Least squares: noise averages out, where a curve's offsets grow as the square of the
    distance, or as its cube."""
    x, off, scale = _offsets(points, i, j)
    bend = np.linalg.lstsq(np.column_stack((np.ones_like(x), x, x * x)), off, rcond=None)[0][2] / scale**2
    if not _sag(2.0 * float(np.linalg.norm(bend)), 2.0 * scale, tolerance):
        return False
    x, off, scale = _offsets(points, line.first, line.last)
    coef = np.linalg.lstsq(np.column_stack((np.ones_like(x), x, x * x, x**3)), off, rcond=None)[0]
    bend, twist = coef[2] / scale**2, coef[3] / scale**3  # offset = ... + bend t² + twist t³: curvature 2 bend + 6 twist t
    kappa = max(float(np.linalg.norm(2 * bend + 6 * twist * end * scale)) for end in (x[0], x[-1]))
    return _sag(kappa, float(np.linalg.norm(line.end - line.start)), tolerance)


def _joined(points: np.ndarray, first: Straight, second: Straight, tolerance: float) -> Straight | None:
    """One line for two straight stretches that one line keeps, with the points between them,
    within LINE_SHARE σ (a line searched from a point where the input is still leaving a bend
    can stop in the middle of the straight after it), else None."""
    if not _line_fits(points, first.first, second.last, LINE_SHARE * tolerance):
        return None
    return _trimmed(points, first.first, second.last, END_SHARE * tolerance)


def _onwards(points: np.ndarray, i: int, j: int, band: float) -> int:
    """j, or the last of the points after it that stay within ``band`` of the least-squares line of
    points i..j one after another (a line searched from a point still inside the bend before it
    stops short of where the straight stretch ends)."""
    centre, u = _fitted_line(points[i : j + 1])
    rel = points[j + 1 :] - centre
    off = np.linalg.norm(rel - (rel @ u)[:, None] * u, axis=1)
    out = np.flatnonzero(off > band)
    return j + (int(out[0]) if len(out) else len(rel))


def _trimmed(points: np.ndarray, i: int, j: int, band: float) -> Straight | None:
    """The least-squares line of points i..j (through the run's end point where the stretch
    reaches it), from the projection of the first point within ``band`` of it to that of the
    last (the run's own end point there), or None where fewer than two points lie within the band."""
    stretch, n = points[i : j + 1], len(points)
    if i == 0 and j == n - 1:  # the whole run: the line between its ends
        centre, u = points[0], (points[-1] - points[0]) / np.linalg.norm(points[-1] - points[0])
    else:  # through the run's end it reaches (where the chain must start or end)
        centre, u = _fitted_line(stretch, points[0] if i == 0 else points[-1] if j == n - 1 else None)
    u = u if (points[j] - points[i]) @ u > 0 else -u
    t = (stretch - centre) @ u
    off = np.linalg.norm(stretch - centre - t[:, None] * u, axis=1)
    near = np.flatnonzero(off <= band)
    if len(near) < 2:
        return None
    a, b = int(near[0]), int(near[-1])
    start = points[0].copy() if i + a == 0 else centre + t[a] * u
    end = points[-1].copy() if i + b == n - 1 else centre + t[b] * u
    return Straight(i + a, i + b, start, end)


def _line_fits(points: np.ndarray, i: int, j: int, within: float) -> bool:
    a, b = points[i], points[j]
    d = b - a
    length = float(np.linalg.norm(d))
    if j - i < 2:
        return True
    if length == 0.0:
        return False
    u = d / length
    rel = points[i : j + 1] - a
    t = np.clip(rel @ u, 0.0, length)
    return float(np.linalg.norm(rel - t[:, None] * u, axis=1).max()) <= within

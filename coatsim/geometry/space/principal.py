"""Arcs only in the principal planes: a 3-D curve as a certified chain whose every arc lies in a
plane x = c, y = c or z = c (its normal along ±X, ±Y or ±Z), for languages that write arcs only
there (G-code G17/G18/G19).

The curve is split into maximal stretches lying within a share of σ of such a plane (a raster
pass cut by a plane normal to an axis, a pass around a cylinder whose axis is an axis); each is
fitted by the planar fitter (the paper's method, coatsim.geometry.segment) in that plane with the
in-plane tolerance √(σ² − h²) and placed back; the stretches between are fitted with lines only
(Ramer–Douglas–Peucker within a share of σ). Two stretches in planes normal to different axes
meet at a point of both (on the line the planes share); two in parallel planes are joined by one
input edge as a line. A G1 chain can change principal plane only where its tangent runs along the
axis both planes share: where the input does, the junction moves to the middle of its stretch in
both planes and the planar fits on either side are pinned to that axis (coatsim.geometry.pinned),
so the change is tangent-continuous; every other junction whose tangents differ — a change of
plane, the start or end of a stretch in no principal plane, a vertex of its lines — is listed as
a corner. The whole
chain is certified by the exact two-sided 3-D Hausdorff check (coatsim.geometry.space.deviation);
the shares are narrowed until it holds.
"""

from __future__ import annotations

import bisect
import math
from collections import deque
from dataclasses import dataclass, replace

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.curves import make_curve
from coatsim.geometry.limits import MIN_LENGTH_SIGMAS
from coatsim.geometry.pinned import fit_pinned
from coatsim.geometry.rdp import rdp_indices
from coatsim.geometry.segment import segment_curve
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import SpaceCurve
from coatsim.geometry.space.deviation import hausdorff3
from coatsim.geometry.space.local import arc_length
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Line3, Segment3, place

ARC_PLANES = ("any", "principal")
#: (plane share, line share) of σ tried in turn: a stretch within the first of a plane normal to
#: an axis is fitted in it; the lines elsewhere stay within the second of the input.
SHARES = ((0.1, 0.9), (0.05, 0.6), (0.02, 0.3))
#: A whole curve within this many plane shares of σ of one principal plane is fitted in it (σ/2 at
#: first, as a planar curve is in its own plane).
WHOLE_SHARES = 5.0
MIN_STRETCH_SIGMAS = 50.0  # a shorter stretch in a principal plane is left to lines (a tilted curve grazes one over a few σ)
NORMAL_TOL = 1e-9  # an arc's normal is along an axis when its other two components are within this
CORNER_BREAK_RAD = 1e-9  # a junction breaking its tangent by more is listed as a corner
PIN_DEG = 10.0  # a change of plane where the input runs this close to the shared axis is tried tangent-continuous
#: Per normal axis: (first, second, normal) axes of its plane, first × second = normal (G17, G18, G19).
PLANE_AXES = {2: (0, 1, 2), 1: (2, 0, 1), 0: (1, 2, 0)}


def check_arc_planes(arc_planes: str) -> None:
    if arc_planes not in ARC_PLANES:
        raise InputError(f"arc_planes: expected any or principal, got {arc_planes!r}", parameters=("arc_planes",))


def is_principal(normal: np.ndarray) -> bool:
    """Whether a unit normal lies along ±X, ±Y or ±Z (its other components within NORMAL_TOL)."""
    return bool(np.sort(np.abs(np.asarray(normal, dtype=float)))[:2].max() <= NORMAL_TOL)


@dataclass(frozen=True)
class Stretch:
    """Input points ``first``..``last`` (indices) lying near the plane ``axis`` = ``level`` (mm),
    or in no principal plane (``axis`` None: fitted with lines)."""

    first: int
    last: int
    axis: int | None = None
    level: float = 0.0


@dataclass(frozen=True, eq=False)
class PrincipalFit:
    """The chain, its certified deviation (mm), the input's tightest radius in its plane
    stretches, whether their limits were kept, the plane frame when one plane holds the whole
    curve, and a note on what keeping arcs in principal planes cost."""

    chain: SpaceChain
    deviation_mm: float
    input_min_radius_mm: float | None
    limits_kept: bool
    plane_pose: Pose | None
    note: str


def plane_pose(axis: int, level: float) -> Pose:
    """The frame whose XY plane is the plane ``axis`` = ``level``, its axes the plane's (first,
    second, normal) axes: placing a planar fit by it is exact (a permutation and a shift)."""
    rotation = np.zeros((3, 3))
    for column, row in enumerate(PLANE_AXES[axis]):
        rotation[row, column] = 1.0
    translation = np.zeros(3)
    translation[axis] = level
    return Pose(rotation, translation)


def _windows(values: np.ndarray, span: float) -> list[tuple[int, int]]:
    """The maximal index windows [i, j], j > i, whose values spread over at most ``span``
    (two pointers with monotone queues of the running maximum and minimum)."""
    n, out, top, low, j = len(values), [], deque(), deque(), 0
    for i in range(n):
        while j < n:
            v = values[j]
            high = max(values[top[0]], v) if top else v
            small = min(values[low[0]], v) if low else v
            if high - small > span:
                break
            while top and values[top[-1]] <= v:
                top.pop()
            while low and values[low[-1]] >= v:
                low.pop()
            top.append(j)
            low.append(j)
            j += 1
        if j - 1 > i and (not out or j - 1 > out[-1][1]):
            out.append((i, j - 1))
        if top and top[0] == i:
            top.popleft()
        if low and low[0] == i:
            low.popleft()
    return out


def _uncovered(i: int, j: int, taken: list[tuple[int, int, int]]) -> list[tuple[int, int]]:
    """The parts of [i, j] outside the (sorted, end-sharing) taken windows."""
    out, cursor = [], i
    for a, b, _ in taken:
        if b <= cursor:
            continue
        if a >= j:
            break
        if a > cursor:
            out.append((cursor, a))
        cursor = max(cursor, b)
    if cursor < j:
        out.append((cursor, j))
    return out


def plane_stretches(points: np.ndarray, tol: float, share: float, closed: bool) -> list[Stretch]:
    """The curve as stretches: the longest windows within ``share``·σ of a principal plane first,
    each at least MIN_STRETCH_SIGMAS·σ long, the rest (in no plane) between them."""
    s = arc_length(points)
    shortest = MIN_STRETCH_SIGMAS * tol
    candidates = sorted(((s[j] - s[i], i, j, axis) for axis in range(3)
                         for i, j in _windows(points[:, axis], 2.0 * share * tol) if s[j] - s[i] >= shortest),
                        reverse=True)
    taken: list[tuple[int, int, int]] = []
    for _, i, j, axis in candidates:
        for a, b in _uncovered(i, j, taken):
            if s[b] - s[a] >= shortest:
                bisect.insort(taken, (a, b, axis))
    return _joinable(points, taken, closed)


def _joinable(points: np.ndarray, taken: list[tuple[int, int, int]], closed: bool) -> list[Stretch]:
    """The taken windows as stretches with the gaps between them in no plane; two neighbours in
    parallel planes (a seam included) get one input edge of lines between them."""
    out: list[Stretch] = []
    cursor, last = 0, len(points) - 1
    for a, b, axis in taken:
        prev = out[-1] if out else None
        if a > cursor:
            out.append(Stretch(cursor, a))
        elif prev is not None and prev.axis == axis:
            out.append(Stretch(a, a + 1))
            a += 1
        if b > a:
            out.append(_levelled(points, Stretch(a, b, axis)))
        cursor = max(cursor, b, a)
    if cursor < last:
        out.append(Stretch(cursor, last))
    if closed and len(out) > 1 and out[0].axis is not None and out[0].axis == out[-1].axis:
        head = out[0]
        out[0:1] = [Stretch(0, 1)] + ([Stretch(1, head.last, head.axis, head.level)] if head.last > 1 else [])
    return _merged(out)


def _merged(stretches: list[Stretch]) -> list[Stretch]:
    """Neighbouring stretches in no plane as one."""
    out: list[Stretch] = []
    for st in stretches:
        if out and st.axis is None and out[-1].axis is None:
            out[-1] = Stretch(out[-1].first, st.last)
        else:
            out.append(st)
    return out


def _levelled(points: np.ndarray, st: Stretch) -> Stretch:
    """The stretch with its plane in the middle of its points' spread along its axis."""
    values = points[st.first : st.last + 1, st.axis]
    return replace(st, level=float(values.max() + values.min()) / 2.0)


def centred(points: np.ndarray, stretches: list[Stretch], band: float) -> tuple[list[Stretch], dict[int, np.ndarray]]:
    """The stretches with every change between planes normal to different axes moved to the middle
    of the input's stretch lying in both (within ``band`` mm: along the axis they share), and the
    junctions (k: between stretch k and k + 1) where the input runs along that axis within PIN_DEG:
    the direction a tangent-continuous chain passes them in."""
    out, pins, s = list(stretches), {}, arc_length(points)
    for k in range(len(out) - 1):
        a, b = out[k], out[k + 1]
        if a.axis is None or b.axis is None or a.axis == b.axis:
            continue
        lo = hi = a.last
        while lo - 1 > a.first and abs(points[lo - 1, b.axis] - b.level) <= band:
            lo -= 1
        while hi + 1 < b.last and abs(points[hi + 1, a.axis] - a.level) <= band:
            hi += 1
        mid = lo + int(np.argmin(np.abs(s[lo : hi + 1] - (s[lo] + s[hi]) / 2.0)))
        out[k], out[k + 1] = _levelled(points, replace(a, last=mid)), _levelled(points, replace(b, first=mid))
        shared = 3 - a.axis - b.axis
        chord = points[hi] - points[lo]
        length = float(np.linalg.norm(chord))
        if length > 0.0 and abs(chord[shared]) >= length * math.cos(math.radians(PIN_DEG)):
            pins[k] = np.eye(3)[shared] * math.copysign(1.0, chord[shared])
    return out, pins


def junction_points(points: np.ndarray, stretches: list[Stretch], closed: bool) -> np.ndarray:
    """Where consecutive stretches meet (first point, each junction, last point): the input point
    moved into the plane of each plane stretch it bounds (by at most that stretch's share of σ)."""
    out = points[[st.first for st in stretches] + [stretches[-1].last]].copy()
    for k, st in enumerate(stretches):
        if st.axis is not None:
            out[k, st.axis] = out[k + 1, st.axis] = st.level
    if closed:
        seam = out[0].copy()
        if stretches[-1].axis is not None:
            seam[stretches[-1].axis] = stretches[-1].level
        out[0] = out[-1] = seam
    return out


def _fit_plane(run: np.ndarray, st: Stretch, loop: bool, tol: float, name: str, options: dict,
               pins: tuple[np.ndarray | None, np.ndarray | None]
               ) -> tuple[tuple[Segment3, ...], tuple[int, ...], float | None, bool]:
    """A plane stretch by the planar fitter in its plane, placed back: the segments, the corners
    of that fit, the input's tightest radius there and whether the fit kept its limits. With
    ``pins`` (the unit directions the chain must leave and arrive in, or None) the pinned fit
    (coatsim.geometry.pinned) is tried first."""
    first, second, normal = PLANE_AXES[st.axis]
    height = float(np.abs(run[:, normal] - st.level).max())
    flat, in_plane = run[:, [first, second]], math.sqrt(tol * tol - height * height)
    pose = plane_pose(st.axis, st.level)
    if any(d is not None for d in pins):
        headings = [None if d is None else math.atan2(d[second], d[first]) for d in pins]
        pinned = fit_pinned(flat, in_plane, *headings, **options)
        if pinned is not None:
            return (tuple(place(s, pose) for s in pinned.segments), (), pinned.input_min_radius_mm,
                    pinned.limits_kept)
    seg = segment_curve(make_curve(flat, name, "yes" if loop else "no"), in_plane, **options)
    return (tuple(place(s, pose) for s in seg.polysegment.segments), seg.polysegment.corners,
            seg.input_min_radius_mm, bool(seg.limits_kept))


def _fit_lines(run: np.ndarray, share: float, tol: float) -> tuple[Line3, ...]:
    """A stretch in no principal plane as lines through input points, every point within
    ``share``·σ of them (its ends exactly)."""
    pts = run[rdp_indices(run, share * tol)]
    return tuple(Line3(a, b) for a, b in zip(pts[:-1], pts[1:]) if np.any(a != b))


def _seam_first(points: np.ndarray, stretches: list[Stretch]) -> np.ndarray:
    """A closed loop relaid to start where its second stretch starts (so no plane stretch runs
    across the seam)."""
    body, k = points[:-1], stretches[1].first
    return np.vstack((body[k:], body[:k], body[k : k + 1]))


def fit_principal(curve: SpaceCurve, tol: float, corner_deg: float, min_segment_mm: float | None,
                  speed_mm_s: float | None, tool_accel_mm_s2: float | None) -> PrincipalFit:
    """The certified chain of ``curve`` within ``tol`` whose every arc lies in a principal plane
    (see the module); InputError when even the narrowest shares miss ``tol``."""
    options = {"corner_deg": corner_deg, "min_segment_mm": min_segment_mm, "speed_mm_s": speed_mm_s,
               "tool_accel_mm_s2": tool_accel_mm_s2}
    dev = math.inf
    for plane_share, line_share in SHARES:
        fit = _attempt(curve, tol, plane_share, line_share, options)
        if fit.deviation_mm <= tol:
            return fit
        dev = fit.deviation_mm
    raise InputError(f"{curve.name}: no chain with arcs in principal planes within {tol:g} mm was found "
                     f"(deviation {dev:.4g} mm); the input may be too noisy for tolerance_mm")


def _attempt(curve: SpaceCurve, tol: float, plane_share: float, line_share: float, options: dict) -> PrincipalFit:
    """One try at the given shares of σ (see :data:`SHARES`)."""
    pts = curve.points
    spans = np.ptp(pts, axis=0)
    axis = int(np.argmin(spans))
    if spans[axis] <= 2.0 * WHOLE_SHARES * plane_share * tol:
        stretches = [Stretch(0, len(pts) - 1, axis, float(pts[:, axis].max() + pts[:, axis].min()) / 2.0)]
    else:
        stretches = plane_stretches(pts, tol, plane_share, False)
    loop = curve.closed and len(stretches) == 1 and stretches[0].axis is not None
    if curve.closed and len(stretches) > 1:
        pts = _seam_first(pts, stretches)
        stretches = plane_stretches(pts, tol, plane_share, True)
    stretches, pins = centred(pts, stretches, plane_share * tol)
    ends = junction_points(pts, stretches, curve.closed and not loop)
    segments, own_corners, radii, kept, n_lines = _fit_stretches(pts, stretches, ends, pins, loop, tol, line_share,
                                                                 curve.name, options)
    chain = SpaceChain(segments, curve.closed)
    breaks = chain.junction_breaks()
    added = sorted({int(k) for k in np.flatnonzero(breaks > CORNER_BREAK_RAD)} - set(own_corners))
    chain = SpaceChain(chain.segments, chain.closed, tuple(sorted(set(own_corners) | set(added))))
    shortest = options["min_segment_mm"] or MIN_LENGTH_SIGMAS * tol
    kept = kept and all(s.length >= shortest for s in segments if isinstance(s, Line3))
    dev = hausdorff3(curve.points, chain, tol).hausdorff
    whole = stretches[0] if len(stretches) == 1 and stretches[0].axis is not None else None
    return PrincipalFit(chain, dev, min(radii) if radii else None, kept,
                        None if whole is None else plane_pose(whole.axis, whole.level),
                        _note(stretches, n_lines, len(added)))


def _fit_stretches(pts: np.ndarray, stretches: list[Stretch], ends: np.ndarray, pins: dict[int, np.ndarray],
                   loop: bool, tol: float, line_share: float, name: str, options: dict
                   ) -> tuple[tuple[Segment3, ...], list[int], list[float], bool, int]:
    """Every stretch fitted between its junction points (tangent-continuous through the pinned
    ones where the planar fitter finds a chain): the segments, the corners the planar fits found,
    their input's tightest radii, whether they kept their limits, the count of lines in no plane."""
    segments: list[Segment3] = []
    own_corners: list[int] = []
    radii, kept, n_lines = [], True, 0
    for k, st in enumerate(stretches):
        run = pts[st.first : st.last + 1].copy()
        run[0], run[-1] = ends[k], ends[k + 1]
        fitted = None
        if st.axis is not None:
            try:
                fitted = _fit_plane(run, st, loop, tol, name, options, (pins.get(k - 1), pins.get(k)))
            except InputError:  # the planar fitter cannot follow this stretch: lines can
                fitted = None
        if fitted is None:
            lines = _fit_lines(run, line_share, tol)
            n_lines += len(lines)
            segments.extend(lines)
            continue
        segs, corners, radius, fitted_kept = fitted
        offset = _extend(segments, segs)
        own_corners += [offset + c for c in corners]
        radii += [radius] if radius is not None else []
        kept = kept and fitted_kept
    return tuple(segments), own_corners, radii, kept, n_lines


def _extend(segments: list[Segment3], more: tuple[Segment3, ...]) -> int:
    """Append ``more`` to ``segments``, a first line running straight on from a last line joined
    to it (a change of plane along the shared axis in the middle of a straight stretch); the index
    in ``segments`` of ``more[0]`` (or of the line it was joined to)."""
    last, first = (segments[-1], more[0]) if segments else (None, None)
    if isinstance(last, Line3) and isinstance(first, Line3) and \
            float(np.linalg.norm(last.direction - first.direction)) <= CORNER_BREAK_RAD:
        segments[-1] = Line3(last.start, first.end)
        segments.extend(more[1:])
        return len(segments) - len(more)
    segments.extend(more)
    return len(segments) - len(more)


def _note(stretches: list[Stretch], n_lines: int, n_added: int) -> str:
    n_plane = sum(st.axis is not None for st in stretches)
    n_free = len(stretches) - n_plane
    return (f"arcs kept in principal planes: {n_plane} stretch(es) within a plane x, y or z = const fitted in it, "
            f"{n_free} in no such plane; {n_lines} line(s) and {n_added} corner(s) added where the chain leaves "
            "a principal plane, changes plane or turns between lines (a tangent-continuous chain changes "
            "principal plane only where its tangent runs along the axis both planes share)")

"""segment_space_curve: a 3-D curve and a tolerance in, a certified G1 chain of Line3/Arc3 out.

A curve that lies in a plane within σ/2 is fitted by the planar fitter (the paper's method,
coatsim.geometry.segment) in that plane and placed back, so it gets exactly the segments of
its 2-D fit (the plane's distance h is taken off the planar tolerance: √(σ² − h²)). A space
curve is split at its true corners and each run fitted by an arc spline whose junctions are
free inside the σ-tube (coatsim.geometry.space.tube_fit), or, where that finds nothing with
fewer pieces, by spatial biarcs through the input narrowed until within (coatsim.geometry.space.fit); a
closed loop without corners keeps its tangent across the seam, which is tried at a few places
(the one knot the fit cannot move); a sparse polyline (taught points) is also fitted between its
vertices (coatsim.geometry.space.taught). Every run is certified by the exact 3-D Hausdorff check.
With ``arc_planes="principal"`` every arc lies in a plane normal to X, Y or Z
(coatsim.geometry.space.principal) unless the curve's own plane already is one.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.curves import make_curve
from coatsim.geometry.limits import check_min_segment
from coatsim.geometry.dynamics import curvature_limit, speed_limited
from coatsim.geometry.limits import MIN_LENGTH_SHARE, MIN_LENGTH_SIGMAS, NEIGHBOURHOOD_WINDOWS, FitLimits
from coatsim.geometry.sampling_check import check_sampling
from coatsim.geometry.scatter import noise_notes
from coatsim.geometry.segment import segment_curve
from coatsim.geometry.space.chain import SpaceChain
from coatsim.geometry.space.curve import SpaceCurve
from coatsim.geometry.space.deviation import hausdorff3
from coatsim.geometry.space.fit import RunChain, fit_run3
from coatsim.geometry.space.greedy import greedy_knots
from coatsim.geometry.space.local import curvature_profile3, detect_corners3, tangent_at, arc_length, window_mm
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3, Line3, Segment3, place
from coatsim.geometry.space.principal import check_arc_planes, fit_principal, is_principal
from coatsim.geometry.space.bend import bend_arc
from coatsim.geometry.space.straight import Straight, lined_loop_run, straight_stretches
from coatsim.geometry.space.taught import is_sparse3, taught_fit
from coatsim.geometry.space.tube_fit import CAP_SLACK, fit_tube_run

PLANAR_SHARE = 0.5  # a curve within this share of σ of its best plane is fitted in that plane
NARROWER = (0.9, 0.75, 0.5, 0.3)  # working tolerances (shares of σ) tried in turn
KINK_RAD = 1e-9  # a junction breaking its tangent by more is listed as a corner
SEAM_SHIFTS = (0.0, 1 / 3, 2 / 3)  # a loop's seams tried, in shares of a greedy arc past its first point


@dataclass(frozen=True, eq=False)
class SpaceSegmentation:
    """A fitted chain with its certified deviation; ``planar_pose`` the frame whose XY plane
    held the curve when it was fitted in a plane (None for a space curve). ``seconds`` is the
    fitter's wall time, reported on request and never written to a file."""

    curve: SpaceCurve
    chain: SpaceChain
    tolerance_mm: float
    max_deviation_mm: float
    seconds: float
    planar_pose: Pose | None
    input_min_radius_mm: float | None = None
    speed_mm_s: float | None = None
    tool_accel_mm_s2: float | None = None
    limits_kept: bool | None = None
    notes: tuple[str, ...] = ()
    added_corners: int = 0

    def stats(self) -> dict:
        chain = self.chain
        radii = [s.radius for s in chain.segments if isinstance(s, Arc3)]
        return {
            "n_segments": chain.n_segments,
            "n_arcs": chain.n_arcs,
            "n_lines": chain.n_lines,
            "max_deviation_mm": self.max_deviation_mm,
            "max_tangent_break_deg": math.degrees(chain.max_tangent_break()),
            "min_radius_mm": min(radii) if radii else None,
            "input_min_radius_mm": self.input_min_radius_mm,
            "min_segment_mm": min(s.length for s in chain.segments),
            "max_curvature_jump_per_mm": chain.max_curvature_jump(),
            "limits_kept": self.limits_kept,
            "planar": self.planar_pose is not None,
            "speed_mm_s": self.speed_mm_s,
            "tool_accel_mm_s2": self.tool_accel_mm_s2,
            "input_points": len(self.curve.points),
        }

    def summary(self) -> str:
        st = self.stats()
        radius = "none" if st["min_radius_mm"] is None else f"r {st['min_radius_mm']:.3f} mm"
        lines = [
            f"{self.curve.name}: {st['input_points']} points in space, length {self.curve.length:.3f} mm, "
            f"{'closed' if self.curve.closed else 'open'}, {'planar (fitted in its plane)' if st['planar'] else 'not planar'}",
            f"tolerance {self.tolerance_mm:g} mm",
            f"segments {st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines), corners {len(self.chain.corners)}"
            + (f" ({self.added_corners} where no arc within the limits follows the input: lines meet there)"
               if self.added_corners else ""),
            f"max deviation {st['max_deviation_mm']:.6f} mm (certified two-sided Hausdorff in 3-D), "
            f"max tangent break {st['max_tangent_break_deg']:.3g} deg",
            f"tightest arc {radius}, shortest segment {st['min_segment_mm']:.3f} mm"
            + ("" if self.limits_kept is not False else "; WARNING: some arcs are tighter than the input allows or shorter than the minimum"),
        ]
        lines += [f"note: {note}" for note in self.notes]
        if self.speed_mm_s is not None:
            limited = self.chain.speed_limited
            slowest = min((v for _, _, v in limited), default=None)
            lines.append(f"at {self.speed_mm_s:g} mm/s and {self.tool_accel_mm_s2 / 1000:g} m/s²: "
                         + (f"{len(limited)} speed-limited stretch(es), slowest {slowest:.1f} mm/s"
                            if limited else "no speed-limited stretch"))
        return "\n".join(lines)


def _check(value: float | None, name: str, unit: str) -> None:
    if value is not None and not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name}: must be a positive number of {unit}, got {value}", parameters=(name,))


def best_plane(points: np.ndarray) -> tuple[Pose, float]:
    """The least-squares plane of the points as a frame (origin at their centroid, z its
    normal, right-handed) and the largest distance of a point from it (mm)."""
    centre = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centre, full_matrices=False)
    x, y = vt[0], vt[1]
    z = np.cross(x, y)
    pose = Pose(np.column_stack((x, y, z / np.linalg.norm(z))), centre)
    return pose, float(np.abs((points - centre) @ pose.rotation[:, 2]).max())


def segment_space_curve(curve: SpaceCurve, tolerance_mm: float, corner_deg: float = defaults.CORNER_DEG,
                        min_segment_mm: float | None = None, speed_mm_s: float | None = None,
                        tool_accel_mm_s2: float | None = None, arc_planes: str = defaults.ARC_PLANES) -> SpaceSegmentation:
    """Approximate a space curve by a G1 chain of lines and arcs within ``tolerance_mm``
    (certified two-sided Hausdorff in 3-D); ``arc_planes`` "principal" keeps every arc in a
    plane normal to X, Y or Z (lines elsewhere; a change of plane is G1 along the axis both
    planes share, a listed corner otherwise); the other parameters as for the planar
    ``segment_curve``."""
    _check(tolerance_mm, "tolerance_mm", "mm")
    _check(min_segment_mm, "min_segment_mm", "mm")
    check_min_segment(min_segment_mm)
    _check(speed_mm_s, "speed_mm_s", "mm/s")
    _check(tool_accel_mm_s2, "tool_accel_mm_s2", "mm/s²")
    if not (math.isfinite(corner_deg) and 0 < corner_deg < 180):
        raise InputError(f"corner_deg: must be between 0 and 180 degrees, got {corner_deg}", parameters=("corner_deg",))
    if (speed_mm_s is None) != (tool_accel_mm_s2 is None):
        raise InputError("speed_mm_s and tool_accel_mm_s2 go together: give both or neither",
                         parameters=("speed_mm_s", "tool_accel_mm_s2"))
    check_arc_planes(arc_planes)
    check_sampling(curve.points, curve.name)
    started = time.perf_counter()
    pose, height = best_plane(curve.points)
    notes: tuple[str, ...] = ()
    added = 0
    planar = height <= PLANAR_SHARE * tolerance_mm
    if arc_planes == "principal" and not (planar and is_principal(pose.rotation[:, 2])):
        fit = fit_principal(curve, tolerance_mm, corner_deg, min_segment_mm, speed_mm_s, tool_accel_mm_s2)
        chain, dev, radius, kept, pose, notes = (fit.chain, fit.deviation_mm, fit.input_min_radius_mm,
                                                 fit.limits_kept, fit.plane_pose, (fit.note,))
    elif planar:
        chain, radius, kept = _fit_planar(curve, pose, height, tolerance_mm, corner_deg, min_segment_mm,
                                          speed_mm_s, tool_accel_mm_s2)
        dev = hausdorff3(curve.points, chain, tolerance_mm).hausdorff
    else:
        pose = None
        chain, dev, radius, kept, added = _fit_space(curve, tolerance_mm, corner_deg, min_segment_mm, speed_mm_s,
                                                     tool_accel_mm_s2)
        fit_guide = lambda guide, within: _fit_space(guide, within, corner_deg, min_segment_mm,  # noqa: E731
                                                     speed_mm_s, tool_accel_mm_s2)[::4]  # (chain, corners added)
        taught = taught_fit(curve, tolerance_mm, corner_deg, fit_guide, chain.n_segments)  # a sparse polyline
        if taught is not None:
            chain, dev, added = taught
        elif kept is False and not is_sparse3(curve.points, curve.closed, tolerance_mm):
            notes += noise_notes(curve.points, curve.closed, tolerance_mm)  # why the caps were loosened
    shortest = min(seg.length for seg in chain.segments)
    if min_segment_mm is not None and chain.n_segments > 1 and shortest < (1 - CAP_SLACK) * min_segment_mm:
        raise InputError(f"{curve.name}: no chain within {tolerance_mm:g} mm was found that keeps every segment at "
                         f"least min_segment_mm {min_segment_mm:g} mm long (the shortest is {shortest:.4g} mm); "
                         "give a shorter one", parameters=("min_segment_mm",))
    if speed_mm_s is not None and not chain.speed_limited:
        chain = replace(chain, speed_limited=speed_limited(chain, speed_mm_s, tool_accel_mm_s2))  # type: ignore[arg-type]
    return SpaceSegmentation(curve, chain, tolerance_mm, dev, time.perf_counter() - started, pose, radius,
                             speed_mm_s, tool_accel_mm_s2, kept, notes, added)


def _fit_planar(curve: SpaceCurve, pose: Pose, height: float, tol: float, corner_deg: float,
                min_segment_mm: float | None, speed_mm_s: float | None,
                tool_accel_mm_s2: float | None) -> tuple[SpaceChain, float | None, bool | None]:
    """The planar fit in the curve's own plane, placed back in space."""
    flat = pose.inverse().apply(curve.points)[:, :2]
    planar = make_curve(flat, curve.name, "yes" if curve.closed else "no")
    seg = segment_curve(planar, math.sqrt(tol * tol - height * height), corner_deg=corner_deg,
                        min_segment_mm=min_segment_mm, speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
    poly = seg.polysegment
    chain = SpaceChain(tuple(place(s, pose) for s in poly.segments), poly.closed, poly.corners, poly.speed_limited)
    return chain, seg.input_min_radius_mm, seg.limits_kept


def _fit_space(curve: SpaceCurve, tol: float, corner_deg: float, min_segment_mm: float | None,
               speed_mm_s: float | None, tool_accel_mm_s2: float | None) -> tuple[SpaceChain, float, float | None, bool, int]:
    """G1 chains over the runs between corners, each certified within ``tol``, and the corners
    added where lines stand in for arcs the limits forbid."""
    pts = curve.points
    corners = detect_corners3(pts, curve.closed, corner_deg, tol)
    if curve.closed and len(corners):
        first = int(corners[0])
        body = pts[:-1]
        pts = np.vstack((body[first:], body[:first], body[first:first + 1]))
        corners = np.sort((corners - first) % len(body))
        cuts = [0, *[int(c) for c in corners if c != 0], len(pts) - 1]
    else:
        cuts = [0, *[int(c) for c in corners], len(pts) - 1]
    loop = curve.closed and not len(corners)
    speed_kappa = curvature_limit(speed_mm_s, tool_accel_mm_s2)
    segments, kept, radii, junctions, devs = [], True, [], [], []
    lined = _fit_lined_loop(curve.name, pts, tol, min_segment_mm, speed_kappa) if loop else None
    for a, b in zip(cuts[:-1], cuts[1:]):
        if lined is not None:
            fitted, dev, radius = lined
            radii.append(radius)
        elif loop:
            fitted, dev, limits = _fit_loop(curve.name, pts, tol, min_segment_mm, speed_kappa)
            radii.append(limits.profile.tightest_radius_mm)
        else:
            fitted, dev, radius = _fit_open_run(curve.name, pts[a : b + 1], tol, min_segment_mm, speed_kappa)
            radii.append(radius)
        segments.extend(fitted.segments)
        junctions.append(len(segments) - 1)
        kept = kept and fitted.limits_kept
        devs.append(dev)
    corner_junctions = tuple(junctions[:-1]) + ((junctions[-1],) if curve.closed and len(corners) else ())
    chain, added = _with_kinks(SpaceChain(tuple(segments), curve.closed, corner_junctions))
    # one run: its certified deviation is the chain's; several: the whole is certified again
    # (an input point may lie nearer another run's segments than its own)
    dev = devs[0] if len(devs) == 1 else hausdorff3(pts, chain, tol).hausdorff
    tightest = min(radii)
    return chain, dev, tightest if math.isfinite(tightest) else None, kept, added


def _fit_open_run(name: str, run: np.ndarray, tol: float, min_segment_mm: float | None,
                  speed_kappa: float | None) -> tuple[RunChain, float, float]:
    """An open run's chain: its straight stretches as lines (coatsim.geometry.space.straight),
    the bends between two lines in one plane as one arc tangent to both
    (coatsim.geometry.space.bend), the other curved stretches fitted with their end tangents
    pinned to the lines' (where one of those then breaks its tangent or the whole misses σ,
    the run without lines); its certified deviation and the tightest radius of its input."""
    lines = straight_stretches(run, tol)
    if lines:
        fitted, _, radius = _fit_stretches(name, run, tol, min_segment_mm, speed_kappa, lines)
        chain = SpaceChain(fitted.segments)
        if not np.any(chain.junction_breaks() > KINK_RAD):
            dev = hausdorff3(run, chain, tol).hausdorff
            if dev <= tol:
                return fitted, dev, radius
    return _fit_stretches(name, run, tol, min_segment_mm, speed_kappa, [])


def _fit_lined_loop(name: str, loop: np.ndarray, tol: float, min_segment_mm: float | None,
                    speed_kappa: float | None) -> tuple[RunChain, float, float] | None:
    """A closed loop without corners that has straight stretches, fitted round it from the start
    of one to that stretch again (coatsim.geometry.space.straight.lined_loop_run): the chain, its
    certified deviation and the tightest radius of its input; None where it has no straight
    stretch, or the chain breaks a tangent (the seam's too) or misses σ."""
    lined = lined_loop_run(loop, tol)
    if lined is None:
        return None
    for bend_back in (True, False):  # each bend leaves its line after re-aimed (lines in space are a hair skew):
        fitted, _, radius = _fit_stretches(name, lined.points, tol, min_segment_mm, speed_kappa,  # the one back
                                           lined.lines, tail=False, bend_back=bend_back)  # onto the first may miss
        segs = fitted.segments                                                   # its direction: pinned arcs there
        chain = SpaceChain((Line3(segs[-1].start, segs[0].end),) + segs[1:-1], closed=True)
        if not np.any(chain.junction_breaks() > KINK_RAD):
            dev = hausdorff3(lined.points[: lined.lap + 1], chain, tol).hausdorff
            return (RunChain(chain.segments, fitted.limits_kept), dev, radius) if dev <= tol else None
    return None


def _fit_stretches(name: str, run: np.ndarray, tol: float, min_segment_mm: float | None, speed_kappa: float | None,
                   lines: list[Straight], tail: bool = True, bend_back: bool = True) -> tuple[RunChain, float, float]:
    """The chain of an open run with ``lines`` standing for its straight stretches (see
    _fit_open_run), the deviation of its last curved stretch (the run's, without lines) and the
    tightest radius of its input; ``tail``: the stretch after the last line too; without
    ``bend_back`` the stretch before the last line is fitted with pinned ends, never as one bend."""
    segments: list[Segment3] = []
    kept, radius, dev = True, math.inf, math.inf
    after: Straight | None = None  # the line before the curved stretch
    for line in [*lines, None] if tail else lines:
        bend = None if after is None or line is None or (line is lines[-1] and not bend_back) \
            else bend_arc(after, line, run, tol)
        if bend is not None:
            after, arc, line = bend
            segments[-1] = Line3(after.start, after.end)
            segments += [arc, Line3(line.start, line.end)]
            after = line
            continue
        head = run[:1] if after is None else after.end[None]
        body = run[(0 if after is None else after.last) + 1 : (len(run) - 1 if line is None else line.first)]
        tail = run[-1:] if line is None else line.start[None]
        stretch = np.vstack((head, body, tail)) if after is not None or line is None or line.first > 0 else None
        if stretch is not None and (len(body) or float(np.linalg.norm(stretch[-1] - stretch[0])) > 0):
            limits, window = _limits(stretch, False, tol, min_segment_mm, speed_kappa)
            fitted, dev = _fit_run(name, stretch, tol, limits, window, None,
                                   None if after is None else after.direction, None if line is None else line.direction)
            segments.extend(fitted.segments)
            kept, radius = kept and fitted.limits_kept, min(radius, limits.profile.tightest_radius_mm)
        if line is not None:
            segments.append(Line3(line.start, line.end))
            after = line
    return RunChain(tuple(segments), kept), dev, radius


def _fit_run(name: str, run: np.ndarray, tol: float, limits: FitLimits, window: float,
             seam: np.ndarray | None, start_tangent: np.ndarray | None = None,
             end_tangent: np.ndarray | None = None) -> tuple[RunChain, float]:
    """A run's chain and its certified deviation: biarcs through the input narrowed until
    within (coatsim.geometry.space.fit), cheap and G1 but with about twice the pieces, then
    the arc spline in the tube (coatsim.geometry.space.tube_fit) searched from no more than
    the biarcs' count (on sharp or noisy runs most of its search is spent on counts no better).
    ``seam``: the run is a closed loop with this tangent at its seam; ``start_tangent`` and
    ``end_tangent`` pin an open run's end tangents (a line's next to it)."""
    if seam is not None:
        start_tangent = end_tangent = seam
    biarcs, dev = None, math.inf
    for share in NARROWER:
        fitted = fit_run3(run, share * tol, limits, window, start_tangent, end_tangent)
        dev = hausdorff3(run, SpaceChain(fitted.segments, seam is not None), tol).hausdorff
        if dev <= tol:
            biarcs = (fitted, dev)
            break
    tube = fit_tube_run(run, tol, limits, window, seam_tangent=seam,
                        start_tangent=None if seam is not None else start_tangent,
                        end_tangent=None if seam is not None else end_tangent,
                        at_most=None if biarcs is None else len(biarcs[0].segments))
    if tube is not None and (biarcs is None or len(tube.segments) <= len(biarcs[0].segments)):
        return tube, tube.deviation_mm
    if biarcs is None:
        raise InputError(f"{name}: no chain within {tol:g} mm was found (deviation {dev:.4g} mm); "
                         "the input may be too noisy for tolerance_mm")
    return biarcs


def _fit_loop(name: str, loop: np.ndarray, tol: float, min_segment_mm: float | None,
              speed_kappa: float | None) -> tuple[RunChain, float, FitLimits]:
    """A closed loop without corners, its seam (where the chain's knots start) tried at a few
    shares of a greedy arc past the input's first point (SEAM_SHIFTS) until the chain has no
    more pieces than the greedy fitter, each seam after the first searched only from one
    piece fewer than the best so far; the fewest kept (the chain, its certified deviation and the
    limits it was fitted under). The seam is the one knot the fit cannot move."""
    body, s = loop[:-1], arc_length(loop)
    greedy = max(len(greedy_knots(loop, tol)) - 1, 1)
    arc = s[-1] / greedy
    best = None
    for share in SEAM_SHIFTS:
        k = int(np.searchsorted(s, share * arc)) % len(body)
        pts = np.vstack((body[k:], body[:k], body[k : k + 1]))
        limits, window = _limits(pts, True, tol, min_segment_mm, speed_kappa)
        tangent = tangent_at(*_seam_view(pts, window), window)
        if best is None:
            fitted, dev = _fit_run(name, pts, tol, limits, window, tangent)
        else:  # another seam is worth a chain of fewer pieces only: the tube fit alone, from one piece fewer
            fewer = len(best[0].segments) - 1
            tube = fit_tube_run(pts, tol, limits, window, seam_tangent=tangent, at_most=fewer, at_least=fewer)
            if tube is None:
                continue
            fitted, dev = tube, tube.deviation_mm
        if best is None or len(fitted.segments) < len(best[0].segments):
            best = (fitted, dev, limits)
        if len(best[0].segments) <= greedy:
            break
    return best


def _with_kinks(chain: SpaceChain) -> tuple[SpaceChain, int]:
    """The chain with every junction whose tangent breaks (where no honest biarc follows the
    input, a line does: coatsim.geometry.space.fit) listed as a corner, and how many were
    added: a break is never left unlisted."""
    breaks = chain.junction_breaks()
    kinks = {int(k) for k in np.flatnonzero(breaks > KINK_RAD)} - set(chain.corners)
    if not kinks:
        return chain, 0
    return replace(chain, corners=tuple(sorted(set(chain.corners) | kinks))), len(kinks)


def _seam_view(points: np.ndarray, window: float) -> tuple[np.ndarray, np.ndarray, int]:
    """A closed loop laid out around its seam (points, arc length, index of the seam vertex)."""
    body = points[:-1]
    pts = np.vstack((body, body, body[:1]))
    return pts, arc_length(pts), len(body)


def _limits(run: np.ndarray, loop: bool, tol: float, min_segment_mm: float | None,
            speed_kappa: float | None) -> tuple[FitLimits, float]:
    """The planar fitter's limits (coatsim.geometry.limits) on the run's 3-D curvature profile,
    and the window of that profile (the tangent window too)."""
    profile = curvature_profile3(run, loop, tol)
    min_length = (max(MIN_LENGTH_SIGMAS * tol, MIN_LENGTH_SHARE * profile.length)
                  if min_segment_mm is None else min_segment_mm)
    near = profile.envelope(max(NEIGHBOURHOOD_WINDOWS * profile.window_mm, min_length))
    floor = tol / max(profile.length, tol) ** 2
    if speed_kappa is not None:
        floor = min(floor, speed_kappa)
    return FitLimits(profile, near, speed_kappa, floor, min(min_length, profile.length)), window_mm(run, tol)

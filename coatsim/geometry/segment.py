"""segment_curve: a curve and a tolerance in, a verified polysegment out."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np

from coatsim.core import defaults
from coatsim.core.progress import progress
from coatsim.core.errors import CoatsimError, InputError
from coatsim.geometry.corners import corners_and_notes
from coatsim.geometry.curves import Curve
from coatsim.geometry.degenerate import (check_chain, check_resolvable, extent_mm, obvious_answer, one_circle,
                                         split_long_arcs)
from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.limits import check_min_segment
from coatsim.geometry.dynamics import curvature_limit, max_curvature_jump, speed_limited
from coatsim.geometry.fit import fit_free, fit_run
from coatsim.geometry.run_fit import RunFit
from coatsim.geometry.limits import fit_limits
from coatsim.geometry.lined import with_lines, lined_loop, lined_run
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.primitives import Arc, Segment
from coatsim.geometry.recover import recover_exact
from coatsim.geometry.sampling_check import check_sampling
from coatsim.geometry.scatter import NOISY_FALLBACK, NOISY_SPACING, THIN_ROOM, noise_hint, noise_notes, thinned
from coatsim.geometry.seam import calm_start, reseat, rotated_loop
from coatsim.geometry.sparse import is_sparse, taught_lines
from coatsim.geometry.taught_retry import retried
from coatsim.geometry.theta import ThetaFunction, paper_within, theta_of_polyline

Method = Literal["optimal", "paper"]
SEAM_TRIES = 4  # a taught loop no chain follows from its calmest point gets quick fits from this many other vertices
HOOK_SHARE = 0.2  # a seam segment shorter than this share of the median segment makes a hook
SMALL_SIGMAS = 10.0  # a curve spanning fewer tolerances than this is most likely in another unit than mm
METHODS = ("optimal", "paper")


@dataclass(frozen=True, eq=False)
class Segmentation:
    """A fitted polysegment with its verified deviation and provenance; ``seconds`` is the
    fitter's wall time (reported on request, never written to a file: outputs depend on the
    inputs alone)."""

    curve: Curve
    polysegment: Polysegment
    method: str
    tolerance_mm: float
    max_deviation_mm: float
    seconds: float
    theta: ThetaFunction
    theta_approx: ThetaFunction | None = None
    theta_tolerance: float | None = None
    input_min_radius_mm: float | None = None
    speed_mm_s: float | None = None
    tool_accel_mm_s2: float | None = None
    limits_kept: bool | None = None
    notes: tuple[str, ...] = ()

    def summary(self) -> str:
        """One screen of text: counts, verified deviation, tangency."""
        st = self.stats()
        lines = [
            f"{self.curve.name}: {st['input_points']} points, length {self.curve.length:.3f} mm, "
            f"{'closed' if self.curve.closed else 'open'}",
            f"method {self.method}, tolerance {self.tolerance_mm:g} mm"
            + (f", θ tolerance {self.theta_tolerance:.4g}" if self.theta_tolerance is not None else ""),
            f"segments {st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines), "
            f"corners {len(self.polysegment.corners)}",
            f"max deviation {st['max_deviation_mm']:.6f} mm (exact two-sided Hausdorff), "
            f"max tangent break {st['max_tangent_break_deg']:.3g} deg",
            f"tightest arc {_mm(st['min_radius_mm'])} (input {_mm(st['input_min_radius_mm'])}), "
            f"shortest segment {st['min_segment_mm']:.3f} mm, "
            f"largest curvature jump {st['max_curvature_jump_per_mm']:.4g} 1/mm"
            + ("" if self.limits_kept is not False else
               "; WARNING: some arcs are tighter than the input allows or shorter than the minimum (fallback fit)"),
        ]
        if self.speed_mm_s is not None:
            limited = self.polysegment.speed_limited
            slowest = min((v for _, _, v in limited), default=None)
            lines.append(f"at {self.speed_mm_s:g} mm/s and {self.tool_accel_mm_s2 / 1000:g} m/s²: "
                         + (f"{len(limited)} speed-limited stretch(es), slowest {slowest:.1f} mm/s"
                            if limited else "no speed-limited stretch"))
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines)

    def stats(self) -> dict:
        poly = self.polysegment
        return {
            "n_segments": poly.n_segments,
            "n_arcs": poly.n_arcs,
            "n_lines": poly.n_lines,
            "max_deviation_mm": self.max_deviation_mm,
            "max_tangent_break_deg": math.degrees(poly.max_tangent_break()),
            "min_radius_mm": _finite(min((s.radius for s in poly.segments if isinstance(s, Arc)), default=math.inf)),
            "input_min_radius_mm": self.input_min_radius_mm,
            "min_segment_mm": min(s.length for s in poly.segments),
            "max_curvature_jump_per_mm": max_curvature_jump(poly),
            "limits_kept": self.limits_kept,
            "speed_mm_s": self.speed_mm_s,
            "tool_accel_mm_s2": self.tool_accel_mm_s2,
            "input_points": len(self.curve.points),
        }


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def _mm(value: float | None) -> str:
    return "none" if value is None else f"r {value:.3f} mm"


def _runs(points: np.ndarray, corners: np.ndarray, closed: bool) -> tuple[np.ndarray, list[np.ndarray]]:
    """Split at corners. Returns (points rotated so a closed curve starts at its first corner,
    list of runs each sharing its end point with the next run's start)."""
    if closed and len(corners):
        first = int(corners[0])
        body = points[:-1]
        points = np.vstack((body[first:], body[:first], body[first:first + 1]))
        corners = (corners - first) % len(body)
        cuts = [0, *sorted(int(c) for c in corners if c != 0), len(points) - 1]
    else:
        cuts = [0, *(int(c) for c in corners), len(points) - 1]
    return points, [points[a : b + 1] for a, b in zip(cuts[:-1], cuts[1:])]


def _corner_junctions(counts: list[int], closed: bool, has_corners: bool) -> tuple[int, ...]:
    """Junction indices (end of segment k) that sit on corners: the ends of all runs but the
    last, and the seam of a closed curve that starts at a corner."""
    ends = np.cumsum(counts) - 1
    junctions = [int(k) for k in ends[:-1]]
    if closed and has_corners:
        junctions.append(int(ends[-1]))
    return tuple(junctions)


def _positive(value: float | None, name: str, unit: str) -> None:
    if value is not None and not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
        raise InputError(f"{name}: must be a positive number of {unit}, got {value}", parameters=(name,))


def segment_curve(
    curve: Curve,
    tol: float,
    method: Method = "optimal",
    corner_deg: float = defaults.CORNER_DEG,
    theta_tolerance: float | None = None,
    min_segment_mm: float | None = None,
    speed_mm_s: float | None = None,
    tool_accel_mm_s2: float | None = None,
) -> Segmentation:
    """Approximate ``curve`` by a G1 chain of arcs and lines within ``tol`` mm.

    ``optimal`` guarantees the two-sided Hausdorff distance <= tol (verified exactly), keeps
    every junction tangent-continuous except at detected true corners, keeps every arc
    within 1.25 x the input's own curvature near it and every segment at least
    ``min_segment_mm`` long (default 5 tol, or 1/500 of the run between corners if that is
    longer), and uses few segments. With ``speed_mm_s`` and
    ``tool_accel_mm_s2`` (both or neither), no arc is tighter than v² / a where the input
    allows that speed; where it does not, the stretch is listed in the polysegment's
    ``speed_limited``. ``paper`` is the paper's literal method: RDP on θ with
    ``theta_tolerance`` if given, otherwise the largest θ tolerance (by bisection) whose
    result stays within ``tol``.

    Args:
        curve: the planar input (make_curve, builtin_curve or a reader's).
        tol: the tolerance σ, mm (the library's ``tolerance_mm``).
        method: ``optimal`` (default) or ``paper``.
        corner_deg: turns sharper than this are true corners, degrees.
        theta_tolerance: the paper method's θ tolerance, if given.
        min_segment_mm: the shortest segment, mm.
        speed_mm_s: the programmed speed, with ``tool_accel_mm_s2`` the tool's acceleration.
        tool_accel_mm_s2: see ``speed_mm_s``.

    Returns:
        The Segmentation: the polysegment, its certified deviation and its statistics.

    Raises:
        InputError: a tolerance, speed or length out of range, or an input that no chain
            within ``tol`` fits (too noisy for the tolerance).
        BudgetExceeded: an exact deviation check or a fit over its budget.
    """
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise InputError(f"tolerance_mm: must be a positive number of mm, got {tol}", parameters=("tolerance_mm",))
    if method not in METHODS:
        raise InputError(f"method: unknown method {method!r}; choose one of {', '.join(METHODS)}", parameters=("method",))
    if not (math.isfinite(corner_deg) and 0 < corner_deg < 180):
        raise InputError(f"corner_deg: must be between 0 and 180 degrees, got {corner_deg}", parameters=("corner_deg",))
    _positive(min_segment_mm, "min_segment_mm", "mm")
    check_min_segment(min_segment_mm)
    _positive(speed_mm_s, "speed_mm_s", "mm/s")
    _positive(tool_accel_mm_s2, "tool_accel_mm_s2", "mm/s²")
    if (speed_mm_s is None) != (tool_accel_mm_s2 is None):
        raise InputError("speed_mm_s and tool_accel_mm_s2 go together: give both or neither",
                         parameters=("speed_mm_s", "tool_accel_mm_s2"))
    started = time.perf_counter()
    pts = curve.points
    try:
        check_resolvable(pts, tol)
    except InputError as exc:
        raise InputError(f"{curve.name}: {exc}", parameters=exc.parameters) from None
    speed_kappa = curvature_limit(speed_mm_s, tool_accel_mm_s2)
    thin = None if method == "paper" else _thinned_fit(curve, tol, corner_deg, min_segment_mm, speed_kappa)
    if thin is None:
        check_sampling(pts, curve.name, lambda: noise_hint(curve))
    theta = theta_of_polyline(pts)
    if method == "paper":
        poly, approx, eps = paper_within(curve.points, curve.closed, curve.name, tol, theta_tolerance)
        dev = hausdorff(pts, poly).hausdorff
        return Segmentation(curve, _with_speed(poly, speed_mm_s, tool_accel_mm_s2), method, tol, dev,
                            time.perf_counter() - started, theta, approx, eps,
                            speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2)
    poly = None if thin is not None else obvious_answer(pts, curve.closed, tol)
    input_radius, kept, notes = None, True, ()
    if thin is not None:
        poly, dev, input_radius, kept, notes = thin
    elif poly is not None:
        dev = hausdorff(pts, poly).hausdorff
    else:
        try:
            poly, dev, input_radius, kept, notes = _fit(curve, tol, corner_deg, min_segment_mm, speed_kappa)
        except InputError as exc:
            raise InputError(f"{curve.name}: {exc}", parameters=exc.parameters) from None
        rescue = None if kept else _thinned_fit(curve, tol, corner_deg, min_segment_mm, speed_kappa, NOISY_FALLBACK)
        if rescue is not None and rescue[0].n_segments < poly.n_segments:  # caps loosened: less noise may be why
            poly, dev, input_radius, kept, notes = rescue
    circle = one_circle(pts, poly, tol)
    if circle is not None:
        poly, dev = circle
    extent = extent_mm(pts)
    check_chain(poly, extent)
    if extent < SMALL_SIGMAS * tol:
        notes += (f"the curve spans {extent:.3g} mm, {extent / tol:.2g} times tolerance_mm {tol:g}: its coordinates "
                  "are read as mm (a curve in metres or inches is scaled to mm first)",)
    if not (kept or thin or is_sparse(pts, curve.closed, tol)):
        notes += noise_notes(pts, curve.closed, tol)
    return Segmentation(curve, _with_speed(poly, speed_mm_s, tool_accel_mm_s2), method, tol, dev,
                        time.perf_counter() - started, theta, input_min_radius_mm=input_radius,
                        speed_mm_s=speed_mm_s, tool_accel_mm_s2=tool_accel_mm_s2, limits_kept=kept, notes=notes)


def _thinned_fit(curve: Curve, tol: float, corner_deg: float, min_segment_mm: float | None, speed_kappa: float | None,
                 share: float = NOISY_SPACING) -> tuple[Polysegment, float, float | None, bool, tuple[str, ...]] | None:
    """The fit of every k-th point of a curve whose points scatter by more than ``share`` of
    their spacing (scatter.thinned), within the tolerance less THIN_ROOM scatters, where it holds
    within the tolerance of all the points; else None (the curve is fitted as it is)."""
    found = thinned(curve, tol, share)
    if found is None:
        return None
    thin, noise = found
    try:
        check_sampling(thin.points, curve.name)
        poly, _, radius, kept, notes = _fit(thin, tol - THIN_ROOM * noise, corner_deg, min_segment_mm, speed_kappa)
    except CoatsimError:
        return None
    dev = hausdorff(curve.points, poly).hausdorff
    if not dev <= tol:
        return None
    return poly, dev, radius, kept, notes + (
        f"the points scatter about {noise:.2g} mm (rms) across the curve, a good share of their spacing (measurement "
        f"noise that turns chords back): fitted through {len(thin.points)} of its {len(curve.points)} points, "
        "checked against all",)


def _with_speed(poly: Polysegment, speed_mm_s: float | None, tool_accel_mm_s2: float | None) -> Polysegment:
    if speed_mm_s is None:
        return poly
    return replace(poly, speed_limited=speed_limited(poly, speed_mm_s, tool_accel_mm_s2))


def _fit(curve: Curve, tol: float, corner_deg: float, min_segment_mm: float | None,
         speed_kappa: float | None) -> tuple[Polysegment, float, float | None, bool, tuple[str, ...]]:
    """The default fitter (_fit_within); a taught (sparse) curve's fit is tried again where it
    fell short (coatsim.geometry.taught_retry)."""
    found = _fit_within(curve, tol, corner_deg, min_segment_mm, speed_kappa)
    if not is_sparse(curve.points, curve.closed, tol):
        return found
    return retried(curve.points, curve.closed, tol, corner_deg,
                   lambda aim, degrees: _fit_within(curve, aim, degrees, min_segment_mm, speed_kappa), found)


def _fit_within(curve: Curve, tol: float, corner_deg: float, min_segment_mm: float | None,
                speed_kappa: float | None) -> tuple[Polysegment, float, float | None, bool, tuple[str, ...]]:
    """The default fitter over the curve's runs between corners (or its whole closed loop).
    Returns (polysegment, verified deviation, the input's tightest radius (robust, mm),
    whether every run kept its curvature caps and minimum length, notes)."""
    pts = curve.points
    exact = recover_exact(pts, curve.closed, tol)
    if exact is not None:  # before corners: a large tolerance must not turn a fillet into one
        exact = split_long_arcs(exact)  # an open run that ends where it starts: one full circle
        return Polysegment(exact, closed=curve.closed), hausdorff(pts, Polysegment(exact)).hausdorff, None, True, ()
    corners, notes = corners_and_notes(pts, curve.closed, corner_deg, tol)
    rotated, runs = _runs(pts, corners, curve.closed)
    closed_loop = curve.closed and len(corners) == 0
    if closed_loop:
        poly, dev, radius, kept, more = _fit_loop(pts, tol, min_segment_mm, speed_kappa)
        return poly, dev, radius, kept, notes + more
    pieces: list[tuple[Segment, ...]] = []
    inner: list[int] = []  # corners inside runs (taught points kept as their lines)
    deviations, radii, kept = [], [], True
    with progress(f"{curve.name}: fitting runs between corners", len(runs)) as advance:
        for run in runs:  # the time budget is checked after each run (coatsim.core.progress)
            limits = fit_limits(run, False, tol, min_segment_mm, speed_kappa)
            found = with_lines(lined_run(run, tol, min_segment_mm, speed_kappa),
                           fit_run(run, tol, False, limits, fillet=min_segment_mm is None))
            segments, run_corners = _split_arcs(found)
            inner += [sum(len(p) for p in pieces) + k for k in run_corners]
            pieces.append(segments)
            deviations.append(found.deviation_mm)
            radii.append(limits.profile.tightest_radius_mm)
            kept = kept and found.limits_kept
            notes += found.notes
            advance()
    segments = tuple(seg for piece in pieces for seg in piece)
    junctions = _corner_junctions([len(p) for p in pieces], curve.closed, len(corners) > 0)
    poly = Polysegment(segments, closed=curve.closed, corners=tuple(sorted(set(junctions) | set(inner))))
    dev = deviations[0] if len(runs) == 1 else hausdorff(rotated, poly).hausdorff
    return poly, dev, _finite(min(radii)), kept, notes


def _split_arcs(found: RunFit) -> tuple[tuple[Segment, ...], list[int]]:
    """A run's segments with long arcs split (split_long_arcs) and its corners renumbered."""
    parts = [split_long_arcs((seg,)) for seg in found.segments]
    ends = np.cumsum([len(p) for p in parts]) - 1
    return tuple(s for p in parts for s in p), [int(ends[k]) for k in found.corners]


def _hooked(segments: tuple[Segment, ...]) -> bool:
    """Whether a closed chain closes with a hook: a segment at the seam much shorter than
    the chain's typical one, or a curvature jump around the seam larger than any elsewhere."""
    if len(segments) < 4:
        return False
    length = np.array([s.length for s in segments])
    if min(length[0], length[-1]) < HOOK_SHARE * float(np.median(length)):
        return True
    jump = np.abs(np.diff(np.array([s.curvature for s in segments + segments[:1]])))  # jump[k]: after segment k
    around = jump[[-3, -2, -1]]
    return bool(around.max() > jump[:-3].max() * (1 + 1e-9))


def _fit_loop(pts: np.ndarray, tol: float, min_segment_mm: float | None,
              speed_kappa: float | None) -> tuple[Polysegment, float, float | None, bool, tuple[str, ...]]:
    """A free-form closed loop without corners: a quick fit from the first point, unless it
    closes with a hook (see _hooked) and a fit from the loop's calmest point, started again at
    the first point, needs at most one segment more (or the quick fit fails). Where the quick
    fit fails and no chain of honest arcs follows taught points from the calmest point, quick
    fits from other vertices are tried (_other_seams); if none follows them either, they come
    back as their lines from the first point. Lines for straight stretches where they cost nothing (with_lines)."""
    limits = fit_limits(pts, True, tol, min_segment_mm, speed_kappa)
    quick = fit_free(pts, tol, True, limits, quick=True)
    found = quick
    if quick is None or _hooked(quick.segments):
        first = calm_start(pts)
        run = rotated_loop(pts, first)
        calm = fit_free(run, tol, True, fit_limits(run, True, tol, min_segment_mm, speed_kappa),
                        fillet=min_segment_mm is None)
        if quick is None and calm.corners and is_sparse(pts, True, tol):
            calm = _other_seams(pts, first, tol, min_segment_mm, speed_kappa) or calm
        calm = taught_lines(pts, True, tol) if calm.corners else \
            replace(calm, segments=reseat(calm.segments, pts[0], limits.min_length_mm))
        if quick is None or len(calm.segments) <= len(quick.segments) + 1:
            found = calm
    found = with_lines(lined_loop(pts, tol, min_segment_mm, speed_kappa), found)
    segments, corners = _split_arcs(found)
    poly = Polysegment(segments, closed=True, corners=tuple(corners))
    return poly, found.deviation_mm, _finite(limits.profile.tightest_radius_mm), found.limits_kept, found.notes


def _other_seams(pts: np.ndarray, first: int, tol: float, min_segment_mm: float | None,
                 speed_kappa: float | None) -> RunFit | None:
    """Of quick fits (under the caps as they are) of a taught loop from SEAM_TRIES vertices
    spread evenly round it from vertex ``first``, the one with the fewest segments (fitted
    from its vertex); None if none fits. The band fit starts and closes a loop on a few
    vertices, and one seam can defeat it where others do not: the calmest point misleads on
    a taught loop whose turning changes sign there (its windowed curvature is about zero)."""
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
    best: RunFit | None = None
    for k in range(1, SEAM_TRIES + 1):
        gap = (s[:-1] - s[first] - k * s[-1] / (SEAM_TRIES + 1)) % s[-1]
        run = rotated_loop(pts, int(np.argmin(np.minimum(gap, s[-1] - gap))))
        fit = fit_free(run, tol, True, fit_limits(run, True, tol, min_segment_mm, speed_kappa), quick=True)
        if fit is not None and (best is None or len(fit.segments) < len(best.segments)):
            best = fit
    return best

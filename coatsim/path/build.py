"""Build a coating program: polysegment (or its polyline variant) -> placed path -> program text.

Variants:
- ``polysegment``: one move per line or arc of the polysegment, blended (CP ON).
- ``polyline-stop``: the curve simplified to a polyline within the same tolerance (RDP on
  positions), one LMOVE per vertex, exact stop at every vertex (CP OFF).
- ``polyline-blend``: the same polyline, blended (CP ON, ACCURACY d).

Every variant switches the gun the same way: on a closed contour the lead-in runs with the gun
closed, the gun opens on the fly at the seam and closes on the fly as the lead-out starts,
after exactly one lap; on an open contour it is open from the start of the lead-in (at rest)
to the end of the lead-out (at rest). See :mod:`coatsim.path.as_writer` for the timing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.rdp import rdp_indices, simplify_closed
from coatsim.core.numbers import fmt_short
from coatsim.path.language import Language
from coatsim.path.plan import ProgramPlan
from coatsim.geometry.space.pose import Pose
from coatsim.path.frames import DEFAULT_TOOL
from coatsim.path.placement import PlacedPath, Placement, place, polyline_polysegment
from coatsim.path.process import ProcessInfo, SprayedContour
from coatsim.path.speed_limits import curve_limits

VARIANTS = ("polysegment", "polyline-stop", "polyline-blend")

# Densest sampling of a polysegment when no input points are given for the polyline variant.
_MAX_SAMPLES = 200_000


@dataclass(frozen=True)
class ProgramOptions:
    """Controller settings of the program; ``name`` defaults to one made from the source."""

    variant: str = "polysegment"
    speed_mm_s: float = defaults.SPEED_MM_S
    accuracy_mm: float = defaults.ACCURACY_MM
    approach_mm: float = defaults.APPROACH_MM
    gun_signal: int = defaults.GUN_SIGNAL
    tool: Pose = DEFAULT_TOOL
    name: Optional[str] = None

    def __post_init__(self) -> None:
        if self.variant not in VARIANTS:
            raise InputError(f"variant {self.variant!r}: expected one of {', '.join(VARIANTS)}", parameters=("variant",))
        for what, value, low in (("speed_mm_s", self.speed_mm_s, 0.0), ("accuracy_mm", self.accuracy_mm, -1.0),
                                 ("approach_mm", self.approach_mm, -1.0)):
            if not (math.isfinite(value) and (value > low if low == 0.0 else value >= 0.0)):
                raise InputError(f"{what} {value}: must be a finite number {'> 0' if low == 0.0 else '>= 0'}",
                                 parameters=(what,))
        if not 1 <= self.gun_signal <= defaults.MAX_SIGNAL:
            raise InputError(f"gun_signal {self.gun_signal}: expected an output number from 1 to {defaults.MAX_SIGNAL}",
                             parameters=("gun_signal",))


@dataclass(frozen=True, eq=False)
class BuiltProgram:
    """A written program with the plan it came from."""

    text: str
    plan: ProgramPlan
    curve: Polysegment

    @property
    def path(self) -> PlacedPath:
        return self.plan.paths[0]


def polyline_of(points: np.ndarray, closed: bool, tolerance_mm: float) -> Polysegment:
    """The RDP polyline of ``points`` (n, 2) within ``tolerance_mm``, as a polysegment."""
    pts = np.asarray(points, dtype=float)
    if closed and not np.array_equal(pts[0], pts[-1]):
        pts = np.vstack((pts, pts[:1]))
    keep = simplify_closed(pts, tolerance_mm) if closed else rdp_indices(pts, tolerance_mm)
    return polyline_polysegment(pts[keep], closed)


def dense_points(poly: Polysegment, tolerance_mm: float) -> np.ndarray:
    """Points on ``poly`` at most ``tolerance_mm`` apart (fewer if the curve is very long)."""
    step = max(tolerance_mm, poly.length / _MAX_SAMPLES)
    return poly.sample(step)[0]


def build_program(poly: Polysegment, placement: Placement, options: ProgramOptions, *, tolerance_mm: float,
                  source: str, language: Language, points: Optional[np.ndarray] = None,
                  polyline: Optional[Polysegment] = None) -> BuiltProgram:
    """Write the ``options.variant`` program of a curve in ``language``.

    ``poly`` is the curve's polysegment; the polyline variants simplify ``points`` (the input
    curve, (n, 2)) or, without them, dense samples of ``poly``, unless ``polyline`` (that simplification, computed once for
    both polyline variants) is given. The stretches where the curve
    does not allow the programmed speed (``poly.speed_limited`` from the fitter, and its true
    corners) go into the header (``speed_limits``), scaled to the variant's own curve length,
    so that every variant is measured over the same stretches.
    """
    if not (math.isfinite(tolerance_mm) and tolerance_mm > 0.0):
        raise InputError(f"tolerance_mm {tolerance_mm}: must be a finite number > 0", parameters=("tolerance_mm",))
    if options.variant == "polysegment":
        curve = poly
        summary = f"{poly.n_segments} segments ({poly.n_lines} lines, {poly.n_arcs} arcs)"
    else:
        raw = points if points is not None else dense_points(poly, tolerance_mm)
        curve = polyline if polyline is not None else polyline_of(raw, poly.closed, tolerance_mm)
        summary = f"polyline of {curve.n_segments} lines (RDP of {len(raw)} points)"
    limits = tuple(lim.scaled(curve.length / poly.length) for lim in curve_limits(poly))
    path = place(curve, placement)
    corners = np.array([p.translation_mm for s in path.segments for p in (s.start, s.end)])
    reach = language.capabilities.max_coordinate_mm
    if not (np.isfinite(corners).all() and np.abs(corners).max() <= reach):
        raise InputError(f"{source}: the placed path leaves the range a program can hold (|x| <= {reach:g} mm)")
    process = ProcessInfo(
        variant=options.variant,
        source=source,
        tolerance_mm=tolerance_mm,
        curve_length_mm=path.curve_length_mm,
        lead_in_mm=placement.lead_in_mm,
        lead_out_mm=placement.lead_out_mm,
        standoff_mm=placement.standoff_mm,
        speed_mm_s=options.speed_mm_s,
        accuracy_mm=options.accuracy_mm,
        gun_signal=options.gun_signal,
        frame=placement.frame,
        n_segments=curve.n_segments,
        n_lines=curve.n_lines,
        n_arcs=curve.n_arcs,
        contours=(SprayedContour(closed=curve.closed, leads_sprayed=not curve.closed, speed_limits=limits),),
    )
    plan = ProgramPlan(
        name=language.check_name(options.name, "name") if options.name is not None else
        language.program_name(source.split(":")[-1].split("/")[-1].rsplit(".", 1)[0]),
        paths=(path,),
        speed_mm_s=options.speed_mm_s,
        accuracy_mm=options.accuracy_mm,
        exact_stop=options.variant == "polyline-stop",
        approach_mm=options.approach_mm,
        gun_signal=options.gun_signal,
        tool=options.tool,
        process=process,
        comments=(f"coatsim {options.variant} program: {summary}, tolerance {fmt_short(tolerance_mm)} mm",),
    )
    return BuiltProgram(language.write(plan), plan, curve)

"""Programs of parts: several contours sprayed one after the other in one program.

Each contour is built by the single-contour builder (:func:`build_program`: its variant
curve, placement, lead-in and lead-out); the program sprays them in order — as drawn, or
``nearest`` (greedy: each next contour is the one whose start is closest to where the
previous one ended) — with the gun off between them: depart along the tool axis by the
approach distance, straight travel at that clearance above the next start, down, gun on
(over the whole path of an open contour, over exactly one lap of a closed one). The process
record holds each contour's own entry in spray order. A part of one contour gives exactly the
single-contour program.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional, Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.polysegment import Polysegment
from coatsim.path.build import BuiltProgram, ProgramOptions, build_program
from coatsim.path.language import Language
from coatsim.path.plan import ProgramPlan
from coatsim.path.placement import PlacedPath, Placement, centering_offset

ORDERS = ("as-drawn", "nearest")


@dataclass(frozen=True, eq=False)
class PartProgram:
    """A written program of one or more contours: the plan, each contour's programmed curve
    (polysegment or polyline) in spray order, and the drawing index of each sprayed contour."""

    text: str
    plan: ProgramPlan
    curves: tuple[Polysegment, ...]
    order: tuple[int, ...]

    @property
    def path(self) -> PlacedPath:
        return self.plan.paths[0]

    @property
    def curve(self) -> Polysegment:
        """The programmed curve of a single-contour program."""
        if len(self.curves) != 1:
            raise ValueError("a part program has one curve per contour; use .curves")
        return self.curves[0]

    @property
    def curve_length_mm(self) -> float:
        return float(sum(p.curve_length_mm for p in self.plan.paths))


def contour_order(contours: Sequence[Polysegment], order: str) -> tuple[int, ...]:
    """Spray order of ``contours``: as drawn, or nearest-next from the first drawn contour."""
    if order not in ORDERS:
        raise InputError(f"--order {order!r}: expected one of {', '.join(ORDERS)}")
    if order == "as-drawn" or len(contours) < 3:
        return tuple(range(len(contours)))
    starts = np.array([c.start for c in contours], dtype=float)
    left = list(range(1, len(contours)))
    sequence = [0]
    while left:
        here = np.asarray(contours[sequence[-1]].end, dtype=float)
        distance = np.linalg.norm(starts[left] - here, axis=1)
        sequence.append(left.pop(int(np.argmin(distance))))
    return tuple(sequence)


def part_centering_offset(contours: Sequence[Polysegment]) -> tuple[float, float]:
    """The shift that moves the centre of the bounding box of every contour to the origin."""
    return centering_offset(Polysegment(tuple(s for c in contours for s in c.segments)))


def build_part_program(contours: Sequence[Polysegment], placement: Placement, options: ProgramOptions, *,
                       tolerance_mm: float, source: str, language: Language,
                       points: Optional[Sequence[Optional[np.ndarray]]] = None, order: str = "as-drawn",
                       polylines: Optional[Sequence[Optional[Polysegment]]] = None) -> PartProgram:
    """The ``options.variant`` program spraying every contour of a part; see the module
    docstring. ``points`` are the contours' input points (for the polyline variants), ``polylines``
    their polylines if already simplified (shared by both polyline variants)."""
    if not contours:
        raise InputError(f"{source}: a part needs at least one contour")
    if len(contours) > 1 and not options.approach_mm > 0.0:
        raise InputError(f"--approach {options.approach_mm:g}: a part of {len(contours)} contours travels between "
                         "them at this clearance above the stand-off; it must be > 0 mm")
    sequence = contour_order(contours, order)
    pts = list(points) if points is not None else [None] * len(contours)
    lines = list(polylines) if polylines is not None else [None] * len(contours)
    built: list[BuiltProgram] = [build_program(contours[k], placement, options, tolerance_mm=tolerance_mm,
                                               source=source, language=language, points=pts[k],
                                               polyline=lines[k])
                                 for k in sequence]
    if len(built) == 1:
        return PartProgram(built[0].text, built[0].plan, (built[0].curve,), sequence)
    curves = tuple(b.curve for b in built)
    first = built[0].plan
    process = replace(
        first.process,
        curve_length_mm=sum(b.plan.paths[0].curve_length_mm for b in built),
        n_segments=sum(c.n_segments for c in curves),
        n_lines=sum(c.n_lines for c in curves),
        n_arcs=sum(c.n_arcs for c in curves),
        contours=tuple(b.plan.process.contours[0] for b in built),
        contour_order=tuple(k + 1 for k in sequence),
    )
    summary = ", ".join(f"{c.n_segments}" for c in curves)
    comment = (f"coatsim {options.variant} program of a part: {len(curves)} contours sprayed in order "
               f"{','.join(str(k + 1) for k in sequence)} ({order}), segments per contour {summary}; "
               f"gun off between contours, travel {fmt_short(options.approach_mm)} mm above the stand-off")
    plan = replace(first, paths=tuple(b.plan.paths[0] for b in built), process=process, comments=(comment,))
    return PartProgram(language.write(plan), plan, curves, sequence)


"""The segmentation benchmark: five dense curves generated from their formulas, and the
reference segment counts measured on them (greedy free-arc fitter, the paper's literal method).

The curves are those of the project's benchmark description (``bench/README.md`` of the shared
design notes), sampled the same way, so tests and ``scripts/bench_*.py`` need nothing outside the
repository: spiral (the paper's Fig. 6, 200 mm wide, 4000 points), ellipse (semi-axes 100 and
50 mm, 4000 points), NACA 0012 (200 mm chord, 3000 points, trailing edge a true corner), rounded
rectangle (150 x 80 mm, radii 10 mm, 3000 points equally spaced in arc length), sine
(y = 20 sin(2πx/100), x in [0, 200], 3000 points).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.builtin_curves import ellipse, naca, sine
from coatsim.geometry.curves import Curve, make_curve
from coatsim.geometry.polysegment import Polysegment, chain

TOLERANCES_MM = (0.01, 0.05, 0.1, 0.5)


def _spiral(points: int = 4000, width: float = 200.0) -> np.ndarray:
    """x = -(1+2t) cos t, y = (1+2t) sin t, t in [0, 4π], equally spaced in arc length, scaled so
    the curve (not its samples) is ``width`` wide."""
    t = np.linspace(0.0, 4 * math.pi, 40 * points + 1)
    dense = np.column_stack((-(1 + 2 * t) * np.cos(t), (1 + 2 * t) * np.sin(t)))
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))))
    u = np.linspace(0.0, s[-1], points)
    xy = np.column_stack((np.interp(u, s, dense[:, 0]), np.interp(u, s, dense[:, 1])))
    return xy * (width / np.ptp(dense[:, 0]))


def _roundrect(points: int = 3000, width: float = 150.0, height: float = 80.0, radius: float = 10.0) -> np.ndarray:
    """4 lines + 4 quarter arcs from the middle of the bottom edge, counter-clockwise, sampled
    at ``points`` arc lengths equally spaced (tangent points are generally not samples)."""
    lw, lh, q, k = width - 2 * radius, height - 2 * radius, math.pi / 2 * radius, 1 / radius
    poly = Polysegment(chain((0.0, -height / 2), 0.0, [0, k, 0, k, 0, k, 0, k, 0],
                             [lw / 2, q, lh, q, lw, q, lh, q, lw / 2]), closed=True)
    s = np.linspace(0.0, poly.length, points)
    starts = np.concatenate(([0.0], np.cumsum([seg.length for seg in poly.segments])))
    out = np.empty((points, 2))
    for i, seg in enumerate(poly.segments):
        mask = (s >= starts[i]) & ((s < starts[i + 1]) | (i == len(poly.segments) - 1))
        out[mask] = seg.points(s[mask] - starts[i])
    out[-1] = out[0]
    return out


# name -> (generator, closed)
CURVES: dict[str, tuple[Callable[[], np.ndarray], bool]] = {
    "spiral": (_spiral, False),
    "ellipse": (lambda: ellipse(4000), True),
    "naca0012": (lambda: naca(3000), True),
    "roundrect": (_roundrect, True),
    "sine": (lambda: sine(3000), False),
}
NAMES = tuple(CURVES)

# Segments needed within each tolerance of TOLERANCES_MM, measured on these curves: the greedy
# free-arc fitter (a widely used G-code arc welder, no tangency between neighbours) and the
# paper's method taken literally (bisection on the RDP tolerance of θ until the deviation holds).
REFERENCE_COUNTS: dict[str, dict[str, tuple[int, ...]]] = {
    "greedy": {
        "spiral": (26, 15, 12, 8),
        "ellipse": (25, 14, 13, 7),
        "naca0012": (17, 11, 9, 5),
        "roundrect": (9, 9, 9, 9),
        "sine": (46, 25, 20, 12),
    },
    "paper": {"spiral": (264, 78, 69, 35)},
}


def bench_points(name: str) -> np.ndarray:
    """The (n, 2) points of benchmark curve ``name`` (mm)."""
    if name not in CURVES:
        raise InputError(f"benchmark curve {name!r}: unknown; choose one of {', '.join(NAMES)}")
    return CURVES[name][0]()


def bench_curve(name: str) -> Curve:
    """Benchmark curve ``name`` as a Curve (closed as the benchmark states)."""
    points = bench_points(name)
    return make_curve(points, f"bench:{name}", "yes" if CURVES[name][1] else "no")


def reference_count(kind: str, name: str, tolerance_mm: float) -> int | None:
    """Reference segment count of ``kind`` ("greedy" or "paper") on a curve at a tolerance of
    TOLERANCES_MM, None where none was measured."""
    counts = REFERENCE_COUNTS[kind].get(name)
    return None if counts is None else counts[TOLERANCES_MM.index(tolerance_mm)]

"""Curves the fitter was not tuned on, from their formulas, with their exact tightest radius.

Each entry: name -> (parametric function of t, t range, closed). The points are resampled
uniformly in arc length; the tightest radius comes from the formula (dense central
differences in t), so it is independent of coatsim's own curvature estimate.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

Param = Callable[[np.ndarray], np.ndarray]
TAU = 2 * math.pi


def _polar(r: Callable[[np.ndarray], np.ndarray]) -> Param:
    return lambda t: np.column_stack((r(t) * np.cos(t), r(t) * np.sin(t)))


def _superellipse(a: float, b: float, n: float) -> Param:
    def f(t: np.ndarray) -> np.ndarray:
        c, s = np.cos(t), np.sin(t)
        return np.column_stack((a * np.sign(c) * np.abs(c) ** (2 / n), b * np.sign(s) * np.abs(s) ** (2 / n)))
    return f


CURVES: dict[str, tuple[Param, float, float, bool]] = {
    "epitrochoid": (lambda t: np.column_stack((66 * np.cos(t) - 6 * np.cos(5.5 * t), 66 * np.sin(t) - 6 * np.sin(5.5 * t))),
                    0.0, 2 * TAU, True),
    "lissajous": (lambda t: np.column_stack((80 * np.sin(3 * t + math.pi / 2), 60 * np.sin(2 * t))), 0.0, TAU, True),
    "superellipse-4": (_superellipse(80.0, 50.0, 4.0), 0.0, TAU, True),
    "superellipse-2.5": (_superellipse(60.0, 60.0, 2.5), 0.0, TAU, True),
    "limacon-loop": (_polar(lambda t: 30 + 40 * np.cos(t)), 0.0, TAU, True),
    "limacon": (_polar(lambda t: 50 + 20 * np.cos(t)), 0.0, TAU, True),
    "trefoil": (lambda t: 20 * np.column_stack((np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t))), 0.0, TAU, True),
    "harmonics-closed": (_polar(lambda t: 60 + 8 * np.cos(3 * t) + 5 * np.sin(5 * t + 0.3)), 0.0, TAU, True),
    "harmonics-open": (lambda t: np.column_stack((t, 15 * np.sin(t / 20) + 6 * np.sin(t / 7 + 1.0))), 0.0, 250.0, False),
    "archimedes": (_polar(lambda t: 5 + 6 * t), 0.5, 6 * math.pi, False),
    "log-spiral": (_polar(lambda t: 10 * np.exp(0.15 * t)), 0.0, 5 * math.pi, False),
}


def heldout_points(name: str, n: int = 4000) -> tuple[np.ndarray, bool]:
    """(n, 2) points of the named curve, uniform in arc length, and whether it is closed."""
    f, t0, t1, closed = CURVES[name]
    dense = f(np.linspace(t0, t1, 40 * n + 1))
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))))
    at = np.linspace(0.0, s[-1], n)
    pts = np.column_stack((np.interp(at, s, dense[:, 0]), np.interp(at, s, dense[:, 1])))
    if closed:
        pts[-1] = pts[0]
    return pts, closed


def tightest_radius_mm(name: str) -> float:
    """1 / the largest |κ| of the formula (central differences on 200 001 parameter values)."""
    f, t0, t1, _ = CURVES[name]
    t = np.linspace(t0, t1, 200_001)
    p = f(t)
    d1 = np.gradient(p, t, axis=0)
    d2 = np.gradient(d1, t, axis=0)
    kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
    return float(1.0 / np.abs(kappa[2:-2]).max())

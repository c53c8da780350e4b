"""Random smooth test curves from formulas (no files): closed sums of harmonics in polar form,
superellipses, open harmonic sums and spirals, each with its exact tightest radius."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from hypothesis import strategies as st

from coatsim.geometry import Curve, make_curve


@dataclass(frozen=True)
class Formula:
    """A parametric curve p(t), t in [t0, t1], closed or open."""

    name: str
    f: Callable[[np.ndarray], np.ndarray]
    t0: float
    t1: float
    closed: bool

    def curve(self, points: int) -> Curve:
        """Points uniform in arc length (a closed curve repeats its first point)."""
        dense = self.f(np.linspace(self.t0, self.t1, 40 * points + 1))
        s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))))
        at = np.linspace(0.0, s[-1], points)
        pts = np.column_stack((np.interp(at, s, dense[:, 0]), np.interp(at, s, dense[:, 1])))
        if self.closed:
            pts[-1] = pts[0]
        return make_curve(pts, self.name, "yes" if self.closed else "no")

    def tightest_radius(self) -> float:
        """1 / the largest |κ| of the formula (central differences on 100 001 values of t)."""
        t = np.linspace(self.t0, self.t1, 100_001)
        d1 = np.gradient(self.f(t), t, axis=0)
        d2 = np.gradient(d1, t, axis=0)
        kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
        return float(1.0 / np.abs(kappa[2:-2]).max())


def _polar(r: Callable[[np.ndarray], np.ndarray]) -> Callable[[np.ndarray], np.ndarray]:
    return lambda t: np.column_stack((r(t) * np.cos(t), r(t) * np.sin(t)))


@st.composite
def closed_harmonics(draw) -> Formula:
    """r(θ) = R + Σ a_k cos(kθ + φ_k): a star-shaped smooth loop (|Σ a_k k²| < R keeps it
    free of cusps and loops)."""
    radius = draw(st.floats(30.0, 90.0))
    terms = draw(st.lists(st.tuples(st.integers(2, 6), st.floats(0.0, 1.0), st.floats(0.0, 2 * math.pi)),
                          min_size=1, max_size=3))
    budget = 0.5 * radius / sum(k * k for k, _, _ in terms)
    terms = [(k, share * budget, phase) for k, share, phase in terms]
    r = lambda t: radius + sum(a * np.cos(k * t + p) for k, a, p in terms)  # noqa: E731
    return Formula(f"harmonics R={radius:.1f} {terms}", _polar(r), 0.0, 2 * math.pi, True)


@st.composite
def superellipses(draw) -> Formula:
    a, b = draw(st.floats(40.0, 100.0)), draw(st.floats(30.0, 80.0))
    n = draw(st.floats(2.2, 4.5))

    def f(t: np.ndarray) -> np.ndarray:
        c, s = np.cos(t), np.sin(t)
        return np.column_stack((a * np.sign(c) * np.abs(c) ** (2 / n), b * np.sign(s) * np.abs(s) ** (2 / n)))
    return Formula(f"superellipse a={a:.1f} b={b:.1f} n={n:.2f}", f, 0.0, 2 * math.pi, True)


@st.composite
def open_harmonics(draw) -> Formula:
    """y = Σ a_k sin(x / λ_k + φ_k) over x in [0, L]."""
    length = draw(st.floats(120.0, 300.0))
    terms = draw(st.lists(st.tuples(st.floats(2.0, 20.0), st.floats(8.0, 40.0), st.floats(0.0, 2 * math.pi)),
                          min_size=1, max_size=3))
    f = lambda t: np.column_stack((t, sum(a * np.sin(t / lam + p) for a, lam, p in terms)))  # noqa: E731
    return Formula(f"harmonics L={length:.0f} {terms}", f, 0.0, length, False)


@st.composite
def spirals(draw) -> Formula:
    if draw(st.booleans()):
        a, b, turns = draw(st.floats(5.0, 20.0)), draw(st.floats(2.0, 8.0)), draw(st.floats(1.0, 3.0))
        return Formula(f"archimedes {a:.1f}+{b:.1f}t", _polar(lambda t: a + b * t), 0.0, 2 * math.pi * turns, False)
    a, k, turns = draw(st.floats(5.0, 20.0)), draw(st.floats(0.08, 0.25)), draw(st.floats(1.0, 2.5))
    return Formula(f"log spiral {a:.1f}e^{k:.2f}t", _polar(lambda t: a * np.exp(k * t)), 0.0, 2 * math.pi * turns, False)


smooth_closed = st.one_of(closed_harmonics(), superellipses())
smooth_open = st.one_of(open_harmonics(), spirals())

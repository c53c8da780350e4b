"""Space curves to benchmark and test the 3-D fit on: one per family of held-out-style input.

Each is a dense polyline (mm) of a curve a gun could follow on a curved part: a helix, a wave
wound on a cylinder, a spiral on a sphere, a closed curve on a saddle, a section of a torus
knot, and a blade-like pass (an airfoil-shaped sweep over a twisted, cambered surface).
``HELD_OUT`` are families the fit was never tuned on: Viviani's curve, a conical spiral, a
trefoil knot, a seam over a free-form surface, and irregular noisy samples.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

Family = Callable[[int], np.ndarray]


def helix(n: int = 3000) -> np.ndarray:
    """Radius 40 mm, 3 turns, 90 mm rise."""
    t = np.linspace(0.0, 6 * math.pi, n)
    return np.column_stack((40 * np.cos(t), 40 * np.sin(t), 90 * t / (6 * math.pi)))


def cylinder_wave(n: int = 3000) -> np.ndarray:
    """A sine wave (amplitude 15 mm, 4 periods) wound once around a cylinder of radius 60 mm."""
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=True)
    return np.column_stack((60 * np.cos(t), 60 * np.sin(t), 15 * np.sin(4 * t)))


def sphere_spiral(n: int = 3000) -> np.ndarray:
    """A spiral from pole to equator on a sphere of radius 80 mm, 2.5 turns."""
    u = np.linspace(0.05, 1.0, n)
    polar, azimuth = u * math.pi / 2, u * 5 * math.pi
    return 80 * np.column_stack((np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)))


def saddle(n: int = 3000) -> np.ndarray:
    """The closed curve over a circle of radius 50 mm on the saddle z = (x² − y²) / 100."""
    t = np.linspace(0.0, 2 * math.pi, n)
    x, y = 50 * np.cos(t), 50 * np.sin(t)
    return np.column_stack((x, y, (x**2 - y**2) / 100))


def torus_section(n: int = 3000) -> np.ndarray:
    """A third of a (2, 3) torus knot on a torus of radii 80 and 30 mm."""
    t = np.linspace(0.0, 2 * math.pi / 3 * 2, n)
    r = 80 + 30 * np.cos(1.5 * t)
    return np.column_stack((r * np.cos(t), r * np.sin(t), 30 * np.sin(1.5 * t)))


def blade_pass(n: int = 3000) -> np.ndarray:
    """One spray pass across a blade: 200 mm along the span over a cambered surface that
    twists by 30 degrees, the pass weaving 10 mm across it."""
    u = np.linspace(0.0, 1.0, n)
    span = 200 * u
    twist = math.radians(30) * u
    chord = 40 * np.sin(3 * math.pi * u) / 4
    camber = 12 * (1 - (chord / 40) ** 2) + 8 * u**2
    return np.column_stack((chord * np.cos(twist) - camber * np.sin(twist), span,
                            chord * np.sin(twist) + camber * np.cos(twist)))


def viviani(n: int = 3000) -> np.ndarray:
    """Viviani's curve (a sphere of radius 80 mm cut by a cylinder of radius 40 mm through
    its centre): a closed figure eight."""
    t = np.linspace(0.0, 4 * math.pi, n)
    return np.column_stack((40 * (1 + np.cos(t)), 40 * np.sin(t), 80 * np.sin(t / 2)))


def conical_spiral(n: int = 3000) -> np.ndarray:
    """Three turns up a cone, the radius growing from 10 to 60 mm over 80 mm of height."""
    u = np.linspace(0.0, 1.0, n)
    r, angle = 10 + 50 * u, 6 * math.pi * u
    return np.column_stack((r * np.cos(angle), r * np.sin(angle), 80 * u))


def trefoil(n: int = 3000) -> np.ndarray:
    """The closed trefoil knot, 20 mm to the unit."""
    t = np.linspace(0.0, 2 * math.pi, n)
    return 20 * np.column_stack((np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)))


def freeform_seam(n: int = 3000) -> np.ndarray:
    """A seam 150 mm long weaving over a free-form surface (two Gaussian bumps and a twist)."""
    u = np.linspace(0.0, 1.0, n)
    x, y = 150 * u, 30 * np.sin(2 * math.pi * u) + 10 * u**2
    z = 25 * np.exp(-((x - 50) ** 2 + (y - 10) ** 2) / 900) - 15 * np.exp(-((x - 110) ** 2 + (y + 5) ** 2) / 600) \
        + 0.002 * x * y
    return np.column_stack((x, y, z))


def noisy_lissajous(n: int = 3000) -> np.ndarray:
    """A space Lissajous arc sampled at irregular spacing with 0.01 mm of Gaussian noise
    (seeded: the same points every time)."""
    rng = np.random.default_rng(23)
    t = np.sort(rng.uniform(0.0, math.pi, n))
    t[[0, -1]] = 0.0, math.pi
    pts = np.column_stack((60 * np.sin(t), 40 * np.sin(2 * t + 0.5), 25 * np.sin(3 * t)))
    return pts + rng.normal(scale=0.01, size=pts.shape)


FAMILIES: dict[str, Family] = {
    "helix": helix, "cylinder": cylinder_wave, "sphere": sphere_spiral,
    "saddle": saddle, "torus": torus_section, "blade": blade_pass,
}
TOLERANCES_MM = (0.05, 0.1, 0.5)
HELD_OUT: dict[str, Family] = {
    "viviani": viviani, "cone": conical_spiral, "trefoil": trefoil, "freeform": freeform_seam,
    "noisy": noisy_lissajous,
}

"""Space curves to benchmark and test the 3-D fit on: one per family of held-out-style input.

Each is a dense polyline (mm) of a curve a gun could follow on a curved part: a helix, a wave
wound on a cylinder, a spiral on a sphere, a closed curve on a saddle, a section of a torus
knot, and a blade-like pass (an airfoil-shaped sweep over a twisted, cambered surface).
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


FAMILIES: dict[str, Family] = {
    "helix": helix, "cylinder": cylinder_wave, "sphere": sphere_spiral,
    "saddle": saddle, "torus": torus_section, "blade": blade_pass,
}
TOLERANCES_MM = (0.05, 0.1, 0.5)

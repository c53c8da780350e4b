"""How far a dense curve's points scatter across it: the measurement noise a fit meets.

Each point's signed distance from the chord of its two neighbours is the curve's own bend over
two spacings (smooth, slowly varying along a densely sampled curve) plus the noise, whose part
there has the variance 1.5 sigma^2 for independent noise of deviation sigma. Less its running
median over ``WINDOW`` points, the median absolute value (scaled to a Gaussian's deviation)
estimates sigma, robust to the few points where the bend changes fast (a corner, a tight turn).
Meaningful on dense curves only: on a taught polygon the distances are its vertices' turns.

Points that scatter by more than a quarter of their spacing turn chords back at random: the fit
runs on every k-th point instead, a tolerance apart, within the tolerance less THIN_ROOM
scatters, and is checked against them all.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from coatsim.geometry.curves import Curve

WINDOW = 9  # points in the running median that takes the curve's own bend out
MAD_TO_SIGMA = 1.4826  # a Gaussian's deviation over its median absolute deviation
THIN_ROOM = 4.0  # scatters of the tolerance kept for the points between the thinned ones
THIN_SCATTERS = 12.0  # points are thinned from a tolerance of this many scatters (the fit keeps 8 of them)
MIN_THINNED = 20  # fewer thinned points than this are no curve to fit
NOISY_SPACING = 0.25  # points scattering by more than this share of their spacing turn chords back at random
NOISY_FALLBACK = 0.05  # ... and by more than this share where the fit of all of them had to loosen its caps
NOISE_SHARE = 0.1  # points scattering by more than this share of the tolerance leave a fit little room


def scatter_mm(points: np.ndarray, closed: bool) -> float:
    """The deviation (mm) of the points' scatter across the curve, plane (n, 2) or space (n, 3)
    (0 on fewer than WINDOW + 2). In space the offset from the chord is a vector across it, its
    running median taken per coordinate; the residual's length is then Rayleigh distributed
    (two independent components of variance 1.5 sigma^2), its median sqrt(2 ln 2) of its scale."""
    p = np.asarray(points, dtype=float)
    if closed:
        p = np.vstack([p[-1:], p, p[:1]])
    a, b, c = p[:-2], p[1:-1], p[2:]
    chord = c - a
    length = np.linalg.norm(chord, axis=1)
    ok = length > 0
    if p.shape[1] == 2:
        offset = (chord[ok, 0] * (b - a)[ok, 1] - chord[ok, 1] * (b - a)[ok, 0]) / length[ok]
    else:
        unit = chord[ok] / length[ok, None]
        rel = (b - a)[ok]
        offset = rel - np.einsum("ij,ij->i", rel, unit)[:, None] * unit
    if len(offset) < WINDOW:
        return 0.0
    pad = ((WINDOW // 2, WINDOW // 2),) + ((0, 0),) * (offset.ndim - 1)
    residual = offset - np.median(sliding_window_view(np.pad(offset, pad, mode="edge"), WINDOW, axis=0), axis=-1)
    if offset.ndim == 1:
        return float(MAD_TO_SIGMA * np.median(np.abs(residual)) / math.sqrt(1.5))
    return float(np.median(np.linalg.norm(residual, axis=1)) / (math.sqrt(2 * math.log(2)) * math.sqrt(1.5)))


def noise_notes(points: np.ndarray, closed: bool, tolerance_mm: float) -> tuple[str, ...]:
    """For a fit that had to loosen its caps: a note where the points scatter across the curve
    by more than NOISE_SHARE of the tolerance (noise the arcs followed), else none."""
    noise = scatter_mm(points, closed)
    if not noise > NOISE_SHARE * tolerance_mm:
        return ()
    return (f"the points scatter about {noise:.2g} mm (rms) across the curve: measurement noise that the arcs "
            f"follow within tolerance_mm {tolerance_mm:g} (their caps loosened); a tolerance many times the scatter, or "
            "smoothed points, fits the curve itself",)


def noise_hint(curve: Curve) -> str:
    """What a refusal of a curve that doubles back can add: its scatter, where it is noise that
    turns chords back, and the tolerance from which such points are thinned and fitted."""
    noise = scatter_mm(curve.points, curve.closed)
    if not noise > NOISY_SPACING * _spacing(curve.points):
        return ""
    need = THIN_SCATTERS * noise
    step = 10.0 ** (math.floor(math.log10(need)) - 1)  # rounded up to two digits: that tolerance is enough
    return (f"; its points scatter about {noise:.2g} mm across it: from a tolerance of "
            f"{math.ceil(need / step) * step:.2g} mm they are fitted through every k-th point")


def _spacing(points: np.ndarray) -> float:
    return float(np.median(np.linalg.norm(np.diff(points, axis=0), axis=1)))


def thinned(curve: Curve, tolerance_mm: float, share: float = NOISY_SPACING) -> tuple[Curve, float] | None:
    """Every k-th point of a curve whose points scatter across it by more than ``share`` of
    their spacing (noise that turns chords back: no shape between the points to fit), k such
    that they lie a tolerance apart, with the scatter; None where the points do not scatter so,
    or the tolerance is under THIN_SCATTERS scatters."""
    pts = curve.points
    spacing, noise = _spacing(pts), scatter_mm(pts, curve.closed)
    if not (noise > share * spacing and THIN_SCATTERS * noise < tolerance_mm):
        return None
    index = np.arange(0, len(pts) - 1, math.ceil(tolerance_mm / spacing))
    if len(index) < MIN_THINNED:
        return None
    return Curve(pts[np.append(index, len(pts) - 1)], curve.closed, curve.name), noise

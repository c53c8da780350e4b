"""Spray axes that keep a pass's tool path from folding back.

On the normal at stand-off h over a section concave with radius R the tool centre point advances
(R − h) / R of the spot's advance on the surface: tighter than the stand-off it stalls (R = h) or
runs backwards (R < h), and where it turns from forwards to backwards the programmed path gets cusps
that no arc, line or pose rate can follow (seen on a scanned part: arcs of microns converging on the
cusp, a 5° turn in place and a programmed speed of 0.06 mm/s on the trace). There the axis turns
only as fast as lets the tool centre point advance at least ``MIN_ADVANCE`` of the spot's way on
every step, lagging behind the normal; run once forwards (the axis lags after the fold) and once
backwards (it leads before it), the two are averaged, so the axis leaves the normal by about half
the lag, on both sides. A pass wholly inside such a trough (the tool runs backwards all along it: a
fan) has no cusp and stays on the normal.
"""

from __future__ import annotations

import math

import numpy as np

MIN_ADVANCE = 0.05  # the tool centre point advances at least this share of the spot's way, every step


def unfolded_axes(points_mm: np.ndarray, axes: np.ndarray, standoff_mm: float) -> np.ndarray:
    """Unit spray axes (n, 3) along a pass's surface points (n, 3): ``axes`` (the spray axes,
    minus the normals) where, at ``standoff_mm``, the tool centre point ``point − standoff ·
    axis`` advances at least ``MIN_ADVANCE`` of the spot's way from each point to the next (or
    runs back at least that much all along the pass), else the axes the turn-rate limit leaves
    (see the module)."""
    axes = np.asarray(axes, dtype=float)
    advance = _advance(points_mm, axes, standoff_mm)
    if np.all(advance >= MIN_ADVANCE) or np.all(advance <= -MIN_ADVANCE):  # no cusp (or a fan: see the module)
        return axes.copy()
    forward = _lagging(points_mm, axes, standoff_mm)
    backward = _lagging(points_mm[::-1], axes[::-1], standoff_mm)[::-1]
    mean = forward + backward
    mean /= np.linalg.norm(mean, axis=1)[:, None]
    return _lagging(points_mm, mean, standoff_mm)  # the mean may fold a hair where the two turn alike


def _lagging(points_mm: np.ndarray, axes: np.ndarray, standoff_mm: float) -> np.ndarray:
    """The axes followed from the first one on, each step turning towards the wanted axis along
    their great circle as far as the advance allows (no turn at all always does: the tool
    centre point then moves with the spot)."""
    out = np.empty_like(axes)
    out[0] = axes[0]
    for i in range(1, len(axes)):
        a, b, dp = out[i - 1], axes[i], points_mm[i] - points_mm[i - 1]
        out[i] = b
        # turned by x towards b: a cos x + w sin x; the advance wants
        # standoff * ((cos x - 1) a.dp + sin x w.dp) <= (1 - MIN_ADVANCE) |dp|^2
        w = b - (a @ b) * a
        norm = math.sqrt(float(w @ w))
        if norm < 1e-15:
            continue
        w /= norm
        angle = math.atan2(norm, float(a @ b))
        alpha, beta = float(a @ dp), float(w @ dp)
        room = (1.0 - MIN_ADVANCE) * float(dp @ dp) / standoff_mm + alpha
        rho = math.hypot(alpha, beta)
        if rho <= room:
            continue
        first = (math.atan2(beta, alpha) - math.acos(room / rho)) % (2 * math.pi)  # where it first reaches the room
        if first < angle:
            out[i] = a * math.cos(first) + w * math.sin(first)
    return out


def _advance(points_mm: np.ndarray, axes: np.ndarray, standoff_mm: float) -> np.ndarray:
    """The tool centre point's advance along the spot's way on each step (n - 1,), as a share of
    it (1 on a flat, 0 stalled, negative backwards; 1 on a repeated point)."""
    dp = np.diff(points_mm, axis=0)
    dt = dp - standoff_mm * np.diff(axes, axis=0)
    way = np.einsum("ij,ij->i", dp, dp)
    return np.einsum("ij,ij->i", dt, dp) / np.where(way > 0, way, 1.0) + (way == 0)

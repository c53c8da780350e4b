"""The passes of a surfacepaths file as the tool runs them, and their orientation-aware 3-D fit.

Per pass the tool centre point runs at ``point + standoff · normal`` with the spray axis along
minus the normal, placed in the robot base frame by the part's pose (:func:`pass_tcp`). Every
variant of a program needs the fit of every pass: the polysegment for its moves, the polylines
for the speed limits the curve's own bends set. The fit is most of a program's time, so it is
made once (:func:`fit_passes`) and shared by the variants written at the same speed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.geometry.space.orient import fit_surface_pass
from coatsim.geometry.space.pose import Pose
from coatsim.path.roll import AxisPiece
from coatsim.path.surfacepaths import SurfacePass, SurfacePaths
from coatsim.path.unfold import unfolded_axes


@dataclass(frozen=True, eq=False)
class PassTcp:
    """A pass's tool centre points (n, 3) mm and spray axes (n, 3) in the base frame, and the
    largest angle (rad) by which an axis leaves the surface normal (coatsim.path.unfold)."""

    tcp_mm: np.ndarray
    axes: np.ndarray
    max_tilt_rad: float


def pass_tcp(surface_pass: SurfacePass, standoff_mm: float, pose: Pose) -> PassTcp:
    """The pass's tool centre points and spray axes: the axis along minus the normal (turning no
    faster than keeps the tool centre point advancing, coatsim.path.unfold), the tool centre
    point ``standoff_mm`` back along it; a closed pass ends where it starts."""
    points, normals = surface_pass.points, surface_pass.normals
    if surface_pass.closed and not np.array_equal(points[0], points[-1]):
        points, normals = np.vstack((points, points[:1])), np.vstack((normals, normals[:1]))
    axes = unfolded_axes(points, -normals, standoff_mm)
    tilt = float(np.max(np.arccos(np.clip(-np.einsum("ij,ij->i", axes, normals), -1.0, 1.0))))
    return PassTcp(pose.apply(points - standoff_mm * axes), pose.apply_vectors(axes), tilt)


@dataclass(frozen=True)
class FitSettings:
    """What the fit of the passes depends on: the stand-off and part pose they are placed with,
    the fit's tolerances, the programmed speed, where it holds (``tcp`` or ``trace``) and the
    tool acceleration (None: no speed limit shapes the fit). Two programs with equal settings
    share one fit."""

    standoff_mm: float
    pose: Pose
    tolerance_mm: float
    angle_tol_deg: float
    speed_mm_s: float
    speed_on: str
    tool_accel_mm_s2: Optional[float]

    def same_as(self, other: "FitSettings") -> bool:
        """Equal settings, the poses compared by value."""
        mine = (self.standoff_mm, self.tolerance_mm, self.angle_tol_deg, self.speed_mm_s, self.speed_on,
                self.tool_accel_mm_s2)
        theirs = (other.standoff_mm, other.tolerance_mm, other.angle_tol_deg, other.speed_mm_s, other.speed_on,
                  other.tool_accel_mm_s2)
        return mine == theirs and np.array_equal(self.pose.as_matrix4(), other.pose.as_matrix4())


@dataclass(frozen=True, eq=False)
class PassFit:
    """One pass fitted in 3-D: its pieces with the spray axis at each one's start, via and end
    point, and the largest angle (rad) between the fitted axis and the planned one."""

    pieces: tuple[AxisPiece, ...]
    max_axis_error_rad: float


@dataclass(frozen=True, eq=False)
class PassFits:
    """The passes placed (:class:`PassTcp`) and fitted (:class:`PassFit`) with ``settings``."""

    settings: FitSettings
    tcps: tuple[PassTcp, ...]
    fits: tuple[PassFit, ...]


def place_passes(paths: SurfacePaths, settings: FitSettings) -> tuple[PassTcp, ...]:
    """Every pass's tool centre points and axes in the base frame."""
    return tuple(pass_tcp(p, settings.standoff_mm, settings.pose) for p in paths.passes)


def fit_passes(paths: SurfacePaths, settings: FitSettings) -> PassFits:
    """Every pass placed and fitted in 3-D within ``settings``. With the speed on the trace the
    fit's speed limits are those of the fastest the tool centre point runs (the spot moves
    slower than it over a convex bend)."""
    tcps = place_passes(paths, settings)
    fits = []
    for k, placed in enumerate(tcps):
        tcp, axes = placed.tcp_mm, placed.axes
        speed = settings.speed_mm_s
        if settings.speed_on == "trace":
            step = np.linalg.norm(np.diff(tcp, axis=0), axis=1)
            trace_step = np.linalg.norm(np.diff(tcp + settings.standoff_mm * axes, axis=0), axis=1)
            speed *= float(np.max(step / np.maximum(trace_step, 1e-12)))
        accel = settings.tool_accel_mm_s2
        fit = fit_surface_pass(tcp, axes, settings.tolerance_mm, settings.angle_tol_deg,
                               speed_mm_s=speed if accel is not None else None, tool_accel_mm_s2=accel,
                               name=f"{paths.source}: passes[{k}]")
        chain = fit.chain
        pieces = tuple(AxisPiece(seg, tuple(np.array(a) for a in trio)) for seg, trio in zip(chain.segments, chain.axes))
        fits.append(PassFit(pieces, fit.max_axis_error_rad))
    return PassFits(settings, tcps, tuple(fits))

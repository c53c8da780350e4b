"""The cell's default frames as poses: where the workpiece lies and where the gun's TCP sits on
the flange (their values are in coatsim.core.defaults)."""

from __future__ import annotations

from coatsim.core import defaults
from coatsim.geometry.space.xyzoat import pose_from_xyzoat

DEFAULT_FRAME = pose_from_xyzoat(defaults.WORKPIECE_FRAME)
DEFAULT_TOOL = pose_from_xyzoat(defaults.GUN_TOOL)

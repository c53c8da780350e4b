"""Plans and programs the language tests share: written by a registered language, read back,
and compared with the plan's placed path by geometry alone."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3, Line3
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions
from coatsim.path.language import ReadOptions
from coatsim.path.part_program import PartProgram, build_part_program
from coatsim.path.placement import Placement, centering_offset
from coatsim.path.toolpath import ToolPath

from program_helpers import arc_spiral, roundrect

__all__ = ["arc_spiral", "roundrect", "planned", "read_text", "path_points", "distance_to_plan", "sprayed_points"]


def planned(name: str, contours: Sequence[Polysegment] | None = None, variant: str = "polysegment",
            frame: Pose | None = None, speed_mm_s: float = 300.0, accuracy_mm: float = 0.5, **placement) -> PartProgram:
    """The program of ``contours`` (a rounded rectangle) written in language ``name``."""
    contours = list(contours) if contours is not None else [roundrect()]
    extra = {"frame": frame} if frame is not None else {}
    place = Placement(lead_in_mm=20.0, lead_out_mm=15.0, offset_xy=centering_offset(contours[0]), **extra,
                      **placement)
    options = ProgramOptions(variant=variant, speed_mm_s=speed_mm_s, accuracy_mm=accuracy_mm)
    return build_part_program(contours, place, options, tolerance_mm=0.1, source="shapes", language=language(name))


def read_text(name: str, text: str, tmp_path: Path, suffix: str | None = None, **options) -> ToolPath:
    """The ToolPath language ``name`` reads from ``text``."""
    lang = language(name)
    path = tmp_path / f"prog{suffix or lang.suffixes[0]}"
    path.write_text(text)
    return lang.read([path], ReadOptions(**options))


def path_points(plan_paths, step_mm: float = 0.5) -> np.ndarray:
    """Dense points along every placed path of a plan (mm, base frame)."""
    out = []
    for path in plan_paths:
        for seg in path.segments:
            n = max(2, math.ceil(seg.length / step_mm) + 1)
            out.append(seg.point_tangent(np.linspace(0.0, 1.0, n))[0])
    return np.vstack(out)


def distance_to_plan(points: np.ndarray, plan_paths) -> float:
    """The largest distance from ``points`` (n, 3) to the plan's placed paths (exact per segment)."""
    best = np.full(len(points), np.inf)
    for path in plan_paths:
        for seg in path.segments:
            best = np.minimum(best, seg.geometry.nearest(points)[0])
    return float(best.max())


def sprayed_points(primitives: Sequence[Line3 | Arc3], step_mm: float = 0.5) -> np.ndarray:
    out = []
    for prim in primitives:
        n = max(2, math.ceil(prim.length / step_mm) + 1)
        out.append(prim.points(np.linspace(0.0, prim.length, n)))
    return np.vstack(out)

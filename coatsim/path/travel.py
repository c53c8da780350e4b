"""The clearance of the gun-off travel between the passes of a 3-D program: each pass is left
and the next entered along the tool axis, far enough that the straight travel between them keeps
at least the stand-off from every point of the part's surface."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.nearest import edge_distance
from coatsim.path.placement import PlacedPath

CLEARANCE_STEPS = 6  # the travel clearance is doubled at most this many times


def travel_clearances(paths: list[PlacedPath], approach: float, surface: np.ndarray, standoff: float,
                      source: str) -> list[PlacedPath]:
    """The paths with their approach and depart clearances: ``approach``, doubled for the two
    ends of a travel until the straight travel between them keeps at least the stand-off from
    every surface point (each travel on its own: one that needs room does not raise the next)."""
    clearance = [[approach, approach] for _ in paths]  # per path: coming in, leaving
    for k in range(len(paths) - 1):
        a, b = paths[k].end, paths[k + 1].start
        c = approach
        for _ in range(CLEARANCE_STEPS + 1):
            p, q = a.translation_mm - c * a.rotation[:, 2], b.translation_mm - c * b.rotation[:, 2]
            if edge_distance(surface, np.array([p, q]), np.zeros(len(surface), dtype=int)).min() >= standoff:
                clearance[k][1] = clearance[k + 1][0] = c
                break
            c *= 2
        else:
            raise InputError(f"{source}: the travel from pass {k + 1} to pass {k + 2} passes closer to the part "
                             f"than the stand-off even {fmt_short(c / 2)} mm off it; spray them in another order or "
                             "split the program", parameters=("approach_mm",))
    return [replace(path, approach_clearance_mm=came, depart_clearance_mm=left)
            for path, (came, left) in zip(paths, clearance)]

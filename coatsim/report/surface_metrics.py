"""Metrics of a run on a 3-D part that the curve runs do not have: the segmentation group of a
program of passes (its moves against the planned tool centre points) and ``metrics.json``'s
"passes" (per pass, per variant, the motion figures and the spray spot's speed) and "plan"."""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np

from coatsim.path.placement import PlacedPath
from coatsim.robot.execute import Execution

#: the programmed curve and the planned tool centre points are compared on samples this many
#: times denser than the tolerance (each distance is then overestimated by at most tolerance / 8)
SAMPLES_PER_TOLERANCE = 4


def _dense(points: np.ndarray, step_mm: float) -> np.ndarray:
    """A polyline (n, 3) resampled every ``step_mm`` or closer, its vertices kept."""
    out = [points[:1]]
    for a, b in zip(points[:-1], points[1:]):
        n = max(1, math.ceil(float(np.linalg.norm(b - a)) / step_mm))
        out.append(a + np.outer(np.arange(1, n + 1) / n, b - a))
    return np.vstack(out)


def _turn_deg(a: np.ndarray, b: np.ndarray) -> float:
    return math.degrees(math.atan2(float(np.linalg.norm(np.cross(a, b))), float(a @ b)))


def surface_segmentation_group(paths: Sequence[PlacedPath], tcp_mm: Sequence[np.ndarray], tolerance_mm: float,
                               corner_deg: float) -> dict[str, Any]:
    """The catalogue's segmentation group of a program of passes: its moves on the passes proper
    (leads left out), the two-sided largest distance between them and the planned tool centre
    points ``tcp_mm`` (one (n, 3) polyline per pass, base frame), the junctions that turn by
    more than ``corner_deg`` (corners) and the largest turn and curvature jump at the others."""
    from scipy.spatial import cKDTree

    step = tolerance_mm / SAMPLES_PER_TOLERANCE
    n_arcs = n_lines = corners = 0
    deviation = turn = jump = 0.0
    for path, tcp in zip(paths, tcp_mm):
        moves = [m for m in path.segments if m.part == "curve"]
        n_arcs += sum(m.is_arc for m in moves)
        n_lines += sum(not m.is_arc for m in moves)
        for a, b in zip(moves[:-1], moves[1:]):
            angle = _turn_deg(a.geometry.end_tangent, b.geometry.start_tangent)
            if angle > corner_deg:
                corners += 1
                continue
            turn = max(turn, angle)
            ka, kb = (1.0 / m.geometry.radius if m.is_arc else 0.0 for m in (a, b))
            jump = max(jump, abs(ka - kb))
        programmed = np.vstack([m.geometry.points(np.linspace(0.0, m.length, max(2, math.ceil(m.length / step) + 1)))
                                for m in moves])
        planned = _dense(tcp, step)
        deviation = max(deviation, float(cKDTree(planned).query(programmed)[0].max()),
                        float(cKDTree(programmed).query(planned)[0].max()))
    return {
        "n_segments": n_arcs + n_lines, "n_arcs": n_arcs, "n_lines": n_lines, "n_corners": corners,
        "max_deviation_mm": deviation, "tolerance_mm": tolerance_mm, "max_tangent_break_deg": turn,
        "curve_length_mm": float(sum(p.curve_length_mm for p in paths)), "max_curvature_jump_per_mm": jump,
    }


def pass_spot_speeds(execution: Execution) -> list[dict[str, float | None]]:
    """Per pass (each spray stretch of the program proper): the spray spot's mean and lowest speed
    on the surface (mm/s) and the lowest over the target (the programmed speed)."""
    log, out = execution.log, []
    target = execution.metrics.programmed_speed_mm_s
    for a, b in execution.curves:
        rows = (log.progress >= a) & (log.progress <= b) & np.asarray(log.spray, bool)
        v = log.spot_speed[rows]
        if not len(v):
            out.append({"spot_mean_mm_s": None, "spot_min_mm_s": None, "spot_min_ratio": None})
            continue
        out.append({"spot_mean_mm_s": float(v.mean()), "spot_min_mm_s": float(v.min()),
                    "spot_min_ratio": float(v.min() / target) if target > 0 else None})
    return out


PASS_MOTION = ("curve_length_mm", "cycle_time_s", "mean_speed_mm_s", "min_speed_mm_s", "min_speed_ratio",
               "fraction_at_speed", "stops")


def passes_section(lengths_mm: Sequence[float], executions: Mapping[str, Execution]) -> list[dict[str, Any]]:
    """``metrics.json`` "passes": per pass its number and planned length, and per variant the
    motion figures of the pass (the catalogue's motion names) and its spray spot's speed."""
    spots = {name: pass_spot_speeds(e) for name, e in executions.items()}
    rows = []
    for k, length in enumerate(lengths_mm):
        row: dict[str, Any] = {"pass": k + 1, "planned_length_mm": float(length), "variants": {}}
        for name, e in executions.items():
            if k < len(e.contour_metrics):
                motion = e.contour_metrics[k].as_dict()
                row["variants"][name] = {**{key: motion[key] for key in PASS_MOTION}, **spots[name][k]}
        rows.append(row)
    return rows

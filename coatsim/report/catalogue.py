"""The metrics of ``metrics.json``: every name, its unit and its meaning, in one place.

Each variant of a run holds the groups ``segmentation``, ``motion`` and ``coating`` with
exactly these names (a value is null where it does not apply). The README's metrics table
lists the same names; a test keeps the two equal.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class MetricInfo:
    unit: str
    meaning: str


GROUPS = ("segmentation", "motion", "coating")

METRICS: dict[str, MetricInfo] = {
    # segmentation: the programmed curve against the input curve
    "segmentation.n_segments": MetricInfo("count", "moves on the curve proper: lines + arcs (polysegment) or LMOVEs (polyline)"),
    "segmentation.n_arcs": MetricInfo("count", "circular moves (C1MOVE/C2MOVE pairs before splitting) on the curve"),
    "segmentation.n_lines": MetricInfo("count", "straight moves on the curve"),
    "segmentation.n_corners": MetricInfo("count", "junctions where tangency is intentionally broken (true corners of the input)"),
    "segmentation.max_deviation_mm": MetricInfo("mm", "two-sided Hausdorff distance between the input curve and the programmed curve"),
    "segmentation.tolerance_mm": MetricInfo("mm", "deviation the fitter was asked to guarantee"),
    "segmentation.max_tangent_break_deg": MetricInfo("deg", "largest heading change at a junction that is not a true corner (0 = tangent-continuous)"),
    "segmentation.curve_length_mm": MetricInfo("mm", "length of the programmed curve (without run-in and run-out)"),
    # motion: the simulated arm running the program text
    "motion.cycle_time_s": MetricInfo("s", "duration of the simulated run, first to last logged step"),
    "motion.curve_time_s": MetricInfo("s", "time the tool spends on the curve proper"),
    "motion.excess_time_s": MetricInfo("s", "curve_time_s minus curve length / programmed speed (time lost to slow-downs)"),
    "motion.fraction_at_speed": MetricInfo("1", "fraction of curve time with tool speed >= 90 % of the programmed speed"),
    "motion.n_stops": MetricInfo("count", "times the tool comes (almost) to rest on the curve: speed < 5 % of the programmed speed"),
    "motion.speed_mean_mm_s": MetricInfo("mm/s", "time-averaged tool speed on the curve"),
    "motion.speed_min_mm_s": MetricInfo("mm/s", "lowest tool speed on the curve"),
    "motion.speed_cv": MetricInfo("1", "coefficient of variation (std / mean) of the tool speed on the curve, time-weighted"),
    "motion.max_path_error_mm": MetricInfo("mm", "largest distance from the simulated tool centre point to the programmed path while spraying"),
    # coating: thickness on the region of interest (the coated band, edges excluded)
    "coating.thickness_mean_um": MetricInfo("µm", "area-weighted mean thickness over the region of interest"),
    "coating.thickness_cv": MetricInfo("1", "area-weighted coefficient of variation (std / mean) of thickness over the region of interest"),
    "coating.thickness_min_um": MetricInfo("µm", "thinnest point of the region of interest"),
    "coating.thickness_max_um": MetricInfo("µm", "thickest point of the region of interest"),
    "coating.thick_spot_fraction": MetricInfo("1", "area fraction of the region of interest thicker than 1.2 x the target thickness"),
    "coating.coverage_fraction": MetricInfo("1", "area fraction of the region of interest at least 0.8 x the target thickness"),
    "coating.deposited_volume_mm3": MetricInfo("mm³", "coating volume on the part, sum of vertex area x thickness"),
    "coating.mass_balance_error": MetricInfo("1", "|deposited + oversprayed volume - Q x spray time| / (Q x spray time): conservation check of the deposition"),
}


def names(group: str) -> list[str]:
    """Metric names (without the group) of one group, in catalogue order."""
    return [k.split(".", 1)[1] for k in METRICS if k.startswith(group + ".")]


def markdown_table() -> str:
    """The README table: ``name | unit | meaning``."""
    rows = ["| name | unit | meaning |", "|---|---|---|"]
    rows += [f"| `{key}` | {info.unit} | {info.meaning} |" for key, info in METRICS.items()]
    return "\n".join(rows) + "\n"

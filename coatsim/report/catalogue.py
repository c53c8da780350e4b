"""The metrics of ``metrics.json``: every name, its unit and its meaning, in one place.

Each variant of a run holds the groups ``segmentation``, ``motion`` and ``coating`` with
exactly these names (a value is null where it does not apply). The documentation's metrics
page (docs/reference/metrics.md) is generated from this catalogue by scripts/docs_reference.py.
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
    "segmentation.n_arcs": MetricInfo("count", "arcs on the curve (one C1MOVE/C2MOVE pair each, more when longer than 170 deg)"),
    "segmentation.n_lines": MetricInfo("count", "straight moves on the curve"),
    "segmentation.n_corners": MetricInfo("count", "true corners: junctions where the heading jumps by more than the scenario's corner_deg"),
    "segmentation.max_deviation_mm": MetricInfo("mm", "two-sided Hausdorff distance between the input curve and the programmed curve"),
    "segmentation.tolerance_mm": MetricInfo("mm", "deviation the fitter was asked to guarantee"),
    "segmentation.max_tangent_break_deg": MetricInfo("deg", "largest heading change at the other junctions (0 = tangent-continuous; a polyline turns at every vertex)"),
    "segmentation.curve_length_mm": MetricInfo("mm", "length of the programmed curve (without run-in and run-out)"),
    "segmentation.max_curvature_jump_per_mm": MetricInfo("1/mm", "largest curvature change at a junction that is not a corner (a tool at speed v feels v² x this as a step of its sideways acceleration; 0 for a polyline)"),
    # motion: the simulated arm running the program text (the robot stage's motion metrics)
    "motion.programmed_speed_mm_s": MetricInfo("mm/s", "tool speed the program asks for on the curve (the largest, where the speed is on the trace and each move asks its own; the other motion figures then measure the tool against each move's)"),
    "motion.curve_length_mm": MetricInfo("mm", "length of the curve proper along the programmed path (run-in and run-out excluded)"),
    "motion.cycle_time_s": MetricInfo("s", "time the simulated tool takes over the curve proper"),
    "motion.ideal_time_s": MetricInfo("s", "curve length / programmed speed: the cycle time of a tool that never slows down"),
    "motion.total_time_s": MetricInfo("s", "duration of the whole simulated program: approach, run-in, curve, run-out, depart"),
    "motion.mean_speed_mm_s": MetricInfo("mm/s", "mean tool speed over the curve proper"),
    "motion.min_speed_mm_s": MetricInfo("mm/s", "lowest tool speed over the curve proper"),
    "motion.speed_cv": MetricInfo("1", "coefficient of variation (std / mean) of the tool speed over the curve proper"),
    "motion.fraction_at_speed": MetricInfo("1", "fraction of the curve length travelled at >= 95 % of the programmed speed"),
    "motion.fraction_at_speed_feasible": MetricInfo("1", "the same over the stretches where the programmed speed is feasible for the arm's tool acceleration (speed² x curvature <= limit)"),
    "motion.min_speed_ratio": MetricInfo("1", "lowest tool speed / programmed speed where the curve allows the programmed speed: the curve proper without its true corners and turns tighter than v² / tool acceleration, and without 1.5 x the distance to brake for them or to speed up after them, at the tool acceleration limit (null if the curve allows the speed nowhere)"),
    "motion.stops": MetricInfo("count", "times the tool comes to rest on the curve proper (speed < 5 % of the programmed speed)"),
    "motion.max_path_error_mm": MetricInfo("mm", "largest distance from the simulated tool centre point to the programmed path over the curve proper"),
    "motion.rms_path_error_mm": MetricInfo("mm", "root-mean-square of that distance"),
    "motion.max_joint_speed_ratio": MetricInfo("1", "largest joint speed of the simulated arm over its limit (<= 1 within limits)"),
    "motion.max_joint_accel_ratio": MetricInfo("1", "largest joint acceleration of the simulated arm over its limit (<= 1 within limits)"),
    "motion.max_ik_residual_mm": MetricInfo("mm", "largest inverse-kinematics position residual over the path samples"),
    "motion.max_ik_residual_deg": MetricInfo("deg", "largest inverse-kinematics orientation residual over the path samples"),
    # coating: thickness on the region of interest (the coated band or the part's region, edges excluded)
    "coating.roi_area_mm2": MetricInfo("mm²", "area of the region of interest"),
    "coating.thickness_mean_um": MetricInfo("µm", "area-weighted mean thickness over the region of interest"),
    "coating.thickness_cv": MetricInfo("1", "area-weighted coefficient of variation (std / mean) of thickness over the region of interest"),
    "coating.thickness_min_um": MetricInfo("µm", "thinnest point of the region of interest"),
    "coating.thickness_max_um": MetricInfo("µm", "thickest point of the region of interest"),
    "coating.thick_spot_fraction": MetricInfo("1", "area fraction of the region of interest thicker than 1.2 x the target thickness"),
    "coating.coverage_fraction": MetricInfo("1", "area fraction of the region of interest at least 0.8 x the target thickness"),
    "coating.coated_fraction": MetricInfo("1", "area fraction of the region of interest that received any coating (thickness > 0: in the footprint's reach and not in a shadow)"),
    "coating.target_um": MetricInfo("µm", "target thickness of the specification"),
    "coating.tolerance_pct": MetricInfo("%", "tolerance of the specification: thickness within this per cent of the target"),
    "coating.within_spec_fraction": MetricInfo("1", "area fraction of the region of interest within the specification (abs(thickness - target) <= tolerance)"),
    "coating.low_angle_fraction": MetricInfo("1", "area fraction of the region of interest sprayed at a spray angle below 60 deg (the deposit-weighted mean angle between the spray and the surface; 90 deg = normal)"),
    "coating.standoff_min_mm": MetricInfo("mm", "shortest stand-off at which coating landed on the region of interest (per vertex the deposit-weighted mean distance from the nozzle along the spray axis)"),
    "coating.standoff_max_mm": MetricInfo("mm", "longest stand-off at which coating landed on the region of interest (as above)"),
    "coating.deposited_volume_mm3": MetricInfo("mm³", "coating volume on the part, sum of vertex area x thickness"),
    "coating.deposition_efficiency": MetricInfo("1", "deposited volume / sprayed volume (Q x spray time): the share of the sprayed material that stays on the part"),
    "coating.mass_balance_error": MetricInfo("1", "abs(deposited volume / (Q x spray time) - 1): conservation check, 0 when all the spray lands on the part (otherwise the overspray fraction)"),
}


def names(group: str) -> list[str]:
    """Metric names (without the group) of one group, in catalogue order."""
    return [k.split(".", 1)[1] for k in METRICS if k.startswith(group + ".")]


def markdown_table() -> str:
    """The metrics table of the documentation: ``name | unit | meaning``."""
    rows = ["| name | unit | meaning |", "|---|---|---|"]
    rows += [f"| `{key}` | {info.unit} | {info.meaning} |" for key, info in METRICS.items()]
    return "\n".join(rows) + "\n"

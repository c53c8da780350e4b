"""How the report names and shows each metric of the catalogue: a human name, the unit shown
(a fraction or a ratio of two like quantities, unit "1" in the catalogue, is shown in %), and
whether a ratio to the polysegment's value means something (times, speeds, lengths, thickness
and counts of moves do; angles that are 0 for the polysegment, residuals, errors and
fractions already in % do not).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

from coatsim.report.catalogue import METRICS


@dataclass(frozen=True)
class Shown:
    """A metric as the report shows it."""

    label: str
    ratio: bool = False


SHOWN: dict[str, Shown] = {
    "segmentation.n_segments": Shown("moves on the curve", True),
    "segmentation.n_arcs": Shown("arcs"),
    "segmentation.n_lines": Shown("straight moves"),
    "segmentation.n_corners": Shown("true corners"),
    "segmentation.max_deviation_mm": Shown("largest deviation from the input curve"),
    "segmentation.tolerance_mm": Shown("tolerance"),
    "segmentation.max_tangent_break_deg": Shown("largest tangent break"),
    "segmentation.max_curvature_jump_per_mm": Shown("largest curvature jump at a tangent junction"),
    "segmentation.curve_length_mm": Shown("programmed curve length", True),
    "motion.programmed_speed_mm_s": Shown("programmed speed"),
    "motion.curve_length_mm": Shown("curve length along the path", True),
    "motion.cycle_time_s": Shown("cycle time on the curve", True),
    "motion.ideal_time_s": Shown("ideal cycle time"),
    "motion.total_time_s": Shown("whole program time", True),
    "motion.mean_speed_mm_s": Shown("mean tool speed", True),
    "motion.min_speed_mm_s": Shown("lowest tool speed", True),
    "motion.speed_cv": Shown("speed variation (CV)", True),
    "motion.fraction_at_speed": Shown("length at speed (≥ 95 %)"),
    "motion.fraction_at_speed_feasible": Shown("length at speed where feasible"),
    "motion.min_speed_ratio": Shown("lowest speed where the curve allows it"),
    "motion.stops": Shown("stops on the curve"),
    "motion.max_path_error_mm": Shown("largest path error"),
    "motion.rms_path_error_mm": Shown("RMS path error"),
    "motion.max_joint_speed_ratio": Shown("highest joint speed (of its limit)"),
    "motion.max_joint_accel_ratio": Shown("highest joint acceleration (of its limit)"),
    "motion.max_ik_residual_mm": Shown("largest IK position residual"),
    "motion.max_ik_residual_deg": Shown("largest IK orientation residual"),
    "coating.roi_area_mm2": Shown("region area"),
    "coating.thickness_mean_um": Shown("mean thickness", True),
    "coating.thickness_cv": Shown("thickness variation (CV)", True),
    "coating.thickness_min_um": Shown("thinnest", True),
    "coating.thickness_max_um": Shown("thickest", True),
    "coating.thick_spot_fraction": Shown("area of thick spots (> 1.2 x target)"),
    "coating.coverage_fraction": Shown("area covered (≥ 0.8 x target)"),
    "coating.coated_fraction": Shown("area coated at all"),
    "coating.target_um": Shown("target thickness"),
    "coating.tolerance_pct": Shown("specification tolerance (± % of target)"),
    "coating.within_spec_fraction": Shown("area within the specification"),
    "coating.low_angle_fraction": Shown("area sprayed below 60°"),
    "coating.standoff_min_mm": Shown("shortest stand-off"),
    "coating.standoff_max_mm": Shown("longest stand-off"),
    "coating.deposited_volume_mm3": Shown("deposited volume", True),
    "coating.deposition_efficiency": Shown("deposition efficiency"),
    "coating.mass_balance_error": Shown("mass balance error"),
}


def shown(key: str) -> Shown:
    """How ``key`` is shown (its catalogue name when the table above lacks it)."""
    return SHOWN.get(key, Shown(key.split(".", 1)[1].replace("_", " ")))


def is_percent(key: str) -> bool:
    return METRICS[key].unit == "1"


def unit(key: str) -> str:
    return "%" if is_percent(key) else METRICS[key].unit


def value_text(key: str, value: Any) -> str:
    """A value in the unit shown: percent with up to 4 significant digits, counts plainly."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int) and not is_percent(key):
        return str(value)
    number = 100.0 * float(value) if is_percent(key) else float(value)
    return f"{number:.4g}"


def ratio_text(key: str, value: Any, base: Any) -> Optional[str]:
    """value / base where the metric's ratio means something and both are positive numbers."""
    if not shown(key).ratio:
        return None
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (value, base)):
        return None
    if not (math.isfinite(value) and math.isfinite(base)) or base <= 0 or value < 0:
        return None
    return f"{value / base:.3g}"

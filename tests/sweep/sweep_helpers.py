"""Tiny scenarios and sweep files for the sweep tests (fast mode, two variants, a curve file)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

BASE = """\
name: tiny_sweep
curve: {file: curves/slot.csv}
segmentation: {tolerance_mm: 0.1}
workpiece: {kind: plate, size_mm: [100.0, 70.0]}
gun: {footprint: "gaussian:sigma=5", target_thickness_um: 16.0}
motion: {speed_mm_s: 200.0, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0}
coating: {spacing_mm: 4.0, band_halfwidth_mm: 2.5}
variants: [polysegment, polyline-blend]
fast: {coating_spacing_mm: 4.0, sample_step_mm: 2.0}
gates:
  - {metric: coating.mass_balance_error, op: "<=", threshold: 0.01}
"""

# a 2 x 2 grid and one explicit point far out of the arm's reach
SWEEP = """\
base: scenario/base.yaml
fast: true
grid:
  motion.speed_mm_s: [150, 250]
  segmentation.tolerance_mm: [0.05, 0.2]
points:
  - {workpiece.pose.position_mm: [2000, 0, 200]}
metrics: [motion.cycle_time_s, coating.thickness_cv]
"""


def slot_points() -> np.ndarray:
    """A closed slot: two 40 mm straights joined by semicircles of 10 mm radius, ~0.5 mm apart."""
    t = np.linspace(0.0, 40.0, 81)
    a = np.linspace(-np.pi / 2, np.pi / 2, 64)
    bottom = np.column_stack((t, np.full_like(t, -10.0)))
    right = np.column_stack((40.0 + 10.0 * np.cos(a), 10.0 * np.sin(a)))
    top = np.column_stack((t[::-1], np.full_like(t, 10.0)))
    left = np.column_stack((-10.0 * np.cos(a), -10.0 * np.sin(a)))
    return np.vstack((bottom, right[1:], top[1:], left[1:]))


def write_case(folder: Path, sweep: str = SWEEP, base: str = BASE) -> Path:
    """Write the base scenario (with its curve file) and the sweep file; the sweep file's path."""
    (folder / "scenario" / "curves").mkdir(parents=True, exist_ok=True)
    np.savetxt(folder / "scenario" / "curves" / "slot.csv", slot_points(), delimiter=",", header="x,y", comments="")
    (folder / "scenario" / "base.yaml").write_text(base, encoding="utf-8")
    path = folder / "sweep.yaml"
    path.write_text(sweep, encoding="utf-8")
    return path

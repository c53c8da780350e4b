"""The small scenario several test modules run (fast mode, seconds)."""

# A small scenario that runs in seconds in fast mode (one gate fails on purpose: exit 1).
SMALL = """\
name: small_job
description: two 60 mm passes joined by one semicircular turn-around
curve:
  builtin: raster
  params: {width: 60.0, pitch: 20.0, passes: 2}
segmentation: {tolerance_mm: 0.1}
workpiece: {kind: plate, size_mm: [130.0, 90.0]}
gun: {footprint: "gaussian:sigma=5", target_thickness_um: 16.0}
motion: {speed_mm_s: 200.0, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0}
coating: {spacing_mm: 2.0, band_halfwidth_mm: 2.5}
fast: {coating_spacing_mm: 2.5}
gates:
  - {metric: segmentation.max_deviation_mm, op: "<=", threshold: 0.1}
  - {metric: coating.mass_balance_error, op: "<=", threshold: 0.001}
  - {metric: motion.stops, op: "==", threshold: 0}
  - {metric: coating.thickness_cv, op: "<", threshold: 0.0}
"""

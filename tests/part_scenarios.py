"""Cheap copies of the shipped 3-D scenarios for the tests: the shipped part, pose, region and
gun, with coarser numerics (and, for all but the tube, wider pass spacing) and the deviation
gate, reading the shipped mesh where it is."""

from __future__ import annotations

from pathlib import Path

import yaml

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
PARTS = ("cylinder_3d", "blade_3d", "wear_plate_3d", "scan_patch_3d")


def cheap_scenario(folder: Path, name: str, variants: list[str], spacing_mm: float | None = None,
                   coating_mm: float = 4.0, sample_mm: float = 3.0) -> Path:
    """A copy of scenarios/NAME.yaml in ``folder`` with the given variants and numerics."""
    doc = yaml.safe_load((SCENARIOS / f"{name}.yaml").read_text(encoding="utf-8"))
    doc["part"]["mesh"] = str(((SCENARIOS / name).parent / doc["part"]["mesh"]).resolve())
    doc["variants"] = variants
    if spacing_mm is not None:
        doc.setdefault("paths", {})["spacing_mm"] = spacing_mm
    doc["fast"] = {"coating_spacing_mm": coating_mm, "sample_step_mm": sample_mm}
    # the programs' tolerance holds at any numerics; the other gates are the shipped runs' (slow tests)
    doc["gates"] = [gate for gate in doc.get("gates", []) if gate["metric"] == "segmentation.max_deviation_mm"]
    path = folder / f"{Path(name).name}.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
    return path

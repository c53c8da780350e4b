"""Coating runs whose results must not change (the ROI golden files): a plate, a cylinder and a
mesh file, each with its own path and edge band. ``python tests/spray/roi_cases.py`` rewrites
tests/spray/data/roi_golden.json (the metrics) and roi_golden.npz (the ROI masks and thickness
fields)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import trimesh

from coatsim.spray.coat import coat
from coatsim.spray.surfaces import cylinder, mesh_file, plate
from spray_helpers import H0, V, gun, make_log

GOLDEN = Path(__file__).parent / "data" / "roi_golden.json"
GOLDEN_ARRAYS = GOLDEN.with_suffix(".npz")


def _ellipse_log(a: float, b: float, z: float, n: int = 600):
    phase = np.linspace(0.0, 2 * math.pi, n + 1)
    length = 2 * math.pi * math.sqrt((a * a + b * b) / 2)
    return make_log(phase / (2 * math.pi) * length / V, np.column_stack((a * np.cos(phase), b * np.sin(phase), np.full(n + 1, z))))


def _open_log():
    x = np.linspace(-70.0, 70.0, 300)
    return make_log((x - x[0]) / V, np.column_stack((x, 15 * np.sin(x / 20), np.full(len(x), H0))))


def _mesh(tmp: Path) -> Path:
    """An open box (no bottom): its border is the bottom rim, 20 mm below the sprayed top."""
    box = trimesh.creation.box(extents=(160.0, 110.0, 20.0))
    box.apply_translation((0.0, 0.0, -10.0))
    box.update_faces(box.face_normals[:, 2] > -0.5)
    path = tmp / "tray.stl"
    box.export(path)
    return path


def cases(tmp: Path):
    """(name, coat keyword arguments) of every golden case."""
    yield "plate band", dict(log=_ellipse_log(60, 35, H0), surface=plate(180, 120, 1.5), roi="band", spacing=1.5)
    yield "plate part edge 4", dict(log=_open_log(), surface=plate(170, 90, 2.0), roi="part", edge_band_mm=4.0,
                                    spacing=2.0)
    yield "cylinder band", dict(log=_open_log(), surface=cylinder(60, 160, 2.0, "x"),
                                roi="band", edge_band_mm=9.0, spacing=2.0)
    yield "mesh part", dict(log=_ellipse_log(50, 30, 100.0), surface=mesh_file(_mesh(tmp), 4.0), roi="part",
                            edge_band_mm=12.0, spacing=4.0)


def write_golden(tmp: Path) -> None:
    """Both golden files from this machine's results."""
    metrics, arrays = {}, {}
    for name, kwargs in cases(tmp):
        result = coat(model=gun(), **kwargs)
        metrics[name] = {k: float(v) for k, v in sorted(result.metrics.items())}
        arrays[f"{name}/roi"] = result.roi
        arrays[f"{name}/thickness_um"] = result.thickness_um
    GOLDEN.write_text(json.dumps(metrics, indent=2) + "\n", encoding="utf-8")
    np.savez_compressed(GOLDEN_ARRAYS, **arrays)


if __name__ == "__main__":
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        write_golden(Path(tmp))
    print(f"wrote {GOLDEN} and {GOLDEN_ARRAYS}")

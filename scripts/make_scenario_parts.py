"""Write the meshes of the shipped 3-D scenarios (scenarios/parts/*.stl) from their formulas
(coatsim.geometry.surface.shapes); the same files byte for byte on every run.

    python scripts/make_scenario_parts.py [--check]

``--check`` compares instead of writing and exits 1 when a committed file differs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from coatsim.geometry.surface.shapes import SHAPES, stl_bytes

FOLDER = Path(__file__).resolve().parents[1] / "scenarios" / "parts"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the committed files, write nothing")
    args = parser.parse_args()
    stale = 0
    for name, build in SHAPES.items():
        vertices, faces = build()
        data = stl_bytes(vertices, faces, name)
        path = FOLDER / f"{name}.stl"
        if args.check:
            same = path.is_file() and path.read_bytes() == data
            stale += not same
            print(f"{path.name}: {'ok' if same else 'differs'}")
        else:
            path.write_bytes(data)
            print(f"{path.name}: {len(faces)} triangles, {len(data)} bytes")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())

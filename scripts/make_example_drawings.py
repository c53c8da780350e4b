"""Write the example drawings the shipped scenarios use (scenarios/drawings/), with ezdxf.

    python scripts/make_example_drawings.py

flange.dxf: a 140 x 100 mm plate outline with 12 mm corner radii (one LWPOLYLINE with bulges)
and two holes (CIRCLEs) on layer CUT, a slot drawn as separate LINE and ARC entities (one line
drawn backwards) on layer SLOT, and a title (TEXT) and a dimension on layer NOTES, in mm.
"""

from __future__ import annotations

import math
from pathlib import Path

import ezdxf

OUT = Path(__file__).resolve().parents[1] / "scenarios" / "drawings"


def flange(path: Path) -> None:
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4  # mm
    for name in ("CUT", "SLOT", "NOTES"):
        doc.layers.add(name)
    msp = doc.modelspace()
    w, h, r = 140.0, 100.0, 12.0
    b = math.tan(math.pi / 8)  # bulge of a quarter circle
    outline = [(r, 0, b * 0), (w - r, 0, b), (w, r, 0), (w, h - r, b), (w - r, h, 0), (r, h, b), (0, h - r, 0), (0, r, b)]
    msp.add_lwpolyline([(x, y, 0, 0, bulge) for x, y, bulge in outline], format="xyseb", close=True,
                       dxfattribs={"layer": "CUT"})
    msp.add_circle((35, 50), 12, dxfattribs={"layer": "CUT"})
    msp.add_circle((105, 50), 15, dxfattribs={"layer": "CUT"})
    msp.add_line((60, 20), (80, 20), dxfattribs={"layer": "SLOT"})
    msp.add_arc((80, 26), 6, -90, 90, dxfattribs={"layer": "SLOT"})
    msp.add_line((60, 32), (80, 32), dxfattribs={"layer": "SLOT"})  # drawn left to right: reversed on chaining
    msp.add_arc((60, 26), 6, 90, 270, dxfattribs={"layer": "SLOT"})
    msp.add_text("FLANGE 140x100", dxfattribs={"layer": "NOTES", "height": 4}).set_placement((5, h + 5))
    msp.add_linear_dim(base=(0, -10), p1=(0, 0), p2=(w, 0), dxfattribs={"layer": "NOTES"}).render()
    doc.saveas(path)


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    flange(OUT / "flange.dxf")
    print(f"wrote {OUT / 'flange.dxf'}")

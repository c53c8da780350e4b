"""The report's interactive 3-D view: every variant's thickness on the part and its tool path,
drawn by a small canvas viewer bundled into the HTML (``viewer.js``, package data: no network,
no WebGL, so it works in any browser, with or without a GPU).

The data travel as one JSON block: the part mesh once (the report's coarse copy of the coating
mesh, positions in mm, centred), per variant the vertex colours on the report's colour scale and
the sprayed aim points (one polyline per spray stretch), and the colour bar.
"""

from __future__ import annotations

import base64
import json
from importlib.resources import files
from typing import Any

import numpy as np

from coatsim.report.data import VIEW_FACES, aim_paths
from coatsim.report.html import esc
from coatsim.spray.outputs import colours

PATH_POINTS = 1500  # per variant, at most


def _b64(array: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(array).tobytes()).decode("ascii")


def payload(data: Any) -> dict[str, Any]:
    """The viewer's data (JSON-ready)."""
    coarse = data.coarse
    centre = 0.5 * (coarse.vertices.min(axis=0) + coarse.vertices.max(axis=0))
    vmin, vmax = data.scale_um
    index = "<u2" if len(coarse.vertices) < 65536 else "<u4"
    stops = np.linspace(vmin, vmax, 11)
    return {
        "positions": _b64((coarse.vertices - centre).astype("<f4")),
        "faces": _b64(coarse.faces.astype(index)),
        "index": "u16" if index == "<u2" else "u32",
        "up": [float(v) for v in np.mean(coarse.normals, axis=0)],
        "scale": [vmin, vmax],
        "bar": ["#%02x%02x%02x" % tuple(int(c) for c in rgb) for rgb in colours(stops, vmin, vmax)],
        "variants": [
            {"name": r.name, "colours": _b64(colours(coarse.field(r.coating.thickness_um), vmin, vmax)),
             "paths": [_b64((p - centre).astype("<f4")) for p in aim_paths(r.execution.log, data.standoff_mm,
                                                                           PATH_POINTS)]}
            for r in data.runs
        ],
    }


def script() -> str:
    """The viewer's code (package data)."""
    return files("coatsim.report").joinpath("viewer.js").read_text(encoding="utf-8")


def viewer_html(data: Any) -> str:
    """The viewer's block: canvas, controls, data and code."""
    block = json.dumps(payload(data), separators=(",", ":")).replace("</", "<\\/")
    buttons = "".join(f'<label><input type="radio" name="coatsim-variant" value="{k}"{" checked" if k == 0 else ""}> '
                      f"{esc(r.name)}</label> " for k, r in enumerate(data.runs))
    return (
        '<h3>Interactive view of the coated part</h3>'
        '<div class="viewer" id="coatsim-viewer">'
        f'<div class="controls">{buttons}<label><input type="checkbox" id="coatsim-path" checked> tool path</label> '
        '<button type="button" id="coatsim-reset">reset view</button></div>'
        '<canvas id="coatsim-canvas" width="900" height="560"></canvas>'
        '<p class="muted">Drag to turn, shift-drag to move, wheel to zoom. Colours: thickness on the report\'s scale '
        '(the heat maps\', the PLY and GLB files\'); the line: the sprayed aim points of the chosen variant. The part '
        'is drawn from a coarser copy of the coating mesh (about '
        f'{VIEW_FACES // 1000}k triangles), each vertex the area-weighted mean of those it merges.</p></div>'
        f'<script type="application/json" id="coatsim-viewer-data">{block}</script>'
        f"<script>{script()}</script>"
    )

"""Helpers for the CAD tests: drawings written with ezdxf or as SVG text, and independent
checks of what comes back (computed here from the primitives, not with coatsim's helpers)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Callable

import numpy as np

from coatsim.geometry import Arc, Line, Polysegment

EXACT = 1e-9  # mm: what "exactly" means after degrees, cosines and a DXF round trip


def write_dxf(folder: Path, draw: Callable, version: str = "R2010", name: str = "part.dxf", units: int | None = 4) -> Path:
    """A DXF file drawn by ``draw(msp, doc)``."""
    import ezdxf

    doc = ezdxf.new(version)
    if units is not None:
        doc.header["$INSUNITS"] = units
    draw(doc.modelspace(), doc)
    path = folder / name
    doc.saveas(path)
    return path


def write_svg(folder: Path, body: str, name: str = "part.svg", attrs: str = 'width="200mm" height="100mm" viewBox="0 0 200 100"') -> Path:
    path = folder / name
    path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" '
                    f'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" {attrs}>\n{body}\n</svg>\n',
                    encoding="utf-8")
    return path


def points_along(poly: Polysegment, step: float = 0.05) -> np.ndarray:
    """Dense points on a polysegment, from its primitives directly."""
    out = []
    for s in poly.segments:
        n = max(2, int(math.ceil(s.length / step)) + 1)
        u = np.linspace(0.0, 1.0, n)
        if isinstance(s, Line):
            a, b = np.array(s.start), np.array(s.end)
            out.append(a + u[:, None] * (b - a))
        else:
            c = np.array(s.center)
            a0 = math.atan2(s.start[1] - c[1], s.start[0] - c[0])
            phi = a0 + u * s.sweep
            out.append(c + s.radius * np.column_stack((np.cos(phi), np.sin(phi))))
    return np.vstack(out)


def max_distance(points: np.ndarray, poly: Polysegment, step: float = 0.02) -> float:
    """Two-sided distance between dense samples ``points`` of a curve and dense samples of
    ``poly``: above the true Hausdorff distance by at most about half the larger spacing."""
    from scipy.spatial import cKDTree

    mine = points_along(poly, step)
    edges = np.linalg.norm(np.diff(points, axis=0), axis=1)
    n = np.maximum(1, np.ceil(edges / step).astype(int))  # the curve's samples, densified to ``step``
    dense = np.vstack([points[:-1][k] + np.outer(np.arange(m) / m, points[k + 1] - points[k])
                       for k, m in enumerate(n)] + [points[-1:]])
    d1, _ = cKDTree(mine).query(points)
    d2, _ = cKDTree(dense).query(mine)
    return float(max(d1.max(), d2.max()))


def g1_breaks(poly: Polysegment) -> list[float]:
    """Heading change (rad) at each junction, seam last if closed, from the primitives."""
    def heading(s, at_end: bool) -> float:
        if isinstance(s, Line):
            return math.atan2(s.end[1] - s.start[1], s.end[0] - s.start[0])
        p = s.end if at_end else s.start
        radial = math.atan2(p[1] - s.center[1], p[0] - s.center[0])
        return radial + math.copysign(math.pi / 2, s.sweep)

    segs = list(poly.segments)
    pairs = list(zip(segs[:-1], segs[1:])) + ([(segs[-1], segs[0])] if poly.closed else [])
    return [abs(math.remainder(heading(b, False) - heading(a, True), 2 * math.pi)) for a, b in pairs]


def same_segment(a, b, tol: float = EXACT) -> bool:
    """Whether two primitives are the same line or arc (same direction) within ``tol``."""
    if type(a) is not type(b):
        return False
    close = math.dist(a.start, b.start) <= tol and math.dist(a.end, b.end) <= tol
    if isinstance(a, Arc):
        close = close and math.dist(a.center, b.center) <= tol and abs(a.radius - b.radius) <= tol \
            and abs(a.sweep - b.sweep) <= tol / max(a.radius, 1.0)
    return close

"""A 3-D curve sprayed with the gun along one fixed direction, as one pass of a surface program.

A seam glued from above, a helix sprayed from one side: the curve has no surface to take normals
from, so the user gives the spray axis (from the gun toward the curve, in the curve's frame) and
every point of the pass gets minus that axis as its normal. The surface program then places the
tool centre point the stand-off back along the axis, fits the pass as tangent-continuous 3-D
lines and arcs (the axis never turns, so no pose is added for orientation) and writes it with
the polyline variants, in any language that has arcs in 3-D.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.curves import ClosedMode
from coatsim.geometry.polysegment_json import read_json_document
from coatsim.geometry.space.curve import SpaceCurve, read_any_curve
from coatsim.geometry.space.polysegment_json import FORMAT as SPACE_FORMAT, chain_from_document
from coatsim.geometry.surface.region import unit_vector
from coatsim.path.surfacepaths import SurfacePass, SurfacePaths

SAMPLES_PER_TOLERANCE = 4  # a 3-D polysegment is sampled every tolerance / this for the fit


def _file_tolerance(doc: dict, spec: str) -> float:
    """The tolerance_mm a polysegment document gives (a finite number > 0), else an InputError."""
    given = doc.get("tolerance_mm")
    if isinstance(given, bool) or not isinstance(given, (int, float)) or not (math.isfinite(given) and given > 0):
        raise InputError(f"{spec}: tolerance_mm: the file gives no number > 0 ({given!r}); give the tolerance",
                         parameters=("tolerance_mm",))
    return float(given)


def fixed_axis_paths(spec: str, spray_axis: tuple[float, float, float], tolerance_mm: float | None,
                     closed: ClosedMode = "auto") -> tuple[SurfacePaths, float]:
    """The 3-D curve file ``spec`` (x,y,z columns; or a polysegment/2 file, sampled) as one
    pass sprayed along ``spray_axis``, and the tolerance to fit it within (``tolerance_mm``; a
    polysegment's own when None). A planar x,y curve is refused: it is sprayed along -Z of its
    frame, without a spray axis."""
    axis = unit_vector(spray_axis, "spray_axis", "spray_axis")
    doc = read_json_document(Path(spec)) if Path(spec).suffix.lower() == ".json" else None
    if spec.startswith("builtin:") or (doc is not None and not (isinstance(doc, dict) and doc.get("format") == SPACE_FORMAT)):
        raise InputError(f"{spec}: a planar curve; spray_axis is for 3-D curves (x,y,z columns or a 3-D "
                         "polysegment), a planar one is sprayed along -Z of its frame", parameters=("spray_axis",))
    if doc is not None:
        chain = chain_from_document(doc, spec)
        tolerance = _file_tolerance(doc, spec) if tolerance_mm is None else tolerance_mm
        points, _ = chain.sample(tolerance / SAMPLES_PER_TOLERANCE)
        is_closed = chain.closed
    else:
        if tolerance_mm is None:
            raise InputError(f"{spec}: tolerance_mm is needed to fit a curve", parameters=("tolerance_mm",))
        curve = read_any_curve(spec, closed)
        if not isinstance(curve, SpaceCurve):
            raise InputError(f"{spec}: a planar x,y curve; spray_axis is for 3-D curves (x,y,z columns), a planar "
                             "one is sprayed along -Z of its frame", parameters=("spray_axis",))
        tolerance, points, is_closed = tolerance_mm, curve.points, curve.closed
    normals = np.tile(-axis, (len(points), 1))
    empty = np.zeros((0, 3))
    return SurfacePaths(str(spec), (SurfacePass(points, normals, is_closed, empty, empty),), None, None, None), tolerance

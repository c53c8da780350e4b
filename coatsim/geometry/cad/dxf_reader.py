"""DXF drawings (ezdxf): modelspace geometry as pieces in mm.

Read: LINE, ARC, CIRCLE, ELLIPSE, LWPOLYLINE and 2-D/3-D POLYLINE (bulges become arcs),
SPLINE, and INSERT/MINSERT with nested blocks and their transforms. Entities must lie in a
plane parallel to XY (their z is dropped); others are left out with a note, except that a
drawing lying wholly in one tilted plane (a UCS) is read in that plane's own coordinates. Annotation,
fills, views and meshes (DIMENSION, TEXT, HATCH, VIEWPORT, MESH, ...) are ignored with a
note. Layers: by default every layer that is neither off nor frozen; ``--layer`` names them
(also hidden ones). Entities on layer 0 inside a block take the layer of the INSERT, as CAD
programs draw them. ``$INSUNITS`` converts to mm (unitless drawings are taken as mm).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Iterable, Optional, Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.geometry.cad.drawing import Drawing, check_layers, count_note
from coatsim.geometry.cad.dxf_file import check_structure, entity_label, open_dxf
from coatsim.geometry.cad.pieces import FreePiece, Piece, arc_piece, free_or_native, heading_of, line_piece

# $INSUNITS code -> (name, mm per unit); exact values, not ezdxf's rounded ones
UNITS_MM = {
    1: ("in", 25.4), 2: ("ft", 304.8), 3: ("mi", 1_609_344.0), 4: ("mm", 1.0), 5: ("cm", 10.0), 6: ("m", 1000.0),
    7: ("km", 1e6), 8: ("microinch", 25.4e-6), 9: ("mil", 0.0254), 10: ("yd", 914.4), 11: ("angstrom", 1e-7),
    12: ("nm", 1e-6), 13: ("micron", 1e-3), 14: ("dm", 100.0), 15: ("dam", 1e4), 16: ("hm", 1e5),
    21: ("US survey ft", 1200.0 / 3937.0 * 1000.0), 22: ("US survey in", 100.0 / 3937.0 * 1000.0),
    23: ("US survey yd", 3600.0 / 3937.0 * 1000.0), 24: ("US survey mi", 6336.0 / 3937.0 * 1e6),
}
IGNORED = {
    "annotation": ("TEXT", "MTEXT", "ATTRIB", "ATTDEF", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION",
                   "LEADER", "MLEADER", "MULTILEADER", "TOLERANCE", "ACAD_TABLE", "TABLE", "SHAPE"),
    "fill": ("HATCH", "MPOLYGON", "SOLID", "TRACE", "WIPEOUT"),
    "view": ("VIEWPORT",),
    "mesh or 3-D": ("MESH", "3DFACE", "3DSOLID", "BODY", "REGION", "SURFACE", "PLANESURFACE", "EXTRUDEDSURFACE",
                    "LOFTEDSURFACE", "REVOLVEDSURFACE", "SWEPTSURFACE", "POLYFACE", "POLYMESH"),
    "not a contour": ("POINT", "XLINE", "RAY"),
    "embedded image": ("IMAGE", "OLE2FRAME", "PDFUNDERLAY", "DWFUNDERLAY", "DGNUNDERLAY"),
}
_REASON = {kind: reason for reason, kinds in IGNORED.items() for kind in kinds}
GEOMETRY = ("LINE", "ARC", "CIRCLE", "ELLIPSE", "LWPOLYLINE", "POLYLINE", "SPLINE")
_FLAT = 1e-9  # relative: tilts below this are round-off
_FLAT_Z_MM = 1e-3  # z differences below this (or _FLAT of the coordinates) are round-off, not a 3-D drawing
_FLAT_BULGE = 1e-7  # a polyline's arc sagging less than this share of its chord is a line
_SPLINE_FIT, _SPLINE_FRAME = 4, 16  # POLYLINE flag: spline-fit vertices added; VERTEX flag: frame control point
_QUADRATIC_SMOOTH = 5  # POLYLINE smooth type: quadratic B-spline (6: cubic)


class _Plane:
    """The drawing plane: WCS points to 2-D plane coordinates (its OCS), and the sense of an
    entity's extrusion relative to its normal. The XY plane unless the drawing lies wholly in
    one tilted plane."""

    def __init__(self, normal=(0.0, 0.0, 1.0)) -> None:
        from ezdxf.math import OCS, Vec3

        self.normal = Vec3(normal).normalize()
        self.ocs = None if self.normal.isclose((0.0, 0.0, 1.0), abs_tol=_FLAT) else OCS(self.normal)

    def xyz(self, p) -> tuple[np.ndarray, float]:
        """Plane coordinates (2,) of a WCS point (or direction), and its height above the plane."""
        q = p if self.ocs is None else self.ocs.from_wcs(p)
        return np.array([float(q[0]), float(q[1])]), float(q[2])

    def xy(self, p) -> np.ndarray:
        return self.xyz(p)[0]

    def flat(self, points: Iterable) -> bool:
        """Whether WCS points lie in one plane parallel to the drawing plane."""
        pts = list(points)
        zs = [self.xyz(p)[1] for p in pts]
        scale = max((abs(float(c)) for p in pts for c in p), default=1.0)
        return not zs or max(zs) - min(zs) <= max(_FLAT * scale, _FLAT_Z_MM)

    def sense(self, entity) -> Optional[float]:
        """+1 / -1 for an extrusion along / against the normal; None for a tilted one."""
        n = entity.dxf.get("extrusion", (0.0, 0.0, 1.0))
        dot = float(np.dot(n, self.normal)) / max(float(np.linalg.norm(n)), 1e-300)
        if abs(abs(dot) - 1.0) > _FLAT:
            return None
        return 1.0 if dot > 0 else -1.0


@dataclass
class _Walk:
    """What the walk through the modelspace collects."""

    doc: object
    wanted: Optional[tuple[str, ...]]
    flatten: float
    plane: _Plane = field(default_factory=_Plane)
    pieces: list[Piece] = field(default_factory=list)
    ignored: Counter = field(default_factory=Counter)
    hidden: Counter = field(default_factory=Counter)
    other_layers: Counter = field(default_factory=Counter)
    tilted: list[str] = field(default_factory=list)
    tilts: Counter = field(default_factory=Counter)
    invalid: list[str] = field(default_factory=list)  # entities left out, each with why
    external: list[str] = field(default_factory=list)  # inserts of external references (XREF), each named

    def layer_state(self, name: str) -> tuple[bool, bool]:
        """(off, frozen) of a layer; a layer missing from the table is visible."""
        layer = self.doc.layers.get(name) if self.doc.layers.has_entry(name) else None
        if layer is None:
            return False, False
        return bool(layer.is_off()), bool(layer.is_frozen())

    def tilt(self, entity, label: str) -> None:
        """Note an entity not parallel to the drawing plane (and its extrusion, if it has one)."""
        self.tilted.append(label)
        if entity.dxf.is_supported("extrusion"):
            self.tilts[tuple(round(float(c), 12) for c in entity.dxf.get("extrusion", (0.0, 0.0, 1.0)))] += 1


def _span(start_deg: float, end_deg: float) -> float:
    """Counter-clockwise span (rad) from one angle to the other, a full turn when equal."""
    span = (end_deg - start_deg) % 360.0
    return math.radians(span if span > 1e-12 else 360.0)


def _circle_or_arc(entity, label: str, walk: _Walk) -> None:
    sense = walk.plane.sense(entity)
    radius = float(entity.dxf.radius)
    if sense is None:
        walk.tilt(entity, label)
        return
    if not radius > 0:
        return  # a zero-size circle has no length; dropped like any zero-length piece
    ocs = entity.ocs()
    center = ocs.to_wcs(entity.dxf.center)
    if entity.dxftype() == "CIRCLE":
        start = end = ocs.to_wcs(entity.dxf.center + (radius, 0.0, 0.0))
        sweep = 2 * math.pi
    else:
        start, end = entity.start_point, entity.end_point
        sweep = _span(entity.dxf.start_angle, entity.dxf.end_angle)
    xy = walk.plane.xy
    walk.pieces.append(arc_piece(xy(center), radius, xy(start), xy(end), sense * sweep, label))


def _ellipse(entity, label: str, walk: _Walk) -> None:
    sense = walk.plane.sense(entity)
    if sense is None:
        walk.tilt(entity, label)
        return
    tool = entity.construction_tool()
    span = (tool.end_param - tool.start_param) % (2 * math.pi) or 2 * math.pi
    if span == 2 * math.pi:  # equal parameters are a whole ellipse (ezdxf flattens it to nothing)
        tool.start_param, tool.end_param = 0.0, span
    xy = walk.plane.xy
    if abs(tool.ratio - 1.0) <= 1e-12:  # a circle drawn as an ellipse: a native arc
        walk.pieces.append(arc_piece(xy(tool.center), tool.major_axis.magnitude, xy(tool.start_point),
                                     xy(tool.end_point), sense * span, label))
        return
    pts = np.array([xy(v) for v in tool.flattening(walk.flatten, segments=16)])
    t0, t1 = tool.tangents([tool.start_param, tool.start_param + span])
    walk.pieces.append(FreePiece(pts, heading_of(xy(t0)), heading_of(xy(t1)), label))


def _spline(entity, label: str, walk: _Walk) -> None:
    """A spline, split where it is only C0 (a knot repeated degree times), so its kinks are
    joins with exact tangents on either side."""
    if not walk.plane.flat(list(entity.control_points) or list(entity.fit_points)):
        walk.tilt(entity, label)
        return
    try:
        curve = _closed_fit_spline(entity) or entity.construction_tool()
        knots = np.asarray(curve.knots(), dtype=float)
        degree = int(curve.degree)
    except MemoryError:
        raise
    except Exception as exc:  # ezdxf raises assorted errors on malformed splines
        walk.invalid.append(f"{label}: not a valid spline ({exc})")
        return
    lo, hi = float(knots[degree]), float(knots[-degree - 1])
    values, counts = np.unique(knots, return_counts=True)
    breaks = [float(v) for v, c in zip(values, counts) if c >= degree and lo < v < hi]
    spans = list(zip([lo] + breaks, breaks + [hi]))
    xy = walk.plane.xy
    for k, (a, b) in enumerate(spans):
        def at(t: np.ndarray, a: float = a, b: float = b) -> np.ndarray:
            return np.array([xy(v) for v in curve.points(a + np.asarray(t, float) * (b - a))])

        sub = label if len(spans) == 1 else f"{label} span {k + 1}"
        walk.pieces.append(free_or_native(at, walk.flatten, sub, path=label))


def _closed_fit_spline(entity):
    """The curve of a closed SPLINE given by fit points only, smooth across its seam (CAD
    programs draw it periodic; ezdxf's interpolation would leave a corner there): closed
    onto its first fit point, with the seam's tangent from the fit points either side of it.
    None for any other spline."""
    if not entity.closed or entity.control_point_count() or entity.fit_point_count() < 3:
        return None
    if entity.dxf.hasattr("start_tangent") and entity.dxf.hasattr("end_tangent"):
        return None
    from ezdxf.math import Vec3, fit_points_to_cad_cv

    pts = [Vec3(p) for p in entity.fit_points]
    if not pts[0].isclose(pts[-1], abs_tol=1e-12):
        pts.append(pts[0])
    seam = (pts[1] - pts[-2]).normalize()
    return fit_points_to_cad_cv(pts, tangents=[seam, seam])


def _line(entity, label: str, walk: _Walk) -> None:
    a, b = entity.dxf.start, entity.dxf.end
    if not walk.plane.flat((a, b)):
        walk.tilt(entity, label)
        return
    walk.pieces.append(line_piece(walk.plane.xy(a), walk.plane.xy(b), label))


def _polyline(entity, label: str, walk: _Walk) -> None:
    if entity.dxftype() == "POLYLINE" and not (entity.is_2d_polyline or entity.is_3d_polyline):
        walk.ignored["POLYFACE" if entity.is_poly_face_mesh else "POLYMESH"] += 1
        return
    if entity.dxftype() == "POLYLINE" and entity.is_3d_polyline:
        if not walk.plane.flat([v.dxf.location for v in entity.vertices]):
            walk.tilt(entity, label)
            return
    elif walk.plane.sense(entity) is None:
        walk.tilt(entity, label)
        return
    if _spline_frame(entity, label, walk):
        return
    _drawn(entity)
    first = len(walk.pieces)
    for k, part in enumerate(entity.virtual_entities()):
        sub = f"{label} segment {k + 1}"
        if part.dxftype() == "LINE":
            walk.pieces.append(line_piece(walk.plane.xy(part.dxf.start), walk.plane.xy(part.dxf.end), sub))
        elif part.dxftype() == "ARC":
            _circle_or_arc(part, sub, walk)
    walk.pieces[first:] = [replace(p, path=label) for p in walk.pieces[first:]]


def _spline_frame(entity, label: str, walk: _Walk) -> bool:
    """Read an R12 spline-fit POLYLINE (PEDIT Spline: flag 4) as the B-spline its frame's control
    vertices (flag 16) define, quadratic or cubic as its smooth type says, closed with the
    polyline; its fit vertices are only that curve cut into lines. False for any other polyline."""
    if entity.dxftype() != "POLYLINE" or not entity.dxf.get("flags", 0) & _SPLINE_FIT:
        return False
    frame = [v.dxf.location for v in entity.vertices if v.dxf.get("flags", 0) & _SPLINE_FRAME]
    degree = 2 if entity.dxf.get("smooth_type", 0) == _QUADRATIC_SMOOTH else 3
    if len(frame) <= degree:
        return False
    from ezdxf.math import BSpline, closed_uniform_bspline

    curve = closed_uniform_bspline(frame, order=degree + 1) if entity.is_closed else BSpline(frame, order=degree + 1)
    lo, hi = (float(curve.knots()[degree]), float(curve.knots()[-degree - 1])) if entity.is_closed else (0.0, curve.max_t)

    def at(t: np.ndarray) -> np.ndarray:
        return np.array([walk.plane.xy(v) for v in curve.points(lo + np.asarray(t, float) * (hi - lo))])

    walk.pieces.append(free_or_native(at, walk.flatten, label))
    return True


def _drawn(entity) -> None:
    """A polyline (in the document read, not the file) reduced to the path it draws: a
    spline-fit POLYLINE without a frame to read its curve from keeps its fit vertices (ezdxf
    would draw the frame's control vertices too); bulges are set to zero where they sag from
    their chords by less than ``_FLAT_BULGE`` of it (sagitta / chord = |bulge| / 2): rounding that
    CAD left on straight edges (a bulge of 1e-12 is an arc 5e13 mm from the origin)."""
    limit = 2.0 * _FLAT_BULGE
    if entity.dxftype() == "POLYLINE" and entity.dxf.get("flags", 0) & _SPLINE_FIT:
        entity.vertices[:] = [v for v in entity.vertices if not v.dxf.get("flags", 0) & _SPLINE_FRAME]
    if entity.dxftype() == "LWPOLYLINE":
        points = entity.get_points("xyseb")
        if any(0.0 < abs(p[4]) <= limit for p in points):
            entity.set_points([(*p[:4], 0.0 if abs(p[4]) <= limit else p[4]) for p in points], format="xyseb")
        return
    for vertex in entity.vertices:
        if 0.0 < abs(vertex.dxf.get("bulge", 0.0)) <= limit:
            vertex.dxf.bulge = 0.0


_READERS = {"LINE": _line, "ARC": _circle_or_arc, "CIRCLE": _circle_or_arc, "ELLIPSE": _ellipse,
            "LWPOLYLINE": _polyline, "POLYLINE": _polyline, "SPLINE": _spline}


def _walk(entities: Iterable, walk: _Walk, parent_layer: Optional[str], where: str, depth: int) -> None:
    for entity in entities:
        kind = entity.dxftype()
        layer = entity.dxf.get("layer", "0")
        if parent_layer is not None and layer == "0":
            layer = parent_layer  # block entities on layer 0 take the INSERT's layer
        off, frozen = walk.layer_state(layer)
        if walk.wanted is not None and layer.lower() not in walk.wanted and kind != "INSERT":
            if kind in _READERS:
                walk.other_layers[layer] += 1
            continue
        if kind != "INSERT" and (walk.wanted is None and (off or frozen) or entity.dxf.get("invisible", 0)):
            if kind in _READERS:
                walk.hidden[layer] += 1
            continue
        label = entity_label(entity, where)
        if kind == "INSERT":
            if walk.wanted is None and frozen:
                walk.hidden[layer] += 1
                continue
            _insert(entity, walk, layer, label, depth)
        elif kind in _READERS:
            try:
                _READERS[kind](entity, label, walk)
            except (ArithmeticError, ValueError, IndexError) as exc:  # ezdxf on NaN, inf or degenerate values
                raise InputError(f"{label}: cannot read its geometry ({type(exc).__name__}: {str(exc)[:100]}); "
                                 "check its numbers (NaN, inf, a zero ratio or radius)") from None
        else:
            walk.ignored[kind] += 1


def _insert(entity, walk: _Walk, layer: str, label: str, depth: int) -> None:
    name = entity.dxf.get("name", "?")
    if entity.block() is None:
        raise InputError(f"{label}: inserts block {name!r}, which the drawing does not define")
    if entity.block().block.is_xref:
        walk.external.append(f"{label}: {name!r} from {entity.block().block.dxf.get('xref_path', '?')!r}")
        return
    try:
        inserts = list(entity.multi_insert()) if entity.mcount > 1 else [entity]
        for one in inserts:
            _walk(list(one.virtual_entities()), walk, layer, f"in block {name!r} of {label}", depth + 1)
    except (InputError, MemoryError):
        raise
    except Exception as exc:  # ezdxf: e.g. a transform it cannot apply
        raise InputError(f"{label}: cannot expand block {name!r} ({exc})") from None


def read_dxf(path: Path, layers: Sequence[str] | None, flatten_mm: float) -> Drawing:
    """The geometry of a DXF file's modelspace, in mm; see the module docstring."""
    doc = open_dxf(path)
    msp = doc.modelspace()
    entities = list(msp)
    check_structure(doc, entities, str(path))
    paper = _paperspace_geometry(doc)
    if not entities:
        raise InputError(f"{path}: the modelspace is empty (no entities)"
                         + (f"; {_paper_note(paper)}" if paper else ""))
    known = [layer.dxf.name for layer in doc.layers]
    used = sorted({e.dxf.get("layer", "0") for e in entities} - set(known))
    walk = _Walk(doc, check_layers(str(path), layers, known + used), flatten_mm)
    code = int(doc.header.get("$INSUNITS", 0) or 0)
    if code and code not in UNITS_MM:
        raise InputError(f"{path}: $INSUNITS = {code} is not a length unit coatsim converts to mm")
    unit, factor = UNITS_MM.get(code, ("unitless", 1.0))
    _walk(entities, walk, None, "", 0)
    notes = []
    if not walk.pieces and len(walk.tilts) == 1:
        # everything lies in one tilted plane (a UCS): read the drawing in that plane
        normal = next(iter(walk.tilts))
        walk = _Walk(doc, walk.wanted, flatten_mm, _Plane(normal))
        _walk(entities, walk, None, "", 0)
        notes.append(f"the drawing lies in a plane tilted from XY (normal {', '.join(f'{c:.6g}' for c in normal)}): "
                     "read in that plane's own coordinates (its OCS)")
    if paper:
        notes.append(_paper_note(paper))
    if code == 0:
        notes.append("no $INSUNITS in the header: coordinates taken as mm")
    if walk.ignored:
        notes.append(_ignored_note("ignored", walk.ignored))
    if walk.invalid:
        notes.append(f"left out {len(walk.invalid)} entities that draw nothing readable (first: {walk.invalid[0]})")
    if walk.external:
        notes.append(f"left out {len(walk.external)} inserts of external references (XREF), whose geometry is in "
                     f"another file (first: {walk.external[0]}); bind them into the drawing to read them")
    if walk.tilted:
        notes.append(f"ignored {len(walk.tilted)} entities not parallel to the drawing plane (first: {walk.tilted[0]})")
    if sum(walk.hidden.values()):
        notes.append(f"left out {sum(walk.hidden.values())} entities on layers that are off or frozen "
                     f"({', '.join(sorted(walk.hidden))}; name those layers (--layer) to read them)")
    if not walk.pieces:
        raise InputError(f"{path}: {_nothing(walk, layers)}")
    pieces = tuple(p.transformed(np.eye(2), np.zeros(2), factor) for p in walk.pieces) if factor != 1.0 else tuple(walk.pieces)
    units = "mm" if code in (0, 4) else f"{unit} (x {factor:g} to mm)"
    return Drawing(str(path), pieces, units, tuple(notes))


def _paperspace_geometry(doc) -> Counter:
    """Geometry entities (and block references) per paperspace layout, which coatsim does not read."""
    found: Counter = Counter()
    for name in doc.layout_names():
        layout = doc.layouts.get(name)
        if layout.is_modelspace:
            continue
        found[name] += sum(1 for e in layout if e.dxftype() in GEOMETRY or e.dxftype() == "INSERT")
    return +found


def _paper_note(paper: Counter) -> str:
    return (f"left out {sum(paper.values())} entities in paperspace layouts "
            f"({', '.join(sorted(paper))}): coatsim reads the modelspace only")


def _nothing(walk: _Walk, layers: Sequence[str] | None) -> str:
    """Why a drawing yields no geometry, for the one-line error."""
    read = ", ".join(GEOMETRY)
    if layers and walk.other_layers:
        return (f"no geometry on layer(s) {', '.join(repr(x) for x in layers)} (geometry is on "
                f"{', '.join(repr(x) for x in sorted(walk.other_layers))})")
    if sum(walk.hidden.values()):
        return f"no visible geometry: it is on layers that are off or frozen ({', '.join(sorted(walk.hidden))}); name those layers (--layer) to read them"
    if walk.tilted:
        return (f"no geometry in the XY plane or in one common plane ({len(walk.tilted)} entities are tilted, "
                f"first: {walk.tilted[0]})")
    if walk.ignored:
        return f"{_ignored_note('no geometry to spray: only', walk.ignored)}; coatsim reads {read}"
    if walk.external:
        return (f"no geometry to spray: only inserts of external references (XREF), whose geometry is in another "
                f"file (first: {walk.external[0]}); bind them into the drawing to read them")
    if walk.invalid:
        return f"no geometry to spray: {walk.invalid[0]}" + (f" (and {len(walk.invalid) - 1} more)" if len(walk.invalid) > 1 else "")
    return f"no geometry to spray (coatsim reads {read})"


def _ignored_note(what: str, ignored: Counter) -> str:
    """"ignored 1 MTEXT, 2 TEXT (annotation); 1 HATCH (fill)" by reason."""
    by_reason: dict[str, Counter] = {}
    for kind, n in ignored.items():
        by_reason.setdefault(_REASON.get(kind, "not read"), Counter())[kind] = n
    parts = [count_note("", counts, reason).strip() for reason, counts in sorted(by_reason.items())]
    return f"{what} {'; '.join(parts)}"

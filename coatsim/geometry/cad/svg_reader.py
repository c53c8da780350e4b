"""SVG drawings (svgelements): shapes as pieces in mm with y up.

svgelements parses the whole of SVG 1.1 geometry: ``path`` (M L H V C S Q T A Z, relative
and absolute), ``rect`` (rounded), ``circle``, ``ellipse``, ``line``, ``polyline``,
``polygon``, ``use``, nested ``transform``s, ``viewBox``, ``width``/``height`` with units and
CSS styles, and keeps circular arcs as arcs through similarity transforms. Its user unit is
the CSS pixel, 96 per inch. The mapping to the workpiece plane is

    (x_mm, y_mm) = (25.4 / 96) * (x, -y)

of the user coordinates after every transform (viewBox included): millimetres with y up,
origin at the SVG origin (its top-left corner), so a drawing lies below the x axis.
Circular arcs (including circles and rounded corners) and lines are native; Béziers and
elliptical arcs are free-form. Inkscape layers (groups with ``inkscape:groupmode="layer"``)
are selected with ``--layer LABEL``; hidden elements (``display:none``, ``visibility:hidden``)
are left out. Text and images are ignored with a note.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path
from typing import Iterator, Optional, Sequence

import numpy as np

from coatsim.core.errors import InputError, shown
from coatsim.core.fileio import read_input
from coatsim.geometry.cad.drawing import Drawing, check_layers, count_note
from coatsim.geometry.cad.pieces import Piece, arc_piece, free_or_native, line_piece
from coatsim.geometry.cad.svg_prepare import SVG_NS, prepared
from coatsim.geometry.cad.svg_scan import check_svg_structure

MM_PER_USER_UNIT = 25.4 / 96.0
# svgelements converts mm and cm with 0.0393701 inch per mm (rounded); its px of a document
# sized in mm or cm are converted back with the same constant, so the user's mm stay exact.
_SVGELEMENTS_INCH_PER_MM = 0.0393701
_INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"
_XLINK = "{http://www.w3.org/1999/xlink}"
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_ROUND = 1e-9  # relative: differences below this are round-off
_ARITY = {"m": 2, "l": 2, "t": 2, "h": 1, "v": 1, "c": 6, "s": 4, "q": 4, "a": 7, "z": 0}


def path_data_error(d: str) -> Optional[str]:
    """Why SVG path data is malformed (svgelements silently drops what it cannot read), or
    None when it is well formed."""
    i, n = 0, len(d)

    def skip(i: int) -> int:
        while i < n and (d[i].isspace() or d[i] == ","):
            i += 1
        return i

    i = skip(i)
    if i == n:
        return None
    if d[i] not in "Mm":
        return f"path data must start with M, found {d[i]!r}"
    while True:
        i = skip(i)
        if i == n:
            return None
        cmd = d[i]
        if cmd.lower() not in _ARITY:
            return f"unknown path command {cmd!r} at character {i + 1}"
        i += 1
        arity = _ARITY[cmd.lower()]
        if arity == 0:
            continue
        groups = 0
        while True:
            j = skip(i)
            if j == n or d[j].isalpha() and d[j] not in "eE":
                break
            for k in range(arity):
                j = skip(j)
                if cmd.lower() == "a" and k in (3, 4):
                    if j < n and d[j] in "01":
                        j += 1
                        continue
                    return f"arc flag expected (0 or 1) at character {j + 1} in {cmd!r}"
                m = _NUMBER.match(d, j)
                if m is None:
                    return f"{cmd!r} needs {arity} numbers per step, found {'the end' if j == n else repr(d[j])} at character {j + 1}"
                j = m.end()
            i, groups = j, groups + 1
        if groups == 0:
            return f"{cmd!r} at character {i} has no coordinates"


def _parse(path: Path, data: bytes):
    import io

    import svgelements as se

    check_svg_structure(data, str(path))
    try:
        data = prepared(data)
        svg = se.SVG.parse(io.BytesIO(data), ppi=96.0, reify=False)
    except ET.ParseError as exc:
        line, col = exc.position
        raise InputError(f"{path}:{line}:{col}: not well-formed SVG ({str(exc).split(':')[0]})") from None
    except (ValueError, TypeError, IndexError, KeyError, AttributeError, ArithmeticError) as exc:
        raise InputError(f"{path}: not a readable SVG ({type(exc).__name__}: {str(exc)[:100]}; a number that "
                         "overflows or vanishes, or an attribute svgelements cannot read)") from None
    if not isinstance(svg, se.SVG):
        raise InputError(f"{path}: not an SVG (the root element is not <svg>)")
    return svg


def unresolved_uses(root: ET.Element) -> list[str]:
    """The references of ``<use>`` elements that name nothing in this document (another file,
    or an id it does not have): svgelements draws nothing for them."""
    ids = {el.get("id") for el in root.iter() if el.get("id")}
    hrefs = ((el.get("href") or el.get(f"{_XLINK}href") or "").strip() for el in root.iter(f"{SVG_NS}use"))
    return [h for h in hrefs if not (h.startswith("#") and h[1:] in ids)]


def hidden_by_display(root: ET.Element) -> tuple[list[str], int]:
    """Labels of Inkscape layers hidden with ``display:none``, and how many other elements
    outside ``<defs>`` are (svgelements drops them whole, with what they contain)."""
    unused = {id(el) for defs in root.iter(f"{SVG_NS}defs") for el in defs.iter()}
    layers, others = [], 0
    for el in root.iter():
        style = re.sub(r"\s+", "", el.get("style") or "").lower()
        if id(el) in unused or not ("display:none" in style or (el.get("display") or "").strip().lower() == "none"):
            continue
        if el.get(f"{_INKSCAPE}groupmode") == "layer":
            layers.append(str(el.get(f"{_INKSCAPE}label") or el.get("id") or "layer"))
        else:
            others += 1
    return layers, others


def _walk(node, labels: tuple[str, ...]) -> Iterator[tuple[object, tuple[str, ...]]]:
    """Every non-group element with the labels of the layers it lies in (outermost first)."""
    import svgelements as se

    for el in node:
        if isinstance(el, se.Use):  # a <use>: the referenced shapes, placed
            yield from _walk(el, labels)
        elif isinstance(el, se.Group):
            own = el.values.get("attributes", {})
            inner = labels
            if own.get(f"{_INKSCAPE}groupmode") == "layer":
                inner = labels + (str(own.get(f"{_INKSCAPE}label") or own.get("id") or "layer"),)
            yield from _walk(el, inner)
        else:
            yield el, labels


def _tag(el) -> str:
    return str(el.values.get("tag", type(el).__name__.lower()))


def _name(el, index: int) -> str:
    tag = _tag(el)
    return f"<{tag} id={el.id!r}>" if el.id else f"<{tag}> #{index} (no id)"


def mm_per_px(svg) -> float:
    """Millimetres per svgelements pixel for this document (see _SVGELEMENTS_INCH_PER_MM)."""
    return 1.0 / (96.0 * _SVGELEMENTS_INCH_PER_MM) if re.search(r"\d\s*(mm|cm)\b", _root_size(svg)) else MM_PER_USER_UNIT


def _root_size(svg) -> str:
    """The document's width and height as written, lower case ("200mm 100mm")."""
    own = svg.values.get("attributes", {})
    return f"{own.get('width', '')} {own.get('height', '')}".lower()


def _pixel_note(svg, data: bytes) -> Optional[str]:
    """What the user is told where the document gives no size in a physical unit (px, or none):
    it is read at CSS's 96 px per inch, which the tools that wrote it may not have meant."""
    if re.search(r"\d\s*(mm|cm|in|pt|pc)\b", _root_size(svg)):
        return None
    head = data[:4096]
    version = re.search(rb'inkscape:version="0\.(\d+)', head)
    if b"Adobe Illustrator" in head:
        tool = "; Adobe Illustrator wrote it, whose px are 72 per inch: its drawing is 4/3 as large"
    elif version is not None and int(version.group(1)) <= 91:
        tool = "; Inkscape 0.91 or older wrote it, whose px are 90 per inch: its drawing is 16/15 as large"
    else:
        tool = ""
    return (f"the drawing's size is in px or not given: read at 96 px per inch (CSS), {MM_PER_USER_UNIT:.4g} mm a "
            f"unit{tool}; save it with its size in mm to be sure")


def _circular(arc) -> bool:
    """A circular arc (svgelements compares the radii exactly; this allows round-off)."""
    rx, ry = float(arc.rx), float(arc.ry)
    return abs(rx - ry) <= 1e-9 * max(rx, ry) and rx > 0 and abs(float(arc.sweep)) > 0


def _affine_mm(shape, mm_px: float) -> tuple[np.ndarray, np.ndarray]:
    """The map from the shape's own coordinates to the workpiece plane (mm, y up): every
    transform above it (viewBox included), then the flip."""
    m = shape.transform
    flip = np.diag([mm_px, -mm_px])
    return flip @ np.array([[m.a, m.c], [m.b, m.d]], float), flip @ np.array([m.e, m.f], float)


def _similarity(matrix: np.ndarray) -> bool:
    """Whether a 2 x 2 map keeps circles circles (a rotation or reflection times a scale)."""
    u, v = matrix[:, 0], matrix[:, 1]
    scale = max(float(np.abs(matrix).max()), 1e-300)
    return abs(float(u @ u) - float(v @ v)) <= _ROUND * scale**2 and abs(float(u @ v)) <= _ROUND * scale**2


def _shape_pieces(shape, label: str, flatten_mm: float, mm_px: float) -> list[Piece]:
    """The pieces of one shape (every subpath, Close as a line back to its start), with
    ``mm_px`` mm per pixel. Segments are taken in the shape's own coordinates and mapped
    here: a circular arc stays a native arc only through a similarity (svgelements' own
    transformed arcs are wrong under a skew); a degenerate arc (a radius or sweep of 0) is
    the line SVG draws for it."""
    import svgelements as se

    matrix, offset = _affine_mm(shape, mm_px)
    to_mm = lambda p: matrix @ np.array([float(p[0]), float(p[1])]) + offset  # noqa: E731
    keeps_circles = _similarity(matrix)
    pieces: list[Piece] = []
    for index, seg in enumerate(se.Path(shape).segments(transformed=False)):
        sub = f"{label} segment {index}"
        if isinstance(seg, se.Move) or seg.start is None or seg.end is None:
            continue
        a, b = to_mm(seg.start), to_mm(seg.end)
        if not (np.isfinite(a).all() and np.isfinite(b).all()):
            raise InputError(f"{label}: a coordinate is not finite")
        if isinstance(seg, se.Close) and float(np.linalg.norm(b - a)) <= _ROUND * max(1.0, float(np.abs(a).max())):
            continue  # the path already ends where it started (to round-off): nothing is drawn
        if isinstance(seg, (se.Line, se.Close)) or isinstance(seg, se.Arc) and _degenerate(seg):
            pieces.append(line_piece(a, b, sub, label))
        elif isinstance(seg, se.Arc) and _circular(seg) and keeps_circles:
            radius = (float(seg.rx) + float(seg.ry)) / 2 * math.sqrt(abs(float(np.linalg.det(matrix))))
            sweep = float(seg.sweep) * (1.0 if np.linalg.det(matrix) > 0 else -1.0)
            pieces.append(arc_piece(to_mm(seg.center), radius, a, b, sweep, sub, label))
        else:
            at = lambda t, seg=seg: np.asarray(seg.npoint(np.asarray(t, float)), float) @ matrix.T + offset  # noqa: E731
            pieces.append(free_or_native(at, flatten_mm, sub, label).with_ends(a, b))
    return pieces


def _attribute_error(el) -> Optional[str]:
    """Why a shape's own numbers are malformed (svgelements reads what it can and drops the
    rest, or takes a negative size as a positive one), or None."""
    values = el.values
    if _tag(el) in ("polyline", "polygon"):
        tokens = [t for t in re.split(r"[\s,]+", str(values.get("points", "")).strip()) if t]
        bad = next((t for t in tokens if not _NUMBER.fullmatch(t)), None)
        if bad is not None:
            return f"points: {shown(bad)} is not a number"
        if len(tokens) % 2:
            return f"points: {len(tokens)} numbers, expected x,y pairs"
    for name in ("r", "rx", "ry", "width", "height"):
        raw = str(values.get(name, "")).strip()
        if raw.startswith("-") and _NUMBER.match(raw) and float(_NUMBER.match(raw).group()) < 0:
            return f"{name}={shown(raw)} is negative; SVG draws nothing for a negative size (give it a size >= 0)"
    return None


def _unpainted(shape) -> bool:
    """Whether a shape is drawn with neither fill nor stroke (none, transparent, or a stroke
    of width 0): a viewer shows nothing of it, a guide or a hit area."""
    def none(color) -> bool:
        return color is None or color.value is None or color.alpha == 0

    return none(shape.fill) and (none(shape.stroke) or not float(shape.stroke_width or 0.0) > 0)


def _degenerate(arc) -> bool:
    """An arc SVG draws as a straight line: a radius of zero, or no sweep."""
    return float(arc.rx) == 0.0 or float(arc.ry) == 0.0 or float(arc.sweep) == 0.0


def read_svg(path: Path, layers: Sequence[str] | None, flatten_mm: float) -> Drawing:
    """The geometry of an SVG file in mm, y up; see the module docstring."""
    import svgelements as se

    data = read_input(path, "drawing")
    svg = _parse(path, data)
    k = mm_per_px(svg)
    elements = list(_walk(svg, ()))
    known = sorted({label for _, labels in elements for label in labels})
    raw = ET.fromstring(data)
    hidden_names, undisplayed = hidden_by_display(raw)
    for name in layers or ():
        if name.lower() in {h.lower() for h in hidden_names} and name.lower() not in {k.lower() for k in known}:
            raise InputError(f"{path}: layer {name!r} (--layer) is hidden in the drawing (display:none); "
                             "show it in the drawing to spray it")
    wanted = check_layers(str(path), layers, known)
    pieces: list[Piece] = []
    notes: list[str] = []
    shapes: list[tuple[object, str]] = []
    ignored, hidden, elsewhere = Counter(), 0, 0
    ignored["flowRoot"] = len(re.findall(rb"<(?:\w+:)?flowRoot\b", data))
    for index, (el, labels) in enumerate(elements):
        if not isinstance(el, se.Shape):
            if isinstance(el, (se.Text, se.Image)):
                ignored[_tag(el)] += 1
            continue
        if wanted is not None and not any(label.lower() in wanted for label in labels):
            elsewhere += 1
            continue
        if str(el.values.get("visibility", "visible")).strip() in ("hidden", "collapse"):
            hidden += 1
            continue
        label = _name(el, index)
        problem = path_data_error(str(el.values.get("d", ""))) if isinstance(el, se.Path) else _attribute_error(el)
        if problem is not None:
            raise InputError(f"{path}: {label}: {problem}")
        shapes.append((el, label))
    for el, label in _painted(shapes, notes):
        pieces.extend(_shape_pieces(el, label, flatten_mm, k))
    notes += _document_notes(svg, data)
    unresolved = unresolved_uses(raw)
    if unresolved:
        notes.append(f"left out {len(unresolved)} <use> elements that refer to nothing in this file (first: "
                     f"{unresolved[0][:80]!r}; another file's shapes are not read)")
    ignored = +ignored  # no zero counts
    if ignored:
        notes.append(count_note("ignored", ignored, "not contour geometry"))
    if hidden or undisplayed:
        notes.append(f"left out {hidden + undisplayed} hidden elements (display:none or visibility:hidden)")
    if hidden_names and wanted is None:
        notes.append(f"left out {len(hidden_names)} hidden layers ({', '.join(hidden_names)})")
    if not pieces:
        if wanted is not None and elsewhere:
            raise InputError(f"{path}: no geometry on layer(s) {', '.join(repr(x) for x in layers)}")
        raise InputError(f"{path}: {_nothing(unresolved, ignored)}")
    return Drawing(str(path), tuple(pieces), _units(svg, k), tuple(notes))


def _painted(shapes: list[tuple[object, str]], notes: list[str]) -> list[tuple[object, str]]:
    """The shapes (with their labels) a viewer shows: without those drawn with neither fill
    nor stroke, noted, unless every shape is."""
    bare = [_unpainted(el) for el, _ in shapes]
    painted = [shape for shape, b in zip(shapes, bare) if not b]
    unpainted = len(shapes) - len(painted)
    if painted and unpainted:
        first = shapes[bare.index(True)][1]
        notes.append(f"left out {unpainted} shapes drawn with neither fill nor stroke, which a viewer does not "
                     f"show (first: {first})")
    elif unpainted:
        notes.append(f"every shape is drawn with neither fill nor stroke, which a viewer does not show: all "
                     f"{unpainted} read")
    return painted or shapes


def _nothing(unresolved: list[str], ignored: Counter) -> str:
    """Why a drawing yields no geometry, for the one-line error."""
    if unresolved:
        return (f"no geometry to spray: only <use> elements that refer to nothing in this file (first: "
                f"{unresolved[0][:80]!r}; another file's shapes are not read)")
    if ignored:
        return count_note("no geometry to spray: only", ignored, "coatsim reads path, rect, circle, ellipse, line, polyline, polygon")
    return "no geometry to spray (no path, rect, circle, ellipse, line, polyline or polygon with a length)"


def _document_notes(svg, data: bytes) -> list[str]:
    """Notes on how the document as a whole is read: its scale where it gives none in a
    physical unit, switches reduced, clip paths not applied."""
    notes = [note for note in (_pixel_note(svg, data),) if note]
    switches = len(re.findall(rb"<switch\b", data))
    if switches:
        notes.append(f"{switches} <switch> elements: each read as its first child that needs no extension, as a viewer "
                     "draws it")
    clipped = len(re.findall(rb"clip-path\s*[=:]\s*[\"']?\s*url", data))
    if clipped:
        notes.append(f"{clipped} clip paths not applied: the shapes they clip are read whole")
    return notes


def _units(svg, mm_px: float) -> str:
    """The size of the document's user unit in mm, as the summary states it: what its width,
    height and viewBox make of it (a drawing saved at 1 unit = 1 mm says so)."""
    import svgelements as se

    view = se.Matrix(svg.viewbox_transform) if svg.viewbox_transform else se.Matrix()
    sx, sy = math.hypot(view.a, view.b) * mm_px, math.hypot(view.c, view.d) * mm_px
    if abs(sx - sy) <= 1e-9 * max(sx, sy):
        return f"SVG user unit {sx:.9g} mm (y flipped)"
    return f"SVG user unit {sx:.9g} mm across, {sy:.9g} mm down (the viewBox stretches it; y flipped)"


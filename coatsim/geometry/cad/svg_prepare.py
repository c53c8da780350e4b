"""An SVG document edited before svgelements draws it, where svgelements would draw it other
than a viewer does: symbols placed only where a ``<use>`` places them, the root's missing width or
height completed from its viewBox, flowed text left out, each ``<switch>`` reduced to the child
drawn, ``display`` and ``visibility`` read in any letter case. One parse, and one serialisation
where any edit changed the document."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

SVG_NS = "{http://www.w3.org/2000/svg}"
_HREFS = ("href", "{http://www.w3.org/1999/xlink}href")
_CSS_PX = {"px": 1.0, "": 1.0, "mm": 96 / 25.4, "cm": 96 / 2.54, "in": 96.0, "pt": 96 / 72, "pc": 16.0}


def _length_px(text: str | None, whole: float) -> float | None:
    """An SVG length in user units; a percentage of ``whole``; None if absent or unreadable."""
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(px|mm|cm|in|pt|pc|%)?\s*", text or "")
    if m is None:
        return None
    unit = m.group(2) or ""
    return float(m.group(1)) * (whole / 100 if unit == "%" else _CSS_PX[unit])


def _viewbox_transform(viewbox: str, width: float, height: float, aspect: str) -> str:
    """The transform placing a viewBox into a width x height viewport (preserveAspectRatio)."""
    x, y, w, h = (float(v) for v in re.split(r"[\s,]+", viewbox.strip()))
    if not (w > 0 and h > 0):
        raise ValueError(f"viewBox {viewbox!r} has no area")
    sx, sy = width / w, height / h
    align = (aspect or "xMidYMid meet").split()
    if align[0] != "none":
        sx = sy = max(sx, sy) if align[-1] == "slice" else min(sx, sy)
        fx = {"xMin": 0.0, "xMid": 0.5, "xMax": 1.0}.get(align[0][:4], 0.5)
        fy = {"YMin": 0.0, "YMid": 0.5, "YMax": 1.0}.get(align[0][4:], 0.5)
    else:
        fx = fy = 0.0
    tx, ty = fx * (width - w * sx) - x * sx, fy * (height - h * sy) - y * sy
    return f"translate({tx!r},{ty!r}) scale({sx!r},{sy!r})"


def prepared(data: bytes) -> bytes:
    """The document as svgelements should draw it (one parse, and one serialisation where any
    of these changed it): symbols placed, the root's size completed, flowed text left out,
    switches reduced to the child drawn, display and visibility in lower case."""
    root = ET.fromstring(data)
    changed = [edit(root) for edit in (symbols_placed, sized, without_flowed_text, switched, shown_lowered)]
    return ET.tostring(root) if any(changed) else data


_SHOWN = re.compile(r"(?i)\b(display|visibility)\s*:\s*([a-z-]+)")


def shown_lowered(root: ET.Element) -> bool:
    """``display`` and ``visibility`` in lower case, as attributes and in style (CSS names and
    keywords are case-insensitive, and svgelements drew a shape styled ``DISPLAY:NONE``).
    Whether any was changed."""
    changed = False
    for el in root.iter():
        style = el.get("style")
        if style and _SHOWN.search(style):
            lowered = _SHOWN.sub(lambda m: f"{m.group(1).lower()}:{m.group(2).lower()}", style)
            if lowered != style:
                el.set("style", lowered)
                changed = True
        for name in ("display", "visibility"):
            value = el.get(name)
            if value is not None and value != value.strip().lower():
                el.set(name, value.strip().lower())
                changed = True
    return changed


def without_flowed_text(root: ET.Element) -> bool:
    """Leave out Inkscape's flowed text (``<flowRoot>``): text, and the frame its
    ``<flowRegion>`` flows it into is no contour (svgelements drew that frame as a rectangle).
    Whether anything was left out."""
    changed = False
    for parent in list(root.iter()):
        for child in list(parent):
            if child.tag in (f"{SVG_NS}flowRoot", "flowRoot"):
                parent.remove(child)
                changed = True
    return changed


def switched(root: ET.Element) -> bool:
    """Reduce each ``<switch>`` to the one child a viewer draws: the first that asks for no
    extension (Illustrator puts its own data first, under requiredExtensions); svgelements drew
    every child, one shape over another. Whether there was a switch."""
    switches = list(root.iter(f"{SVG_NS}switch"))
    for switch in switches:
        children = list(switch)
        drawn = next((c for c in children if c.get("requiredExtensions") is None), None)
        for child in children:
            if child is not drawn:
                switch.remove(child)
    return bool(switches)


def sized(root: ET.Element) -> bool:
    """Give the root's missing width or height where it has the other and a viewBox: the
    viewBox's aspect sets it (SVG's auto size; svgelements takes the missing one as 100 % of a
    default viewport, and a width="200mm" over a 100 x 50 viewBox drew a 20-unit square 5.3 mm
    wide instead of 40). Whether it was given."""
    box = (root.get("viewBox") or "").replace(",", " ").split()
    width, height = root.get("width"), root.get("height")
    if len(box) != 4 or (width is None) == (height is None):
        return False
    try:
        w, h = float(box[2]), float(box[3])
    except ValueError:
        return False
    given = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(px|mm|cm|in|pt|pc)?\s*", width or height)
    if given is None or not (w > 0 and h > 0):
        return False
    value, unit = float(given.group(1)), given.group(2) or ""
    if width is None:
        root.set("width", f"{value * w / h!r}{unit}")
    else:
        root.set("height", f"{value * h / w!r}{unit}")
    return True


def symbols_placed(root: ET.Element) -> bool:
    """Draw every ``<symbol>`` only where a ``<use>`` places it, its viewBox fitted into the
    use's width and height (svgelements draws a symbol in place as well, and ignores its
    viewBox). Whether there was a symbol."""
    parents = {child: parent for parent in root.iter() for child in parent}
    symbols = {el.get("id"): el for el in root.iter(f"{SVG_NS}symbol")}
    if not symbols:
        return False
    defs = ET.SubElement(root, f"{SVG_NS}defs")
    for el in symbols.values():
        parents[el].remove(el)
    box = (root.get("viewBox") or "").replace(",", " ").split()
    whole_w = float(box[2]) if len(box) == 4 else _length_px(root.get("width"), 0.0) or 0.0
    whole_h = float(box[3]) if len(box) == 4 else _length_px(root.get("height"), 0.0) or 0.0
    for k, use in enumerate(root.iter(f"{SVG_NS}use")):
        href = next((use.get(h) for h in _HREFS if use.get(h)), "")
        symbol = symbols.get(href.lstrip("#")) if href.startswith("#") else None
        if symbol is None:
            continue
        group = ET.SubElement(defs, f"{SVG_NS}g", {"id": f"{href[1:]}--placed-{k}"})
        group.extend(list(symbol))
        if symbol.get("viewBox"):
            width = _length_px(use.get("width") or symbol.get("width") or "100%", whole_w)
            height = _length_px(use.get("height") or symbol.get("height") or "100%", whole_h)
            if width and height:
                group.set("transform", _viewbox_transform(symbol.get("viewBox"), width, height,
                                                          symbol.get("preserveAspectRatio", "")))
        for h in _HREFS:
            if use.get(h):
                use.set(h, f"#{group.get('id')}")
    return True

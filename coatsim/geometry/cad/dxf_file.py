"""A DXF file opened safely (ezdxf): a DWG or a file that is not DXF refused, its records counted
against the budget drawing_entities before ezdxf builds them, and every entity's numbers and
the blocks' nesting checked before any block is expanded — so a hostile drawing costs neither
memory nor a recursion without end."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from coatsim.core.budgets import check_budget, limit
from coatsim.core.errors import InputError
from coatsim.core.fileio import read_input

_MIN_RATIO = 1e-10  # flatter ellipses are refused (as CAD programs refuse them)
_MAX_DXF_VALUE = 1e15  # no drawing holds a larger number (float64 resolves no millimetre fraction beyond it)
_BINARY_DXF = b"AutoCAD Binary DXF\r\n\x1a\x00"
_RECORD = re.compile(rb"(?:^|\n)[ \t]*0[ \t]*\r?\n[ \t]*[A-Z_]")  # group code 0 and a record's name


def entity_label(entity, where: str) -> str:
    """An entity named for messages: its type, its handle, where it is (``LINE #2F in block 'A'``)."""
    handle = entity.dxf.get("handle")
    own = f"{entity.dxftype()} #{handle}" if handle else entity.dxftype()
    return f"{own} {where}".rstrip()


def open_dxf(path: Path):
    """The ezdxf document of the DXF file at ``path``, read through the safe reader; its records
    (entities, table entries, objects) are counted against the budget drawing_entities before
    ezdxf builds any of them."""
    import ezdxf

    data = read_input(path, "drawing")
    if data.startswith(b"AC10") or data.startswith(b"AC1."):
        raise InputError(f"{path}: a DWG file, not DXF (save it as DXF from the CAD program)")
    try:
        doc = _load(data, path)
    except (UnicodeError, LookupError, ValueError, StopIteration, EOFError, ezdxf.DXFError) as exc:
        detail = str(exc).replace(str(path), "file")[:200] or "it ends before its header does"
        raise InputError(f"{path}: not a readable DXF file ({detail})") from None
    if b"$INSUNITS" not in data:  # ezdxf fills a missing header from its template, which says metres
        doc.header["$INSUNITS"] = 0
    return doc


def _load(data: bytes, path: Path):
    """The ezdxf document of the DXF text or binary ``data``."""
    import io

    import ezdxf
    from ezdxf.document import Drawing as Document
    from ezdxf.filemanagement import dxf_stream_info
    from ezdxf.lldxf.tagger import binary_tags_loader
    from ezdxf.lldxf.validator import is_dxf_stream

    if data.startswith(_BINARY_DXF):
        return Document.load(binary_tags_loader(data, errors="surrogateescape"))
    check_budget(f"{path}: DXF records (entities, table entries, objects)", len(_RECORD.findall(data)),
                 "drawing_entities", "split the drawing or leave out what is not sprayed")
    head = io.StringIO(data[:1 << 16].decode("utf-8", errors="ignore"), newline=None)
    if not is_dxf_stream(head):
        raise InputError(f"{path}: not a readable DXF file (no SECTION where a DXF file starts)")
    head.seek(0)
    encoding = dxf_stream_info(head).encoding
    return ezdxf.read(io.StringIO(data.decode(encoding, errors="surrogateescape"), newline=None))


def _numbers(entity) -> np.ndarray:
    """Every number of an entity that is a coordinate, a size, an angle or a ratio (its DXF
    attributes, its vertices, bulges, control and fit points, knots and weights)."""
    from ezdxf.math import Vec2, Vec3

    values: list[float] = []
    for value in entity.dxfattribs().values():
        if isinstance(value, float):
            values.append(value)
        elif isinstance(value, (Vec2, Vec3, tuple)) and all(isinstance(c, (int, float)) for c in value):
            values.extend(float(c) for c in value)
    kind = entity.dxftype()
    arrays = []
    if kind == "LWPOLYLINE":
        arrays.append(np.asarray(entity.get_points("xyseb"), dtype=float))
    elif kind == "POLYLINE":
        arrays.append(np.asarray([v.dxf.location for v in entity.vertices], dtype=float))
        arrays.append(np.asarray([v.dxf.get("bulge", 0.0) for v in entity.vertices], dtype=float))
    elif kind == "SPLINE":
        arrays += [np.asarray(list(entity.control_points), dtype=float), np.asarray(list(entity.fit_points), dtype=float),
                   np.asarray(list(entity.knots), dtype=float), np.asarray(list(entity.weights), dtype=float)]
    return np.concatenate([np.asarray(values, dtype=float)] + [a.ravel() for a in arrays])


def _check_numbers(entity, label: str) -> None:
    """Refuse an entity holding NaN, inf or a number beyond any drawing (ezdxf computes with them
    without a word, or recurses without end), or an ELLIPSE whose axis ratio is outside (0, 1]."""
    values = _numbers(entity)
    if not np.isfinite(values).all() or (values.size and float(np.abs(values).max()) > _MAX_DXF_VALUE):
        raise InputError(f"{label}: holds a number that is not finite or beyond {_MAX_DXF_VALUE:g}; check the "
                         "drawing's numbers")
    if entity.dxftype() == "ELLIPSE" and not _MIN_RATIO <= abs(float(entity.dxf.get("ratio", 1.0))) <= 1.0 + 1e-9:
        raise InputError(f"{label}: axis ratio {float(entity.dxf.ratio):g} is outside [{_MIN_RATIO:g}, 1]; an "
                         "ellipse's minor axis is a fraction of its major one (draw a line for a flat one)")


def _pieces_of(entity, size: dict[str, float]) -> float:
    """How many entities ``entity`` stands for once expanded (vertices count for polylines)."""
    kind = entity.dxftype()
    if kind == "INSERT":
        return max(int(entity.mcount), 1) * size.get(entity.dxf.get("name", ""), 0.0)
    if kind == "LWPOLYLINE":
        return float(max(len(entity), 1))
    if kind == "POLYLINE":
        return float(max(len(entity.vertices), 1))
    return 1.0


def check_structure(doc, entities: list, source: str) -> None:
    """Before any block is expanded: every entity's numbers (``_check_numbers``), blocks inserted
    into themselves (named), blocks nested deeper than the budget drawing_depth, and the entities
    the INSERTs and MINSERTs would expand to against the budget drawing_entities. Each block is
    visited once, without recursion."""
    size: dict[str, float] = {}
    depth: dict[str, int] = {}
    on_path: list[str] = []
    todo: list[tuple[str, int]] = []

    def members(name: str) -> list:
        block = doc.blocks.get(name)
        return [] if block is None else list(block)

    for entity in entities:
        _check_numbers(entity, entity_label(entity, ""))
    for name in {e.dxf.get("name", "") for e in entities if e.dxftype() == "INSERT"}:
        todo.append((name, 0))
        while todo:
            block, k = todo.pop()
            if block in size:
                continue
            if k == 0:
                on_path.append(block)
            names = [e.dxf.get("name", "") for e in members(block) if e.dxftype() == "INSERT"]
            pending = [n for n in names if n not in size]
            loop = next((n for n in pending if n in on_path), None)
            if loop is not None:
                chain = " -> ".join(on_path[on_path.index(loop):] + [loop])
                raise InputError(f"{source}: block {loop!r} inserts itself ({chain}); a block cannot contain itself")
            if pending:
                todo.append((block, 1))
                todo.extend((n, 0) for n in pending)
                continue
            for entity in members(block):
                _check_numbers(entity, entity_label(entity, f"in block {block!r}"))
            size[block] = sum(_pieces_of(e, size) for e in members(block))
            depth[block] = 1 + max((depth.get(n, 0) for n in names), default=0)
            on_path.remove(block)
            if depth[block] > limit("drawing_depth"):
                check_budget(f"{source}: block {block!r}: blocks nested inside blocks", depth[block], "drawing_depth",
                             "flatten the drawing's blocks")
    check_budget(f"{source}: entities once every INSERT and MINSERT is expanded (polyline vertices counted)",
                 sum(_pieces_of(e, size) for e in entities), "drawing_entities",
                 "explode fewer copies (or simplify the drawing)")

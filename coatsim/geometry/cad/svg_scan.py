"""An SVG's structure checked before svgelements builds it: nesting, ``<use>`` references and size.

One pass of the expat parser (no recursion, no element tree) records every element, its children
and the element each ``<use>`` places. Then, iteratively: a ``<use>`` chain that comes back to
itself is a reference cycle, named; the nesting of elements, counting what each ``<use>`` places
inside it, is checked against the budget drawing_depth; the number of elements once every
``<use>`` is expanded (a few kilobytes of nested uses can stand for billions) against the budget
drawing_entities. All before anything is expanded.
"""

from __future__ import annotations

import re
import xml.parsers.expat
from dataclasses import dataclass, field

from coatsim.core.budgets import check_budget, limit
from coatsim.core.errors import InputError

_HREFS = ("href", "http://www.w3.org/1999/xlink href")
_COMMAND = re.compile(r"[MmLlHhVvCcSsQqTtAaZz]")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _weight(tag: str, attrs: dict[str, str]) -> float:
    """How many pieces an element draws: a path one per command (or per seven numbers, the
    longest command), a polyline one per point, anything else one."""
    if tag == "path":
        d = attrs.get("d", "")
        return float(max(1, len(_COMMAND.findall(d)), len(_NUMBER.findall(d)) // 7))
    if tag in ("polyline", "polygon"):
        return float(max(1, len(_NUMBER.findall(attrs.get("points", ""))) // 2))
    return 1.0


@dataclass
class _Doc:
    """The elements of a document by index: tag, line, children, the index a use places, ids."""

    tags: list[str] = field(default_factory=list)
    weights: list[float] = field(default_factory=list)
    lines: list[int] = field(default_factory=list)
    children: list[list[int]] = field(default_factory=list)
    href: dict[int, str] = field(default_factory=dict)
    ids: dict[str, int] = field(default_factory=dict)


def _read(data: bytes, source: str) -> _Doc:
    """The element structure of ``data``; InputError (file:line:col) when it is not well-formed or
    nests deeper than the budget drawing_depth."""
    doc = _Doc()
    stack: list[int] = []
    budget, entities = limit("drawing_depth"), limit("drawing_entities")
    drawn = [0.0]  # pieces so far, before any use is expanded
    parser = xml.parsers.expat.ParserCreate(namespace_separator=" ")

    def start(tag: str, attrs: dict[str, str]) -> None:
        index = len(doc.tags)
        doc.tags.append(tag.rsplit(" ", 1)[-1])
        doc.weights.append(_weight(doc.tags[index], attrs))
        drawn[0] += doc.weights[index]
        if drawn[0] > entities:
            check_budget(f"{source}:{parser.CurrentLineNumber}: elements (path commands and polyline points "
                         "counted)", drawn[0], "drawing_entities", "simplify the drawing")
        doc.lines.append(parser.CurrentLineNumber)
        doc.children.append([])
        if stack:
            doc.children[stack[-1]].append(index)
        stack.append(index)
        if len(stack) > budget:
            check_budget(f"{source}:{parser.CurrentLineNumber}: elements nested inside each other", len(stack),
                         "drawing_depth", "flatten the groups of the drawing")
        if attrs.get("id"):
            doc.ids.setdefault(attrs["id"], index)
        ref = next((attrs[h] for h in _HREFS if attrs.get(h)), None)
        if doc.tags[index] == "use" and ref and ref.startswith("#"):
            doc.href[index] = ref[1:]

    parser.StartElementHandler = start
    parser.EndElementHandler = lambda tag: stack.pop()
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as exc:
        raise InputError(f"{source}:{exc.lineno}:{exc.offset}: not well-formed SVG "
                         f"({xml.parsers.expat.ErrorString(exc.code)})") from None
    return doc


def _edges(doc: _Doc, index: int) -> list[int]:
    """What an element holds once expanded: its children, and the element its use places."""
    out = list(doc.children[index])
    target = doc.href.get(index)
    if target is not None and target in doc.ids:
        out.append(doc.ids[target])
    return out


def _cycle_text(doc: _Doc, path: list[int], back: int) -> str:
    uses = [i for i in path[path.index(back):] if i in doc.href]
    return " -> ".join(f"<use href=#{doc.href[i]}> (line {doc.lines[i]})" for i in uses) or "an element inside itself"


def check_svg_structure(data: bytes, source: str) -> None:
    """Refuse ``data`` before svgelements parses it: not well-formed, a ``<use>`` reference cycle,
    nesting over the budget drawing_depth or more elements than the budget drawing_entities once
    the uses are expanded (each with the line that shows it)."""
    doc = _read(data, source)
    if not doc.tags:
        return
    size: list[float] = [0.0] * len(doc.tags)   # elements once expanded
    depth: list[int] = [0] * len(doc.tags)      # nesting once expanded
    state = [0] * len(doc.tags)                 # 0 new, 1 on the path, 2 done
    path: list[int] = []
    edges_of: dict[int, list[int]] = {}         # on the path: what it holds (computed once)
    todo: list[tuple[int, int]] = [(0, 0)]      # (element, next edge to follow)
    depth_budget, size_budget = limit("drawing_depth"), limit("drawing_entities")
    while todo:
        node, k = todo.pop()
        if k == 0:
            state[node] = 1
            path.append(node)
            edges_of[node] = _edges(doc, node)
        edges = edges_of[node]
        if k < len(edges):
            todo.append((node, k + 1))
            nxt = edges[k]
            if state[nxt] == 1:
                raise InputError(f"{source}: a <use> cycle: {_cycle_text(doc, path, nxt)}; an element cannot place "
                                 "itself (remove the reference)")
            if state[nxt] == 0:
                todo.append((nxt, 0))
            continue
        size[node] = doc.weights[node] + sum(size[e] for e in edges)
        del edges_of[node]
        depth[node] = 1 + max((depth[e] for e in edges), default=0)
        state[node] = 2
        path.pop()
        line = doc.lines[node]
        if depth[node] > depth_budget:
            check_budget(f"{source}:{line}: elements nested inside each other (counting what <use> places)",
                         depth[node], "drawing_depth", "flatten the groups and uses of the drawing")
        if size[node] > size_budget:
            check_budget(f"{source}:{line}: elements (path commands and polyline points counted) once every <use> "
                         "is expanded", size[node], "drawing_entities",
                         "draw fewer copies (or simplify the drawing)")

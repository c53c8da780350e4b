"""YAML with line numbers: load a document, remember the line of every key path, and turn a
pydantic validation error into one line that names the file, the line and the key path.

Loading is bounded (coatsim.core.budgets): file size, nesting depth, alias uses and the node count
after expanding aliases are checked while composing, before any value is built, so neither a
deeply nested file nor an alias bomb ("billion laughs") nor a recursive alias gets far.
"""

from __future__ import annotations

import difflib
import re
import typing
from pathlib import Path
from typing import Any, Mapping, Union

import yaml
from pydantic import BaseModel, ValidationError

from coatsim.core.budgets import MAX_YAML_ALIASES, MAX_YAML_DEPTH, MAX_YAML_NODES
from coatsim.core.errors import InputError
from coatsim.core.fileio import read_input

Loc = tuple[Union[str, int], ...]

_FLOAT = re.compile(
    r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
    |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
    |[-+]?\.[0-9_]+(?:[eE][-+]?[0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)
    |\.(?:nan|NaN|NAN))$""",
    re.X,
)


class _OverBudget(Exception):
    """A YAML budget was exceeded at ``line`` (1-based)."""

    def __init__(self, line: int, message: str):
        super().__init__(message)
        self.line = line


class _Loader(yaml.SafeLoader):
    """SafeLoader that reads ``1e-3`` as a float (YAML 1.2 style), keeps dates as text and
    refuses nesting deeper than MAX_YAML_DEPTH and more than MAX_YAML_ALIASES alias uses."""

    def __init__(self, stream: str):
        super().__init__(stream)
        self._depth = 0
        self._aliases = 0

    def compose_node(self, parent: Any, index: Any) -> yaml.Node:
        line = self.peek_event().start_mark.line + 1
        if self.check_event(yaml.AliasEvent):
            self._aliases += 1
            if self._aliases > MAX_YAML_ALIASES:
                raise _OverBudget(line, f"more than {MAX_YAML_ALIASES} alias uses (*name); write the values out")
            return super().compose_node(parent, index)
        self._depth += 1
        try:
            if self._depth > MAX_YAML_DEPTH:
                raise _OverBudget(line, f"nested deeper than {MAX_YAML_DEPTH} levels")
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


_Loader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if tag not in ("tag:yaml.org,2002:float", "tag:yaml.org,2002:timestamp")]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()
}
_Loader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT, list("-+0123456789."))


def _key_name(node: yaml.Node, where: str) -> str:
    """A mapping key as written. A plain key that YAML reads as something other than text
    (YAML 1.1 reads on, off, yes, no, true and false as booleans, ~ as null, 12 as a
    number) is an error at its own line, with the fix: quote it."""
    if not isinstance(node, yaml.ScalarNode):
        kind = "list" if isinstance(node, yaml.SequenceNode) else "mapping"
        raise InputError(f"{where}: a key must be a plain name, not a {kind}")
    if node.tag == "tag:yaml.org,2002:str":
        return node.value
    value = _Loader("").construct_object(node)
    if isinstance(value, bool):
        what = f"the boolean {str(value).lower()} (YAML 1.1 reads on, off, yes, no as booleans)"
    elif value is None:
        what = "null"
    else:
        what = f"the number {value!r}"
    raise InputError(f"{where}: key {node.value!r} is read by YAML as {what}, not as a name; "
                     f"quote it: '{node.value}':")


def _record_lines(node: yaml.Node, loc: Loc, lines: dict[Loc, int], path: Path) -> None:
    """Fill ``lines`` with the 1-based line of every key path below ``node``; reject
    duplicate keys, which YAML would otherwise resolve silently to the last one."""
    if isinstance(node, yaml.MappingNode):
        seen: dict[Any, int] = {}
        for key_node, value_node in node.value:
            line = key_node.start_mark.line + 1
            key = _key_name(key_node, f"{path}:{line}")
            if key in seen:
                raise InputError(f"{path}:{line}: duplicate key {key!r} (first given on line {seen[key]})")
            seen[key] = line
            lines[loc + (key,)] = line
            _record_lines(value_node, loc + (key,), lines, path)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            lines[loc + (i,)] = item.start_mark.line + 1
            _record_lines(item, loc + (i,), lines, path)


def _check_expansion(root: yaml.Node) -> None:
    """Refuse a document whose aliases expand past MAX_YAML_NODES nodes or MAX_YAML_DEPTH
    levels, or refer to themselves; linear time (subtree sizes are memoised per node)."""
    memo: dict[int, tuple[int, int]] = {}  # id(node) -> (expanded nodes, expanded height)
    active: set[int] = set()

    def visit(node: yaml.Node, depth: int) -> tuple[int, int]:
        line = node.start_mark.line + 1
        key = id(node)
        if key in active:
            raise _OverBudget(line, "an alias refers to the node that contains it (recursive alias)")
        if key not in memo:
            if depth > MAX_YAML_DEPTH:
                raise _OverBudget(line, f"nested deeper than {MAX_YAML_DEPTH} levels once aliases are expanded")
            children: list[yaml.Node] = []
            if isinstance(node, yaml.MappingNode):
                children = [n for pair in node.value for n in pair]
            elif isinstance(node, yaml.SequenceNode):
                children = list(node.value)
            active.add(key)
            size, height = 1, 1
            for child in children:
                child_size, child_height = visit(child, depth + 1)
                size, height = size + child_size, max(height, child_height + 1)
                if size > MAX_YAML_NODES:
                    raise _OverBudget(line, f"aliases expand to more than {MAX_YAML_NODES:,} values; write the values out")
            active.discard(key)
            memo[key] = (size, height)
        size, height = memo[key]
        if depth + height - 1 > MAX_YAML_DEPTH:
            raise _OverBudget(line, f"nested deeper than {MAX_YAML_DEPTH} levels once aliases are expanded")
        return size, height

    visit(root, 1)


def load_yaml_with_lines(path: Path, expected: str = "a scenario (name, curve, workpiece, ...)") -> tuple[Any, dict[Loc, int]]:
    """Parse one YAML document; return the data and the line of every key path. ``expected``
    says what the file should hold (for the messages on a folder or an empty file)."""
    try:
        text = read_input(path, "YAML file", "yaml_bytes").decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text; expected a YAML file with {expected}") from None
    try:
        loader = _Loader(text)  # its reader refuses control characters at once
    except yaml.YAMLError as exc:
        raise InputError(f"{path}: invalid YAML: {str(exc).splitlines()[0]}") from None
    try:
        node = loader.get_single_node()
        if node is None:
            raise InputError(f"{path}: empty file, expected {expected}")
        _check_expansion(node)
        lines: dict[Loc, int] = {(): node.start_mark.line + 1}
        _record_lines(node, (), lines, path)
        data = loader.construct_document(node)
    except _OverBudget as exc:
        raise InputError(f"{path}:{exc.line}: {exc}") from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = f"{path}:{mark.line + 1}" if mark else str(path)
        raise InputError(f"{where}: invalid YAML: {exc.problem or exc.context}") from None
    except yaml.YAMLError as exc:
        raise InputError(f"{path}: invalid YAML: {exc}") from None
    finally:
        loader.dispose()
    return data, lines


def where_in(path: Path, lines: Mapping[Loc, int], loc: Loc) -> str:
    """``file:line`` of the deepest key path prefix of ``loc`` that the file spells out."""
    for n in range(len(loc), -1, -1):
        if tuple(loc[:n]) in lines:
            return f"{path}:{lines[tuple(loc[:n])]}"
    return str(path)


def data_path(loc: Loc, data: Any) -> Loc:
    """The part of a pydantic error location that indexes the data: union tags and
    validator names are dropped; a missing key (the last item) is kept."""
    out: list[Union[str, int]] = []
    node = data
    for i, item in enumerate(loc):
        if isinstance(node, dict) and item in node:
            node = node[item]
        elif isinstance(node, list) and isinstance(item, int) and 0 <= item < len(node):
            node = node[item]
        elif i < len(loc) - 1 or not isinstance(node, dict):
            continue
        out.append(item)
    return tuple(out)


def _dotted(loc: Loc) -> str:
    text = ""
    for item in loc:
        text += f"[{item}]" if isinstance(item, int) else (f".{item}" if text else str(item))
    return text or "(top level)"


def _annotation_at(model: type[BaseModel], loc: Loc, data: Any) -> Any:
    """The type that validates the value at ``loc`` (a model class when the value is a
    mapping; a union when a discriminated union cannot pick one)."""
    node: Any = data
    current: Any = model
    for item in loc:
        if isinstance(node, dict):
            node = node.get(item)
        elif isinstance(node, list) and isinstance(item, int) and 0 <= item < len(node):
            node = node[item]
        else:
            node = None
        if isinstance(current, type) and issubclass(current, BaseModel):
            field = current.model_fields.get(str(item))
            if field is None:
                return None
            current = field.annotation
        elif typing.get_origin(current) is list:
            current = typing.get_args(current)[0]
        current = _pick(current, node)
    return current


def allowed_keys(model: type[BaseModel], loc: Loc, data: Any) -> list[str]:
    """The keys the schema accepts in the mapping at ``loc`` of ``data`` ([] if not a model)."""
    parent = _annotation_at(model, loc, data)
    return sorted(parent.model_fields) if _is_model(parent) else []


def _is_model(annotation: Any) -> bool:
    return isinstance(annotation, type) and issubclass(annotation, BaseModel)


def _tags(annotation: Any) -> list[str]:
    """The ``kind`` values a discriminated union accepts (an optional one's too)."""
    while True:
        if typing.get_origin(annotation) is typing.Annotated:
            annotation = typing.get_args(annotation)[0]
            continue
        present = [a for a in typing.get_args(annotation) if a is not type(None)]
        if typing.get_origin(annotation) is Union and len(present) == 1:
            annotation = present[0]
            continue
        break
    options = typing.get_args(annotation) if typing.get_origin(annotation) is Union else ()
    return [t for o in options if _is_model(o) and "kind" in o.model_fields for t in typing.get_args(o.model_fields["kind"].annotation)]


def _pick(annotation: Any, node: Any) -> Any:
    """Unwrap Annotated/Optional/discriminated unions to the class that validates ``node``."""
    while True:
        while typing.get_origin(annotation) is typing.Annotated:
            annotation = typing.get_args(annotation)[0]
        if typing.get_origin(annotation) is not Union:
            return annotation
        options = [a for a in typing.get_args(annotation) if a is not type(None)]
        for option in options:
            fields = getattr(option, "model_fields", {})
            kind = fields.get("kind")
            if kind is not None and isinstance(node, dict) and node.get("kind") in typing.get_args(kind.annotation):
                return option
        if len(options) != 1:
            return annotation
        annotation = options[0]  # an optional one: what it holds when present


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _describe(err: Mapping[str, Any], key: Any, allowed: list[str], tags: list[str]) -> str:
    kind, msg = err["type"], err["msg"]
    if kind == "extra_forbidden":
        close = difflib.get_close_matches(str(key), allowed, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else (f"; allowed: {', '.join(allowed)}" if allowed else "")
        return f"unknown key{hint}"
    if kind == "missing":
        return "required key is missing"
    if kind == "union_tag_not_found":
        return f"missing key 'kind' (one of {', '.join(tags)})" if tags else "missing key 'kind'"
    if kind == "union_tag_invalid":
        return f"kind must be one of {err['ctx']['expected_tags']} (got {_short(err['ctx']['tag'])})"
    if kind == "value_error":
        return msg.removeprefix("Value error, ")
    if isinstance(err.get("input"), (dict, list)):
        return msg
    return f"{msg} (got {_short(err.get('input'))})"


def format_validation_error(
    exc: ValidationError, path: Path, data: Any, lines: Mapping[Loc, int], model: type[BaseModel]
) -> str:
    """One line for the first error: ``file:line: key.path: what is wrong`` (+ a count)."""
    errors = exc.errors()
    err = errors[0]
    loc = data_path(tuple(err["loc"]), data)
    line = next((lines[loc[:n]] for n in range(len(loc), -1, -1) if loc[:n] in lines), None)
    allowed = allowed_keys(model, loc[:-1], data) if loc else sorted(model.model_fields)
    tags = _tags(_annotation_at(model, loc, data))
    text = f"{path}:{line}: {_dotted(loc)}: {_describe(err, loc[-1] if loc else None, allowed, tags)}"
    if len(errors) > 1:
        text += f" (and {len(errors) - 1} more problem{'s' if len(errors) > 2 else ''})"
    return text

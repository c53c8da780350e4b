"""The files a scenario reads, gathered so they can travel with a task.

A worker may run on another machine: every file a point's scenario names (the curve file, a
mesh workpiece, a footprint table, a robot MJCF with the files it includes) is read on the
client, travels with the task as bytes, and is written into the worker's scratch folder under a
name made of its content digest; the scenario the worker runs names those copies. The digests
also enter the point's cache key, so editing an input file reruns the points that use it.
"""

from __future__ import annotations

import copy
import hashlib
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from coatsim.core.errors import InputError
from coatsim.core.fileio import check_input, read_input

# element -> compiler attribute its ``file`` is relative to (MuJoCo's rules; assetdir sets both)
_ASSET_DIRS = {"mesh": "meshdir", "skin": "meshdir", "hfield": "meshdir", "texture": "texturedir"}
_FILE_ATTRS = ("file", "fileright", "fileleft", "fileup", "filedown", "filefront", "fileback")


@dataclass(frozen=True)
class Bundle:
    """What a point's scenario reads: the scenario as the worker must run it (input paths
    rewritten to ``files``' names), the files by worker-relative name, and one digest per
    scenario key that names a file (dotted, for the cache key)."""

    scenario: dict[str, Any]
    files: Mapping[str, Path]
    digests: Mapping[str, str]


def _digest(paths: list[Path], root: Path) -> str:
    """sha256 over the files' names relative to ``root`` and their contents."""
    h = hashlib.sha256()
    for p in paths:
        name = p.relative_to(root).as_posix().encode()
        data = read_input(p, "input file")
        h.update(b"%d:%s%d:" % (len(name), name, len(data)) + data)
    return h.hexdigest()


def _mjcf_files(model: Path) -> list[Path]:
    """The MJCF file and every local file it (and its includes) references."""
    found: list[Path] = []
    todo = [model]
    root_dir = model.parent
    dirs: dict[str, Path] = {"meshdir": root_dir, "texturedir": root_dir}
    while todo:
        current = todo.pop()
        if current in found or not os.path.lexists(current):  # a FIFO or a device is refused when read
            continue
        found.append(current)
        try:
            tree = ET.ElementTree(ET.fromstring(read_input(current, "cell model")))
        except ET.ParseError:
            continue  # MuJoCo will say what is wrong with it on the worker
        for compiler in tree.iter("compiler"):
            for attr in ("assetdir", "meshdir", "texturedir"):
                if attr in compiler.attrib:
                    where = root_dir / compiler.attrib[attr]
                    for target in (("meshdir", "texturedir") if attr == "assetdir" else (attr,)):
                        dirs[target] = where
        for element in tree.iter():
            for attr in _FILE_ATTRS:
                name = element.attrib.get(attr)
                if not name or Path(name).is_absolute():
                    continue
                if element.tag in ("include", "model"):
                    todo.append(root_dir / name)
                else:
                    found_path = dirs[_ASSET_DIRS[element.tag]] / name if element.tag in _ASSET_DIRS else root_dir / name
                    if os.path.lexists(found_path) and found_path not in found:
                        found.append(found_path)
    return found


def _references(scenario: Mapping[str, Any]) -> list[tuple[tuple, str, str]]:
    """(key path, role, file as written) of every file the scenario names."""
    refs: list[tuple[tuple, str, str]] = []
    if (scenario.get("curve") or {}).get("file"):
        refs.append((("curve", "file"), "curve", scenario["curve"]["file"]))
    if (scenario.get("workpiece") or {}).get("kind") == "mesh":
        refs.append((("workpiece", "file"), "mesh", scenario["workpiece"]["file"]))
    if scenario.get("part"):
        refs.append((("part", "mesh"), "mesh", scenario["part"]["mesh"]))
    if scenario["robot"]["model"] != "default":
        refs.append((("robot", "model"), "robot", scenario["robot"]["model"]))
    footprint = scenario["gun"]["footprint"].strip()
    if footprint.lower().startswith("table:"):
        refs.append((("gun", "footprint"), "footprint", footprint.split(":", 1)[1].strip()))
    for i, entry in enumerate(scenario.get("variants", ())):
        if isinstance(entry, dict):  # a program of the user's own: its AS files
            refs += [(("variants", i, "program", j), "program", name) for j, name in enumerate(entry["program"])]
    return refs


def dotted(key: tuple) -> str:
    """``("variants", 2, "program", 0)`` -> ``variants[2].program[0]``."""
    return "".join(f"[{k}]" if isinstance(k, int) else (f".{k}" if i else k) for i, k in enumerate(key))


def _set(data: dict, key: tuple, value: Any) -> None:
    node = data
    for part in key[:-1]:
        node = node[part]
    node[key[-1]] = value


def bundle(scenario: Mapping[str, Any], base_dir: Path) -> Bundle:
    """Gather the files ``scenario`` (resolved, JSON-ready) names, relative to ``base_dir``;
    InputError (naming the key) when one cannot be read."""
    out = copy.deepcopy(dict(scenario))
    files: dict[str, Path] = {}
    digests: dict[str, str] = {}
    for key, role, written in _references(scenario):
        path = Path(written).expanduser()
        path = path if path.is_absolute() else base_dir / path
        try:
            check_input(path, "input file")
            members = _mjcf_files(path) if role == "robot" else [path]
            root = Path(os.path.commonpath([p.parent for p in members]))
            digest = _digest(members, root)
        except InputError as exc:
            raise InputError(f"{dotted(key)}: {exc}") from None
        digests[dotted(key)] = digest
        if role == "robot":
            folder = f"inputs/robot_{digest[:12]}"
            for member in members:
                files[f"{folder}/{member.relative_to(root).as_posix()}"] = member
            name = f"{folder}/{path.relative_to(root).as_posix()}"
        else:
            name = f"inputs/{role}_{digest[:12]}{path.suffix.lower()}"
            files[name] = path
        _set(out, key, f"table:{name}" if role == "footprint" else name)
    return Bundle(out, files, digests)


def with_absolute_paths(scenario: Mapping[str, Any], base_dir: Path) -> dict[str, Any]:
    """The scenario with every file it names by absolute path (``coatsim run`` on it, from any
    folder, reads the same files)."""
    out = copy.deepcopy(dict(scenario))
    for key, role, written in _references(scenario):
        path = Path(written).expanduser()
        path = path if path.is_absolute() else (base_dir / path).resolve()
        _set(out, key, f"table:{path}" if role == "footprint" else str(path))
    return out

"""The manifest of an output folder: what coatsim wrote there, so that a later run replaces only that.

``.coatsim-outputs.json``: ``{"format": "coatsim.outputs/1", "files": {name: {"sha256", "bytes",
"command"}}}``; a name ending in ``/`` is a folder coatsim made there (``{"folder": true,
"command"}``, e.g. a sweep's ``points/``). A planned name whose existing file is not in the
manifest, or changed since, is *foreign*: replaced only with ``force``. The manifest is read
without following links: one that is a symbolic link, a device, a FIFO or a folder is refused (exit
2); one that is unreadable or invalid counts as empty (every existing output is then foreign).
"""

from __future__ import annotations

import hashlib
import json
import os
import stat
from pathlib import Path
from typing import Iterable, Optional

from coatsim.core.errors import InputError
from coatsim.core.fileio import os_problem, special_kind, write_text
from coatsim.core.jsonfile import parse_json

MANIFEST_NAME = ".coatsim-outputs.json"
MANIFEST_FORMAT = "coatsim.outputs/1"
_MAX_MANIFEST_BYTES = 16 << 20
_NOFOLLOW = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)

Stamp = Optional[tuple[int, int, int, int]]


def _open_regular(path: Path) -> Optional[int]:
    """A descriptor of ``path`` if it is a regular file reached without a link, else None."""
    try:
        fd = os.open(path, _NOFOLLOW)
    except OSError:
        return None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return None
    return fd


def read_manifest(folder: Path) -> dict[str, dict]:
    """The entries of ``folder``'s manifest ({} when there is none or it is invalid)."""
    path = folder / MANIFEST_NAME
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return {}
    except OSError as exc:
        raise InputError(f"{path}: cannot read the output folder's manifest ({os_problem(exc)})") from None
    if not stat.S_ISREG(mode):
        raise InputError(f"{path}: the output folder's manifest is {special_kind(mode)}; coatsim neither reads nor "
                         "writes through it: remove it or choose another output folder")
    fd = _open_regular(path)
    if fd is None:
        return {}
    try:
        doc = parse_json(os.read(fd, _MAX_MANIFEST_BYTES).decode("utf-8"), str(path))
    except (OSError, ValueError, InputError):
        return {}
    finally:
        os.close(fd)
    files = doc.get("files") if isinstance(doc, dict) and doc.get("format") == MANIFEST_FORMAT else None
    return {k: v for k, v in files.items() if isinstance(v, dict)} if isinstance(files, dict) else {}


def _sha256(fd: int) -> str:
    digest = hashlib.sha256()
    with os.fdopen(os.dup(fd), "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def stamp(path: Path) -> Stamp:
    """Identity, size and time of ``path`` (None when absent): a change means it was written."""
    try:
        st = os.lstat(path)
    except OSError:
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _ours(path: Path, entry: Optional[dict]) -> bool:
    """Whether the existing ``path`` is what the manifest entry records."""
    if entry is None:
        return False
    if entry.get("folder"):
        return path.is_dir() and not path.is_symlink()
    fd = _open_regular(path)
    if fd is None:
        return False
    try:
        return os.fstat(fd).st_size == entry.get("bytes") and _sha256(fd) == entry.get("sha256")
    finally:
        os.close(fd)


def foreign(folder: Path, names: Iterable[str], manifest: dict[str, dict]) -> list[str]:
    """Planned names whose existing file (or folder, for a name ending in ``/``) coatsim did not
    write there, or that changed since."""
    return [name for name in names
            if os.path.lexists(folder / name) and not _ours(folder / name.rstrip("/"), manifest.get(name))]


def record(folder: Path, names: list[str], before: dict[str, Stamp], manifest: dict[str, dict], command: str) -> None:
    """Add the files this run replaced or created (a new stamp) and the folders it made to the
    manifest; drop entries whose file is gone."""
    written = {n for n in names if not n.endswith("/") and stamp(folder / n) not in (None, before[n])}
    made = {n for n in names if n.endswith("/") and (folder / n).is_dir() and not (folder / n.rstrip("/")).is_symlink()}
    if not written and made <= set(manifest):
        return
    files = {n: e for n, e in manifest.items() if n not in written and os.path.lexists(folder / n.rstrip("/"))}
    for name in made:
        files[name] = {"folder": True, "command": command}
    for name in written:
        fd = _open_regular(folder / name)
        if fd is None:
            continue
        try:
            files[name] = {"sha256": _sha256(fd), "bytes": os.fstat(fd).st_size, "command": command}
        finally:
            os.close(fd)
    doc = {"format": MANIFEST_FORMAT, "files": dict(sorted(files.items()))}
    write_text(folder / MANIFEST_NAME, json.dumps(doc, indent=2) + "\n")

"""Atomic file output: write to a temporary name in the same folder, then rename.

An interrupted run never leaves a half-written file under the final name.
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Iterator

from coatsim.core.errors import InputError


def _temporary_beside(target: Path) -> tuple[int, str]:
    """A new temporary file in ``target``'s folder (created if missing): (descriptor, name)."""
    folder = target.parent if str(target.parent) else Path(".")
    try:
        folder.mkdir(parents=True, exist_ok=True)
        return tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise InputError(f"{target}: cannot write ({exc.strerror or exc})") from None


def _rename(tmp: str, target: Path) -> None:
    try:
        os.replace(tmp, target)
    except OSError as exc:  # e.g. the target is an existing folder
        raise InputError(f"{target}: cannot write ({exc.strerror or exc})") from None


@contextmanager
def atomic_open(path: str | Path, mode: str = "w") -> Iterator[IO]:
    """Open a temporary file beside ``path``; rename it onto ``path`` on success."""
    target = Path(path)
    fd, tmp = _temporary_beside(target)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600; give the file the usual mode
    encoding = None if "b" in mode else "utf-8"
    try:
        with os.fdopen(fd, mode, encoding=encoding, newline="" if encoding else None) as handle:
            yield handle
        _rename(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    with atomic_open(path, "w") as handle:
        handle.write(text)


def write_bytes(path: str | Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_open(path, "wb") as handle:
        handle.write(data)


@contextmanager
def temporary_path(path: str | Path) -> Iterator[Path]:
    """A temporary file name beside ``path`` for a writer that takes a file name (an encoder);
    renamed onto ``path`` on success, removed on failure."""
    target = Path(path)
    fd, tmp = _temporary_beside(target)
    os.close(fd)
    try:
        yield Path(tmp)
        _rename(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


UTF8_BOM = b"\xef\xbb\xbf"


def read_input_bytes(path: str | Path, what: str) -> bytes:
    """The bytes of an input file; InputError naming ``what`` (e.g. "program") if it cannot be read."""
    try:
        return Path(path).read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot read {what} ({exc.strerror or exc})") from None


def decode_text(data: bytes) -> str:
    """Text of a program file: UTF-8 (a leading byte-order mark dropped) if valid, else Latin-1
    (controllers save 8-bit text)."""
    if data.startswith(UTF8_BOM):
        data = data[len(UTF8_BOM):]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")

"""Files in and out: every input read through one safe reader, every output written atomically.

Reading: an input must be a regular file. A folder, a named pipe (FIFO), a device, a socket or a
loop of symbolic links is refused by its type before anything is read (so ``/dev/zero`` never
fills memory and a FIFO never hangs the command: the file is opened non-blocking and its type
checked again on the open descriptor). The read is bounded by a size budget even when the size
the file system reports is wrong (``/proc`` files report 0).

Writing: to a temporary name in the same folder, then renamed, so an interrupted run never leaves
a half-written file under the final name. An output name that is a folder, a device, a FIFO or a
socket is refused (renaming over it would replace a device node or starve a FIFO's reader); a
symbolic link there is replaced, never written through.
"""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Iterator, Optional

from coatsim.core.budgets import check_budget, limit
from coatsim.core.errors import InputError

UTF8_BOM = b"\xef\xbb\xbf"
_CHUNK = 1 << 20
_OPEN_FLAGS = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)


def special_kind(mode: int) -> Optional[str]:
    """What a file of this mode is when it is not a regular file ("a folder", "a device", ...)."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISLNK(mode):
        return "a symbolic link"
    return "not a regular file"


def os_problem(exc: OSError) -> str:
    """An OSError in a few words ("no such file", "a loop of symbolic links", ...)."""
    words = {errno.ENOENT: "no such file", errno.ELOOP: "a loop of symbolic links (or too many of them)",
             errno.ENAMETOOLONG: "the file name is too long", errno.ENOTDIR: "a part of the path is not a folder",
             errno.EACCES: "permission denied", errno.EPERM: "operation not permitted",
             errno.EROFS: "read-only file system", errno.ENOSPC: "no space left on the device",
             errno.EISDIR: "is a folder", errno.EXDEV: "on another file system"}
    return words.get(exc.errno or 0, (exc.strerror or str(exc)).lower())


def _refuse_kind(path: str | Path, mode: int, what: str) -> None:
    kind = special_kind(mode)
    if kind is not None:
        raise InputError(f"{path}: is {kind}, not a file; give the {what} as a regular file")


@contextmanager
def open_input(path: str | Path, what: str) -> Iterator[int]:
    """A read-only descriptor of the regular file ``path``; InputError naming ``what`` (e.g.
    "curve file") for anything else or when it cannot be opened."""
    try:
        _refuse_kind(path, os.stat(path).st_mode, what)
        fd = os.open(path, _OPEN_FLAGS)
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read the {what} ({os_problem(exc)})") from None
    try:
        _refuse_kind(path, os.fstat(fd).st_mode, what)  # replaced between the check and the open
        yield fd
    finally:
        os.close(fd)


def check_input(path: str | Path, what: str, budget: str = "input_bytes") -> None:
    """Check, without reading it, that ``path`` is a regular file within the size budget (for a
    library that opens the file itself)."""
    with open_input(path, what) as fd:
        check_budget(f"{path}: bytes of the {what}", os.fstat(fd).st_size, budget, f"give a smaller {what}")


def read_input(path: str | Path, what: str, budget: str = "input_bytes") -> bytes:
    """The bytes of the regular file ``path``, at most the budget ``budget`` of them (checked
    against the reported size first, then while reading)."""
    cap = limit(budget)
    fix = f"give a smaller {what}"
    with open_input(path, what) as fd:
        check_budget(f"{path}: bytes of the {what}", os.fstat(fd).st_size, budget, fix)
        chunks, total = [], 0
        try:
            while True:
                block = os.read(fd, _CHUNK if cap - total > _CHUNK else int(cap - total) + 1)
                if not block:
                    break
                chunks.append(block)
                total += len(block)
                if total > cap:
                    check_budget(f"{path}: bytes of the {what} (more than the file system reports)", total, budget, fix)
        except OSError as exc:
            raise InputError(f"{path}: cannot read the {what} ({os_problem(exc)})") from None
    return b"".join(chunks)


def read_program_file(path: str | Path) -> bytes:
    """The bytes of a robot program file, its lines counted against the budget program_lines
    before anything parses them."""
    data = read_input(path, "program")
    check_budget(f"{path}: lines of the program", data.count(b"\n") + 1, "program_lines",
                 "split the program or program fewer points")
    return data


def decode_text(data: bytes) -> str:
    """Text of a program file: UTF-8 (a leading byte-order mark dropped) if valid, else Latin-1
    (controllers save 8-bit text)."""
    if data.startswith(UTF8_BOM):
        data = data[len(UTF8_BOM):]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


# --- output ------------------------------------------------------------------------------------

def check_output(target: Path) -> None:
    """Refuse an output name that is a folder, a device, a FIFO or a socket (a symbolic link is
    replaced by the rename, never followed)."""
    try:
        mode = os.lstat(target).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise InputError(f"{target}: cannot write ({os_problem(exc)})") from None
    if not (stat.S_ISREG(mode) or stat.S_ISLNK(mode)):
        raise InputError(f"{target}: is {special_kind(mode)}; coatsim writes its outputs as regular files only, "
                         "choose another output name")


def _temporary_beside(target: Path) -> tuple[int, str]:
    """A new temporary file in ``target``'s folder (created if missing): (descriptor, name)."""
    folder = target.parent if str(target.parent) else Path(".")
    check_output(target)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        return tempfile.mkstemp(prefix=f".{target.name[:100]}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise InputError(f"{target}: cannot write ({os_problem(exc)})") from None


def _rename(tmp: str, target: Path) -> None:
    check_output(target)  # made a device or a FIFO while the file was written
    try:
        os.replace(tmp, target)
    except OSError as exc:  # e.g. the target is an existing folder
        raise InputError(f"{target}: cannot write ({os_problem(exc)})") from None


@contextmanager
def atomic_open(path: str | Path, mode: str = "w") -> Iterator[IO]:
    """Open a temporary file beside ``path``; rename it onto ``path`` on success."""
    target = Path(path)
    fd, tmp = _temporary_beside(target)
    umask = os.umask(0)
    os.umask(umask)
    encoding = None if "b" in mode else "utf-8"
    try:
        os.fchmod(fd, 0o666 & ~umask)  # mkstemp creates 0600; give the file the usual mode
        with os.fdopen(fd, mode, encoding=encoding, newline="" if encoding else None) as handle:
            yield handle
        _rename(tmp, target)
    except OSError as exc:  # the device is full, the folder became read-only
        Path(tmp).unlink(missing_ok=True)
        raise InputError(f"{target}: cannot write ({os_problem(exc)})") from None
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

"""What a command may write: never onto one of its inputs, and into an output folder only
while it holds the folder, replacing only files coatsim wrote there before.

``check_distinct`` compares every output with every input and with the other outputs, by
resolved path (``./a.csv``, ``sub/../a.csv`` and symbolic links) and by file identity (hard
links, bind mounts), before anything is written. ``output_folder`` takes a folder for one run:
a lock file names the owning process (pid, host, command) and is held with ``flock``, so a lock
left by a killed run is stale and taken over (where ``flock`` is unavailable the recorded pid is
checked instead); a manifest (``.coatsim-outputs.json``) records the SHA-256 of every file
coatsim wrote there, and a file of a planned name that is not in it (or was changed since) is
replaced only with ``force``.
"""

from __future__ import annotations

import os
import stat
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Iterator, Optional

from coatsim.core.errors import InputError
from coatsim.core.fileio import os_problem, special_kind
from coatsim.core.folder_lock import LOCK_NAME, FolderInUse, FolderLock
from coatsim.core.manifest import MANIFEST_FORMAT, MANIFEST_NAME, foreign, read_manifest, record, stamp

__all__ = ["LOCK_NAME", "MANIFEST_FORMAT", "MANIFEST_NAME", "FolderInUse", "check_distinct", "output_folder"]

Labelled = tuple[str, Optional["str | Path"]]


@dataclass(frozen=True)
class _Identity:
    resolved: str
    inode: Optional[tuple[int, int]]

    def same_as(self, other: _Identity) -> bool:
        return self.resolved == other.resolved or (self.inode is not None and self.inode == other.inode)


def _identity(path: str | Path) -> _Identity:
    try:
        resolved = Path(path).expanduser().resolve()
    except (OSError, RuntimeError):  # a loop of symbolic links: compared by its own name
        resolved = Path(os.path.abspath(Path(path).expanduser()))
    try:
        st = os.stat(resolved)
        inode = (st.st_dev, st.st_ino)
    except OSError:
        inode = None
    return _Identity(str(resolved), inode)


def check_distinct(inputs: Iterable[Labelled], outputs: Iterable[Labelled]) -> None:
    """Raise an InputError naming both paths when an output is an input or two outputs are one
    file. Labels say what a path is (``--plot``, ``the input curve``); None paths are skipped."""
    ins = [(label, str(p), _identity(p)) for label, p in inputs if p is not None]
    seen: list[tuple[str, str, _Identity]] = []
    for label, p in outputs:
        if p is None:
            continue
        out = _identity(p)
        for in_label, in_path, ident in ins:
            if out.same_as(ident):
                raise InputError(f"{label} {p} is the same file as {in_label} {in_path}; writing it would "
                                 "overwrite that input, choose another output name")
        for other_label, other_path, ident in seen:
            if out.same_as(ident):
                raise InputError(f"{other_label} {other_path} and {label} {p} are the same file; give each "
                                 "output its own name")
        seen.append((label, str(p), out))


@contextmanager
def output_folder(folder: str | Path, names: Iterable[str], command: str, force: bool = False) -> Iterator[Path]:
    """Hold ``folder`` for one run that writes the files ``names`` into it (a name ending in
    ``/``: a folder it owns; see the module docstring); at exit record what the run wrote in the
    manifest and release the lock.

    Raises FolderInUse when another process holds the folder, InputError when the folder is not
    a folder that can be written, its lock or manifest is not a regular file, or a planned file
    exists that coatsim did not write there (unless ``force``).
    """
    folder = Path(folder)
    names = list(dict.fromkeys(names))
    created = _make_folder(folder)
    lock = FolderLock(folder, command)
    try:
        lock.acquire()
    except BaseException:
        lock.abandon()
        if created:
            _remove_if_empty(folder)
        raise
    try:
        manifest = read_manifest(folder)
        _refuse_special(folder, names)
        found = [] if force else foreign(folder, names, manifest)
        if found:
            more = f" and {len(found) - 1} more" if len(found) > 1 else ""
            raise InputError(f"{folder / found[0]}{more}: not written by coatsim (or changed since); "
                             "move it away, choose another output folder or pass --force to replace it")
        before = {name: stamp(folder / name) for name in names}
        try:
            yield folder
        finally:
            record(folder, names, before, manifest, command)
    finally:
        lock.release()
        if created:
            _remove_if_empty(folder)


def _make_folder(folder: Path) -> bool:
    """Create the output folder if missing (True when this call made it); InputError when the
    path is anything but a folder or cannot be made."""
    try:
        mode = os.stat(folder).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:
        raise InputError(f"{folder}: cannot use as the output folder ({os_problem(exc)})") from None
    if mode is not None and not stat.S_ISDIR(mode):
        kind = special_kind(mode)
        raise InputError(f"{folder}: is {'a file' if kind is None else kind}, expected an output folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"{folder}: cannot create the output folder ({os_problem(exc)})") from None
    return mode is None


def _refuse_special(folder: Path, names: list[str]) -> None:
    """Even with force, an output name that is a folder, a device, a FIFO or a socket is not
    replaced (a symbolic link is: the rename replaces the link, never its target)."""
    for name in names:
        path = folder / name.rstrip("/")
        try:
            mode = os.lstat(path).st_mode
        except OSError:
            continue
        wanted = stat.S_ISDIR(mode) if name.endswith("/") else stat.S_ISREG(mode)
        if not (wanted or stat.S_ISLNK(mode) and not name.endswith("/")):
            raise InputError(f"{path}: is {special_kind(mode) or 'a file'}; coatsim replaces only "
                             f"{'folders' if name.endswith('/') else 'regular files'} in an output folder: move it "
                             "away or choose another output folder")


def _remove_if_empty(folder: Path) -> None:
    try:
        folder.rmdir()
    except OSError:
        pass

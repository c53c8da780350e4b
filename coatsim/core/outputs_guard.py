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

import hashlib
import json
import os
import socket
import warnings
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Iterator, Optional

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.fileio import write_text

LOCK_NAME = ".coatsim.lock"
MANIFEST_NAME = ".coatsim-outputs.json"
MANIFEST_FORMAT = "coatsim.outputs/1"

Labelled = tuple[str, Optional["str | Path"]]


class FolderInUse(InputError):
    """Another coatsim process holds the output folder (exit 2)."""


@dataclass(frozen=True)
class _Identity:
    resolved: str
    inode: Optional[tuple[int, int]]

    def same_as(self, other: _Identity) -> bool:
        return self.resolved == other.resolved or (self.inode is not None and self.inode == other.inode)


def _identity(path: str | Path) -> _Identity:
    resolved = Path(path).expanduser().resolve()
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


def _owner_text(info: dict) -> str:
    return (f"{info.get('command', 'coatsim')} (pid {info.get('pid', '?')} on {info.get('host', '?')}, "
            f"started {info.get('started', '?')})")


def _pid_alive(pid: object) -> bool:
    if not isinstance(pid, int) or pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def _read_info(path: Path) -> dict:
    try:
        info = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return info if isinstance(info, dict) else {}


class _Lock:
    """The folder's lock file, held (flock) from ``acquire`` until ``release``."""

    def __init__(self, folder: Path, command: str):
        import datetime

        self.path = folder / LOCK_NAME
        self.info = {"command": command, "pid": os.getpid(), "host": socket.gethostname(),
                     "started": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}
        self.fd: Optional[int] = None
        self.created = False  # this process made the lock file (and removes it if interrupted before holding it)

    def _refuse(self, info: dict) -> None:
        raise FolderInUse(f"{self.path.parent}: output folder in use by {_owner_text(info)}; wait for it to "
                          "finish or choose another output folder")

    def _stale(self, info: dict) -> None:
        if info:
            warnings.warn(f"{self.path.parent}: took over the lock of {_owner_text(info)}, which is no longer "
                          "running; files it was writing there may be incomplete", CoatsimWarning, stacklevel=4)

    def acquire(self) -> None:
        try:
            import fcntl
        except ImportError:  # no flock on this platform
            return self._acquire_by_pid()
        for _ in range(100):
            try:
                fd, created = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o644), True
                self.created = True
            except FileExistsError:
                try:
                    fd, created = os.open(self.path, os.O_RDWR), False
                except FileNotFoundError:
                    continue
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:  # another run holds it (even if this one made the file)
                os.close(fd)
                self.created = False
                self._refuse(_read_info(self.path))
            except OSError:  # the file system has no flock
                os.close(fd)
                if created:
                    self.path.unlink(missing_ok=True)
                self.created = False
                return self._acquire_by_pid()
            try:  # the holder may have removed the file between our open and flock
                same = os.path.samestat(os.fstat(fd), os.stat(self.path))
            except FileNotFoundError:
                same = False
            if not same:
                os.close(fd)
                self.created = False
                continue
            self._stale(_read_info(self.path))
            os.ftruncate(fd, 0)
            os.write(fd, (json.dumps(self.info) + "\n").encode())
            self.fd = fd
            return None
        raise FolderInUse(f"{self.path.parent}: cannot take the output folder's lock (it keeps changing)")

    def _acquire_by_pid(self) -> None:
        for _ in range(2):
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
            except FileExistsError:
                info = _read_info(self.path)
                if info.get("host") != self.info["host"] or _pid_alive(info.get("pid")):
                    self._refuse(info)
                self._stale(info)
                self.path.unlink(missing_ok=True)
                continue
            os.write(fd, (json.dumps(self.info) + "\n").encode())
            os.close(fd)
            return
        self._refuse(_read_info(self.path))

    def abandon(self) -> None:
        """Undo a lock file this process created but never came to hold (an interrupt or a
        refusal during ``acquire``)."""
        if self.fd is None and self.created:
            self.path.unlink(missing_ok=True)

    def release(self) -> None:
        self.path.unlink(missing_ok=True)
        if self.fd is not None:
            os.close(self.fd)  # releases the flock
            self.fd = None


def _sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _read_manifest(folder: Path) -> dict[str, dict]:
    doc = _read_info(folder / MANIFEST_NAME)
    files = doc.get("files") if doc.get("format") == MANIFEST_FORMAT else None
    return {k: v for k, v in files.items() if isinstance(v, dict)} if isinstance(files, dict) else {}


def _stamp(path: Path) -> Optional[tuple[int, int, int, int]]:
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _foreign(folder: Path, names: Iterable[str], manifest: dict[str, dict]) -> list[str]:
    """Planned names whose existing file coatsim did not write (or that changed since)."""
    found = []
    for name in names:
        path = folder / name
        if not os.path.lexists(path):
            continue
        if path.is_symlink() or not path.is_file():
            found.append(name)
        elif manifest.get(name, {}).get("sha256") != _sha256(path):
            found.append(name)
    return found


@contextmanager
def output_folder(folder: str | Path, names: Iterable[str], command: str, force: bool = False) -> Iterator[Path]:
    """Hold ``folder`` for one run that writes the files ``names`` into it (see the module
    docstring); at exit record every file the run wrote in the manifest and release the lock.

    Raises FolderInUse when another process holds the folder, InputError when a planned file
    exists that coatsim did not write there (unless ``force``).
    """
    folder = Path(folder)
    names = list(dict.fromkeys(names))
    if os.path.lexists(folder) and not folder.is_dir():
        raise InputError(f"{folder}: is a file, expected an output folder")
    created = not folder.exists()
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"{folder}: cannot create the output folder ({exc.strerror or exc})") from None
    lock = _Lock(folder, command)
    try:
        lock.acquire()
    except BaseException:
        lock.abandon()
        if created:
            _remove_if_empty(folder)
        raise
    try:
        manifest = _read_manifest(folder)
        foreign = [] if force else _foreign(folder, names, manifest)
        if foreign:
            more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
            raise InputError(f"{folder / foreign[0]}{more}: not written by coatsim (or changed since); "
                             "move it away, choose another output folder or pass --force to replace it")
        before = {name: _stamp(folder / name) for name in names}
        try:
            yield folder
        finally:
            _record(folder, names, before, manifest, command)
    finally:
        lock.release()
        if created:
            _remove_if_empty(folder)


def _record(folder: Path, names: list[str], before: dict, manifest: dict[str, dict], command: str) -> None:
    """Add the files this run replaced or created (new stamp) to the manifest; drop vanished ones."""
    written = {n for n in names if _stamp(folder / n) not in (None, before[n])}
    if not written:
        return
    files = {n: e for n, e in manifest.items() if n not in written and (folder / n).is_file()}
    for name in written:
        path = folder / name
        files[name] = {"sha256": _sha256(path), "bytes": path.stat().st_size, "command": command}
    doc = {"format": MANIFEST_FORMAT, "files": dict(sorted(files.items()))}
    write_text(folder / MANIFEST_NAME, json.dumps(doc, indent=2) + "\n")


def _remove_if_empty(folder: Path) -> None:
    try:
        folder.rmdir()
    except OSError:
        pass

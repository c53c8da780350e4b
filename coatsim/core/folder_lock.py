"""The lock of an output folder: one process at a time, a stale lock taken over.

``.coatsim.lock`` names its owner (pid, host, command, start time) and is held with ``flock``, so
a lock left by a killed process is stale and taken over (where ``flock`` is unavailable the
recorded pid is checked instead). It is only ever opened as the regular file coatsim made: never
through a symbolic link (``O_NOFOLLOW``), never a FIFO, a device, a folder or a file with other
names (hard links), each of which is refused (exit 2) without being written.
"""

from __future__ import annotations

import datetime
import json
import os
import socket
import stat
import warnings
from pathlib import Path
from typing import Optional

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.fileio import os_problem, special_kind
from coatsim.core.jsonfile import parse_json

LOCK_NAME = ".coatsim.lock"
_MAX_LOCK_BYTES = 1 << 16
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0) | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0)


class FolderInUse(InputError):
    """Another coatsim process holds the output folder (exit 2)."""


def owner_text(info: dict) -> str:
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
    except OverflowError:
        return False
    return True


def _info(fd: int) -> dict:
    """The owner recorded in an open lock file ({} when it is unreadable)."""
    try:
        info = parse_json(os.pread(fd, _MAX_LOCK_BYTES, 0).decode("utf-8"), "lock")
    except (OSError, ValueError, InputError):
        return {}
    return info if isinstance(info, dict) else {}


class FolderLock:
    """The folder's lock file, held from ``acquire`` until ``release``."""

    def __init__(self, folder: Path, command: str):
        self.path = folder / LOCK_NAME
        self.info = {"command": command, "pid": os.getpid(), "host": socket.gethostname(),
                     "started": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}
        self.fd: Optional[int] = None
        self.identity: Optional[tuple[int, int]] = None
        self.created = False  # this process made the lock file (and removes it if interrupted before holding it)

    def _refuse(self, info: dict) -> None:
        raise FolderInUse(f"{self.path.parent}: output folder in use by {owner_text(info)}; wait for it to "
                          "finish or choose another output folder")

    def _stale(self, info: dict) -> None:
        if info:
            warnings.warn(f"{self.path.parent}: took over the lock of {owner_text(info)}, which is no longer "
                          "running; files it was writing there may be incomplete", CoatsimWarning, stacklevel=4)

    def _not_ours(self, why: str) -> InputError:
        return InputError(f"{self.path}: the output folder's lock {why}; coatsim never writes through it: remove it "
                          "or choose another output folder")

    def _open(self, create: bool) -> int:
        """The lock file opened read-write without following a link; InputError for anything but
        a regular file of one name; FileExistsError / FileNotFoundError as os.open raises them."""
        try:
            mode = os.lstat(self.path).st_mode
        except FileNotFoundError:
            mode = None
        except OSError as exc:
            raise self._not_ours(f"cannot be read ({os_problem(exc)})") from None
        if mode is not None and not stat.S_ISREG(mode):
            raise self._not_ours(f"is {special_kind(mode)}")
        flags = os.O_RDWR | _NOFOLLOW | (os.O_CREAT | os.O_EXCL if create else 0)
        try:
            fd = os.open(self.path, flags, 0o644)
        except (FileExistsError, FileNotFoundError):
            raise
        except OSError as exc:
            raise self._not_ours(f"cannot be opened ({os_problem(exc)})") from None
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode) or st.st_nlink != 1:
            os.close(fd)
            raise self._not_ours("has other names (hard links)" if stat.S_ISREG(st.st_mode) else
                                 f"is {special_kind(st.st_mode)}")
        return fd

    def _hold(self, fd: int) -> None:
        os.ftruncate(fd, 0)
        os.pwrite(fd, (json.dumps(self.info) + "\n").encode(), 0)
        st = os.fstat(fd)
        self.fd, self.identity = fd, (st.st_dev, st.st_ino)

    def acquire(self) -> None:
        try:
            import fcntl
        except ImportError:  # no flock on this platform
            return self._acquire_by_pid()
        for _ in range(100):
            try:
                fd, created = self._open(create=True), True
                self.created = True
            except FileExistsError:
                try:
                    fd, created = self._open(create=False), False
                except FileNotFoundError:
                    continue
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:  # another run holds it (even if this one made the file)
                info = _info(fd)
                os.close(fd)
                self.created = False
                self._refuse(info)
            except OSError:  # the file system has no flock
                os.close(fd)
                if created:
                    self.path.unlink(missing_ok=True)
                self.created = False
                return self._acquire_by_pid()
            if not self._same(fd):  # the holder removed the file between our open and flock
                os.close(fd)
                self.created = False
                continue
            self._stale(_info(fd))
            self._hold(fd)
            return None
        raise FolderInUse(f"{self.path.parent}: cannot take the output folder's lock (it keeps changing)")

    def _same(self, fd: int) -> bool:
        try:
            return os.path.samestat(os.fstat(fd), os.lstat(self.path))
        except FileNotFoundError:
            return False

    def _acquire_by_pid(self) -> None:
        for _ in range(2):
            try:
                fd = self._open(create=True)
            except FileExistsError:
                try:
                    fd = self._open(create=False)
                except FileNotFoundError:
                    continue
                info = _info(fd)
                os.close(fd)
                if info.get("host") != self.info["host"] or _pid_alive(info.get("pid")):
                    self._refuse(info)
                self._stale(info)
                self.path.unlink(missing_ok=True)
                continue
            self.created = True
            self._hold(fd)
            os.close(fd)
            self.fd = None
            return
        self._refuse({})

    def abandon(self) -> None:
        """Undo a lock file this process created but never came to hold (an interrupt or a
        refusal during ``acquire``)."""
        if self.fd is None and self.identity is None and self.created:
            self.path.unlink(missing_ok=True)

    def release(self) -> None:
        """Remove the lock file (only if it is still the one this process holds) and release it."""
        try:
            st = os.lstat(self.path)
            if (st.st_dev, st.st_ino) == self.identity:
                self.path.unlink()
        except FileNotFoundError:
            pass
        if self.fd is not None:
            os.close(self.fd)  # releases the flock
            self.fd = None
        self.identity = None

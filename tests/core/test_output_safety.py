"""Never write through what coatsim did not create: locks, manifests and outputs are opened without
following links and only as regular files; special files and read-only folders are one-line errors
and nothing is written anywhere else."""

from __future__ import annotations

import os
import socket
import stat
import subprocess
import sys

import pytest

from cli_helpers import cli
from coatsim.core.errors import InputError
from coatsim.core.fileio import write_text
from coatsim.core.outputs_guard import LOCK_NAME, MANIFEST_NAME, output_folder

PRECIOUS = "precious user data\n"


def _victim(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text(PRECIOUS)
    return victim


def _special(kind: str, path) -> None:
    if kind == "symlink":
        path.symlink_to(path.parent.parent / "victim.txt")
    elif kind == "loop":
        path.symlink_to(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "socket":
        socket.socket(socket.AF_UNIX).bind(str(path))
    elif kind == "hardlink":
        os.link(path.parent.parent / "victim.txt", path)


KINDS = ["symlink", "loop", "folder", "fifo", "socket", "hardlink"]


@pytest.mark.parametrize("force", [False, True])
@pytest.mark.parametrize("name", [LOCK_NAME, MANIFEST_NAME])
@pytest.mark.parametrize("kind", KINDS)
def test_a_lock_or_manifest_that_is_not_a_regular_file_of_ours_is_refused(tmp_path, name, kind, force):
    victim = _victim(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    _special(kind, out / name)
    if (kind, name) == ("hardlink", MANIFEST_NAME):  # replaced by a rename: the other name keeps its data
        with output_folder(out, ["metrics.json"], "coatsim run", force):
            write_text(out / "metrics.json", "{}")
        assert victim.read_text() == PRECIOUS
        return
    with pytest.raises(InputError) as info:
        with output_folder(out, ["metrics.json"], "coatsim run", force):
            write_text(out / "metrics.json", "{}")
    assert "\n" not in str(info.value)
    assert victim.read_text() == PRECIOUS
    assert not (out / "metrics.json").exists()


@pytest.mark.parametrize("kind", ["fifo", "socket", "folder"])
@pytest.mark.parametrize("force", [[], ["--force"]])
def test_an_output_name_that_is_a_special_file_is_refused_even_with_force(tmp_path, kind, force):
    target = tmp_path / "out.json"
    _special(kind, target)
    code, _, err = cli("segment", "builtin:ellipse:a=40,b=20", "--tol", "0.2", "-o", target, *force)
    assert code == 2 and err.count("\n") == 1, err
    mode = os.lstat(target).st_mode
    assert {"fifo": stat.S_ISFIFO, "socket": stat.S_ISSOCK, "folder": stat.S_ISDIR}[kind](mode)


def test_an_output_name_that_is_a_symlink_is_replaced_never_written_through(tmp_path):
    victim = _victim(tmp_path)
    target = tmp_path / "out.json"
    target.symlink_to(victim)
    assert cli("segment", "builtin:ellipse:a=40,b=20", "--tol", "0.2", "-o", target)[0] == 0
    assert victim.read_text() == PRECIOUS and not target.is_symlink()


def _immutable(path) -> bool:
    return subprocess.run(["chattr", "+i", str(path)], capture_output=True).returncode == 0


def test_a_read_only_output_folder_is_one_line(tmp_path):
    out = tmp_path / "frozen"
    out.mkdir()
    if not _immutable(out):
        pytest.skip("chattr +i is not available here (root writes into any mode-555 folder)")
    try:
        code, _, err = cli("coat", tmp_path / "none.csv", "--surface", "plate:100x100@0,0,0", "-o", out)
        assert code == 2 and err.count("\n") == 1, err
        with pytest.raises(InputError, match="cannot"):
            with output_folder(out, ["metrics.json"], "coatsim run"):
                pass
    finally:
        subprocess.run(["chattr", "-i", str(out)], capture_output=True)


@pytest.mark.parametrize("args", [["--version"], ["--help"], ["segment", "builtin:ellipse", "--tol", "0.5"]])
def test_stdout_on_a_full_device_is_one_line(args):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with open("/dev/full", "w") as full:
        proc = subprocess.run([sys.executable, "-m", "coatsim.cli", *args], stdout=full, stderr=subprocess.PIPE,
                              text=True, env={**os.environ, "COLUMNS": "100"}, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1 and "No space left" in proc.stderr, proc.stderr

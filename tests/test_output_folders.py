"""Output folders (issue 14 item 3): one run at a time (a lock naming its process, stale locks
taken over), and only files coatsim wrote there are replaced (a manifest); others need --force."""

from __future__ import annotations

import errno
import json
import os
import socket
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
from cli_helpers import cli

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.outputs_guard import LOCK_NAME, MANIFEST_NAME, FolderInUse, output_folder

TINY = """\
name: tiny_job
curve: {builtin: ellipse, params: {a: 30.0, b: 20.0}}
workpiece: {kind: plate, size_mm: [100.0, 80.0]}
motion: {speed_mm_s: 200.0, lead_in_mm: 5.0, lead_out_mm: 5.0}
variants: [polysegment]
fast: {coating_spacing_mm: 4.0, sample_step_mm: 2.0}
"""




def coatsim(*args: object, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "coatsim.cli", *map(str, args)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, **kwargs)


@pytest.fixture
def scenario(tmp_path: Path) -> Path:
    path = tmp_path / "tiny_job.yaml"
    path.write_text(TINY)
    return path


HOLD = textwrap.dedent("""\
    import sys
    from coatsim.core.outputs_guard import output_folder
    with output_folder(sys.argv[1], ["metrics.json"], "coatsim run"):
        print("held", flush=True)
        sys.stdin.readline()
""")


def test_a_second_run_is_refused_while_another_process_holds_the_folder(tmp_path, scenario):
    out = tmp_path / "out"
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(out)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                              text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        code, _, err = cli("run", scenario, "--fast", "-o", out)
        assert code == 2 and err.count("\n") == 1, err
        assert f"{out}: output folder in use by coatsim run (pid {holder.pid} on {socket.gethostname()}" in err
        assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]  # the refused run wrote nothing
    finally:
        holder.communicate("\n", timeout=60)
    assert holder.returncode == 0
    assert not (out / LOCK_NAME).exists()  # removed at the end
    code, _, err = cli("run", scenario, "--fast", "-o", out)
    assert code == 0, err


@pytest.mark.slow
def test_two_coatsim_runs_into_one_folder(tmp_path, scenario):
    """Two real `coatsim run` processes: the second is refused while the first runs, and the folder
    holds the first run's outputs only."""
    other = tmp_path / "other_job.yaml"
    other.write_text(TINY.replace("tiny_job", "other_job"))
    long_job = tmp_path / "long_job.yaml"  # all three variants at full resolution: long enough to overlap
    long_job.write_text(TINY.replace("tiny_job", "long_job").replace("variants: [polysegment]\n", "")
                        + "coating: {spacing_mm: 0.5}\n")
    out = tmp_path / "out"
    first = coatsim("run", long_job, "-o", out)
    deadline = time.monotonic() + 120
    while not (out / LOCK_NAME).exists() and first.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    second = coatsim("run", other, "--fast", "-o", out)
    _, err2 = second.communicate(timeout=300)
    _, err1 = first.communicate(timeout=600)
    assert first.returncode == 0, err1
    assert second.returncode == 2 and "output folder in use by coatsim run (pid" in err2, err2
    assert json.loads((out / "metrics.json").read_text())["scenario"]["name"] == "long_job"


def test_a_stale_lock_is_taken_over_with_a_warning(tmp_path, scenario):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    out = tmp_path / "out"
    out.mkdir()
    (out / LOCK_NAME).write_text(json.dumps({"command": "coatsim run", "pid": dead.pid,
                                             "host": socket.gethostname(), "started": "earlier"}))
    code, _, err = cli("run", scenario, "--fast", "-o", out)
    assert code == 0, err
    assert f"coatsim: warning: {out}: took over the lock of coatsim run (pid {dead.pid}" in err
    assert "no longer running" in err
    assert not (out / LOCK_NAME).exists()


@pytest.fixture
def no_flock(monkeypatch):
    """A file system without flock: the lock falls back to the recorded pid."""
    import fcntl

    def refuse(fd, op):
        raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(fcntl, "flock", refuse)


def test_without_flock_a_live_pid_holds_and_a_dead_one_is_stale(tmp_path, no_flock):
    folder = tmp_path / "out"
    folder.mkdir()
    lock = folder / LOCK_NAME
    with output_folder(folder, ["a.txt"], "first"):
        assert json.loads(lock.read_text())["pid"] == os.getpid()
        with pytest.raises(FolderInUse, match=f"in use by first \\(pid {os.getpid()}"):
            with output_folder(folder, ["a.txt"], "second"):
                pass
    assert not lock.exists()
    with subprocess.Popen([sys.executable, "-c", "import sys; sys.stdin.read()"], stdin=subprocess.PIPE) as alive:
        lock.write_text(json.dumps({"pid": alive.pid, "host": socket.gethostname(), "command": "coatsim coat"}))
        with pytest.raises(FolderInUse, match=f"in use by coatsim coat \\(pid {alive.pid}"):
            with output_folder(folder, ["a.txt"], "test"):
                pass
        alive.stdin.close()
    lock.write_text(json.dumps({"pid": alive.pid, "host": socket.gethostname(), "command": "coatsim coat"}))
    with pytest.warns(CoatsimWarning, match="no longer running"):
        with output_folder(folder, ["a.txt"], "test"):
            assert json.loads(lock.read_text())["pid"] == os.getpid()
    assert not lock.exists()
    lock.write_text(json.dumps({"pid": 1, "host": "elsewhere", "command": "coatsim run"}))
    with pytest.raises(FolderInUse, match="on elsewhere"):  # another host's process cannot be checked
        with output_folder(folder, ["a.txt"], "test"):
            pass


def test_in_process_claims_exclude_each_other(tmp_path):
    with output_folder(tmp_path / "x", ["a.txt"], "first"):
        with pytest.raises(FolderInUse, match=f"in use by first \\(pid {os.getpid()}"):
            with output_folder(tmp_path / "x", ["b.txt"], "second"):
                pass
    with output_folder(tmp_path / "x", ["b.txt"], "third"):
        pass
    assert not (tmp_path / "x").exists()  # created for a run that wrote nothing: removed again


# --- only files coatsim wrote are replaced -------------------------------------------------

def test_a_users_file_under_an_output_name_needs_force(tmp_path, scenario):
    out = tmp_path / "out"
    out.mkdir()
    mine = out / "report.html"
    mine.write_text("<p>my notes</p>")
    code, _, err = cli("run", scenario, "--fast", "-o", out)
    assert code == 2 and err.count("\n") == 1, err
    assert f"{mine}: not written by coatsim (or changed since)" in err and "--force" in err
    assert mine.read_text() == "<p>my notes</p>"
    assert sorted(p.name for p in out.iterdir()) == ["report.html"]
    code, _, err = cli("run", scenario, "--fast", "-o", out, "--force")
    assert code == 0, err
    manifest = json.loads((out / MANIFEST_NAME).read_text())
    assert manifest["format"] == "coatsim.outputs/1"
    assert set(manifest["files"]) == {"polysegment.json", "polysegment.as", "polysegment.trajectory.csv",
                                      "polysegment.thickness.ply", "polysegment.thickness.glb", "metrics.json",
                                      "report.html"}
    code, _, err = cli("run", scenario, "--fast", "-o", out)  # its own files: replaced without --force
    assert code == 0, err
    (out / "metrics.json").write_text("{}")  # changed by hand since coatsim wrote it
    code, _, err = cli("run", scenario, "--fast", "-o", out)
    assert code == 2 and "metrics.json: not written by coatsim (or changed since)" in err


def test_execute_and_coat_keep_foreign_files(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "speed.png").write_bytes(b"a photo")
    (out / "section.png").write_bytes(b"another")
    code, _, err = cli("execute", Path(__file__).parent / "robot" / "data" / "missing.as", "-o", out)
    assert code == 2  # no such program: refused before the folder is touched
    prog = tmp_path / "p.as"
    assert cli("program", "builtin:ellipse:a=40,b=20,points=300", "--tol", "0.2", "-o", prog)[0] == 0
    code, _, err = cli("execute", prog, "-o", out, "--step-mm", "4")
    assert code == 2 and "speed.png: not written by coatsim" in err, err
    code, _, err = cli("coat", out / "missing.csv", "--surface", "plate:100x100@700,0,100", "-o", out)
    assert code == 2
    assert (out / "speed.png").read_bytes() == b"a photo" and (out / "section.png").read_bytes() == b"another"
    assert sorted(p.name for p in out.iterdir()) == ["section.png", "speed.png"]


def test_an_output_folder_that_is_a_file_is_refused(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(InputError, match="is a file, expected an output folder"):
        with output_folder(tmp_path / "f", ["a"], "test"):
            pass

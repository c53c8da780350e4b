"""No output may be an input (issue 14 item 2): every command compares its outputs with its
inputs and with each other, by resolved path and by file identity, before it writes."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import pytest
import trimesh
from cli_helpers import cli
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.core.outputs_guard import check_distinct


def write_arc(path: Path, n: int = 60) -> bytes:
    t = np.linspace(0.0, np.pi / 2, n)
    path.write_text("".join(f"{100 * np.cos(a):.6f},{100 * np.sin(a):.6f}\n" for a in t))
    return path.read_bytes()


def assert_refused(result: tuple[int, str, str], *names: str) -> None:
    code, _, err = result
    assert code == 2, err
    assert err.startswith("coatsim: error: ") and err.count("\n") == 1, err
    assert "same file" in err, err
    for name in names:
        assert name in err, err


# --- the exact inputs of the issue ------------------------------------------------------------

def test_segment_onto_its_input_is_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    original = write_arc(tmp_path / "a.csv")
    assert_refused(cli("segment", "a.csv", "-o", "a.csv"), "-o a.csv", "the input curve a.csv")
    assert_refused(cli("segment", "a.csv", "--tol", "0.1", "--plot", "a.csv"), "--plot a.csv")
    assert (tmp_path / "a.csv").read_bytes() == original


def test_json_and_plot_under_one_name_are_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_arc(tmp_path / "a.csv")
    assert_refused(cli("segment", "a.csv", "-o", "X", "--plot", "X"), "-o X", "--plot X")
    assert not (tmp_path / "X").exists()


def test_program_onto_its_polysegment_json_is_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write_arc(tmp_path / "a.csv")
    assert cli("segment", "a.csv", "-o", "a.json")[0] == 0
    original = (tmp_path / "a.json").read_bytes()
    assert_refused(cli("program", "a.json", "-o", "a.json"), "-o a.json", "the input a.json")
    assert_refused(cli("program", "a.csv", "--tol", "0.1", "-o", "./a.csv"), "-o a.csv", "the input a.csv")
    assert (tmp_path / "a.json").read_bytes() == original


def test_execute_and_coat_refuse_an_output_name_that_is_their_input(tmp_path):
    program = tmp_path / "motion.json"  # an AS program saved under the name of an output
    program.write_text(".PROGRAM p()\n  LMOVE a\n.END\n")
    assert_refused(cli("execute", program, "-o", tmp_path), "output", "the program")
    assert program.read_text() == ".PROGRAM p()\n  LMOVE a\n.END\n"
    log = tmp_path / "coating.json"  # a trajectory saved under the name of an output
    log.write_text("t_s,x_mm\n0,0\n")
    assert_refused(cli("coat", log, "--surface", "plate:100x100@0,0,0", "-o", tmp_path), "the trajectory")
    assert log.read_text() == "t_s,x_mm\n0,0\n"


def test_run_refuses_a_workpiece_mesh_that_a_run_would_replace(tmp_path):
    mesh = tmp_path / "polysegment.thickness.ply"
    trimesh.creation.box((200.0, 100.0, 2.0)).export(mesh)
    original = mesh.read_bytes()
    scenario = tmp_path / "job.yaml"
    scenario.write_text("name: job\ncurve: {builtin: ellipse, params: {a: 30, b: 20}}\n"
                        "workpiece: {kind: mesh, file: polysegment.thickness.ply}\nvariants: [polysegment]\n")
    assert_refused(cli("run", scenario, "-o", tmp_path), "workpiece.file", "polysegment.thickness.ply")
    assert mesh.read_bytes() == original
    scenario_as_output = tmp_path / "metrics.json"
    scenario_as_output.write_text(scenario.read_text().replace("mesh, file: polysegment.thickness.ply",
                                                               "plate, size_mm: [100, 80]"))
    assert_refused(cli("run", scenario_as_output, "-o", tmp_path), "the scenario")


def test_check_distinct_sees_symlinks_and_hard_links(tmp_path):
    a = tmp_path / "a.csv"
    a.write_text("0,0\n1,1\n")
    (tmp_path / "link.csv").symlink_to(a)
    os.link(a, tmp_path / "hard.csv")
    for alias in ("link.csv", "hard.csv", "./a.csv", "sub/../a.csv"):
        (tmp_path / "sub").mkdir(exist_ok=True)
        with pytest.raises(InputError, match="same file"):
            check_distinct([("the input", a)], [("-o", tmp_path / alias)])
    check_distinct([("the input", a)], [("-o", tmp_path / "b.json"), ("--plot", tmp_path / "b.png")])
    check_distinct([("builtin", None)], [("-o", None), ("--plot", tmp_path / "b.png")])


# --- property: whatever the combination, no input is ever modified -----------------------------

NAMES = ["a.csv", "./a.csv", "sub/../a.csv", "link.csv", "hard.csv", "ABS", "out.json", "./out.json",
         "out.png", "sub/out.json", "linkdir/out.json", "dangling.json"]


def _setup(folder: Path) -> bytes:
    original = write_arc(folder / "a.csv", 40)
    (folder / "sub").mkdir()
    (folder / "link.csv").symlink_to("a.csv")
    os.link(folder / "a.csv", folder / "hard.csv")
    (folder / "linkdir").symlink_to("sub")
    (folder / "dangling.json").symlink_to("sub/out.json")  # points where another name writes
    return original


def _real(folder: Path, name: str) -> str:
    """What a name stands for: the inode of an existing file (hard links too), else its real path."""
    path = os.path.realpath(folder / "a.csv" if name == "ABS" else folder / name)
    return f"inode {os.stat(path).st_ino}" if os.path.exists(path) else path


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(command=st.sampled_from(["segment", "program"]), source=st.sampled_from(NAMES[:6]),
       output=st.one_of(st.none(), st.sampled_from(NAMES)), plot=st.one_of(st.none(), st.sampled_from(NAMES)))
def test_no_combination_of_paths_modifies_an_input(command, source, output, plot):
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        original = _setup(folder)
        outputs = [o for o in (output, plot if command == "segment" else None) if o is not None]
        real = [_real(folder, o) for o in outputs]
        clash = any(r == _real(folder, "a.csv") for r in real) or len(set(real)) < len(real)
        here = os.getcwd()
        os.chdir(folder)
        try:
            name = lambda n: str(folder / "a.csv") if n == "ABS" else n  # noqa: E731
            args = [command, name(source), "--tol", "0.1"]
            if output is not None:
                args += ["-o", name(output)]
            if plot is not None and command == "segment":
                args += ["--plot", name(plot)]
            code, _, err = cli(*args)
        finally:
            os.chdir(here)
        assert (folder / "a.csv").read_bytes() == original
        assert os.path.samefile(folder / "a.csv", folder / "hard.csv")
        if clash:
            assert code == 2 and "same file" in err, err
        else:
            assert code == 0, err
            assert all(os.path.exists(folder / ("a.csv" if o == "ABS" else o)) for o in outputs)

"""Every input through one safe reader: special files refused by type before a byte is read,
reads bounded by a budget even when the file system reports a wrong size; budgets by name."""

from __future__ import annotations

import os
import socket

import pytest

from cli_helpers import cli
from coatsim.core.budgets import BudgetExceeded, limit, parse_settings
from coatsim.core.errors import InputError
from coatsim.core.fileio import read_input
from coatsim.core.jsonfile import parse_json, read_json


def _fifo(tmp_path):
    path = tmp_path / "pipe.csv"
    os.mkfifo(path)
    return path


def _loop(tmp_path):
    (tmp_path / "a.csv").symlink_to(tmp_path / "b.csv")
    (tmp_path / "b.csv").symlink_to(tmp_path / "a.csv")
    return tmp_path / "a.csv"


def _socket(tmp_path):
    path = tmp_path / "s.csv"
    sock = socket.socket(socket.AF_UNIX)
    sock.bind(str(path))
    return path


@pytest.mark.parametrize("make, words", [
    (_fifo, "is a named pipe"), (lambda d: d, "is a folder"), (_loop, "symbolic links"),
    (_socket, "is a socket"), (lambda d: "/dev/zero", "is a device"),
])
def test_special_files_are_refused_by_type_without_reading(tmp_path, make, words):
    with pytest.raises(InputError, match=words):
        read_input(make(tmp_path), "curve file")


def test_a_file_longer_than_it_says_is_cut_at_the_budget(monkeypatch):
    """/proc files report size 0: the read itself is bounded."""
    monkeypatch.setenv("COATSIM_BUDGET", "input_bytes=100")
    with pytest.raises(BudgetExceeded, match="more than the file system reports"):
        read_input("/proc/self/maps", "drawing")


def test_budgets_are_named_and_set_per_process(monkeypatch):
    monkeypatch.setenv("COATSIM_BUDGET", "curve_points=10,seconds=inf")
    assert limit("curve_points") == 10 and limit("seconds") == float("inf")
    for bad in ("nope=1", "curve_points=0", "curve_points", "curve_points=abc"):
        with pytest.raises(InputError, match="COATSIM_BUDGET"):
            parse_settings(bad)


def test_json_nested_past_the_budget_is_refused_before_parsing(tmp_path):
    with pytest.raises(BudgetExceeded, match="nesting"):
        parse_json("[" * 100_000 + "]" * 100_000, "deep.json")
    path = tmp_path / "deep.json"
    path.write_text('{"a":' * 50_000 + "1" + "}" * 50_000)
    with pytest.raises(BudgetExceeded):
        read_json(path)


@pytest.mark.parametrize("command", [["segment", "{p}.csv", "--tol", "0.1"], ["check-program", "{p}.as"],
                                     ["coat", "{p}.csv", "--surface", "plate:100x100@0,0,0", "-o", "{d}/o"]])
@pytest.mark.parametrize("make", [_fifo, _loop, lambda d: "/dev/zero"])
def test_commands_refuse_special_inputs_in_one_line(tmp_path, command, make):
    """A FIFO would hang, /dev/zero fill memory, a link loop raise an OSError: each is one line."""
    stem = tmp_path / "input"
    target = make(tmp_path)
    for suffix in (".csv", ".as"):
        os.symlink(target, f"{stem}{suffix}")
    code, _, err = cli(*(a.replace("{p}", str(stem)).replace("{d}", str(tmp_path)) for a in command))
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("coatsim: error: "), err


def test_the_budget_option_changes_a_budget_for_one_command(tmp_path, monkeypatch):
    monkeypatch.setenv("COATSIM_BUDGET", "")  # the in-process command sets it: restored afterwards
    code, _, err = cli("--budget", "curve_points=10", "segment", "builtin:ellipse:points=200", "--tol", "0.1")
    assert code == 2 and "--budget curve_points=N" in err, err
    code, _, err = cli("--budget", "bogus=1", "segment", "builtin:ellipse", "--tol", "0.1")
    assert code == 2 and "no such budget" in err and "--budget" in err, err

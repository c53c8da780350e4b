"""`coatsim sweep` end to end on real Dask clusters: rows, statuses, errors, resume, and the same
results from a LocalCluster and from a scheduler with workers started by the test."""

from __future__ import annotations

import contextlib
import csv
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time

import dask
import pyarrow.parquet as pq
import pytest

from coatsim.report.catalogue import METRICS
from coatsim.sweep.inputs import bundle
from coatsim.sweep.points import expand
from coatsim.sweep.run import cache_key, run_sweep
from coatsim.sweep.spec import load_sweep

from sweep_helpers import SWEEP, write_case

UNREACHABLE = "workpiece.pose.position_mm"
COLUMNS = ["point", "motion.speed_mm_s", "axis.segmentation.tolerance_mm", UNREACHABLE, "variant", "status", "error",
           *METRICS]


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    path = write_case(folder)
    result = run_sweep(path, folder / "out", workers=2, progress=False)
    return path, result


def rows_of(result) -> list[dict]:
    return [dict(zip(result.table.columns, r)) for r in result.table.rows]


def test_rows_statuses_and_errors(swept):
    _, result = swept
    rows = rows_of(result)
    assert list(result.table.columns) == COLUMNS
    assert len(rows) == 5 * 2 and len(result.ran) == 5
    assert [r["variant"] for r in rows] == ["polysegment", "polyline-blend"] * 5
    far = [r for r in rows if r[UNREACHABLE] == "[2000.0,0.0,200.0]"]
    near = [r for r in rows if r not in far]
    assert len(far) == 2 and len(near) == 8
    for r in far:
        assert r["status"] == "failed"
        assert "cannot reach pose" in r["error"] and "move the path within the arm's reach" in r["error"]
        assert "\n" not in r["error"] and "coatsim-point-" not in r["error"]
        assert all(r[m] is None for m in METRICS)
    for r in near:
        assert r["status"] == "ok" and r["error"] is None
        assert r["motion.programmed_speed_mm_s"] == r["motion.speed_mm_s"]
        assert r["axis.segmentation.tolerance_mm"] in (0.05, 0.2)
        assert r["segmentation.tolerance_mm"] == r["axis.segmentation.tolerance_mm"]
        assert r["segmentation.max_deviation_mm"] <= r["segmentation.tolerance_mm"] + 1e-9
        # the curve (a 142.8 mm slot) at the programmed speed, or slower where the arm cannot follow
        assert r["motion.ideal_time_s"] == pytest.approx(142.83 / r["motion.speed_mm_s"], rel=0.01)
        assert r["motion.cycle_time_s"] >= 0.99 * r["motion.ideal_time_s"]
    faster = {(r["variant"], r["segmentation.tolerance_mm"]): r["motion.cycle_time_s"] for r in near
              if r["motion.speed_mm_s"] == 250.0}
    slower = {(r["variant"], r["segmentation.tolerance_mm"]): r["motion.cycle_time_s"] for r in near
              if r["motion.speed_mm_s"] == 150.0}
    assert all(faster[k] < slower[k] for k in faster)
    assert result.failed_points == [result.points[4].id]


def test_files_on_disk(swept):
    _, result = swept
    out = result.outdir
    table = pq.read_table(out / "results.parquet")
    assert table.column_names == COLUMNS
    assert str(table.schema.field("motion.stops").type) == "int64"
    assert str(table.schema.field("motion.speed_mm_s").type) == "double"
    assert table.to_pylist() == rows_of(result)
    with open(out / "results.csv", newline="", encoding="utf-8") as handle:
        lines = list(csv.reader(handle))
    assert lines[0] == COLUMNS and len(lines) == 11
    for line, row in zip(lines[1:], rows_of(result)):
        for text, value in zip(line, row.values()):
            assert text == ("" if value is None else str(value)) or float(text) == value
    for point in result.points:
        record = json.loads((out / "points" / point.id / "point.json").read_text())
        assert record["point"] == point.id and record["status"] == result.outcomes[point.id].status
        document = json.loads((out / "points" / point.id / "metrics.json").read_text())
        assert record["parameters"] == json.loads(json.dumps(dict(point.params)))
        if point is result.points[4]:
            assert document["variants"] == {} and set(document["failed"]) == {"polysegment", "polyline-blend"}
        else:
            assert set(document["variants"]) == {"polysegment", "polyline-blend"} and document["passed"]
        assert not (out / "points" / point.id / "report.html").exists()  # outputs only with --keep-outputs
    page = (out / "sweep.html").read_text(encoding="utf-8")
    for anchor in ("summary", "plots", "failed", "gates", "table"):
        assert f'<section id="{anchor}">' in page
    assert page.count("data:image/png;base64,") == 2
    assert not re.search(r"""(src|href)=["']?(https?:|//)""", page)  # nothing outside the file
    assert "cannot reach pose" in page and result.points[4].id in page


def test_rerun_reuses_every_point_and_runs_only_new_ones(swept, tmp_path):
    path, first = swept
    again = run_sweep(path, first.outdir, workers=2, progress=False)
    assert again.ran == ()
    assert again.table == first.table
    grown = tmp_path / "grown"
    shutil.copytree(first.outdir, grown)
    path.with_name("grown.yaml").write_text(SWEEP.replace("[150, 250]", "[150, 250, 300]"), encoding="utf-8")
    more = run_sweep(path.with_name("grown.yaml"), grown, workers=1, progress=False)
    assert len(more.points) == 7
    assert sorted(more.ran) == sorted(p.id for p in more.points if p.axes["motion.speed_mm_s"] == 300.0)
    old = {r["point"] + r["variant"]: r for r in rows_of(first)}
    for r in rows_of(more):
        if r["point"] + r["variant"] in old:
            assert r == old[r["point"] + r["variant"]]


def test_cli_exits_1_on_a_failed_point_and_prints_it(swept, run_cli):
    path, first = swept
    code, out, err = run_cli(["sweep", str(path), "-o", str(first.outdir), "--workers", "1"])
    assert code == 1
    assert "5 points (0 run, 5 reused), 10 rows: 8 ok, 2 failed" in out
    assert f"failed: {first.points[4].id} [polysegment]" in out and "cannot reach pose" in out
    assert err.strip() == f"coatsim: error: 1 of 5 point(s) failed (see {first.outdir / 'sweep.html'})"


def test_cache_key_follows_the_input_file_contents(tmp_path):
    path = write_case(tmp_path)
    _, points = expand(load_sweep(path))
    base_dir = path.parent / "scenario"
    before = cache_key(points[0].scenario, bundle(points[0].scenario, base_dir).digests, True)
    assert before == cache_key(points[0].scenario, bundle(points[0].scenario, base_dir).digests, True)
    assert before != cache_key(points[0].scenario, bundle(points[0].scenario, base_dir).digests, False)
    curve = base_dir / "curves" / "slot.csv"
    lines = curve.read_text().splitlines()
    curve.write_text("\n".join([lines[0], "0.5,-10.0", *lines[2:]]) + "\n")
    assert before != cache_key(points[0].scenario, bundle(points[0].scenario, base_dir).digests, True)


def test_a_users_files_in_the_sweep_folder_are_left_alone(tmp_path):
    """The sweep holds its folder like every output folder: its own names only, foreign ones need --force."""
    path = write_case(tmp_path)
    keep = tmp_path / "mine"
    keep.mkdir()
    (keep / "notes.txt").write_text("mine")
    (keep / "sweep.html").write_text("my page")
    from coatsim.core.errors import InputError

    with pytest.raises(InputError, match="sweep.html: not written by coatsim"):
        run_sweep(path, keep, progress=False)
    assert sorted(p.name for p in keep.iterdir()) == ["notes.txt", "sweep.html"]
    assert (keep / "sweep.html").read_text() == "my page"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def dask_processes(folder, worker_args=(), scheduler_env=None):
    """A real `dask scheduler` and one `dask worker` process on 127.0.0.1 (stopped afterwards)."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, DASK_DISTRIBUTED__WORKER__DAEMON="False", **(scheduler_env or {}))
    dask = [sys.executable, "-m", "dask"]  # the `dask` command of this interpreter
    quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, cwd=folder, start_new_session=True)
    procs = [subprocess.Popen([*dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                              **quiet)]
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise RuntimeError("dask scheduler did not start")
                time.sleep(0.2)
        procs.append(subprocess.Popen([*dask, "worker", address, "--nworkers", "1", "--nthreads", "1",
                                       "--no-dashboard", *worker_args], **quiet))
        from distributed import Client

        with Client(address, timeout="60s") as client:
            client.wait_for_workers(1, timeout=120)
        yield address
    finally:  # each in a session of its own: the worker's nanny and its worker process go together
        for proc in reversed(procs):
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=20)


@pytest.fixture
def scheduler_with_worker(tmp_path):
    with dask_processes(tmp_path) as address:
        yield address


def test_scheduler_gives_the_same_results_as_the_local_cluster(swept, scheduler_with_worker, tmp_path):
    path, local = swept
    remote = run_sweep(path, tmp_path / "remote", scheduler=scheduler_with_worker, progress=False)
    assert len(remote.ran) == 5
    assert remote.table == local.table
    assert (tmp_path / "remote" / "results.parquet").read_bytes() == (local.outdir / "results.parquet").read_bytes()


HOG = """\
base: scenario/base.yaml
fast: true
grid:
  fast.coating_spacing_mm: [4.0, 3.0, 0.22]   # 0.22 mm on a 300 mm plate: 1.9 M vertices (within the budget)
  workpiece.size_mm: [[300.0, 300.0]]
"""


@pytest.mark.slow
def test_a_killed_worker_is_retried_and_a_point_that_kills_every_worker_fails(tmp_path):
    """A worker killed under a running point: Dask reruns it and it finishes. A point that needs
    more memory than a worker has: its workers die until Dask gives up; a failed row, the other
    points done, and a rerun tries it again."""
    from distributed import Client

    path = write_case(tmp_path, HOG)
    hog_id = next(p.id for p in expand(load_sweep(path))[1] if p.axes["fast.coating_spacing_mm"] == 0.22)
    with dask_processes(tmp_path, ("--memory-limit", "500MB"),
                        {"DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "1",
                         "DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0"}) as address, \
            Client(address, timeout="60s") as spy:
        done = {}
        runner = threading.Thread(target=lambda: done.update(
            result=run_sweep(path, tmp_path / "out", scheduler=address, progress=False)))
        runner.start()
        killed = False
        deadline = time.monotonic() + 120
        while runner.is_alive() and not killed and time.monotonic() < deadline:
            busy = [w for w, keys in spy.processing().items()
                    if any("coatsim-point-" in str(k) and hog_id not in str(k) for k in keys)]
            if busy:
                pid = spy.run(os.getpid, workers=busy[:1])[busy[0]]
                os.kill(pid, signal.SIGKILL)
                killed = True
            time.sleep(0.05)
        runner.join(timeout=600)
    assert killed
    result = done["result"]
    rows = rows_of(result)
    hog = [r for r in rows if r["fast.coating_spacing_mm"] == 0.22]
    assert {r["status"] for r in hog} == {"failed"}
    assert all("died 2 times" in r["error"] for r in hog)
    assert {r["status"] for r in rows if r not in hog} == {"ok"}, [r["error"] for r in rows if r not in hog]
    record = json.loads((tmp_path / "out" / "points" / hog[0]["point"] / "point.json").read_text())
    assert record["reusable"] is False


def test_a_points_scenario_reproduces_its_metrics_with_coatsim_run(swept, tmp_path, run_cli):
    _, result = swept
    point = result.points[0]
    folder = result.outdir / "points" / point.id
    code, _, _ = run_cli(["run", str(folder / "scenario.yaml"), "--fast", "-o", str(tmp_path / "again")])
    assert code == 0
    mine = json.loads((tmp_path / "again" / "metrics.json").read_text())
    theirs = json.loads((folder / "metrics.json").read_text())
    assert mine["variants"] == theirs["variants"] and mine["gates"] == theirs["gates"]


@pytest.mark.slow
def test_keep_outputs_keeps_every_output_and_reruns_points_stored_without(tmp_path):
    path = write_case(tmp_path, "base: scenario/base.yaml\nfast: true\npoints:\n  - {motion.speed_mm_s: 180}\n")
    out = tmp_path / "out"
    first = run_sweep(path, out, workers=1, progress=False)
    folder = out / "points" / first.points[0].id
    assert sorted(p.name for p in folder.iterdir()) == ["metrics.json", "point.json", "scenario.yaml"]
    kept = run_sweep(path, out, workers=1, progress=False, keep_outputs=True)
    assert kept.ran == (first.points[0].id,)
    names = {p.name for p in folder.iterdir()}
    for variant in ("polysegment", "polyline-blend"):
        assert {f"{variant}.as", f"{variant}.trajectory.csv", f"{variant}.thickness.ply"} <= names
    assert {"report.html", "polysegment.json", "metrics.json", "point.json", "scenario.yaml"} <= names
    assert run_sweep(path, out, workers=1, progress=False).ran == ()
    assert run_sweep(path, out, workers=1, progress=False, keep_outputs=True).ran == ()
    assert kept.table == first.table


def test_cli_metric_choice_and_option_errors(swept, run_cli, tmp_path):
    path, first = swept
    code, out, _ = run_cli(["sweep", str(path), "-o", str(first.outdir), "--metric", "motion.stops",
                            "--metric", "coating.coverage_fraction"])
    assert code == 1 and "(0 run, 5 reused)" in out
    page = (first.outdir / "sweep.html").read_text(encoding="utf-8")
    assert "motion.stops against every axis" in page and "coating.coverage_fraction against every axis" in page
    assert "motion.cycle_time_s against every axis" not in page
    for argv, message in (
        (["--metric", "motion.stop"], "--metric: 'motion.stop' is not a metric"),
        (["--workers", "0"], "--workers 0: give at least 1"),
        (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers sizes the local cluster only"),
        (["--scheduler", "tcp://127.0.0.1:1"], "--scheduler tcp://127.0.0.1:1: cannot connect"),
        (["--scheduler", "garbage"], "--scheduler garbage: not a scheduler address (missing port number"),
        (["--scheduler", "tcp://127.0.0.1:99999"], "port 99999 is not 1 .. 65535"),
        (["--scheduler", "http://127.0.0.1:8786"], "no Dask comm speaks http://"),
    ):
        with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
            code, _, err = run_cli(["sweep", str(path), "-o", str(tmp_path / "other"), *argv])
        assert code == 2 and message in err and len(err.strip().splitlines()) == 1, err

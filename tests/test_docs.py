"""The documentation cannot drift: its reference pages are what the code generates, every metric a
run writes is in the metrics page, the site builds strictly, and every command block of a page
marked ``<!-- test: run -->`` runs on the shipped data."""

from __future__ import annotations

import functools
import http.server
import json
import os
import re
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
DOCS = REPO / "docs"
MARK = re.compile(r"^<!-- test: run -->\n```(bash|python)\n(.*?)^```", re.S | re.M)
# pages whose blocks run whole scenarios or a Dask cluster: the long tests (-m slow)
SLOW = {"getting-started.md", "tutorials/contour-csv.md", "tutorials/dxf-part.md", "tutorials/as-program.md",
        "tutorials/sweep.md", "how-to/ci-gates.md", "how-to/custom-arm.md", "how-to/custom-gun.md",
        "how-to/pandas.md", "how-to/tolerances-speeds.md"}


def test_the_reference_pages_are_what_the_code_generates() -> None:
    """In a fresh interpreter: the generator imports every coatsim module to find the error classes."""
    result = subprocess.run([sys.executable, str(REPO / "scripts" / "docs_reference.py"), "--check"], cwd=REPO,
                            capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    assert result.returncode == 0, result.stderr


def test_every_metric_a_run_writes_is_in_the_metrics_page(small_report) -> None:
    *_, outdir = small_report
    page = (DOCS / "reference" / "metrics.md").read_text(encoding="utf-8")
    document = json.loads((outdir / "metrics.json").read_text(encoding="utf-8"))
    written = {f"{g}.{n}" for groups in document["variants"].values() for g, values in groups.items() for n in values}
    assert written and all(f"| `{name}` |" in page for name in written)


@pytest.mark.slow
def test_the_site_builds_strictly(tmp_path: Path) -> None:
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings_handlers.python")
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-d", str(tmp_path / "site")],
                            cwd=REPO, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr[-3000:]
    assert (tmp_path / "site" / "index.html").is_file()
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        return
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(tmp_path / "site"))
    with http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler) as server:
        threading.Thread(target=server.serve_forever, daemon=True).start()
        for page in ("", "getting-started/", "reference/api/", "tutorials/part-3d/"):
            url = f"http://127.0.0.1:{server.server_address[1]}/{page}"
            opened = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr",
                                     "--v=0", "--virtual-time-budget=3000", "--dump-dom", url],
                                    capture_output=True, text=True, timeout=120)
            assert "</html>" in opened.stdout and ":CONSOLE" not in opened.stderr, (url, opened.stderr[-2000:])
        server.shutdown()


def runnable_blocks(page: Path) -> list[tuple[str, str]]:
    """(language, code) of every block marked to run, in page order."""
    return MARK.findall(page.read_text(encoding="utf-8"))


PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md") if runnable_blocks(p))


def test_every_mark_is_on_a_bash_or_python_block() -> None:
    for page in DOCS.rglob("*.md"):
        marks = re.findall(r"^<!-- test: run -->$", page.read_text(encoding="utf-8"), re.M)
        assert len(marks) == len(runnable_blocks(page)), page


def test_the_tutorials_and_how_tos_have_runnable_blocks() -> None:
    assert {"tutorials/contour-csv.md", "tutorials/dxf-part.md", "tutorials/as-program.md",
            "tutorials/part-3d.md", "tutorials/sweep.md", "how-to/ci-gates.md"} <= set(PAGES)


@pytest.mark.parametrize("page", [pytest.param(p, marks=[pytest.mark.slow] if p in SLOW else []) for p in PAGES])
def test_every_command_of_a_page_runs(page: str, tmp_path: Path) -> None:
    """The page's marked blocks, in order, in a fresh folder holding the shipped data (as the
    repository's top folder would); each must exit 0."""
    if page == "how-to/pandas.md":
        pytest.importorskip("pandas")
    for name in ("scenarios", "sweeps", "models"):
        shutil.copytree(REPO / name, tmp_path / name, symlinks=False)
    env = {**os.environ, "MPLBACKEND": "Agg", "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl"),
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
           "PYTHONPATH": os.pathsep.join(filter(None, [str(REPO), os.environ.get("PYTHONPATH")]))}
    for k, (language, code) in enumerate(runnable_blocks(DOCS / page)):
        command = ["bash", "-euo", "pipefail", "-c", code] if language == "bash" else [sys.executable, "-c", code]
        result = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        assert result.returncode == 0, f"{page} block {k + 1} exited {result.returncode}:\n{code}\n{result.stderr[-3000:]}"

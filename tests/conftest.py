"""Shared test fixtures."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Callable

import pytest
from hypothesis import settings

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()  # as the console entry point does, before numerical libraries load

from coatsim import cli  # noqa: E402

from small_scenario import SMALL

# Property tests are reproducible by default (and in CI): derandomised, no example database, so a
# run never replays a failure found by an earlier one. `--hypothesis-profile=explore` searches
# with fresh random examples (and remembers failures) when hunting for bugs.
settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", derandomize=False, print_blob=True)
settings.load_profile("ci")


def _import_every_module() -> None:
    """Import every coatsim module now. Hypothesis draws some examples from the constants of
    the project's modules loaded so far, so without this a property test's examples would
    depend on which tests ran before it (a file run alone got other examples than in the
    whole suite)."""
    import importlib
    import pkgutil

    import coatsim

    for info in pkgutil.walk_packages(coatsim.__path__, "coatsim."):
        if not info.name.endswith("__main__"):
            importlib.import_module(info.name)


_import_every_module()

METRICS_PAGE = Path(__file__).resolve().parents[1] / "docs" / "reference" / "metrics.md"



@pytest.fixture(scope="session")
def small_report(tmp_path_factory: pytest.TempPathFactory) -> tuple[int, str, str, Path]:
    """`coatsim run SMALL --fast --junit gates.xml` once per session, in-process: (exit code, stdout,
    stderr, output folder); the JUnit file is written beside the output folder."""
    import contextlib
    import io

    folder = tmp_path_factory.mktemp("small")
    scenario = folder / "small_job.yaml"
    scenario.write_text(SMALL, encoding="utf-8")
    outdir = folder / "out"
    out, err = io.StringIO(), io.StringIO()
    old = sys.argv
    sys.argv = ["coatsim", "run", str(scenario), "--fast", "-o", str(outdir), "--junit", str(folder / "gates.xml")]
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), pytest.raises(SystemExit) as info:
            cli.main()
    finally:
        sys.argv = old
    return int(info.value.code or 0), out.getvalue(), err.getvalue(), outdir


@pytest.fixture(scope="session")
def reference_metric_names() -> list[str]:
    """Metric names listed, in order, in the generated reference page docs/reference/metrics.md."""
    names: list[str] = []
    for line in METRICS_PAGE.read_text(encoding="utf-8").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.lstrip().startswith("|") and cells[0].startswith("`"):
            names.append(cells[0].strip("`"))
    return names


@pytest.fixture
def run_cli(capsys) -> Callable[[list[str]], tuple[int, str, str]]:
    """Run the console entry point in-process: (exit code, stdout, stderr)."""

    def run(argv: list[str]) -> tuple[int, str, str]:
        old = sys.argv
        sys.argv = ["coatsim", *argv]
        try:
            with pytest.raises(SystemExit) as info:
                cli.main()
        finally:
            sys.argv = old
        out, err = capsys.readouterr()
        return info.value.code, out, err

    return run


@pytest.fixture(scope="session")
def tube_run(tmp_path_factory: pytest.TempPathFactory):
    """The tube scenario with its three variants in fast mode at coarse numerics, report written:
    (RunResult, scenario file)."""
    from part_scenarios import cheap_scenario

    from coatsim.run.pipeline import run_scenario

    folder = tmp_path_factory.mktemp("tube")
    scenario = cheap_scenario(folder, "cylinder_3d", ["polysegment", "polyline-stop", "polyline-blend"])
    return run_scenario(scenario, folder / "out", fast=True, progress=False), scenario

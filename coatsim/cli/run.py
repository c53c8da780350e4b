"""``coatsim run``: a scenario end to end — programs, simulated arm, coating, metrics, report, gates."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer


def run(
    scenario: Path = typer.Argument(..., help="scenario YAML file (see `coatsim schema`)"),
    outdir: Optional[Path] = typer.Option(None, "-o", "--outdir", help="output folder [default: runs/NAME]"),
    fast: bool = typer.Option(False, "--fast", help="the scenario's coarser mesh and path sampling (for CI)"),
    model: Optional[Path] = typer.Option(None, "--model", help="Cell MJCF replacing the scenario's robot.model [default: the scenario's]."),
    timings: bool = typer.Option(False, "--timings", help="Print wall times per stage on stderr."),
    video: bool = typer.Option(False, "--video", help="Also write polysegment.mp4: the polysegment run rendered offscreen (needs imageio-ffmpeg)."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
    junit: Optional[Path] = typer.Option(None, "--junit", help="Also write the gates as JUnit XML to this file: one test case per gate (for CI test reports)."),
) -> None:
    """Run a scenario: programs, simulated arm, coating, metrics.json and report.html for every
    variant; exit 1 if a gate fails, 3 if the simulated arm diverges."""
    import time

    from coatsim.core.runtime import keep_frozen, long_lived_imports

    with long_lived_imports():
        from coatsim.core.errors import CoatsimError, GateFailure
        from coatsim.core.fileio import write_text
        from coatsim.core.outputs_guard import check_distinct
        from coatsim.report.junit import error_junit, gates_junit
        from coatsim.report.summary import summary_text
        from coatsim.run.pipeline import run_scenario

    check_distinct([("the scenario", scenario)], [("--junit", junit)])
    started = time.perf_counter()
    try:
        with keep_frozen():
            result = run_scenario(scenario, outdir, fast=fast, model=model, force=force, video=video)
    except CoatsimError as exc:
        if junit is not None:  # the CI report shows why the run stopped
            write_text(junit, error_junit(scenario.stem, str(exc), type(exc).__name__))
        raise
    if junit is not None:
        write_text(junit, gates_junit(result.document))
    typer.echo(summary_text(result.document))
    for warning in result.document["warnings"]:
        typer.echo(f"warning: {warning['variant']}: {warning['message']}", err=True)
    typer.echo(f"wrote {len(result.files)} files to {result.outdir} (report: {result.outdir / 'report.html'})")
    if timings:
        parts = [f"segmentation {result.segmentation_s:.2f} s"]
        parts += [f"{v.name} " + ", ".join(f"{k.removesuffix('_s')} {t:.2f} s" for k, t in v.execution.wall.items())
                  for v in result.variants]
        parts.append(f"report {result.report_s:.2f} s")
        typer.echo(f"timings: {'; '.join(parts)}; total {time.perf_counter() - started:.1f} s", err=True)
    failed = [g["label"] for g in result.document["gates"] if not g["passed"]]
    if failed:
        raise GateFailure(f"{len(failed)} gate(s) failed: {'; '.join(failed)}")

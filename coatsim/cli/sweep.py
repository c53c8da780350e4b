"""``coatsim sweep``: many scenario points on Dask, one table of results."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer


def sweep(
    sweep_file: Path = typer.Argument(..., help="sweep YAML file: base scenario, grid and/or points"),
    outdir: Optional[Path] = typer.Option(None, "-o", "--outdir", help="output folder [default: runs/SWEEP_FILE_NAME]"),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Dask scheduler address, tcp://host:port [default: a local cluster]"),
    workers: Optional[int] = typer.Option(None, "--workers", help="worker processes of the local cluster [default: one per core]"),
    keep_outputs: bool = typer.Option(False, "--keep-outputs", help="keep every run's full outputs in OUTDIR/points/ID/"),
    metric: Optional[list[str]] = typer.Option(None, "--metric", metavar="NAME", help="metric sweep.html plots against each axis (repeatable) [default: the sweep file's]"),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
) -> None:
    """Run many scenario points on Dask: results.parquet, results.csv, sweep.html; exit 1 if a
    point or a gate failed. Rerunning into the same folder runs only what is missing."""
    from coatsim.cli.flags import speaking_flags
    from coatsim.sweep.run import reused_count, run_sweep, sweep_problems

    # an interrupt ends here like any command's (exit 130); the finished points stay for a rerun
    with speaking_flags({"workers": "--workers", "metrics": "--metric"}):
        result = run_sweep(sweep_file, outdir, scheduler=scheduler, workers=workers, keep_outputs=keep_outputs,
                           metrics=metric, force=force)
    rows = result.table.rows
    ok = sum(r[result.table.columns.index("status")] == "ok" for r in rows)
    typer.echo(f"{len(result.points)} points ({len(result.ran)} run, {reused_count(result.points, result.ran)} reused), "
               f"{len(rows)} rows: {ok} ok, {len(rows) - ok} failed; {len(result.gate_failures)} point(s) failed a gate")
    for p in result.points:
        outcome = result.outcomes[p.id]
        for variant, error in outcome.variants.items():
            if error is not None:
                typer.echo(f"failed: {p.id} [{variant}] ({p.label}): {error}")
        for label in result.gate_failures.get(p.id, ()):
            typer.echo(f"gate failed: {p.id} ({p.label}): {label}")
    typer.echo(f"wrote {', '.join(str(f) for f in result.files)} in {result.seconds:.1f} s")
    problem = sweep_problems(result)
    if problem is not None:
        raise problem

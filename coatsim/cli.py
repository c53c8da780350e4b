"""Command-line layer: parse arguments, call one stage function, print, return the exit code.

Every CoatsimError becomes one line on stderr and its exit code; nothing else is done here.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Optional

import typer

from coatsim.errors import CoatsimError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="coatsim: curves -> tangent-continuous arc/line robot programs -> simulated arm -> coating.",
)


def fail(message: str, code: int = 2) -> None:
    """Print a one-line error and exit with ``code``."""
    typer.echo(f"coatsim: error: {message}", err=True)
    raise typer.Exit(code)


@app.command()
def schema() -> None:
    """Print the JSON Schema of scenario files (point your editor's YAML plugin at it)."""
    from coatsim.scenario import json_schema

    typer.echo(json_schema(), nl=False)


@app.command()
def coat(
    trajectory: Path = typer.Argument(..., help="Trajectory CSV (coatsim execute / run)."),
    surface: str = typer.Option(..., "--surface", help="plate:WxH@x,y,z | cylinder:RxL@x,y,z[,axis] | MESH.stl/ply/obj/glb[@x,y,z] (mm, base frame)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Mesh vertex spacing, mm [default: footprint sigma/3]."),
    footprint: str = typer.Option("gaussian:sigma=5", "--footprint", help="gaussian:sigma= | elliptic:sx=,sy= | beta:radius=,beta= | double-beta:a=,b=,beta1=,beta2= | table:FILE.csv (mm)."),
    rate: float = typer.Option(40.0, "--rate", help="Deposited volume rate Q, mm3/s."),
    standoff: float = typer.Option(100.0, "--standoff", help="Reference stand-off h0 at which the footprint is given, mm."),
    target_um: Optional[float] = typer.Option(None, "--target-um", help="Target thickness for coverage, um [default: ROI mean]."),
    roi: str = typer.Option("band", "--roi", help="band (sprayed strip) | part (whole part), both minus an edge band."),
    edge_band: Optional[float] = typer.Option(None, "--edge-band", help="Edge band left out of the ROI, mm [default: 3 sigma]."),
    de_exponent: float = typer.Option(1.0, "--de-exponent", help="Deposition efficiency cos^(n-1) of the incidence angle; 1 = off."),
    occlusion: bool = typer.Option(False, "--occlusion", help="Ray-cast visibility for concave parts (slow)."),
    section: Optional[str] = typer.Option(None, "--section", help="Cross-section line x0,y0,x1,y1 in heat-map coordinates, mm."),
    out: Path = typer.Option(Path("out/coat"), "-o", "--out", help="Output folder."),
) -> None:
    """Spray a logged trajectory onto a surface: thickness.ply, coating.json, heatmap.png, section.png."""
    from coatsim.spray.coat import run_coat

    result, files = run_coat(trajectory, surface, spacing, footprint, rate, standoff, target_um, roi,
                             edge_band, de_exponent, occlusion, section, out)
    m = result.metrics
    typer.echo(f"{result.surface.n_vertices} vertices, spray {m['spray_time_s']:.3f} s; ROI ({roi}) "
               f"mean {m['thickness_mean_um']:.3f} um, CV {m['thickness_cv']:.4f}, "
               f"min {m['thickness_min_um']:.3f}, max {m['thickness_max_um']:.3f} um; "
               f"deposited {m['deposited_volume_mm3']:.3f} of {m['sprayed_volume_mm3']:.3f} mm3")
    typer.echo(f"wrote {', '.join(str(f) for f in files)}")


def main() -> None:
    """Console entry point: run the app, turning CoatsimError into a one-line error."""
    try:
        app(standalone_mode=False)
    except CoatsimError as exc:
        typer.echo(f"coatsim: error: {exc}", err=True)
        sys.exit(exc.exit_code)
    except typer.Exit as exc:
        sys.exit(exc.exit_code)
    except typer.Abort:
        typer.echo("coatsim: aborted", err=True)
        sys.exit(130)
    except Exception as exc:  # click usage errors and the like
        import click

        if isinstance(exc, click.ClickException):
            exc.show()
            sys.exit(2 if isinstance(exc, click.UsageError) else exc.exit_code)
        raise
    sys.exit(0)


if __name__ == "__main__":
    main()

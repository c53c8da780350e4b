"""``coatsim coat``: spray a logged trajectory onto a surface and measure the coat."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from coatsim.core import defaults

#: The coating library's parameters as this command's flags.
FLAGS = {"shadows": "--shadows", "tolerance_pct": "--tolerance-pct", "units": "--surface-units"}


def coat(
    trajectory: Path = typer.Argument(..., help="Trajectory CSV (coatsim execute / run)."),
    surface: str = typer.Option(..., "--surface", help="plate:WxH@x,y,z | cylinder:RxL@x,y,z[,axis] | MESH.stl/ply/obj/glb optionally @x,y,z (mm, base frame)."),
    surface_units: str = typer.Option(defaults.PLAN_UNITS, "--surface-units", help="A mesh surface's unit: mm | cm | m | in | auto (from the file, else from the extent, with a warning), as plan --units."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Mesh vertex spacing, mm (default: sigma/3; R/20 for beta footprints)."),
    footprint: str = typer.Option(defaults.FOOTPRINT, "--footprint", help="gaussian:sigma= | elliptic:sx=,sy= | beta:radius=,beta= | double-beta:a=,b=,beta1=,beta2= | table:FILE.csv (mm)."),
    rate: float = typer.Option(defaults.FLOW_MM3_S, "--rate", help="Deposited volume rate Q, mm3/s."),
    standoff: float = typer.Option(defaults.STANDOFF_MM, "--standoff", help="Reference stand-off h0 at which the footprint is given, mm."),
    target_um: Optional[float] = typer.Option(None, "--target-um", help="Target thickness for coverage, um (default: the ROI mean)."),
    roi: str = typer.Option("band", "--roi", help="band (sprayed strip) | field (the strip without the edge band along its own border) | part (whole part), all minus an edge band."),
    edge_band: Optional[float] = typer.Option(None, "--edge-band", help="Edge band left out of the ROI, mm (default: 3 sigma)."),
    tolerance_pct: float = typer.Option(defaults.TOLERANCE_PCT, "--tolerance-pct", help="Specification band: thickness within this % of the target."),
    efficiency: str = typer.Option(defaults.EFFICIENCY, "--efficiency", help="Deposition efficiency by spray angle: none | angle (1 down to 60 deg, the documented curve below) | angle:60=1,45=0.9,... | table:FILE.csv | cosine:n=N."),
    shadows: str = typer.Option(defaults.SHADOWS, "--shadows", help="auto (ray-cast where the part can shadow itself; without embreex: a warning, no shadows) | on (the same; without embreex: an error) | off."),
    section: Optional[str] = typer.Option(None, "--section", help="Cross-section line x0,y0,x1,y1 in heat-map coordinates, mm."),
    out: Path = typer.Option(Path("out/coat"), "-o", "--out", help="Output folder."),
    force: bool = typer.Option(False, "--force", help="Replace files in the output folder that coatsim did not write."),
) -> None:
    """Spray a logged trajectory onto a surface: thickness.ply, coating.json, heatmap.png, section.png."""
    from coatsim.cli.flags import speaking_flags
    from coatsim.core.errors import EmptyRegionOfInterest, InputError
    from coatsim.spray.coat import run_coat

    try:
        with speaking_flags(FLAGS):
            result, files = run_coat(trajectory, surface, spacing, footprint, rate, standoff, target_um, roi,
                                     edge_band, efficiency, shadows, section, out, force, tolerance_pct,
                                     surface_units)
    except EmptyRegionOfInterest as exc:
        raise InputError(f"{exc}; try --roi part or a smaller --edge-band") from None
    m = result.metrics
    typer.echo(f"{result.surface.n_vertices} vertices, spray {m['spray_time_s']:.3f} s; ROI ({roi}) "
               f"mean {m['thickness_mean_um']:.3f} um, CV {m['thickness_cv']:.4f}, "
               f"min {m['thickness_min_um']:.3f}, max {m['thickness_max_um']:.3f} um; "
               f"deposited {m['deposited_volume_mm3']:.3f} of {m['sprayed_volume_mm3']:.3f} mm3")
    typer.echo(f"sprayed {m['sprayed_volume_mm3']:.3f} mm3 = deposited {m['deposited_volume_mm3']:.3f} + lost "
               f"{m['lost_volume_mm3']:.3f} (efficiency) + missed {m['missed_volume_mm3']:.3f} (off the part); "
               f"shadowed {m['shadowed_volume_mm3']:.3f} (landed on the faces in front)")
    typer.echo(f"wrote {', '.join(str(f) for f in files)}")

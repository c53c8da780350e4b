"""``coatsim run --video``: an MP4 of the reference (polysegment) run, the cell rendered offscreen
by MuJoCo from LEAD_S before the gun opens to LEAD_S after it closes, at FPS frames per second
of simulated time, the part coloured by the thickness sprayed so far on the report's colour
scale. Needs imageio-ffmpeg (``pip install coatsim[video]``).

The thickness sprayed so far is what the run's coat does not keep: the deposit is additive in
time, so each stretch between two frames is deposited once more here, on request only."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.fileio import temporary_path

FPS = 25
LEAD_S = 0.5
SIZE = (640, 420)


def spray_rows(run: Any) -> np.ndarray:
    """Rows of the log with the gun open."""
    return np.flatnonzero(np.asarray(run.execution.log.spray, bool))


def thickness_until(run: Any, rows: Sequence[int]) -> list[np.ndarray]:
    """The thickness (µm per vertex) sprayed from the start up to each of ``rows`` (increasing)."""
    from coatsim.spray.deposition import deposit

    log, coating = run.execution.log, run.coating
    spray = np.asarray(log.spray, bool)
    out, total, start = [], np.zeros(coating.surface.n_vertices), 0
    for row in rows:
        if row >= len(spray) - 1 or row >= spray_rows(run)[-1]:
            out.append(coating.thickness_um)
            continue
        part = spray.copy()
        part[:start] = False
        part[row:] = False
        if part.any():
            total = total + deposit(coating.surface, replace(log, spray=part), coating.model).thickness_um
        out.append(total.copy())
        start = row
    return out


def camera_points(data: Any, run: Any) -> np.ndarray:
    """What the pictures must show: the part, the tool's path and the gun above it."""
    log = run.execution.log
    on = spray_rows(run)
    tcp = log.position[on[0]:on[-1] + 1:10]
    gun = tcp - 250.0 * log.axis[on[0]:on[-1] + 1:10]
    return np.vstack((data.surface.vertices, tcp, gun))


def make_renderer(data: Any, cell: Any) -> Any:
    """The cell with the report's coarse part mesh, coloured on the report's scale."""
    from coatsim.robot.render import CellRenderer
    from coatsim.spray.outputs import colours

    vmin, vmax = data.scale_um
    cmap = colours(np.linspace(vmin, vmax, 256), vmin, vmax)
    coarse = data.coarse
    return CellRenderer(cell, coarse.vertices, coarse.faces, coarse.normals, cmap, *SIZE)


def write_video(path: Path, data: Any, cell: Any) -> Path:
    """Render the frames and encode them (H.264, yuv420p) to ``path``."""
    try:
        import imageio_ffmpeg
    except ImportError:
        raise InputError("--video needs imageio-ffmpeg: pip install 'coatsim[video]'") from None
    from coatsim.robot.render import framing

    run = data.reference
    log = run.execution.log
    on = spray_rows(run)
    if not len(on):
        raise InputError(f"--video: the {run.name} run never opens the gun")
    t0, t1 = float(log.t[on[0]]) - LEAD_S, float(log.t[on[-1]]) + LEAD_S
    times = np.arange(max(t0, float(log.t[0])), min(t1, float(log.t[-1])), 1.0 / FPS)
    rows = [int(r) for r in np.clip(np.searchsorted(log.t, times), 0, len(log.t) - 1)]
    renderer = make_renderer(data, cell)
    vmin, vmax = data.scale_um
    camera = framing(camera_points(data, run), elevation_deg=-38.0)
    standoff = data.spec.gun.standoff_mm
    aim = log.position + (standoff - 1.0) * log.axis  # 1 mm above the part, over its drawn surface
    writer = None
    with temporary_path(path) as tmp:
        try:
            writer = imageio_ffmpeg.write_frames(str(tmp), (renderer.width, renderer.height), fps=FPS,
                                                 codec="libx264", pix_fmt_out="yuv420p", macro_block_size=2,
                                                 output_params=["-f", "mp4"])
            writer.send(None)
            for row, thickness in zip(rows, thickness_until(run, rows)):
                done = on[on <= row]
                spray = (log.position[row], aim[row]) if log.spray[row] else None
                image = renderer.frame(log.q[row], (data.coarse.field(thickness) - vmin) / (vmax - vmin), camera,
                                       aim[done] if len(done) > 1 else None, spray)
                writer.send(np.ascontiguousarray(image))
        finally:
            if writer is not None:
                writer.close()
            renderer.close()
    return path

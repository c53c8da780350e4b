"""``coatsim run --video``: an MP4 of the reference (polysegment) run, rendered offscreen like the
report's pictures: from LEAD_S before the gun opens to LEAD_S after it closes, at FPS frames per
second of simulated time, the part coloured by the thickness sprayed so far. Needs
imageio-ffmpeg (``pip install coatsim[video]``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.fileio import temporary_path

FPS = 25
LEAD_S = 0.5


def write_video(path: Path, data: Any, cell: Any) -> Path:
    """Render the frames and encode them (H.264, yuv420p) to ``path``."""
    try:
        import imageio_ffmpeg
    except ImportError:
        raise InputError("--video needs imageio-ffmpeg: pip install 'coatsim[video]'") from None
    from coatsim.report.sections.view3d import (
        RENDER_FACES,
        camera_points,
        make_renderer,
        spray_rows,
        thickness_until,
    )
    from coatsim.robot.render import framing
    from coatsim.spray.decimate import decimate

    run = data.reference
    log = run.execution.log
    on = spray_rows(run)
    if not len(on):
        raise InputError(f"--video: the {run.name} run never opens the gun")
    t0, t1 = float(log.t[on[0]]) - LEAD_S, float(log.t[on[-1]]) + LEAD_S
    times = np.arange(max(t0, float(log.t[0])), min(t1, float(log.t[-1])), 1.0 / FPS)
    rows = [int(r) for r in np.clip(np.searchsorted(log.t, times), 0, len(log.t) - 1)]
    renderer = make_renderer(data, cell)
    coarse = decimate(data.surface, RENDER_FACES)
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
                image = renderer.frame(log.q[row], (coarse.field(thickness) - vmin) / (vmax - vmin), camera,
                                       aim[done] if len(done) > 1 else None, spray)
                writer.send(np.ascontiguousarray(image))
        finally:
            if writer is not None:
                writer.close()
            renderer.close()
    return path

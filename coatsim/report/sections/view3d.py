"""The view3d section: the cell rendered offscreen by MuJoCo at a few instants of the reference
(polysegment) run, the part coloured by the thickness sprayed so far on the report's colour
scale; then the interactive 3-D view of every variant's thickness mesh and tool path
(:mod:`coatsim.report.viewer`); and the MP4 of the run when one was made (``--video``)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Optional, Sequence

import numpy as np

from coatsim.report.html import Figure, Section, esc, figure_html
from coatsim.report.plots import png_bytes, pyplot
from coatsim.report.viewer import viewer_html

FRACTIONS = (0.25, 0.5, 0.75, 1.0)  # instants: these fractions of the spray time
RENDER_FACES = 20_000                # the rendered part mesh is decimated to about this many triangles
SIZE = (640, 420)


def spray_rows(run: Any) -> np.ndarray:
    """Rows of the log with the gun open."""
    return np.flatnonzero(np.asarray(run.execution.log.spray, bool))


def instant_rows(run: Any, fractions: Sequence[float]) -> list[int]:
    """Log rows at the given fractions of the time from the gun's first opening to its last closing."""
    log, on = run.execution.log, spray_rows(run)
    t0, t1 = float(log.t[on[0]]), float(log.t[on[-1]])
    return [int(np.clip(np.searchsorted(log.t, t0 + f * (t1 - t0)), on[0], on[-1])) for f in fractions]


def thickness_until(run: Any, rows: Sequence[int]) -> list[np.ndarray]:
    """The thickness (µm per vertex) sprayed from the start up to each of ``rows`` (increasing):
    the deposit is additive in time, so each stretch between two instants is deposited once."""
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


def render_instants(data: Any, run: Any, renderer: Any, fractions: Sequence[float]) -> list[tuple[float, np.ndarray]]:
    from coatsim.robot.render import framing
    from coatsim.spray.decimate import decimate

    coarse = decimate(data.surface, RENDER_FACES)
    rows = instant_rows(run, fractions)
    log = run.execution.log
    vmin, vmax = data.scale_um
    camera = framing(camera_points(data, run), elevation_deg=-38.0)
    standoff = data.spec.gun.standoff_mm
    out = []
    path = log.position[spray_rows(run)] + (standoff - 1.0) * log.axis[spray_rows(run)]  # 1 mm above the part
    for row, thickness in zip(rows, thickness_until(run, rows)):
        fraction = (coarse.field(thickness) - vmin) / (vmax - vmin)
        nozzle = log.position[row]
        sprayed = path[: max(2, int(np.searchsorted(spray_rows(run), row)))]
        image = renderer.frame(log.q[row], fraction, camera, sprayed, (nozzle, nozzle + standoff * log.axis[row]))
        out.append((float(log.t[row]), image))
    return out


def make_renderer(data: Any, cell: Any) -> Any:
    from coatsim.robot.render import CellRenderer
    from coatsim.spray.decimate import decimate
    from coatsim.spray.outputs import colours

    coarse = decimate(data.surface, RENDER_FACES)
    vmin, vmax = data.scale_um
    cmap = colours(np.linspace(vmin, vmax, 256), vmin, vmax)
    return CellRenderer(cell, coarse.vertices, coarse.faces, coarse.normals, cmap, *SIZE)


def instants_figure(frames: Sequence[tuple[float, np.ndarray]], t_open: float, vmax: float) -> bytes:
    plt = pyplot()
    cols = 2
    rows = (len(frames) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(cols * 5.2, rows * 3.55), squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for ax, (t, image) in zip(axes.ravel(), frames):
        ax.imshow(image)
        ax.set_title(f"t = {t:.2f} s ({t - t_open:.2f} s after the gun opened)", fontsize=9)
    fig.tight_layout()
    return png_bytes(fig, dpi=100)


def renders_html(data: Any, cell: Optional[Any]) -> str:
    """The rendered instants, or a note saying why there are none."""
    from coatsim.robot.render import RenderUnavailable

    run = data.reference
    if cell is None or not len(spray_rows(run)):
        return '<p class="muted">No rendering: the run has no cell model or the gun never opened.</p>'
    try:
        renderer = make_renderer(data, cell)
    except RenderUnavailable as exc:
        return f'<p class="muted">No rendering of the cell on this machine: {esc(exc)}.</p>'
    try:
        frames = render_instants(data, run, renderer, FRACTIONS)
    finally:
        renderer.close()
    t_open = float(run.execution.log.t[spray_rows(run)[0]])
    vmin, vmax = data.scale_um
    return figure_html(Figure(
        f"The cell during the {run.name} run", instants_figure(frames, t_open, vmax),
        f"The simulated arm and the part at {', '.join(f'{100 * f:.0f} %' for f in FRACTIONS)} of the spray time, "
        f"rendered offscreen by MuJoCo ({renderer.backend.upper()} backend), the part coloured by the thickness sprayed "
        f"so far on the report's scale ({vmin:g} to {vmax:.3g} µm, the colours of the heat maps), the sprayed aim "
        f"points as a white line and the spray axis as a yellow ray."))


def section(data: Any, cell: Optional[Any] = None, video: Optional[str] = None) -> Section:
    body = renders_html(data, cell)
    body += viewer_html(data)
    if video:
        body += (f'<p>Video of the {esc(data.reference.name)} run: <a href="{esc(video)}">{esc(video)}</a> '
                 "(beside this report).</p>")
    return Section("view3d", "The cell and the part in 3-D", body)

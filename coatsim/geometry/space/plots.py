"""The figure of a 3-D segmentation: the curve in space with its arcs and lines, and the distance
from every input point to the chain along the curve against σ."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from coatsim.core.fileio import write_bytes
from coatsim.geometry.plots import ARC_COLOUR, LINE_COLOUR, figure_png
from coatsim.geometry.space.deviation import distance_to_chain
from coatsim.geometry.space.local import arc_length
from coatsim.geometry.space.primitives import Arc3
from coatsim.geometry.space.segment import SpaceSegmentation

SAMPLES_PER_RADIAN = 60  # an arc is drawn with this many points per radian it turns (and at least 2)


def space_segmentation_figure_png(seg: SpaceSegmentation, dpi: int = 110) -> bytes:
    """PNG bytes: left the input curve in space, arcs and lines in two colours, junctions and
    corners, at equal scale on the three axes; right the distance from each input point to the
    chain along the curve, with σ."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    chain, pts = seg.chain, seg.curve.points
    fig = plt.figure(figsize=(12, 5), constrained_layout=True)
    ax_curve = fig.add_subplot(1, 2, 1, projection="3d")
    ax_dist = fig.add_subplot(1, 2, 2)
    ax_curve.plot(*pts.T, color="0.75", lw=4, label="input curve")
    for s in chain.segments:
        turn = abs(s.sweep) if isinstance(s, Arc3) else 0.0
        xyz = s.points(np.linspace(0.0, s.length, max(2, int(SAMPLES_PER_RADIAN * turn) + 2)))
        ax_curve.plot(*xyz.T, color=ARC_COLOUR if isinstance(s, Arc3) else LINE_COLOUR, lw=1.6)
    joints = np.array([s.start for s in chain.segments] + [chain.segments[-1].end])
    ax_curve.plot(*joints.T, "k.", ms=5, ls="none")
    if chain.corners:
        c = np.array([chain.segments[k].end for k in chain.corners])
        ax_curve.plot(*c.T, "kx", ms=8, mew=2, ls="none", label="corner")
    n_arcs = sum(isinstance(s, Arc3) for s in chain.segments)
    ax_curve.plot([], [], color=ARC_COLOUR, label=f"arc ({n_arcs})")
    ax_curve.plot([], [], color=LINE_COLOUR, label=f"line ({chain.n_segments - n_arcs})")
    ax_curve.set_box_aspect(tuple(np.maximum(np.ptp(pts, axis=0), 1e-3 * max(float(np.ptp(pts)), 1e-9))))
    ax_curve.set_xlabel("x (mm)")
    ax_curve.set_ylabel("y (mm)")
    ax_curve.set_zlabel("z (mm)")
    fig.suptitle(f"{Path(seg.curve.name).name}: {chain.n_segments} segments, deviation {seg.max_deviation_mm:.4g} mm "
                 f"(σ = {seg.tolerance_mm:g} mm)")  # (a 3-D axes' own title is cut at the figure's edge)
    ax_curve.legend(loc="upper left", fontsize=8)

    s = arc_length(pts)
    ax_dist.plot(s, distance_to_chain(pts, chain, seg.tolerance_mm), color=ARC_COLOUR, lw=1.0,
                 label="input point to chain")
    ax_dist.axhline(seg.tolerance_mm, color="k", ls="--", lw=1.0, label="σ")
    ax_dist.set_xlabel("arc length along the input (mm)")
    ax_dist.set_ylabel("distance (mm)")
    ax_dist.set_ylim(0.0, 1.15 * max(seg.tolerance_mm, seg.max_deviation_mm))
    ax_dist.set_title("deviation of the input from the chain")
    ax_dist.legend(loc="upper right", fontsize=8)
    ax_dist.grid(alpha=0.3)
    return figure_png(fig, dpi)


def write_space_segmentation_plot(seg: SpaceSegmentation, path: str | Path) -> None:
    write_bytes(path, space_segmentation_figure_png(seg))

"""Speed and path error against path length, for one executed program."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.fileio import write_bytes
from coatsim.robot.motion_metrics import AT_SPEED, MotionMetrics
from coatsim.robot.trajectory_log import TrajectoryLog


def plot_speed(log: TrajectoryLog, metrics: MotionMetrics, curve: tuple[float, float] | Sequence[tuple[float, float]],
               path: str | Path, title: str = "") -> None:
    """Write a PNG: tool speed (top) and path error (bottom) against progress along the path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = metrics.programmed_speed_mm_s
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True, height_ratios=(3, 1.4))
    spans = [curve] if np.ndim(curve) == 1 else list(curve)
    for ax in (top, bottom):
        for k, span in enumerate(spans):
            ax.axvspan(*span, color="0.93", zorder=0, label="curve proper" if ax is top and k == 0 else None)
        ax.grid(True, lw=0.4, color="0.8")
    top.plot(log.progress, log.speed, lw=1.0, color="C0", label="simulated tool speed")
    top.axhline(v, color="C2", lw=0.9, ls="--", label=f"programmed {v:g} mm/s")
    top.axhline(AT_SPEED * v, color="C1", lw=0.7, ls=":", label=f"{AT_SPEED:.0%} of programmed")
    top.set_ylabel("speed (mm/s)")
    top.set_ylim(0, max(1.15 * v, 1.05 * float(log.speed.max())))
    top.legend(loc="lower center", fontsize=8, ncol=2)
    top.set_title(title or (f"cycle {metrics.cycle_time_s:.2f} s (ideal {metrics.ideal_time_s:.2f} s), "
                            f"{metrics.fraction_at_speed:.1%} of the curve at speed, {metrics.stops} stops"),
                  fontsize=10)
    bottom.plot(log.progress, log.path_error, lw=0.9, color="C3")
    bottom.set_ylabel("path error (mm)")
    bottom.set_xlabel("progress along the programmed path (mm)")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    write_bytes(path, buf.getvalue())

"""Speed and path error against path length, for one executed program."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Sequence

import numpy as np

from coatsim.core.fileio import write_bytes
from coatsim.robot.motion_metrics import AT_SPEED, MotionMetrics
from coatsim.robot.trajectory_log import TrajectoryLog

Spans = tuple[float, float] | Sequence[tuple[float, float]]


def _spans(curve: Spans) -> list[tuple[float, float]]:
    """One curve proper, or one per contour of a part."""
    return [tuple(curve)] if np.ndim(curve) == 1 else [tuple(span) for span in curve]


def sprayed_window(log: TrajectoryLog, curve: Spans, margin: float = 0.06) -> tuple[float, float]:
    """Progress interval (mm) the plot shows: the stretch with the gun open and the curve proper
    (every contour's), plus ``margin`` of its length on either side (the approach from home is
    left out)."""
    spans = _spans(curve)
    lo, hi = min(a for a, _ in spans), max(b for _, b in spans)
    on = np.asarray(log.spray, bool)
    if on.any():
        lo, hi = min(lo, float(log.progress[on].min())), max(hi, float(log.progress[on].max()))
    pad = margin * max(hi - lo, 1.0)
    return max(float(log.progress.min()), lo - pad), min(float(log.progress.max()), hi + pad)


def plot_speed(log: TrajectoryLog, metrics: MotionMetrics, curve: Spans, path: str | Path, title: str = "") -> None:
    """Write a PNG: tool speed (top) and path error (bottom) against progress along the path,
    over the sprayed stretch (:func:`sprayed_window`); ``curve`` is the curve proper (one
    interval, or one per contour); ``title`` names the program and variant, the line under it
    gives the motion figures."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = metrics.programmed_speed_mm_s
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(11, 5.5), sharex=True, height_ratios=(3, 1.4))
    lo, hi = sprayed_window(log, curve)
    on = np.asarray(log.spray, bool)
    for ax in (top, bottom):
        for k, span in enumerate(_spans(curve)):
            ax.axvspan(*span, color="0.93", zorder=0, label="curve proper" if ax is top and k == 0 else None)
        ax.fill_between(log.progress, 0, 1, where=on, transform=ax.get_xaxis_transform(), color="#ffe9c7",
                        zorder=0, lw=0, label="gun open" if ax is top else None)
        ax.grid(True, lw=0.4, color="0.8")
        ax.set_xlim(lo, hi)
    top.plot(log.progress, log.speed, lw=1.0, color="C0", label="simulated tool speed")
    top.axhline(v, color="C2", lw=0.9, ls="--", label=f"programmed {v:g} mm/s")
    top.axhline(AT_SPEED * v, color="C1", lw=0.7, ls=":", label=f"{AT_SPEED:.0%} of programmed")
    top.set_ylabel("speed (mm/s)")
    top.set_ylim(0, max(1.15 * v, 1.05 * float(log.speed.max())))
    top.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)  # off the data
    figures = (f"cycle {metrics.cycle_time_s:.2f} s (ideal {metrics.ideal_time_s:.2f} s), "
               f"{metrics.fraction_at_speed:.1%} of the curve at speed, {metrics.stops} stops")
    top.set_title(f"{title}\n{figures}" if title else figures, fontsize=10)
    bottom.plot(log.progress, log.path_error, lw=0.9, color="C3")
    window = (log.progress >= lo) & (log.progress <= hi)
    bottom.set_ylim(0, 1.1 * max(float(log.path_error[window].max()) if window.any() else 0.0, 1e-3))
    bottom.set_ylabel("path error (mm)")
    bottom.set_xlabel("progress along the programmed path (mm)")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    write_bytes(path, buf.getvalue())

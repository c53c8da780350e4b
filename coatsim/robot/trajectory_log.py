"""The logged tool trajectory and its CSV file (contract in docs/formats.md).

One row per simulation step, robot base frame:
``t_s,x_mm,y_mm,z_mm,ax,ay,az,speed_mm_s,spray,progress_mm,path_error_mm,q1,...,q6,trace_speed_mm_s``.
The last column is the speed of the spray spot on the surface (TCP + stand-off · spray axis); a
file without it (written before it existed) reads with the tool speed there.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.core.budgets import MAX_TRAJECTORY_BYTES, check_budget
from coatsim.core.errors import InputError, shown
from coatsim.core.fileio import write_text

COLUMNS = (
    "t_s", "x_mm", "y_mm", "z_mm", "ax", "ay", "az", "speed_mm_s", "spray",
    "progress_mm", "path_error_mm", "q1", "q2", "q3", "q4", "q5", "q6", "trace_speed_mm_s",
)
OPTIONAL = ("trace_speed_mm_s",)


@dataclass(frozen=True, eq=False)
class TrajectoryLog:
    """Arrays of one simulated run; n rows.

    t (n,) s; position (n, 3) mm; axis (n, 3) unit spray axis; speed (n,) mm/s;
    spray (n,) bool; progress (n,) mm along the programmed path; path_error (n,) mm;
    q (n, 6) rad; trace_speed (n,) mm/s the spray spot's speed on the surface (None: the tool's).
    """

    t: np.ndarray
    position: np.ndarray
    axis: np.ndarray
    speed: np.ndarray
    spray: np.ndarray
    progress: np.ndarray
    path_error: np.ndarray
    q: np.ndarray
    trace_speed: np.ndarray | None = None

    @property
    def spot_speed(self) -> np.ndarray:
        """The spray spot's speed (mm/s): the trace speed, or the tool's where none is known."""
        return self.speed if self.trace_speed is None else self.trace_speed

    def __len__(self) -> int:
        return len(self.t)

    def to_csv_text(self) -> str:
        """CSV text with the header row; fixed precision so equal runs give equal bytes."""
        out = io.StringIO()
        out.write(",".join(COLUMNS) + "\n")
        table = np.column_stack((
            self.t, self.position, self.axis, self.speed, self.spray.astype(float),
            self.progress, self.path_error, self.q, self.spot_speed,
        ))
        fmt = ["%.4f"] + ["%.4f"] * 3 + ["%.7f"] * 3 + ["%.3f", "%d", "%.4f", "%.5f"] + ["%.7f"] * 6 + ["%.3f"]
        np.savetxt(out, table, fmt=fmt, delimiter=",")
        return out.getvalue()

    def write_csv(self, path: str | Path) -> None:
        write_text(path, self.to_csv_text())


def read_trajectory_csv(path: str | Path) -> TrajectoryLog:
    """Read a trajectory CSV; any defect raises InputError naming the file and line."""
    path = Path(path)
    try:
        check_budget(f"{path}: bytes of trajectory", path.stat().st_size, MAX_TRAJECTORY_BYTES,
                     "log the motion at a coarser rate")
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: cannot read trajectory ({getattr(exc, 'strerror', None) or exc})") from None
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        raise InputError(f"{path}: empty file, expected a trajectory CSV with header {','.join(COLUMNS[:4])},...")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in COLUMNS if c not in header and c not in OPTIONAL]
    if missing:
        raise InputError(f"{path}:1: trajectory CSV header lacks column(s) {', '.join(missing)}")
    columns = [c for c in COLUMNS if c in header]
    index = [header.index(c) for c in columns]
    data = np.empty((len(rows) - 1, len(columns)))
    for i, row in enumerate(rows[1:]):
        line = i + 2
        if len(row) < len(header):
            raise InputError(f"{path}:{line}: expected {len(header)} values, found {len(row)}")
        for j, k in enumerate(index):
            try:
                value = float(row[k])
            except ValueError:
                raise InputError(f"{path}:{line}: column {columns[j]} is not a number: {shown(row[k])}") from None
            if not math.isfinite(value):
                raise InputError(f"{path}:{line}: column {columns[j]} is not finite: {shown(row[k], names=True)}")
            data[i, j] = value
    if len(data) < 2:
        raise InputError(f"{path}: a trajectory needs at least 2 rows, found {len(data)}")
    if np.any(np.diff(data[:, 0]) <= 0):
        bad = int(np.argmax(np.diff(data[:, 0]) <= 0)) + 3
        raise InputError(f"{path}:{bad}: t_s must increase strictly")
    return TrajectoryLog(
        t=data[:, 0], position=data[:, 1:4], axis=data[:, 4:7], speed=data[:, 7],
        spray=data[:, 8] > 0.5, progress=data[:, 9], path_error=data[:, 10], q=data[:, 11:17],
        trace_speed=data[:, 17] if len(columns) > 17 else None,
    )

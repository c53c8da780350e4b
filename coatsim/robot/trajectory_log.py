"""The logged tool trajectory and its CSV file (contract in docs/formats.md).

One row per simulation step, robot base frame:
``t_s,x_mm,y_mm,z_mm,ax,ay,az,speed_mm_s,spray,progress_mm,path_error_mm,q1,...,q6,trace_speed_mm_s``.
The last column is the speed of the spray spot on the surface (TCP + stand-off · spray axis); a
file without it (written before it existed) reads with the tool speed there.
"""

from __future__ import annotations

import io
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.core.fileio import read_input, write_text
from coatsim.core.number_text import read_rows, table_text

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
    """Read a trajectory CSV (numbers as coatsim.core.number_text reads them); any defect raises
    InputError naming the file and line."""
    path = Path(path)
    data = read_input(path, "trajectory", "trajectory_bytes")
    try:
        text = table_text(data)
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text (nor UTF-16 or UTF-32 with a byte-order mark); expected a "
                         "trajectory CSV with header "
                         f"{','.join(COLUMNS[:4])},...") from None
    if not text.strip():
        raise InputError(f"{path}: empty file, expected a trajectory CSV with header {','.join(COLUMNS[:4])},...")
    rows = read_rows(text, str(path), f"the trajectory columns {','.join(COLUMNS[:4])},...")
    header = rows.header
    missing = [c for c in COLUMNS if c not in header and c not in OPTIONAL]
    if missing:
        raise InputError(f"{path}:1: trajectory CSV header lacks column(s) {', '.join(missing)}")
    short = rows.widths < len(header)
    if short.any():
        k = int(np.argmax(short))
        raise InputError(f"{path}:{int(rows.lines[k])}: expected {len(header)} values, found {int(rows.widths[k])}")
    for note in rows.notes:
        warnings.warn(note, CoatsimWarning, stacklevel=2)
    columns = [c for c in COLUMNS if c in header]
    index = [header.index(c) for c in columns]
    table = rows.columns(index)
    if len(table) < 2:
        raise InputError(f"{path}: a trajectory needs at least 2 rows, found {len(table)}")
    if np.any(np.diff(table[:, 0]) <= 0):
        bad = int(rows.lines[int(np.argmax(np.diff(table[:, 0]) <= 0)) + 1])
        raise InputError(f"{path}:{bad}: t_s must increase strictly")
    return TrajectoryLog(
        t=table[:, 0], position=table[:, 1:4], axis=table[:, 4:7], speed=table[:, 7],
        spray=table[:, 8] > 0.5, progress=table[:, 9], path_error=table[:, 10], q=table[:, 11:17],
        trace_speed=table[:, 17] if len(columns) > 17 else None,
    )

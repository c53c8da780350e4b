"""Fanuc positions: the ``/POS`` section of an .LS file and X-Y-Z-W-P-R values.

A position ``P[n]`` (or ``P[n:"comment"]``) holds, per motion group, the user frame and tool
numbers it was taught with (``UF : 1, UT : 1``), the arm configuration (``CONFIG : 'N U T, 0, 0,
0'``: wrist flip, elbow up, front, turn counts of J1/J4/J6) and either Cartesian values ``X Y Z``
(mm) ``W P R`` (deg; W about the fixed x, P about y, R about z, see
:mod:`coatsim.geometry.space.rotations`) in that user frame, or joint values ``J1``… (deg). The
twin reads group 1 (the arm); its configuration is not used (the twin's inverse kinematics
follows the arm from where it is), other groups and extended axes are noted.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Optional

import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt
from coatsim.geometry.space.pose import InvalidPose, Pose
from coatsim.geometry.space.rotations import matrix_to_wpr, wpr_to_matrix

DECIMALS = 3  # as every controller writes them (the controller stores 32-bit values)
DEFAULT_CONFIG = "N U T, 0, 0, 0"
_BLOCK = re.compile(r"P\[\s*(\d+)\s*(?::[^\]]*)?\]\s*\{(.*?)\}\s*;", re.S | re.I)
_GROUP = re.compile(r"GP(\d+)\s*:", re.I)
_VALUE = re.compile(r"\b([XYZWPR]|J\d+|E\d+)\s*=\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)", re.I)


@dataclass(frozen=True, eq=False)
class Position:
    """A position: user frame and tool numbers (None where the data does not say, as in a
    position register), a Cartesian pose in the user frame or joint values (deg), the extended
    axes it moves, the source line."""

    uf: Optional[int]
    ut: Optional[int]
    pose: Optional[Pose]
    joints_deg: Optional[np.ndarray]
    line: int
    extended: bool = False


def pose_of(values: tuple[float, ...] | np.ndarray) -> Pose:
    """The pose of X, Y, Z (mm), W, P, R (deg); ValueError unless all are finite."""
    x, y, z, w, p, r = (float(v) for v in values)
    return Pose(wpr_to_matrix(w, p, r), np.array([x, y, z]))


def values_of(pose: Pose) -> tuple[float, float, float, float, float, float]:
    """X, Y, Z (mm), W, P, R (deg) of a pose."""
    w, p, r = matrix_to_wpr(pose.rotation)
    x, y, z = (float(v) for v in pose.translation_mm)
    return (x, y, z, w, p, r)


def format_position(index: int, pose: Pose, uf: int, ut: int, config: str = DEFAULT_CONFIG) -> list[str]:
    """The ``/POS`` lines of a Cartesian position."""
    x, y, z, w, p, r = (fmt(v, DECIMALS).rjust(10) for v in values_of(pose))
    return [f"P[{index}]{{", "   GP1:",
            f"\tUF : {uf}, UT : {ut},\t\tCONFIG : '{config}',",
            f"\tX = {x}  mm,\tY = {y}  mm,\tZ = {z}  mm,",
            f"\tW = {w} deg,\tP = {p} deg,\tR = {r} deg", "};"]


def _group_one(body: str, where: str, line: int) -> Position:
    groups = [(int(m.group(1)), m.end()) for m in _GROUP.finditer(body)]
    if not groups:
        text, extra_groups = body, False
    else:
        ends = [start for _, start in groups[1:]] + [len(body)]
        first = next((k for k, (number, _) in enumerate(groups) if number == 1), None)
        if first is None:
            raise InputError(f"{where}: the position has no GP1 (the arm's values)")
        text, extra_groups = body[groups[first][1]:ends[first]], len(groups) > 1
    uf = re.search(r"\bUF\s*:\s*(\d+)", text, re.I)
    ut = re.search(r"\bUT\s*:\s*(\d+)", text, re.I)
    values = {k.upper(): float(v) for k, v in _VALUE.findall(text)}
    cartesian = [values.get(k) for k in "XYZWPR"]
    joints = [values.get(f"J{k}") for k in range(1, 7)]
    extended = extra_groups or any(k.startswith("E") for k in values)
    try:
        if all(v is not None for v in cartesian):
            return Position(int(uf.group(1)) if uf else 0, int(ut.group(1)) if ut else 0, pose_of(cartesian), None,
                            line, extended)
        if all(v is not None for v in joints):
            if not np.isfinite(joints).all():
                raise ValueError
            return Position(int(uf.group(1)) if uf else 0, int(ut.group(1)) if ut else 0, None, np.array(joints),
                            line, extended)
    except (ValueError, InvalidPose):
        raise InputError(f"{where}: the position's values are not finite numbers") from None
    raise InputError(f"{where}: the position needs X, Y, Z, W, P, R (mm, deg) or J1 to J6 (deg)")


def parse_positions(text: str, source: str, first_line: int) -> dict[int, Position]:
    """Every position of a ``/POS`` section (``text`` starts on file line ``first_line``)."""
    positions: dict[int, Position] = {}
    covered, line = 0, first_line  # the file line at ``covered``
    for match in _BLOCK.finditer(text):
        gap = text[covered:match.start()]
        if gap.strip():
            raise InputError(f"{source}:{line + gap[:len(gap) - len(gap.lstrip())].count(chr(10))}: expected a "
                             "position P[n]{ ... }; in /POS")
        line += gap.count("\n")
        covered = match.end()
        index = int(match.group(1))
        if index in positions:
            raise InputError(f"{source}:{line}: P[{index}] is given twice")
        positions[index] = _group_one(match.group(2), f"{source}:{line}", line)
        line += match.group(0).count("\n")
    rest = text[covered:]
    if rest.strip():
        raise InputError(f"{source}:{line + rest[:len(rest) - len(rest.lstrip())].count(chr(10))}: expected a "
                         "position P[n]{ ... }; in /POS")
    return positions

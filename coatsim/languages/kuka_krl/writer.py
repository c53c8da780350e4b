"""KRL writer: a ProgramPlan becomes a ``.src``/``.dat`` pair a WorkVisual user would load.

``name.src``: the process record as ``;coatsim: key=value`` comments, ``DEF name( )``, an INI
fold (``BAS(#INITMOV,0)``), ``$TOOL`` and ``$BASE`` set to the gun and the workpiece frame (poses
are written in it), ``$VEL.CP`` in m/s and ``$APO.CDIS`` in mm, a ``PTP`` above the start, per path
``LIN`` per line and ``CIRC aux, end`` (the auxiliary point at the arc's middle) per arc piece of
at most ``max_arc_sweep_deg``, ``C_DIS`` on every blended point (none: an exact stop), a ``LIN``
depart; ``END``. ``name.dat``: ``DEFDAT name`` with one ``DECL E6POS`` per pose, ``ENDDAT``. The
gun: ``$OUT[n]=TRUE`` at rest (it stops the advance run: the robot is at rest there anyway), and
on the fly ``TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[n]=...`` before the move it starts with.
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from coatsim.core.numbers import MM_DECIMALS, fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import DegenerateArc, arc_through
from coatsim.geometry.space.rotations import matrix_to_abc
from coatsim.languages.kuka_krl.names import check_name
from coatsim.languages.script.header import header_comments
from coatsim.languages.script.names import sanitize_comment
from coatsim.path.placement import PlacedMove, PlacedPath
from coatsim.path.plan import ProgramPlan

MAX_ARC_SWEEP_DEG = 170.0
MAX_COORDINATE_MM = 1e6  # KRL REAL is a 32-bit float
DEG_DECIMALS = 8
DAT_MARK = "DEFDAT"


def _n(value: float, decimals: int = MM_DECIMALS) -> str:
    return fmt_short(value, decimals)


def frame_text(pose: Pose, extra: str = "") -> str:
    a, b, c = matrix_to_abc(pose.rotation)
    x, y, z = pose.translation_mm
    return (f"{{X {_n(x)},Y {_n(y)},Z {_n(z)},A {_n(a, DEG_DECIMALS)},B {_n(b, DEG_DECIMALS)},"
            f"C {_n(c, DEG_DECIMALS)}{extra}}}")


class _Body:
    def __init__(self, frame: Pose, blend: bool) -> None:
        self.lines: list[str] = []
        self.poses: list[Pose] = []
        self.inverse = frame.inverse()
        self.blend = blend

    def name(self, pose: Pose) -> str:
        self.poses.append(self.inverse @ pose)
        return f"P{len(self.poses)}"

    def add(self, statement: str, comment: str = "") -> None:
        text = "  " + statement
        self.lines.append(f"{text.ljust(56)} ; {sanitize_comment(comment)}" if comment else text)

    def move(self, statement: str, stop: bool, comment: str = "") -> None:
        self.add(statement + ("" if stop or not self.blend else " C_DIS"), comment)


def _writable(start: Pose, via: Pose, end: Pose) -> bool:
    points = [np.array([float(_n(v)) for v in p.translation_mm]) for p in (start, via, end)]
    try:
        arc_through(*points)
    except DegenerateArc:
        return False
    return True


def _segment(body: _Body, seg: PlacedMove, label: str, max_sweep: float) -> list[Callable[[bool], None]]:
    if not seg.is_arc:
        return [lambda last, e=seg.end: body.move(f"LIN {body.name(e)}", last, label)]
    pieces = seg.split(math.radians(max_sweep))
    out = []
    for k, piece in enumerate(pieces):
        tag = label if len(pieces) == 1 else f"{label} ({k + 1}/{len(pieces)})"
        if _writable(piece.start, piece.via, piece.end):
            out.append(lambda last, p=piece, t=tag: body.move(f"CIRC {body.name(p.via)}, {body.name(p.end)}", last, t))
        else:
            out.append(lambda last, p=piece, t=tag: body.move(f"LIN {body.name(p.end)}", last,
                                                              f"{t}, arc flatter than the pose resolution"))
    return out


def _path(body: _Body, path: PlacedPath, spray_leads: bool, gun: int, max_sweep: float) -> None:
    moves = []
    count = 0
    for seg in path.segments:
        count += seg.part == "curve"
        label = f"segment {count}" if seg.part == "curve" else seg.part.replace("_", "-")
        moves += [(spray_leads or seg.part == "curve", m) for m in _segment(body, seg, label, max_sweep)]
    gun_on = False
    for k, (sprayed, move) in enumerate(moves):
        if sprayed != gun_on:
            value = "TRUE" if sprayed else "FALSE"
            if k == 0:
                body.add(f"$OUT[{gun}]={value}", f"gun {'on' if sprayed else 'off'}, at rest")
            else:
                body.add(f"TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[{gun}]={value}",
                         f"gun {'on' if sprayed else 'off'} as the next move starts (on the fly)")
            gun_on = sprayed
        move(k == len(moves) - 1)
    if gun_on:
        body.add(f"$OUT[{gun}]=FALSE", "gun off, at rest")


def write_krl(plan: ProgramPlan, max_arc_sweep_deg: float = MAX_ARC_SWEEP_DEG) -> str:
    """The ``.src`` text then the ``.dat`` text of ``plan`` (ASCII, '\\n' line ends)."""
    check_name(plan.name)
    frame = plan.user_frame
    body = _Body(frame, not plan.exact_stop and plan.accuracy_mm > 0)
    back = lambda mm: f"{{X 0,Y 0,Z {_n(-mm)},A 0,B 0,C 0}}"  # noqa: E731
    for index, (path, spray_leads) in enumerate(plan.legs):
        which = f" of contour {index + 1}" if len(plan.paths) > 1 else ""
        start = body.name(path.start)
        if index == 0:
            body.move(f"PTP {start}:{back(plan.approach_of(path))}", False, f"above the start{which}")
        else:
            body.move(f"LIN {start}:{back(plan.approach_of(path))}", False, f"gun off: travel above the start{which}")
        body.move(f"LIN {start}", True, "down to the stand-off")
        _path(body, path, spray_leads, plan.gun_signal, max_arc_sweep_deg)
        end = body.name(path.segments[-1].end)
        body.move(f"LIN {end}:{back(plan.depart_of(path))}", index == len(plan.paths) - 1, "back along the tool axis")
    src = ["&ACCESS RVP", "&REL 1"]
    src += header_comments(plan, ";")
    src += [f"DEF {plan.name}( )", ";FOLD INI", "  BAS(#INITMOV,0)", ";ENDFOLD (INI)",
            f"  $TOOL={frame_text(plan.tool)}", f"  $BASE={frame_text(frame)}",
            f"  $VEL.CP={_n(plan.speed_mm_s / 1000.0, 9)}", f"  $APO.CDIS={_n(plan.accuracy_mm)}",
            *body.lines, "END"]
    dat = ["&ACCESS RVP", "&REL 1", f"{DAT_MARK} {plan.name} PUBLIC"]
    axes = "".join(f",E{k} 0" for k in range(1, 7))
    dat += [f"  DECL E6POS P{k + 1}={frame_text(p, axes)}" for k, p in enumerate(body.poses)]
    dat.append("ENDDAT")
    return "\n".join(src) + "\n" + "\n".join(dat) + "\n"


def split_files(text: str) -> tuple[tuple[str, str], ...]:
    """The ``.src`` and ``.dat`` texts of a written program (the ``.dat`` starts at the header
    line before ``DEFDAT``)."""
    lines = text.splitlines(keepends=True)
    at = next((k for k, line in enumerate(lines) if line.startswith(DAT_MARK)), None)
    if at is None:
        return ((".src", text),)
    start = at
    while start > 0 and lines[start - 1].startswith("&"):
        start -= 1
    return ((".src", "".join(lines[:start])), (".dat", "".join(lines[start:])))

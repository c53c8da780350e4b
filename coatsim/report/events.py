"""Everything that went wrong, or deserves a look, in each variant's run, tied to a program line.

Sources: the robot stage's warnings (``Execution.events``: TOOL mismatch, joint-limit approach,
singularity proximity, tracking error, joint speed or acceleration over the limit; each message
starts with the program step, ``NAME: line N (KIND): ...``), what the twin did not simulate
(``Execution.warnings``, e.g. statements of a user's program), the IK residual, the speed dips
below AT_SPEED of the programmed speed on the curve proper (at the move where the speed is
lowest), the stretches where the curve itself does not allow the programmed speed (the
program header's ``speed_limits``) and, for a closed contour, the seam where the gun switches.
Positions ``s_mm`` are along the curve proper from its start (negative on the run-in).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Optional, Sequence

import numpy as np

from coatsim.path.toolpath import ToolPath

if TYPE_CHECKING:
    from coatsim.robot.execute import Execution

AT_SPEED = 0.95          # a dip: the tool below 95 % of the programmed speed on the curve proper
STOP = 0.05              # at rest: below 5 % of the programmed speed (as motion.stops counts)
IK_NOTE_MM = 0.01        # an IK residual above this is listed (the solver's bound is 0.05 mm)
_MERGE_MM = 1.0          # dips closer than this along the path are one dip

_STEP = re.compile(r"^(?P<program>.*?): (?:line (?P<line>\d+) \((?P<kind>[^)]*)\)|start \(joint move from home\)): (?P<text>.*)$")
_TIME = re.compile(r"at t = (?P<t>[-0-9.]+) s")
_KINDS = (("off the commanded path", "tracking error"), ("joint speed", "joint speed over the limit"),
          ("joint acceleration", "joint acceleration over the limit"), ("singularity", "singularity proximity"),
          ("of its limit [", "joint limit approach"), ("TOOL", "TOOL mismatch"))


@dataclass(frozen=True)
class Event:
    """One event of one variant: what (``kind``), how serious (``warning`` or ``note``), the
    program line (None: not tied to one), the message, where along the curve proper (mm) and
    when (s), where known."""

    variant: str
    kind: str
    severity: str
    line: Optional[int]
    message: str
    s_mm: Optional[float] = None
    t_s: Optional[float] = None


def parse_step(message: str) -> tuple[Optional[int], str, str]:
    """(program line or None, instruction kind, the rest) of a robot-stage message."""
    m = _STEP.match(message)
    if m is None:
        return None, "", message
    return (int(m["line"]) if m["line"] else None), (m["kind"] or "joint move from home"), m["text"]


def _kind(message: str) -> str:
    for key, kind in _KINDS:
        if key in message:
            return kind
    return "other"


class _Locator:
    """Maps log rows and progress (mm) of one run to program lines and curve positions."""

    def __init__(self, execution: Execution, toolpath: ToolPath) -> None:
        self.execution, self.toolpath = execution, toolpath
        self.start = execution.curve[0]

    def move_at(self, progress_mm: float) -> int:
        """The move whose span holds ``progress_mm``; at a junction, the move that ends there
        (the programmed point the arm slows down for)."""
        ref = self.execution.reference
        k = int(np.clip(np.searchsorted(ref.offsets, progress_mm, side="right") - 1, 0, len(ref.offsets) - 1))
        if k > 0 and progress_mm - ref.offsets[k] < 0.5 and ref.moves[k - 1] != ref.moves[k]:
            k -= 1
        return int(ref.moves[k])

    def line_at(self, progress_mm: float) -> Optional[int]:
        move = self.move_at(progress_mm)
        return None if move < 0 else int(self.toolpath.moves[move].line)

    def line_span(self, line: int) -> Optional[tuple[float, float]]:
        """Progress interval of the moves written on ``line``."""
        ref = self.execution.reference
        moves = [i for i, m in enumerate(self.toolpath.moves) if m.line == line and np.any(ref.moves == i)]
        if not moves:
            return None
        spans = [ref.move_span(i) for i in moves]
        return min(a for a, _ in spans), max(b for _, b in spans)

    def s_at_time(self, t_s: float) -> float:
        log = self.execution.log
        row = int(np.clip(np.searchsorted(log.t, t_s), 0, len(log.t) - 1))
        return float(log.progress[row]) - self.start


def robot_events(name: str, execution: Execution, toolpath: ToolPath) -> list[Event]:
    """The robot stage's warnings of one run, each with its line and position."""
    where = _Locator(execution, toolpath)
    out = []
    for message in execution.events:
        line, _, text = parse_step(message)
        t = _TIME.search(text)
        t_s = float(t["t"]) if t else None
        if t_s is not None:
            s = where.s_at_time(t_s)
        else:
            span = None if line is None else where.line_span(line)
            s = None if span is None else 0.5 * (span[0] + span[1]) - where.start
        out.append(Event(name, _kind(text), "warning", line, text, s, t_s))
    for message in getattr(execution, "warnings", ()):  # what the twin did not simulate
        line, _, text = parse_step(message)
        out.append(Event(name, "not simulated", "warning", line, text))
    residual = execution.metrics.max_ik_residual_mm
    if residual > IK_NOTE_MM:
        out.append(Event(name, "IK residual", "note", None,
                         f"largest inverse-kinematics residual {residual:.3f} mm (solver bound 0.05 mm)"))
    return out


def curve_spans(execution: Execution) -> tuple[tuple[float, float], ...]:
    """Progress intervals (mm) of the curve proper: one, or one per contour of a part (the
    travel between contours is no part of it)."""
    return tuple(getattr(execution, "curves", ()) or (execution.curve,))


def speed_dips(name: str, execution: Execution, toolpath: ToolPath) -> list[Event]:
    """Every stretch of the curve proper below AT_SPEED of the programmed speed, at the line of
    the move where the speed is lowest."""
    log, (a, _) = execution.log, execution.curve
    v = execution.metrics.programmed_speed_mm_s
    where = _Locator(execution, toolpath)
    inside = np.zeros(len(log.progress), bool)
    for lo, hi in curve_spans(execution):
        inside |= (log.progress >= lo) & (log.progress <= hi)
    rows = np.flatnonzero(inside)
    if len(rows) == 0:
        return []
    slow = rows[log.speed[rows] < AT_SPEED * v]
    if len(slow) == 0:
        return []
    breaks = np.flatnonzero((np.diff(slow) > 1) & (np.diff(log.progress[slow]) > _MERGE_MM)) + 1
    spans = curve_spans(execution)
    limits = [(lo - a + lim.s0_mm, lo - a + lim.s1_mm, lim.v_max_mm_s)
              for (lo, _), contour in zip(spans, toolpath.process.contours_for(len(spans), toolpath.name))
              for lim in contour.speed_limits]
    out = []
    for run in np.split(slow, breaks):
        low = int(run[np.argmin(log.speed[run])])
        s0, s1, s = (float(log.progress[i]) - a for i in (run[0], run[-1], low))
        allowed = [v_max for s_lo, s_hi, v_max in limits if s_lo - 1.0 <= s <= s_hi + 1.0]
        why = f"; the curve allows at most {min(allowed):.0f} mm/s here" if allowed else ""
        resting = log.speed[run] < STOP * v
        stops = int(np.count_nonzero(resting[1:] & ~resting[:-1]) + resting[0])
        why += f"; {stops} stop{'s' if stops != 1 else ''}" if stops else ""
        out.append(Event(name, "speed dip", "warning", where.line_at(float(log.progress[low])),
                         f"speed falls to {log.speed[low]:.0f} mm/s ({100 * log.speed[low] / v:.0f} % of {v:g}) at "
                         f"s = {s:.1f} mm, below {100 * AT_SPEED:.0f} % from {s0:.1f} to {s1:.1f} mm{why}",
                         s, float(log.t[low])))
    return out


def curve_notes(name: str, execution: Execution, toolpath: ToolPath) -> list[Event]:
    """The curve's speed-limited stretches and true corners (from the program header) and the
    seam of a closed contour; for a part, those of every contour (s from the first contour's
    start, as on the speed plots)."""
    where = _Locator(execution, toolpath)
    spans = curve_spans(execution)
    origin = execution.curve[0]
    part = len(spans) > 1
    out = []
    for k, ((a, b), contour) in enumerate(zip(spans, toolpath.process.contours_for(len(spans), toolpath.name))):
        which = f"contour {k + 1}: " if part else ""
        for lim in contour.speed_limits:
            s0, s1 = a - origin + lim.s0_mm, a - origin + lim.s1_mm
            if lim.s0_mm == lim.s1_mm:
                kind, text = "true corner", f"{which}true corner at s = {s0:.1f} mm: the tool must stop there"
            else:
                kind = "speed-limited stretch"
                text = (f"{which}speed-limited stretch from s = {s0:.1f} to {s1:.1f} mm: the curve allows at most "
                        f"{lim.v_max_mm_s:.0f} mm/s within the tool acceleration limit")
            out.append(Event(name, kind, "note", where.line_at(a + lim.s0_mm), text, s0))
        if contour.closed:
            out.append(Event(name, "seam", "note", where.line_at(a + 1.0),
                             f"{which}seam at s = {a - origin:.1f} mm (= {b - origin:.1f} mm): the gun opens on the fly "
                             "as the lap starts and closes as it ends", a - origin))
    return out


def run_events(name: str, execution: Execution, toolpath: Optional[ToolPath]) -> list[Event]:
    """Every event of one variant's run, warnings first, each group in path order."""
    if toolpath is None:  # nothing to tie the messages to
        messages = (*getattr(execution, "warnings", ()), *execution.events)
        return [Event(name, _kind(m), "warning", parse_step(m)[0], parse_step(m)[2]) for m in messages]
    warnings = robot_events(name, execution, toolpath) + speed_dips(name, execution, toolpath)
    key = lambda e: (e.severity != "warning", e.s_mm if e.s_mm is not None else np.inf)  # noqa: E731
    return sorted(warnings + curve_notes(name, execution, toolpath), key=key)


def lines_of(events: Sequence[Event], variant: str) -> set[int]:
    """Program lines the warnings of ``variant`` point to."""
    return {e.line for e in events if e.variant == variant and e.line is not None and e.severity == "warning"}

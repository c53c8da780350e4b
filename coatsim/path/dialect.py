"""The common interface of robot-language dialects.

A dialect writes a :class:`ProgramPlan` (what to do, independent of any language) as program
text and reads program text back into a :class:`~coatsim.path.toolpath.ToolPath`. Kawasaki AS
is the first; RAPID, KRL or G-code plug in by implementing the same two methods.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from coatsim.path.frames import Frame
from coatsim.path.placement import PlacedPath
from coatsim.path.process import ProcessInfo
from coatsim.path.toolpath import ToolPath


@dataclass(frozen=True, eq=False)
class ProgramPlan:
    """Everything a coating program says, before it is written in a language.

    ``paths`` are sprayed in order; the program approaches the start of the first from
    ``approach_mm`` back along the tool axis, reaches each next one with the gun off by a
    straight travel at that clearance, and departs the same distance after each. The gun is open
    along a whole path (lead-in, curve, lead-out: an open contour) when its contour in
    ``process`` has ``leads_sprayed``, otherwise exactly along its curve part (one lap of a
    closed contour: no double coat at the seam). ``exact_stop`` asks for a stop at every
    programmed point (no blending). ``process`` is written into the program in the language's
    own way and comes back in ``ToolPath.process``; ``comments`` are free header lines for people.
    """

    name: str
    paths: tuple[PlacedPath, ...]
    speed_mm_s: float
    accuracy_mm: float
    exact_stop: bool
    approach_mm: float
    gun_signal: int
    tool: Frame
    process: ProcessInfo = ProcessInfo()
    comments: tuple[str, ...] = ()

    @property
    def legs(self) -> tuple[tuple[PlacedPath, bool], ...]:
        """Every sprayed path with whether the gun covers its lead-in and lead-out."""
        contours = self.process.contours_for(len(self.paths), self.name)
        return tuple((path, contour.leads_sprayed) for path, contour in zip(self.paths, contours))


class Dialect(Protocol):
    """A robot language coatsim can write and read."""

    name: str
    suffix: str

    def write(self, plan: ProgramPlan) -> str:
        """Complete program text for ``plan`` (deterministic)."""
        ...

    def read(self, text: str, source: str, gun_signal: int = 1) -> ToolPath:
        """The ToolPath the program text makes the robot execute; InputError on any defect."""
        ...

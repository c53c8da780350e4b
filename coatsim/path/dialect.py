"""The common interface of robot-language dialects.

A dialect writes a :class:`ProgramPlan` (what to do, independent of any language) as program
text and reads program text back into a :class:`~coatsim.path.toolpath.ToolPath`. Kawasaki AS
is the first; RAPID, KRL or G-code plug in by implementing the same two methods.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from coatsim.path.placement import Frame, PlacedPath
from coatsim.path.toolpath import ToolPath


@dataclass(frozen=True, eq=False)
class ProgramPlan:
    """Everything a coating program says, before it is written in a language.

    The program approaches the start of ``path`` from ``approach_mm`` back along the tool axis
    and departs the same distance after its end. The gun is open along the whole path when
    ``spray_leads`` (lead-in, curve, lead-out: an open contour), otherwise exactly along its
    ``curve`` part (one lap of a closed contour: no double coat at the seam).
    ``further_paths`` (the other contours of a part, each with its own ``spray_leads``) are
    sprayed after it in order, each reached with the gun off by a straight travel at the
    approach clearance.
    ``exact_stop`` asks for a stop at every programmed point (no blending).
    ``metadata`` pairs are written as machine-readable header comments and come back in
    ``ToolPath.metadata``; ``comments`` are free header lines for people.
    """

    name: str
    path: PlacedPath
    speed_mm_s: float
    accuracy_mm: float
    exact_stop: bool
    approach_mm: float
    gun_signal: int
    tool: Frame
    spray_leads: bool = True
    metadata: tuple[tuple[str, str], ...] = ()
    comments: tuple[str, ...] = ()
    further_paths: tuple[tuple[PlacedPath, bool], ...] = ()

    @property
    def paths(self) -> tuple[PlacedPath, ...]:
        """Every sprayed path, in spray order."""
        return (self.path, *(path for path, _ in self.further_paths))

    @property
    def legs(self) -> tuple[tuple[PlacedPath, bool], ...]:
        """Every sprayed path with whether the gun covers its lead-in and lead-out."""
        return ((self.path, self.spray_leads), *self.further_paths)


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

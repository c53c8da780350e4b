"""ProgramPlan: what a coating program does, before it is written in a language."""

from __future__ import annotations

from dataclasses import dataclass

from coatsim.geometry.space.pose import Pose
from coatsim.path.placement import PlacedPath
from coatsim.path.process import ProcessInfo


@dataclass(frozen=True, eq=False)
class ProgramPlan:
    """Everything a coating program says, before it is written in a language.

    ``paths`` are sprayed in order; the program approaches the start of the first from
    ``approach_mm`` back along the tool axis, reaches each next one with the gun off by a
    straight travel at that clearance, and departs the same distance after each (a path may
    ask for more: ``approach_of``, ``depart_of``). The gun is open
    along a whole path (lead-in, curve, lead-out: an open contour) when its contour in
    ``process`` has ``leads_sprayed``, otherwise exactly along its curve part (one lap of a
    closed contour: no double coat at the seam). ``exact_stop`` asks for a stop at every
    programmed point (no blending). ``process`` is written into the program in the language's
    own way and comes back in ``ToolPath.process``; ``comments`` are free header lines for people.
    Poses are in the robot base frame; ``work_frame`` (None: the workpiece frame of ``process``,
    else the base frame) is the user frame a language that names one (RAPID ``wobjdata``, KRL
    ``$BASE``) writes them relative to: the same path, in coordinates a person reads on the part.
    """

    name: str
    paths: tuple[PlacedPath, ...]
    speed_mm_s: float
    accuracy_mm: float
    exact_stop: bool
    approach_mm: float
    gun_signal: int
    tool: Pose
    process: ProcessInfo = ProcessInfo()
    comments: tuple[str, ...] = ()
    work_frame: Pose | None = None

    @property
    def user_frame(self) -> Pose:
        """The frame poses are written relative to by a language that names one (see above)."""
        frame = self.work_frame if self.work_frame is not None else self.process.frame
        return frame if frame is not None else Pose.identity()

    def approach_of(self, path: PlacedPath) -> float:
        """How far back along the tool axis the tool comes in to the start of ``path`` (mm)."""
        return self.approach_mm if path.approach_clearance_mm is None else path.approach_clearance_mm

    def depart_of(self, path: PlacedPath) -> float:
        """How far back along the tool axis the tool leaves the end of ``path`` (mm)."""
        return self.approach_mm if path.depart_clearance_mm is None else path.depart_clearance_mm

    @property
    def legs(self) -> tuple[tuple[PlacedPath, bool], ...]:
        """Every sprayed path with whether the gun covers its lead-in and lead-out."""
        contours = self.process.contours_for(len(self.paths), self.name)
        return tuple((path, contour.leads_sprayed) for path, contour in zip(self.paths, contours))

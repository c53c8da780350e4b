"""What a robot language must offer coatsim: write a plan, read program files back.

A language is a plug-in (one package under ``coatsim.languages``, one line in its registry)
implementing :class:`Language`. The program core (this package) only ever sees this interface:
it builds language-neutral :class:`~coatsim.path.plan.ProgramPlan` values and hands them to a
language; the twin only ever runs what a language's reader makes of the text.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, Mapping, Optional, Protocol, Sequence, Union

from coatsim.core import defaults
from coatsim.path.plan import ProgramPlan
from coatsim.path.reading import Reading
from coatsim.path.toolpath import Kinematics, ToolPath

UNTILTED_TOL_RAD = 1e-6  # a gun axis this far from -Z is a tilt a language without tool orientation cannot write

#: Where a language's native circular move may lie: in any plane, only in the principal planes
#: of its frame (G-code G17/G18/G19), or nowhere (arcs are written as lines).
ArcPlanes = Literal["any", "principal", "none"]


@dataclass(frozen=True)
class Capabilities:
    """What a language can express, so that the program core plans what it can write.

    ``arc_planes`` where native arcs may lie; ``max_arc_sweep_deg`` the longest arc one
    circular move may turn (longer arcs are split); ``blend`` how the controller rounds a
    corner between blended moves, in the language's terms; ``max_name_length`` the longest
    program name; ``max_coordinate_mm`` the largest coordinate a program may hold;
    ``rotation`` the convention its poses are written in; ``motions`` the words of its linear and
    circular moves, as messages name them (``LMOVE/C1MOVE/C2MOVE``); ``named_by_file``: the
    controller requires a program's name to be its file's name (KRL ``DEF``, Fanuc ``/PROG``);
    ``program_files`` the suffixes of the files one written program is saved as, the main first
    (empty: the one file of the language's first suffix); ``tool_orientation``: its poses turn
    the gun (False: the gun points along -Z, within ``UNTILTED_TOL_RAD``, everywhere).
    """

    arc_planes: ArcPlanes
    max_arc_sweep_deg: float
    blend: str
    max_name_length: int
    max_coordinate_mm: float
    rotation: str
    motions: str = "linear and circular"
    named_by_file: bool = False
    program_files: tuple[str, ...] = ()
    tool_orientation: bool = True


@dataclass(frozen=True)
class ReadOptions:
    """How to read program files: the process output (``gun_signal``), the main program
    (None: the language's rule, e.g. the first one loaded), the state of inputs a program waits
    for, the cell's kinematics (for poses given in joints), values of variables no file gives
    (the controller keeps them), and whether the reading needs the path the gun sprays
    (``needs_spray``: a program that never opens the gun is then refused, naming the outputs it
    does switch; reading is not spraying otherwise)."""

    gun_signal: int = defaults.GUN_SIGNAL
    program: Optional[str] = None
    inputs: Mapping[int, bool] = field(default_factory=dict)
    kinematics: Optional[Kinematics] = None
    variables: Mapping[str, Union[str, float]] = field(default_factory=dict)
    needs_spray: bool = False


class Language(Protocol):
    """A robot language coatsim writes and reads."""

    name: str
    title: str
    suffixes: tuple[str, ...]
    capabilities: Capabilities

    def write(self, plan: ProgramPlan) -> str:
        """Complete program text for ``plan`` (deterministic): for a language whose program is
        several files (KRL's ``.src`` and ``.dat``), every file one after the other, as
        :meth:`files` splits them."""
        ...

    def files(self, text: str) -> tuple[tuple[str, str], ...]:
        """The files a written program's text is saved as: (suffix, text) each, the main file
        first (for most languages the one file ``((suffixes[0], text),)``)."""
        ...

    def recognizes(self, text: str) -> bool:
        """Whether the opening of a file (its first few kB, decoded) looks like this language:
        how a file whose suffix several languages claim, or none, is told apart."""
        ...

    def read(self, files: Sequence[Path], options: ReadOptions) -> ToolPath:
        """The ToolPath the program files, loaded together, make the robot execute;
        InputError naming file:line on any defect, ExecutionError where it cannot run
        (``reading(files, options).toolpath_to_run(...)``)."""
        ...

    def reading(self, files: Sequence[Path], options: ReadOptions) -> Reading:
        """The files read and interpreted with what check-program and convert need (every
        move's source lines, the output switches, problems); reading is not running: a statement
        that cannot run for want of a value is skipped and listed, not an error."""
        ...

    def check_name(self, name: str, what: str) -> str:
        """``name`` if it is a valid program name; InputError naming ``what`` otherwise."""
        ...

    def program_name(self, text: str) -> str:
        """A valid program name made from any text."""
        ...

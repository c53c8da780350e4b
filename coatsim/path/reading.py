"""Reading: what a language's reader makes of program files, beyond the ToolPath.

``check-program`` reports from it and ``convert`` rewrites from it without knowing the language:
each move's source (file, program, lines), the frame its poses were given in, the statements
that switch outputs, the variables read that no file gives, the statements skipped for want of a
value, and the problems and counts only the language can tell (its name rules, its data). The
language builds it; everything here is language-neutral.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

from coatsim.core.errors import ExecutionError, InputError
from coatsim.geometry.space.pose import Pose
from coatsim.path.toolpath import ToolPath


@dataclass(frozen=True)
class MoveSource:
    """Where one move comes from: the ``source`` file, the ``program`` (routine) it runs in, and
    the first and last source lines of the statements that make it (an arc written as a via
    statement and an end statement spans two lines)."""

    source: str
    program: str
    first_line: int
    last_line: int


@dataclass(frozen=True)
class OutputSwitch:
    """A statement that switches outputs, as the language writes it (``text``: ``SetDO do1, 1``,
    with what it does to the gun in brackets where it is the gun)."""

    source: str
    line: int
    text: str

    def __str__(self) -> str:
        return f"{self.source}:{self.line}: {self.text}"


@dataclass(frozen=True, eq=False)
class Reading:
    """Program files read and interpreted, whether or not the twin can run them.

    ``sources`` the files read, ``program`` the main program with the file and
    line that define it, ``programs`` every program (routine) loaded; ``ended`` how the main
    program ends (``it ends at line 12`` or ``prog.mod:9: Stop ends it``). ``move_sources`` and
    ``move_frames`` hold one entry per move of ``toolpath``: where it comes from and the user frame
    (BASE, work object) its poses were given in. ``n_steps`` counts the main program's statements,
    ``n_poses`` the poses the files declare. ``switches`` lists every statement that switches
    outputs, ``outputs`` the outputs switched, ``unnumbered`` the output signals switched that
    have no number (a RAPID signal named without digits: no output number until a variable gives
    it one), each with where it is first switched. ``problems`` are what is legal but suspicious in the
    language's own terms, ``notes`` what a reader must know; ``unknowns`` the variables read that
    no file gives (with their first line), ``skipped`` the statements not run for want of a
    value, of which ``unsimulated`` are those the twin does not simulate. ``gun_on_at_end``: the
    gun output is still on when the program ends. ``external_axes``: the poses hold external axis
    values (a rail, a positioner), which coatsim does not move.
    """

    toolpath: ToolPath
    sources: tuple[str, ...]
    program: str
    program_source: str
    program_line: int
    programs: tuple[str, ...]
    ended: str
    move_sources: tuple[MoveSource, ...]
    move_frames: tuple[Pose, ...]
    n_steps: int
    n_poses: int
    switches: tuple[OutputSwitch, ...] = ()
    outputs: tuple[int, ...] = ()
    unnumbered: tuple[str, ...] = ()
    problems: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    unknowns: tuple[str, ...] = ()
    skipped: tuple[str, ...] = ()
    unsimulated: tuple[str, ...] = ()
    gun_on_at_end: bool = False
    external_axes: bool = False

    @property
    def source(self) -> str:
        """The files read, comma-separated."""
        return ", ".join(self.sources)

    def require_complete(self) -> None:
        """What simulates or rewrites the path needs every statement: InputError naming the first
        one skipped for want of a value, ExecutionError when it is one the twin does not simulate."""
        require_every_statement(self.skipped, self.unsimulated)

    def toolpath_to_run(self, gun_signal: int, needs_spray: bool, first_file: str) -> ToolPath:
        """The ToolPath the twin runs: every statement run (see :meth:`require_complete`), and
        with ``needs_spray`` a sprayed path (InputError naming the outputs switched instead)."""
        self.require_complete()
        if needs_spray and not self.toolpath.spray_moves:
            raise InputError(f"{gun_never_on(first_file, gun_signal, self.outputs, self.unnumbered)}; give the output that opens the "
                             "gun as gun_signal", parameters=("gun_signal",))
        return self.toolpath


def gun_never_on(source: str, gun_signal: int, outputs: tuple[int, ...], unnumbered: tuple[str, ...] = ()) -> str:
    """What to say of a program that never sprays: the outputs it switches instead."""
    return f"{source}: the gun (output {gun_signal}) is never on during a motion; {outputs_switched(outputs, unnumbered)}"


def outputs_switched(outputs: tuple[int, ...], unnumbered: tuple[str, ...]) -> str:
    """The outputs a program switches (it never opens the gun): their numbers, and the signals
    it switches that have no number (with where, and how to number them)."""
    said = [f"output{'s' if len(outputs) > 1 else ''} {', '.join(map(str, outputs))}"] if outputs else []
    if unnumbered:
        said.append(f"signal{'s' if len(unnumbered) > 1 else ''} {', '.join(unnumbered)} with no number (a "
                    "variable of the signal's name numbers it, NAME=N)")
    return f"it switches {' and '.join(said)}" if said else "it switches no output"


def require_every_statement(skipped: Sequence[str], unsimulated: Collection[str]) -> None:
    """What simulates or rewrites a path needs every statement: InputError naming the first of
    ``skipped`` (left out for want of a value), ExecutionError when it is one of ``unsimulated``."""
    if not skipped:
        return
    more = f" (and {len(skipped) - 1} more)" if len(skipped) > 1 else ""
    if skipped[0] in unsimulated:
        raise ExecutionError(f"{skipped[0]}{more}; a simulation runs every statement, and the twin does not "
                             "simulate this one")
    raise InputError(f"{skipped[0]}{more}; a simulation runs every statement (give missing values as "
                     "NAME=VALUE)")

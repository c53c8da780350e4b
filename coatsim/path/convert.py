"""``coatsim convert``: an existing program in, the same process path sprayed with arcs out.

The program is read in its language (:class:`~coatsim.path.reading.Reading`). The process path
is every stretch of Cartesian moves the gun sprays (or the moves of a range of lines). Each is
fitted in its plane, or in space if it has none, with the original's tool at every pose
(:mod:`coatsim.path.path_fit`), and written as linear and circular moves: in place of the
statements that made it, by a language that edits its programs in place
(:mod:`coatsim.path.edit`; same poses, tool, speed and signals around it, every other line kept
byte for byte), or as a clean standalone program in any language (the same frame, tool, speed and
gun output). The result is read back and interpreted: the deviation reported is measured on the
program as written, against the original path.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Mapping, Optional, Sequence, Union

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import CoatsimError, InputError
from coatsim.core.fileio import read_input
from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.pose import Pose
from coatsim.path.edit import EditsInPlace, FittedPath
from coatsim.path.frames import DEFAULT_TOOL
from coatsim.path.language import Language, ReadOptions
from coatsim.path.path_fit import fit_path, moves_written, taught_move
from coatsim.path.placement import PlacedPath
from coatsim.path.plan import ProgramPlan
from coatsim.path.process import ProcessInfo
from coatsim.path.process_path import dense_points, moves_in_lines, path_distance, spray_runs
from coatsim.path.reading import Reading, outputs_switched
from coatsim.path.taught_orientation import tool_angle
from coatsim.path.toolpath import CircularMove, Kinematics, ToolPath

Paths = Union[str, Path, Sequence[Union[str, Path]]]

@dataclass(frozen=True)
class ConvertOptions:
    """What to convert and how; ``lines`` a (first, last) source line range instead of the
    sprayed moves."""

    tolerance_mm: float
    gun_signal: int = 1
    program: Optional[str] = None
    lines: Optional[tuple[int, int]] = None
    standalone: bool = False
    corner_deg: float = defaults.CORNER_DEG
    approach_mm: float = 50.0
    name: Optional[str] = None
    angle_tol_deg: float = defaults.ANGLE_TOL_DEG

    def __post_init__(self) -> None:
        if not (math.isfinite(self.angle_tol_deg) and 0.0 < self.angle_tol_deg < 90.0):
            raise InputError(f"angle_tol_deg {self.angle_tol_deg}: must be between 0 and 90 (deg)",
                             parameters=("angle_tol_deg",))
        if not (math.isfinite(self.tolerance_mm) and self.tolerance_mm > 0.0):
            raise InputError(f"tolerance_mm {self.tolerance_mm}: must be a finite number > 0 (mm)",
                             parameters=("tolerance_mm",))
        if not (math.isfinite(self.approach_mm) and self.approach_mm >= 0.0):
            raise InputError(f"approach_mm {self.approach_mm}: must be a finite number >= 0 (mm)",
                             parameters=("approach_mm",))


@dataclass(frozen=True)
class PathReport:
    """Figures of one converted path: the source lines replaced (in place) or the path came
    from (standalone); ``plane_deviation_mm`` how far the path leaves its plane (None: fitted
    in space); ``deviation_mm`` measured on the program written; ``tool_angle_deg`` the largest
    angle the new program's tool (its spray axis, in a language that does not turn the gun)
    turns away from the original's; ``kept``: the arcs gained no move, the path is as it was."""

    first_line: int
    last_line: int
    moves_before: int
    moves_after: int
    n_arcs: int
    n_lines: int
    plane_deviation_mm: Optional[float]
    deviation_mm: float
    length_mm: float
    kept: bool = False
    tool_angle_deg: float = 0.0


@dataclass(frozen=True, eq=False)
class Conversion:
    """The written program text, the input file it replaces (None: standalone), the figures;
    ``data`` the bytes to write (the original's encoding and line ends kept); ``written`` False
    when no path gains a move in the original's language: there is nothing to write."""

    text: str
    replaces: Optional[str]
    paths: tuple[PathReport, ...]
    notes: tuple[str, ...]
    tolerance_mm: float
    data: bytes
    written: bool = True


def _candidates(reading: Reading, options: ConvertOptions, motions: str) -> list[tuple[int, ...]]:
    toolpath = reading.toolpath
    if options.lines is not None:
        moves = moves_in_lines(toolpath, reading.move_sources, *options.lines, motions)
        sprayed = {toolpath.moves[i].spray for i in moves}
        if len(sprayed) > 1:
            off = next(toolpath.moves[i].line for i in moves if not toolpath.moves[i].spray)
            raise InputError(f"lines {options.lines[0]}-{options.lines[1]}: the gun sprays some of these moves and "
                             f"not others (line {off}); choose lines the gun sprays throughout, or none of",
                             parameters=("lines",))
        return [moves]
    runs = [r for r in spray_runs(toolpath) if len(r) >= 2]
    if not runs:
        switched = outputs_switched(reading.outputs, reading.unnumbered)
        raise InputError(f"no process path: the gun (output {options.gun_signal}) is never on over two or more "
                         f"consecutive {motions} moves ({switched}: is the process signal one of "
                         "them?); name the moves with lines FIRST-LAST", parameters=("lines",))
    return runs


def _settings(toolpath: ToolPath, f: FittedPath) -> tuple[float, float, bool]:
    """Speed (of the longest move), accuracy and CP a path was sprayed with."""
    moves = [toolpath.moves[i] for i in f.path.moves]
    lengths = np.array([float(np.linalg.norm(m.end.translation_mm - m.start.translation_mm)) for m in moves])
    first = moves[0].settings
    return float(moves[int(np.argmax(lengths))].settings.speed_mm_s), float(first.accuracy_mm), first.cp


def _program_name(target: Language, options: ConvertOptions, original: str) -> str:
    """The standalone program's name: ``options.name`` (checked), else the original's if the
    target language allows it (cut to its length), else one made from it."""
    if options.name is not None:
        return target.check_name(options.name, "name")
    cut = original[:target.capabilities.max_name_length]
    try:
        return target.check_name(cut, "program name")
    except InputError:
        return target.program_name(original)


def _standalone(reading: Reading, fitted: list[FittedPath], options: ConvertOptions, target: Language) -> str:
    """One clean program spraying every path in turn (each approached and departed alike), in
    the frame the original gave the first path's poses in, with its tool."""
    toolpath = reading.toolpath
    spans = ", ".join(f"{f.lines[0]}-{f.lines[1]}" for f in fitted)
    settings = {_settings(toolpath, f) for f in fitted}
    if len(settings) != 1:
        raise InputError(f"choose one path with lines FIRST-LAST: the {len(fitted)} process paths (at {spans}) are "
                         "sprayed with different speeds or accuracies and a standalone program writes them with one",
                         parameters=("lines",))
    speed, accuracy, cp = settings.pop()
    tool = toolpath.tool
    tool_frame = Pose(tool.rotation, tool.offset_mm) if tool is not None else DEFAULT_TOOL
    paths = tuple(PlacedPath(f.segments, -f.segments[0].start.rotation[:, 2] if f.plane is None else f.plane.normal,
                             0.0, 0.0, 0.0, float(sum(s.length for s in f.segments))) for f in fitted)
    n_moves = sum(len(f.path.moves) for f in fitted)
    n_segments = sum(len(f.segments) for f in fitted)
    process = ProcessInfo(variant="convert", source=f"{toolpath.name} lines {spans}",
                          tolerance_mm=options.tolerance_mm, curve_length_mm=sum(p.length for p in paths),
                          gun_signal=options.gun_signal, n_segments=n_segments,
                          n_lines=sum(f.n_lines for f in fitted), n_arcs=sum(f.n_arcs for f in fitted))
    frame = reading.move_frames[fitted[0].path.moves[0]] if reading.move_frames else None
    plan = ProgramPlan(
        name=_program_name(target, options, toolpath.name), paths=paths, speed_mm_s=speed,
        accuracy_mm=accuracy, exact_stop=not cp, approach_mm=options.approach_mm, gun_signal=options.gun_signal,
        tool=tool_frame, process=process, work_frame=frame,
        comments=(f"coatsim convert: lines {spans} of {toolpath.name}, {n_moves} moves -> "
                  f"{n_segments} lines and arcs within {fmt_short(options.tolerance_mm)} mm",),
    )
    return target.write(plan)


def _read_written(language: Language, files: Sequence[tuple[str, bytes]], options: ReadOptions) -> Reading:
    """Read program files not yet saved ((name, bytes), the main first) from a temporary folder,
    so any reader reads them as it reads files."""
    with tempfile.TemporaryDirectory(prefix="coatsim-convert-") as folder:
        written = []
        for name, data in files:
            path = Path(folder) / name
            path.write_bytes(data)
            written.append(path)
        return language.reading(written, options)


def convert_program(paths: Paths, options: ConvertOptions, *, language: Language, target: Optional[Language] = None,
                    inputs: Optional[Mapping[int, bool]] = None, kinematics: Optional[Kinematics] = None,
                    variables: Optional[Mapping[str, Union[str, float]]] = None) -> Conversion:
    """Convert the process path(s) of program files of ``language`` loaded together: in place
    (a language that edits in place, ``target`` None or the same language, not ``standalone``)
    or as a standalone program in ``target`` (default: the same language). InputError on what
    cannot be converted (not editable in place, a statement skipped for want of a
    value that ``variables`` does not give), with the reason."""
    items = [Path(paths)] if isinstance(paths, (str, Path)) else [Path(p) for p in paths]
    target = target or language
    standalone = options.standalone or target is not language
    read_options = ReadOptions(gun_signal=options.gun_signal, program=options.program, inputs=inputs or {},
                               kinematics=kinematics, variables=variables or {})
    if options.name is not None:
        target.check_name(options.name, "name")
    if not standalone and not isinstance(language, EditsInPlace):
        raise InputError(f"{language.title} programs are not edited in place: write a standalone program",
                         parameters=("standalone",))
    reading = language.reading(items, read_options)
    reading.require_complete()
    motions = language.capabilities.motions
    limit, taught = target.capabilities.max_arc_sweep_deg, target is language
    fitted = [fit_path(reading, c, options.tolerance_mm, options.corner_deg, limit, taught, options.angle_tol_deg,
                       target.capabilities.arc_planes) for c in _candidates(reading, options, motions)]
    notes = [n for f in fitted for n in f.notes]
    gains = [moves_written(f.segments, limit) < len(f.path.moves) for f in fitted]
    notes += [f"lines {f.lines[0]}-{f.lines[1]}: the arc program has no fewer moves "
              f"({moves_written(f.segments, limit)} against {len(f.path.moves)}: {f.n_lines} lines and {f.n_arcs} "
              f"arcs): the path is {'kept as it was' if taught else 'written move for move as the original'}"
              for f, gained in zip(fitted, gains) if not gained]
    kept = [_kept_report(reading, f) for f, gained in zip(fitted, gains) if not gained]
    if taught and not any(gains):
        return Conversion("", None, tuple(kept), tuple(notes), options.tolerance_mm, b"", written=False)
    if standalone:
        fitted = [f if gained else _as_taught(reading, f, taught) for f, gained in zip(fitted, gains)]
        text, replaces, counts, ranges = _standalone(reading, fitted, options, target), None, None, [f.lines for f in fitted]
        data = text.encode("ascii")
        written = [(f"converted{suffix}", body.encode("ascii")) for suffix, body in target.files(text)]
        notes += _dwells_dropped(reading.toolpath, fitted)
        if reading.external_axes:
            notes.append("the original's poses hold external axis values (a rail, a positioner); the standalone "
                         "program's poses have none: add them before loading it on such a cell")
    else:
        fitted = [f for f, gained in zip(fitted, gains) if gained]
        edit = language.edit_in_place(items, read_options, fitted, options.tolerance_mm)
        replaces, data, counts, ranges = edit.source, edit.data, list(edit.counts), list(edit.ranges)
        text = data.decode("utf-8" if _is_utf8(data) else "latin-1")
    try:
        if standalone:
            given = read_options.variables if target is language else {}  # the original's values are of its language
            new = _read_written(target, written, replace(read_options, program=None, variables=given))
        else:
            new = _read_edited(language, items, replaces, data, read_options)
    except CoatsimError as exc:
        raise InputError(f"the converted program does not run as the original ({exc}); use --standalone") from None
    reports = _verify(reading.toolpath, new.toolpath, fitted, counts, ranges, options.tolerance_mm,
                      target.capabilities.tool_orientation, replaces or "the standalone program")
    notes += _axis_only(target)
    fitted_reports = reports if not standalone else [r for r, gained in zip(reports, gains) if gained]
    notes += [f"lines {r.first_line}-{r.last_line}: the arc program has no fewer moves ({r.moves_after} against "
              f"{r.moves_before}: {r.n_lines} lines and {r.n_arcs} arcs; an arc over {limit:g} deg takes several "
              f"{target.capabilities.motions} moves)" for r in fitted_reports if r.moves_after >= r.moves_before]
    if standalone:
        reports = [replace(r, kept=taught and not gained) for r, gained in zip(reports, gains)]
    else:
        reports = sorted(reports + kept, key=lambda r: r.first_line)
    return Conversion(text, replaces, tuple(reports), tuple(notes), options.tolerance_mm, data)


def _axis_only(target: Language) -> list[str]:
    """The note for a language that does not turn the gun: the tool's angle is its axis's."""
    if target.capabilities.tool_orientation:
        return []
    return [f"{target.title} does not turn the gun: the angle given is the spray axis's (the gun's turn about it "
            "is the work frame's)"]


def _as_taught(reading: Reading, f: FittedPath, taught: bool) -> FittedPath:
    """The path ``f`` as the original moves it, move for move."""
    segments = tuple(taught_move(reading.toolpath.moves[i], taught) for i in f.path.moves)
    n_arcs = sum(s.is_arc for s in segments)
    return replace(f, segments=segments, n_arcs=n_arcs, n_lines=len(segments) - n_arcs, fit_deviation_mm=0.0)


def _kept_report(reading: Reading, f: FittedPath) -> PathReport:
    """The figures of a path kept as it was: its own moves, no deviation."""
    n = len(f.path.moves)
    n_arcs = sum(isinstance(reading.toolpath.moves[i], CircularMove) for i in f.path.moves)
    return PathReport(f.lines[0], f.lines[1], n, n, n_arcs, n - n_arcs, _plane_deviation(f), 0.0, f.path.length_mm,
                      kept=True)


def _plane_deviation(f: FittedPath) -> Optional[float]:
    return None if f.plane is None else f.plane.deviation_mm


def _read_edited(language: Language, items: Sequence[Path], replaces: str, data: bytes, options: ReadOptions) -> Reading:
    """Read ``items`` with the file ``replaces`` holding ``data`` instead, in their order: every
    file from a temporary folder (the edited one under its own name)."""
    with tempfile.TemporaryDirectory(prefix="coatsim-convert-") as folder:
        paths = []
        for k, item in enumerate(items):
            path = Path(folder) / str(k) / item.name
            path.parent.mkdir()
            path.write_bytes(data if str(item) == replaces else read_input(item, "program"))
            paths.append(path)
        return language.reading(paths, options)


def _dwells_dropped(toolpath: ToolPath, fitted: list[FittedPath]) -> list[str]:
    """Notes for the waits inside a process path (TWAIT, DELAY between two sprayed moves: a
    thick spot in the original) that the standalone program, moving on, does not have."""
    notes = []
    for f in fitted:
        first, last = f.path.moves[0], f.path.moves[-1]
        inside = [d for d in toolpath.dwells if first <= d.after < last and d.seconds > 0]
        if inside:
            waits = ", ".join(f"line {d.line} ({d.seconds:g} s)" for d in inside)
            notes.append(f"lines {f.lines[0]}-{f.lines[1]}: the original waits on the path at {waits}; the "
                         "standalone program sprays the path without stopping")
    return notes


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


def _same(a, b) -> bool:
    end_a = a.target if a.kind == "joint" else a.end
    end_b = b.target if b.kind == "joint" else b.end
    return a.kind == b.kind and a.spray == b.spray and np.allclose(end_a.translation_mm, end_b.translation_mm, atol=1e-6)


def _verify(original: ToolPath, converted: ToolPath, fitted: list[FittedPath], counts: Optional[list[int]],
            ranges: list[tuple[int, int]], tolerance_mm: float, roll: bool, where: str) -> list[PathReport]:
    """Each new process path against its original, measured both ways on the programs' paths
    (and the tool along it against the original's: its spray axis alone without ``roll``); in
    place, every other move must be the same as before (``where`` names the file edited)."""
    old, new = original.moves, converted.moves
    blocks = []
    if counts is None:
        blocks = [[new[i] for i in r] for r in spray_runs(converted)]
        if len(blocks) != len(fitted):
            raise InputError(f"the standalone program sprays {len(blocks)} paths, not the {len(fitted)} converted")
    else:
        if len(new) != len(old) + sum(c - len(f.path.moves) for f, c in zip(fitted, counts)):
            raise InputError(f"{where}: the converted program moves differently from the original outside the "
                             "process path; use --standalone")
        offset, done = 0, 0
        for f, c in zip(fitted, counts):
            first, n = f.path.moves[0], len(f.path.moves)
            if not all(_same(old[i], new[i + offset]) for i in range(done, first)):
                raise InputError(f"{where}: the converted program moves differently from the original before the "
                                 "process path; use --standalone")
            block = list(new[first + offset:first + offset + c])
            if any(m.spray != old[first].spray for m in block):
                raise InputError(f"{where}: the gun does not spray the converted path as it sprayed the original; "
                                 "use --standalone")
            blocks.append(block)
            offset, done = offset + c - n, first + n
        if not all(_same(old[i], new[i + offset]) for i in range(done, len(old))):
            raise InputError(f"{where}: the converted program moves differently from the original after the "
                             "process path; use --standalone")
    reports = []
    for f, block, (first, last) in zip(fitted, blocks, ranges):
        old_moves = [old[i] for i in f.path.moves]
        a, b = dense_points(old_moves, tolerance_mm / 20.0), dense_points(block, tolerance_mm / 20.0)
        deviation = max(path_distance(a, b), path_distance(b, a))
        tool = tool_angle([taught_move(m, False) for m in block], f.path, tolerance_mm, roll)
        reports.append(PathReport(first, last, len(old_moves), len(block), f.n_arcs, f.n_lines,
                                  _plane_deviation(f), deviation, f.path.length_mm, tool_angle_deg=math.degrees(tool)))
    return reports


def conversion_summary(c: Conversion) -> str:
    """The report of ``coatsim convert``: one line per path, then the notes."""
    out = []
    for r in c.paths:
        if r.kept:
            out.append(f"lines {r.first_line}-{r.last_line}: {r.moves_before} moves ({r.n_lines} lines + {r.n_arcs} arcs) "
                       "kept as they were")
            continue
        where = ("in space, arcs each in its own plane" if r.plane_deviation_mm is None
                 else f"out of plane {r.plane_deviation_mm:.4f} mm")
        tool = f"; tool within {r.tool_angle_deg:.2f} deg of the original's" if r.tool_angle_deg >= 0.005 else ""
        out.append(f"lines {r.first_line}-{r.last_line}: {r.moves_before} moves -> {r.moves_after} "
                   f"({r.n_lines} lines + {r.n_arcs} arcs), path {r.length_mm:.3f} mm, deviation {r.deviation_mm:.4f} mm "
                   f"(tolerance {c.tolerance_mm:g} mm; {where}{tool})")
    before, after = sum(r.moves_before for r in c.paths), sum(r.moves_after for r in c.paths)
    done = ("nothing gained: no program written (the original stays as it is)" if not c.written
            else f"path replaced in a copy of {c.replaces} (every other line as it was)" if c.replaces
            else "standalone program")
    out.append(f"moves on the process path: {before} -> {after}; {done}")
    out += [f"note: {n}" for n in c.notes]
    return "\n".join(out)

"""The ``coatsim program`` stage function: input -> program file, and its one-paragraph summary."""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path
from typing import Optional

from coatsim.core.errors import CoatsimWarning
from coatsim.core.fileio import write_text
from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.languages.kawasaki_as.parser import parse_as
from coatsim.path.build import BuiltProgram, ProgramOptions
from coatsim.path.check import ProgramCheck
from coatsim.path.inputs import load_part_input
from coatsim.path.part_program import PartProgram, build_part_program, part_centering_offset
from coatsim.path.frames import Frame
from coatsim.path.placement import Placement


def run_program(spec: str, tol: Optional[float], options: ProgramOptions, *, frame: str, standoff_mm: float,
                lead_in_mm: float, lead_out_mm: float, roll_deg: float = 0.0, follow_tangent: bool = False,
                center: Optional[bool] = None, output: Optional[Path] = None, layers: Optional[list[str]] = None,
                join_tol: Optional[float] = None, order: str = "as-drawn",
                tool_accel_mm_s2: Optional[float] = None) -> PartProgram:
    """Load ``spec`` (a curve, a drawing or a polysegment/part JSON), place it, write the
    program (to ``output`` if given); a part's contours are sprayed in ``order``.

    ``center`` None centres built-in curves on the frame origin and leaves file curves where
    their coordinates put them. With ``tool_accel_mm_s2`` the curve is segmented for the
    programmed speed (see :func:`load_program_input`).
    """
    from coatsim.core.outputs_guard import check_distinct

    placement = Placement(frame=Frame.parse(frame), standoff_mm=standoff_mm, roll_deg=roll_deg,
                          follow_tangent=follow_tangent, lead_in_mm=lead_in_mm, lead_out_mm=lead_out_mm)
    check_distinct([("the input", None if spec.startswith("builtin:") else spec)], [("-o", output)])
    speed = options.speed_mm_s if tool_accel_mm_s2 is not None else None
    inp = load_part_input(spec, tol, layers, join_tol, speed_mm_s=speed, tool_accel_mm_s2=tool_accel_mm_s2)
    if inp.builtin if center is None else center:
        placement = replace(placement, offset_xy=part_centering_offset(inp.contours))
    built = build_part_program(inp.contours, placement, options, language=KAWASAKI_AS, tolerance_mm=inp.tolerance_mm,
                               source=inp.source, points=inp.points, order=order)
    parse_as(built.text)  # what goes to disk must read back (raises InputError otherwise)
    longest = max(max(s.length for path in built.plan.paths for s in path.segments), options.approach_mm)
    if options.accuracy_mm > longest:
        warnings.warn(f"--accuracy {options.accuracy_mm:g} mm is longer than every move (the longest is {longest:.4g} "
                      "mm); blended corners are rounded as far as the controller allows, half their shorter "
                      "neighbouring move", CoatsimWarning, stacklevel=2)
    if output is not None:
        write_text(output, built.text)
    return built


def program_summary(built: BuiltProgram | PartProgram) -> str:
    """Two lines (and one per contour of a part) describing a written program."""
    plan = built.plan
    curves = getattr(built, "curves", None) or (built.curve,)
    n_steps = len(parse_as(built.text).programs[0].body)
    n_lines, n_arcs = sum(c.n_lines for c in curves), sum(c.n_arcs for c in curves)
    length = sum(p.curve_length_mm for p in plan.paths)
    lines = [
        f"program {plan.name}: {plan.process.variant}, {n_lines} lines + {n_arcs} arcs, "
        f"{n_steps} steps, {built.text.count(chr(10))} lines of text",
        f"path: curve {length:.3f} mm + lead-in {plan.paths[0].lead_in_mm:g} + lead-out "
        f"{plan.paths[0].lead_out_mm:g} mm at stand-off {plan.paths[0].standoff_mm:g} mm, {plan.speed_mm_s:g} mm/s",
    ]
    if len(curves) > 1:
        lines[1] += f"; {len(curves)} contours, lead-in and lead-out on each, gun off between them"
        lines += [f"  contour {k + 1} (drawn {i + 1}): {c.n_segments} segments, {p.curve_length_mm:.3f} mm"
                  for k, (i, c, p) in enumerate(zip(built.order, curves, plan.paths))]
    return "\n".join(lines)


def check_summary(check: ProgramCheck) -> str:
    """The report of ``coatsim check-program``: counts, lengths, then one line per problem."""
    lines = [
        f"{check.source}: program {check.program}: {check.n_steps} steps, {check.n_poses} poses; moves: "
        f"{check.n_joint_moves} joint, {check.n_linear_moves} linear, {check.n_arc_moves} arc",
        f"path length {check.path_length_mm:.3f} mm (sprayed {check.spray_length_mm:.3f} mm)",
    ]
    lines += [f"signal: {s}" for s in check.signals]
    lines += [f"sprayed: lines {r.first_line}-{r.last_line} of {r.source}, {r.moves} move{'' if r.moves == 1 else 's'}, {r.length_mm:.3f} mm"
              for r in check.spray_runs]
    lines += [f"warning: {w}" for w in check.warnings]
    lines += [f"problem: {p}" for p in check.problems] or ["no problems found"]
    return "\n".join(lines)

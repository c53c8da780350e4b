"""Resource budgets: the largest work coatsim accepts, checked before anything big is allocated.

Each budget bounds one quantity that a small input can blow up (a tiny step, a tiny spacing, a
slow speed, a YAML alias, a nested block, a FIFO given as a file). Past a budget the stage raises
a BudgetExceeded (an InputError, exit 2) naming the quantity, the amount asked for, the budget and
what would fix it, before the work starts. The values are sized for a workstation: at each budget
a stage needs about 1 to 2.5 GB and a few minutes (``python scripts/bench_budgets.py`` measures
the cost per unit; figures in docs/guide/conventions.md).

Every budget has a name and can be changed for one process: ``COATSIM_BUDGET="name=value,..."``
(the command line's ``coatsim --budget name=value`` sets it, and Dask workers started by the
command inherit it). ``seconds`` bounds the wall time of long work (unbounded by default).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from coatsim.core.errors import InputError

ENV = "COATSIM_BUDGET"

#: Cartesian IK samples of one program (path length / --step-mm, blends included); ~5 kB each
#: through IK and timing.
MAX_PATH_SAMPLES = 200_000
#: MuJoCo steps of one program (motion time / 2 ms: 1000 s of motion); ~1.7 kB each through
#: timing, playback, projection and the log.
MAX_SIM_STEPS = 500_000
#: Size of a trajectory CSV read by ``coat``: 256 bytes per row at the step budget (rows that
#: coatsim writes take ~170 bytes).
MAX_TRAJECTORY_BYTES = 256 * MAX_SIM_STEPS
#: Vertices of a coated surface mesh (~0.8 kB each through deposition, metrics and the files).
MAX_MESH_VERTICES = 2_000_000
#: Integration sub-steps of the coating stage (sprayed path / footprint sub-step, sigma/2 by
#: default); ~0.2 kB each before the deposition kernel runs over them.
MAX_SPRAY_SUBSTEPS = 2_000_000
#: Memory of the coating stage's ray caster for shadows: Embree's scene (~100 bytes per
#: triangle with our float32 copies), the exposure test's hull, the clear cosines' triangles
#: (~120 bytes each) and one batch of rays, estimated before it is built (a surface at the
#: mesh_vertices budget stays within it).
MAX_SHADOW_BYTES = 2_000_000_000
#: Distinct points of an input curve (files and built-in curves), after dropping repeated ones.
MAX_CURVE_POINTS = 2_000_000
#: Size of a curve text file (CSV/TXT): 64 bytes per point at the point budget.
MAX_CURVE_FILE_BYTES = 64 * MAX_CURVE_POINTS
#: Largest coordinate of an input curve, mm (float64 still resolves 1e-7 mm there).
MAX_ABS_COORDINATE_MM = 1e9
#: Scenario (and other YAML) files: size, nesting depth, alias uses, nodes after expanding
#: aliases. Shipped scenarios are ~2 kB, depth 4, no aliases.
MAX_YAML_BYTES = 1 << 20
MAX_YAML_DEPTH = 32
MAX_YAML_ALIASES = 100
MAX_YAML_NODES = 100_000
#: Any other input file (drawings, programs, JSON, meshes, cell models, footprint tables).
MAX_INPUT_BYTES = 256 << 20
#: Entities of a drawing once its blocks (DXF INSERT/MINSERT) and uses (SVG <use>) are expanded;
#: ~10 kB and 0.2 ms each through reading, chaining and fitting.
MAX_DRAWING_ENTITIES = 200_000
#: Nesting of a drawing: SVG elements inside each other, DXF blocks inside blocks.
MAX_DRAWING_DEPTH = 64
#: Nesting of a JSON document (a polysegment is 4 deep).
MAX_JSON_DEPTH = 64
#: Characters of one string value of a program (an AS string holds 128 on a controller).
MAX_STRING_CHARS = 1 << 20
#: Lines of one robot program file (~50 us each to parse and run; a controller holds far fewer).
MAX_PROGRAM_LINES = 500_000
#: Points of a sweep (the grid product and the explicit points); each point is a run.
MAX_SWEEP_POINTS = 10_000
#: Point-feature pairs the exact deviation check compares at once (~100 bytes each through the
#: distance kernels); a curve with structure puts a few features near each of the 16 points of a
#: batch, one that crosses itself everywhere (random or aliased points) nearly all of them.
MAX_DEVIATION_PAIRS = 5_000_000
#: Points where an input curve doubles back (turns by more than 90° between consecutive chords):
#: a drawn or sampled shape has few, random or aliased points have most of theirs so (the fit
#: of 3 000 random points takes minutes).
MAX_CURVE_REVERSALS = 1_000
#: Triangles ``plan`` works on (a part mesh as read, and its region refined to the pass spacing);
#: ~2 kB each through normals, the heat method's factorisation and fast marching.
MAX_PLAN_TRIANGLES = 1_000_000
#: Size of a part mesh file ``plan`` reads: an ASCII STL takes ~250 bytes per triangle.
MAX_PLAN_MESH_BYTES = 256 * MAX_PLAN_TRIANGLES
#: Passes of one plan.
MAX_PLAN_PASSES = 20_000


@dataclass(frozen=True)
class Budget:
    """One named budget: its default and what it bounds (docs/reference/budgets.md is generated from them)."""

    name: str
    default: float
    bounds: str


BUDGETS: dict[str, Budget] = {b.name: b for b in (
    Budget("path_samples", MAX_PATH_SAMPLES, "IK samples of a program: path length / step"),
    Budget("sim_steps", MAX_SIM_STEPS, "2 ms simulation steps of a program"),
    Budget("trajectory_bytes", MAX_TRAJECTORY_BYTES, "bytes of a trajectory CSV"),
    Budget("mesh_vertices", MAX_MESH_VERTICES, "vertices of a coated surface"),
    Budget("spray_substeps", MAX_SPRAY_SUBSTEPS, "coating sub-steps along the sprayed path"),
    Budget("shadow_bytes", MAX_SHADOW_BYTES, "memory of the coating stage's ray caster for shadows"),
    Budget("curve_points", MAX_CURVE_POINTS, "distinct points of an input curve"),
    Budget("curve_file_bytes", MAX_CURVE_FILE_BYTES, "bytes of a CSV/TXT/NPY curve file"),
    Budget("yaml_bytes", MAX_YAML_BYTES, "bytes of a scenario or sweep file"),
    Budget("input_bytes", MAX_INPUT_BYTES, "bytes of any other input file"),
    Budget("drawing_entities", MAX_DRAWING_ENTITIES, "entities of a drawing with its blocks and uses expanded"),
    Budget("drawing_depth", MAX_DRAWING_DEPTH, "nesting of SVG elements and DXF blocks"),
    Budget("json_depth", MAX_JSON_DEPTH, "nesting of a JSON document"),
    Budget("string_chars", MAX_STRING_CHARS, "characters of a program's string value"),
    Budget("program_lines", MAX_PROGRAM_LINES, "lines of one robot program file"),
    Budget("sweep_points", MAX_SWEEP_POINTS, "points of a sweep"),
    Budget("deviation_pairs", MAX_DEVIATION_PAIRS, "point-feature pairs the exact deviation check compares at once"),
    Budget("curve_reversals", MAX_CURVE_REVERSALS, "points where an input curve doubles back (its sampling is "
           "coarser than its features)"),
    Budget("plan_triangles", MAX_PLAN_TRIANGLES, "triangles of a part mesh plan works on"),
    Budget("plan_mesh_bytes", MAX_PLAN_MESH_BYTES, "bytes of a part mesh file plan reads"),
    Budget("plan_passes", MAX_PLAN_PASSES, "passes of one plan"),
    Budget("seconds", math.inf, "wall time of one command's long work (fitting, drawings, runs, sweeps)"),
)}


class BudgetExceeded(InputError):
    """Work over a budget, refused before it starts (exit 2)."""


def parse_settings(text: str) -> dict[str, float]:
    """``"name=value,..."`` as {name: value}; InputError naming a bad item (``parameters``
    names the budget setting itself)."""
    out: dict[str, float] = {}
    for item in filter(None, (part.strip() for part in text.split(","))):
        name, sep, value = item.partition("=")
        name = name.strip()
        if name not in BUDGETS:
            raise InputError(f"budget {name!r} ({ENV}): no such budget; budgets: {', '.join(BUDGETS)}",
                             parameters=(ENV,))
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        if not sep or not number > 0:
            raise InputError(f"budget {item!r} ({ENV}): expected {name}=N with N > 0 (or inf)", parameters=(ENV,))
        out[name] = number
    return out


def limit(name: str) -> float:
    """The budget ``name`` for this process: its default unless ``COATSIM_BUDGET`` sets it."""
    return parse_settings(os.environ.get(ENV, "")).get(name, BUDGETS[name].default)


def _amount(needed: float) -> str:
    try:
        value = float(needed)
        if math.isfinite(value) and value.is_integer() and abs(value) < 1e15:
            return f"{int(value):,}"
        return f"{value:.3g}" if math.isfinite(value) else "an unbounded number"
    except OverflowError:  # an int beyond float range
        return "an unbounded number"


def check_budget(what: str, needed: float, name: str, fix: str, parameters: tuple[str, ...] = (),
                 left: float | None = None) -> None:
    """Raise a BudgetExceeded when ``needed`` (a count: any int, or a float that may be inf or
    nan) exceeds the budget ``name`` (or ``left`` of it, when earlier work used the rest). ``fix``
    says what would make the work smaller (naming ``parameters`` in the library's terms); the
    message ends with the budget's own name, which the command line says as its option."""
    budget = limit(name) if left is None else left
    if not needed <= budget:
        raise BudgetExceeded(f"{what}: {_amount(needed)} needed, over the budget of {budget:,.0f}; {fix}, or raise "
                             f"the budget {name}", parameters=(*parameters, f"the budget {name}"))

"""Resource budgets: the largest work coatsim accepts, checked before anything big is allocated.

Each budget bounds one quantity that a small input can blow up (a tiny step, a tiny spacing, a
slow speed, a YAML alias). Past a budget the stage raises an InputError (exit 2) that names the
quantity, the amount asked for, the budget and the option that would fix it. The values are
sized for a workstation: at each budget a stage needs about 1 to 2.5 GB and a few minutes
(``python scripts/bench_budgets.py`` measures the cost per unit; figures in docs/guide/conventions.md).
"""

from __future__ import annotations

import math

from coatsim.core.errors import InputError

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
#: triangle with our float32 copies) and one batch of rays, estimated before it is built.
MAX_SHADOW_BYTES = 1_500_000_000
#: Points of an input curve (files and built-in curves).
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
#: Triangles ``plan`` works on (a part mesh as read, and its region refined to the pass spacing);
#: ~2 kB each through normals, the heat method's factorisation and fast marching.
MAX_PLAN_TRIANGLES = 1_000_000
#: Size of a part mesh file ``plan`` reads: an ASCII STL takes ~250 bytes per triangle.
MAX_PLAN_MESH_BYTES = 256 * MAX_PLAN_TRIANGLES
#: Passes of one plan.
MAX_PLAN_PASSES = 20_000


def check_budget(what: str, needed: float, budget: int, fix: str, parameters: tuple[str, ...] = ()) -> None:
    """Raise an InputError when ``needed`` (a count: any int, or a float that may be inf or
    nan) exceeds ``budget``; ``parameters`` those the message names (see CoatsimError)."""
    if not needed <= budget:
        try:
            amount = f"{float(needed):.3g}" if math.isfinite(needed) else "an unbounded number"
        except OverflowError:  # an int beyond float range
            amount = "an unbounded number"
        raise InputError(f"{what}: {amount} needed, over the budget of {budget:,}; {fix}", parameters=parameters)

"""Figures of ``coatsim plan`` (coatsim.geometry.surface): passes on analytic and generated parts,
the planning CPU time against the mesh size (and its exponent), public meshes when a folder of
them is given, and the heat method's error against exact geodesic distances.

Prints figures only (never asserts). Run: python scripts/bench_plan.py [MESH_FOLDER]
(MESH_FOLDER: e.g. a checkout's corpus of public meshes holding engine_bracket.obj and
wavy_mesh_with_hole.ply; those files are read, never copied into the project.)
"""

from __future__ import annotations

import math
import resource
import sys
import time
from pathlib import Path

from coatsim.core.runtime import single_threaded_numerics

single_threaded_numerics()

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from coatsim.geometry.surface import (  # noqa: E402
    Everything,
    Facing,
    FromBoundary,
    FromPlane,
    FromPoints,
    PlanOptions,
    load_part,
    part_from_arrays,
    plan,
)

SIGMA, SPACING = 5.0, 10.0
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "geometry" / "surface"))
from heldout_parts import filleted_slab, l_bracket, noisy_dome, plate_with_arm  # noqa: E402
from surface_helpers import cone, grid, plate_with_hole, tube  # noqa: E402


def _options(**kw) -> PlanOptions:
    kw.setdefault("footprint_sigma_mm", SIGMA)
    kw.setdefault("standoff_mm", 100.0)
    return PlanOptions(**kw)


def _row(name: str, part, **kw) -> tuple[float, object]:
    started = time.process_time()
    paths = plan(part, _options(**kw))
    cpu = time.process_time() - started
    s = paths.stats
    gaps = "-" if s.spacing_median_mm is None else \
        f"{s.spacing_min_mm:.2f} / {s.spacing_median_mm:.2f} / {s.spacing_max_mm:.2f}"
    print(f"| {name} | {paths.pattern} | {len(part.faces):,} | {s.passes} | {gaps} (target {paths.spacing_mm:g}) | "
          f"{100 * s.coverage:.1f} % | {s.normal_smoothing_mm:g} mm, {s.normal_max_angle_deg:.1f} deg, "
          f"{s.normal_off_faces_deg:.2f} deg | {cpu:.2f} |")
    return cpu, paths


def _wavy(n: int, size: float = 300.0) -> tuple[np.ndarray, np.ndarray]:
    vertices, faces = grid(size, size, n, n)
    vertices[:, 2] = 8.0 * np.sin(vertices[:, 0] / 25.0) * np.cos(vertices[:, 1] / 35.0)
    return vertices, faces


def analytic() -> None:
    print("## Analytic and generated parts (footprint sigma 5 mm, spacing 10 mm)\n")
    print("| part | pattern | triangles | passes | spacing along the surface min / median / max mm | coverage | "
          "normals smoothed, largest angle to a face, largest outside the faces near a point | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    plate = part_from_arrays(*grid(200.0, 100.0, 10, 5))
    _row("plate 200 x 100", plate, spacing_mm=SPACING, step_direction=(0, 1, 0))
    tilt = math.radians(35.0)
    rot = np.array([[1, 0, 0], [0, math.cos(tilt), -math.sin(tilt)], [0, math.sin(tilt), math.cos(tilt)]])
    v, f = grid(120.0, 100.0, 12, 10)
    _row("plate tilted 35 deg", part_from_arrays(v @ rot.T, f), spacing_mm=SPACING, step_direction=(0, 1, 0),
         region=Facing(tuple(rot @ [0, 0, 1.0])))
    cylinder = part_from_arrays(*tube(50.0, 200.0, 180, 20))
    _row("cylinder R50, along the axis", cylinder, spacing_mm=SPACING, region=Facing((1, 0, 0)),
         step_direction=(0, 1, 0))
    _row("cylinder R50, round the axis", cylinder, spacing_mm=SPACING, region=Everything(), step_direction=(0, 0, 1))
    _row("cone R60 H120, round", part_from_arrays(*cone(60.0, 120.0, 160, 40)), spacing_mm=SPACING,
         region=Everything(), step_direction=(0, 0, 1))
    sphere = trimesh.creation.icosphere(5, radius=50.0)
    pole = tuple(sphere.vertices[np.argmax(sphere.vertices[:, 2])])
    _row("sphere R50 from a pole", part_from_arrays(sphere.vertices, sphere.faces), spacing_mm=SPACING,
         pattern="geodesic", region=Everything(), start=FromPoints((pole,)))
    box = trimesh.creation.box((100.0, 80.0, 20.0))
    _row("closed box, top", part_from_arrays(box.vertices, box.faces), spacing_mm=SPACING, region=Facing((0, 0, 1)))
    hole = part_from_arrays(*plate_with_hole(200.0, 160.0, 25.0, 2.0))
    for pattern in ("raster", "geodesic", "boundary"):
        _row("plate 200 x 160, hole R25", hole, spacing_mm=SPACING, pattern=pattern)
    noisy_v, noisy_f = grid(120.0, 120.0, 120, 120)
    noisy_v[:, 2] = np.random.default_rng(7).normal(0.0, 0.1, len(noisy_v))
    _row("noisy plane (0.1 mm rms)", part_from_arrays(noisy_v, noisy_f), spacing_mm=SPACING)
    print()


def heldout() -> None:
    print("## Parts like users bring (tests/geometry/surface/heldout_parts.py; sigma 5 mm, spacing 10 mm)\n")
    print("| part | pattern | triangles | passes | spacing along the surface min / median / max mm | coverage | "
          "normals smoothed, largest angle to a face, largest outside the faces near a point | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    bracket = part_from_arrays(*l_bracket())
    slab = part_from_arrays(*filleted_slab(n_profile=96, n_along=40))
    dome = part_from_arrays(*noisy_dome())
    arm = part_from_arrays(*plate_with_arm())
    for pattern in ("raster", "geodesic", "boundary"):
        _row("L bracket, through-hole (CAD, sharp edges)", bracket, spacing_mm=SPACING, pattern=pattern,
             region=Facing((0.6, 0, 0.8), 60.0))
        _row("slab, fillets R10, bore", slab, spacing_mm=SPACING, pattern=pattern, region=Facing((0, 0, 1)))
        _row("dome R120, 0.1 mm noise, hole R12", dome, spacing_mm=SPACING, pattern=pattern)
        _row("plate with an 8 mm arm", arm, spacing_mm=SPACING, pattern=pattern, region=Facing((0, 0, 1)))
    print()


def scaling() -> None:
    print("## CPU time against size (wavy 300 x 300 mm surface, 8 mm waves, region facing +z)\n")
    print("| part | pattern | triangles | passes | spacing along the surface min / median / max mm | coverage | "
          "normals smoothed, largest angle to a face, largest outside the faces near a point | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    sizes = (50, 100, 200, 316)
    times: dict[str, list[float]] = {}
    stages: dict[str, tuple] = {}
    for pattern in ("raster", "geodesic", "boundary"):
        for n in sizes:
            cpu, paths = _row("wavy", part_from_arrays(*_wavy(n)), spacing_mm=SPACING, pattern=pattern,
                              region=Facing((0, 0, 1)))
            times.setdefault(pattern, []).append(cpu)
            stages[pattern] = paths.timings_s
    triangles = np.array([2 * n * n for n in sizes], dtype=float)
    print()
    for pattern, cpu in times.items():
        overall = np.polyfit(np.log(triangles[1:]), np.log(cpu[1:]), 1)[0]
        marginal = math.log(cpu[-1] / cpu[-2]) / math.log(triangles[-1] / triangles[-2])
        print(f"- {pattern}: CPU ~ triangles^{overall:.2f} from 20 000 to 200 000 triangles (a fixed cost of about "
              f"2 s first), ^{marginal:.2f} from 80 000 to 200 000; at 200 000: "
              + ", ".join(f"{name} {seconds:.2f} s" for name, seconds in stages[pattern]))
    print()


def public(folder: Path) -> None:
    cases = [("engine_bracket.obj", "cm", [dict(), dict(pattern="geodesic"),
                                           dict(pattern="geodesic", start=FromPlane((0, 0, 0), (1, 0, 0)))]),
             ("wavy_mesh_with_hole.ply", "cm", [dict(), dict(pattern="geodesic"), dict(pattern="boundary")])]
    print(f"## Public meshes ({folder})\n")
    print("| part | pattern | triangles | passes | spacing along the surface min / median / max mm | coverage | "
          "normals smoothed, largest angle to a face, largest outside the faces near a point | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    for name, units, runs in cases:
        path = folder / name
        if not path.is_file():
            print(f"| {name} | (not found) | | | | | | |")
            continue
        part = load_part(path, units)
        for kw in runs:
            try:
                _row(f"{name} ({units})", part, spacing_mm=SPACING, **kw)
            except Exception as exc:  # a figure, not a test: show what happened
                print(f"| {name} ({units}) | {kw.get('pattern', 'raster')} | {len(part.faces):,} | refused: {exc} |")
    print()


def heat_errors() -> None:
    import potpourri3d as pp3d

    from coatsim.geometry.surface.distance import heat_distance
    from coatsim.geometry.surface.geodesic import assign_points, geodesic_piece
    from coatsim.geometry.surface.normals import vertex_normals
    from coatsim.geometry.surface.piece import Piece
    from coatsim.geometry.surface.refine import refined
    from coatsim.geometry.surface.topology import border_vertices, mesh_edges

    def piece(v, f):
        border = border_vertices(len(v), mesh_edges(f))
        return Piece(v, f, vertex_normals(v, f), np.where(border, 0.0, 1.0))

    def edge(v, f):
        return float(np.linalg.norm(v[f[:, 0]] - v[f[:, 1]], axis=1).mean())

    print("## Heat method against exact geodesic distance (mm; in mean edge lengths in brackets)\n")
    print("| case | mean edge | median error | max, inside (> 15 mm from an open border) | "
          "max, within 5 mm of an open border |")
    print("|---|---|---|---|---|")

    def report(name, error, h, inside, border):
        print(f"| {name} | {h:.2f} | {np.median(error):.3f} ({np.median(error) / h:.2f}) | "
              f"{error[inside].max():.3f} ({error[inside].max() / h:.2f}) | "
              + (f"{error[border].max():.3f} ({error[border].max() / h:.2f}) |" if border.any() else "- |"))

    sphere = trimesh.creation.icosphere(5, radius=50.0)
    v, f = np.asarray(sphere.vertices), np.asarray(sphere.faces)
    top = int(np.argmax(v[:, 2]))
    exact = 50.0 * np.arccos(np.clip(v @ v[top] / 2500.0, -1, 1))
    error = np.abs(heat_distance(v, f, np.array([top])) - exact)
    report("sphere R50, from a vertex (closed)", error, edge(v, f), exact < 150, np.zeros(len(v), bool))
    v, f = grid(100.0, 100.0, 100, 100)
    inner = (v[:, 0] > 0) & (v[:, 0] < 100) & (v[:, 1] > 0) & (v[:, 1] < 100)
    v[inner, :2] += np.random.default_rng(0).uniform(-0.25, 0.25, (inner.sum(), 2))
    to_border = np.minimum.reduce([v[:, 0], v[:, 1], 100 - v[:, 0], 100 - v[:, 1]])
    start = (50.3, 50.2, 0.0)
    p = piece(v, f)
    field = geodesic_piece(p, FromPoints((start,)), SPACING, 0.0, assign_points([p], FromPoints((start,)), 10.0)[0]).field
    report("jittered plate, from a point", np.abs(field - np.linalg.norm(v - start, axis=1)), edge(v, f),
           to_border > 15, to_border < 5)
    normal = np.array([math.cos(0.4), math.sin(0.4), 0.0])
    field = geodesic_piece(p, FromPlane((40 / math.cos(0.4), 0, 0), tuple(normal)), SPACING, 0.0).field
    report("jittered plate, from a plane", np.abs(field - (v @ normal - 40.0)), edge(v, f), to_border > 15,
           to_border < 5)
    v, f = plate_with_hole(200.0, 160.0, 25.0, 2.0)
    v, f, _ = refined(v, f, 2.5, "plate", "")
    x, y = v[:, 0], v[:, 1]
    exact = np.minimum.reduce([np.hypot(x, y) - 25.0, 100 - np.abs(x), 80 - np.abs(y)])
    corner = np.minimum(100 - np.abs(x), 80 - np.abs(y)) < 0.9 * np.maximum(100 - np.abs(x), 80 - np.abs(y))
    field = geodesic_piece(piece(v, f), FromBoundary(), SPACING, 0.0).field
    report("plate with a hole, from its border (off the corner ridges)", np.abs(field - exact), edge(v, f),
           ~corner, np.zeros(len(v), bool))
    border = np.flatnonzero(border_vertices(len(v), mesh_edges(f)))
    theirs = pp3d.MeshHeatMethodDistanceSolver(v, f).compute_distance_multisource(list(border))
    report("the same with potpourri3d's own solver", np.abs(theirs - exact), edge(v, f), ~corner,
           np.zeros(len(v), bool))
    print()


def main() -> None:
    analytic()
    heldout()
    scaling()
    if len(sys.argv) > 1:
        public(Path(sys.argv[1]))
    heat_errors()
    print(f"peak resident memory {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")


if __name__ == "__main__":
    main()

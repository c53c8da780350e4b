"""Planning passes on a part: ``plan(part, options) -> SurfacePaths``.

1. The part is wound consistently and outward (an open scan toward the gun's side) and refined
   so that no edge exceeds the smoothing length (or 1/200 of the part).
2. The region is selected by its face normals (facing, box or all; only what the gun sees) and
   refined to edges of at most ``max_edge_mm`` (a quarter of the spacing by default); it is cut
   along its sharp edges (features.py), and its normals are smoothed within each feature region
   and over the surface running on past its border (up to two smoothing lengths, not across a
   sharp edge, region.smoothing_ring); it is split into connected pieces (a sharp edge bounds
   them like a border, so no pass crosses one; islands smaller than a spacing squared are
   dropped) and the distance to its border is measured along the surface.
3. Each piece gets the pattern's field and levels (raster, geodesic, boundary); the level curves
   lose the edge band and become passes in spraying order with lead-in and lead-out.
4. The gaps between passes and the coverage are measured along the surface, and the result is
   checked independently (``verify``) before it is returned.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np

from coatsim.core import defaults
from coatsim.core.errors import EmptyRegionOfInterest, InputError
from coatsim.geometry.surface.boundary import boundary_piece
from coatsim.geometry.surface.boxes import SmallTriangles
from coatsim.geometry.surface.contours import level_curves
from coatsim.geometry.surface.distance import Marching
from coatsim.geometry.surface.features import SHARP_EDGE_DEG, edge_length_mm, selection_normals, sharp_at_scale
from coatsim.geometry.surface.fill import MIN_LENGTH_FRACTION, filled
from coatsim.geometry.surface.geodesic import FromBoundary, FromPoints, Start, assign_points, geodesic_piece
from coatsim.geometry.surface.gun_side import oriented_for
from coatsim.geometry.surface.mesh import Part
from coatsim.geometry.surface.normals import (
    face_normals,
    Facets,
    kept_outward,
    largest_angle_deg,
    smooth_normals,
    vertex_normals,
)
from coatsim.geometry.surface.passes import ORDERS, Order, Trace, clip, leads, spraying_order
from coatsim.geometry.surface.piece import Piece
from coatsim.geometry.surface.raster import raster_levels, raster_step
from coatsim.geometry.surface.refine import refined
from coatsim.geometry.surface.region import (
    Box,
    Everything,
    Facing,
    RegionSpec,
    check_region,
    principal_axes,
    select_faces,
    sign_fixed,
    smoothing_ring,
    unit_vector,
)
from coatsim.geometry.surface.spacing import band_note, measure, ripple_pct, spacing_for_ripple
from coatsim.geometry.surface.standoff import blocked_standoff
from coatsim.geometry.surface.surfacepaths import PATTERNS, MeshInfo, Pass, PlanStats, SurfacePaths
from coatsim.geometry.surface.topology import (
    border_vertices,
    face_components,
    face_pairs,
    manifold_split,
    mesh_edges,
    submesh,
)
from coatsim.geometry.surface.verify import verify
from coatsim.geometry.vectors import unit_rows

Pattern = Literal["raster", "geodesic", "boundary"]
#: the whole part is refined to at most max(smoothing length, extent / this) before selection
SELECTION_CELLS = 200.0
#: normals are smoothed over the surface running on past the region this many smoothing lengths
RING_SMOOTHING_LENGTHS = 2.0
#: a face touches a pass point within this fraction of the part's extent
TOUCH_FRACTION = 1e-7
#: a face narrower than this share of the smoothing length (a scan's sliver), or folded against its
#: neighbours, does not judge whether a pass point's normal leans into the part (normals.kept_outward)
SLIVER_SHARE = 0.02
#: the stand-off is checked from this fraction of the part's extent over a pass point's lift (standoff.py)
STANDOFF_CLEAR_FRACTION = 1e-4


@dataclass(frozen=True)
class PlanOptions:
    """What to plan. The footprint's standard deviation sets the defaults: spacing 2 sigma
    (ripple 2.9 %) unless ``spacing_mm`` or ``ripple_pct`` is given, normals smoothed over sigma,
    lead-in/out of 3 sigma. ``step_direction`` (raster) is the planes' normal (default: the
    region's middle principal axis); ``start`` (geodesic) defaults to the region's border;
    ``pose`` (the part in the robot base frame, x, y, z mm, O, A, T deg) is only recorded."""

    footprint_sigma_mm: float
    standoff_mm: float
    pattern: Pattern = defaults.PLAN_PATTERN
    spacing_mm: float | None = None
    ripple_pct: float | None = None
    step_direction: tuple[float, float, float] | None = None
    start: Start = field(default_factory=FromBoundary)
    region: RegionSpec = field(default_factory=Facing)
    margin_mm: float | None = None
    edge_band_mm: float = defaults.PLAN_EDGE_BAND_MM
    order: Order = defaults.PLAN_ORDER
    max_edge_mm: float | None = None
    pose: tuple[float, float, float, float, float, float] = defaults.WORKPIECE_FRAME


@dataclass(frozen=True)
class _Settings:
    spacing_mm: float
    margin_mm: float
    max_edge_mm: float
    smoothing_mm: float


def _positive(name: str, value: float, allow_zero: bool = False) -> float:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and (value > 0 or (allow_zero and value == 0))):
        raise InputError(f"{name} must be a {'non-negative' if allow_zero else 'positive'} number, found {value!r}",
                         parameters=(name,))
    return float(value)


def _settings(o: PlanOptions) -> _Settings:
    """The options checked, with their defaults filled in."""
    sigma = _positive("footprint_sigma_mm", o.footprint_sigma_mm)
    _positive("standoff_mm", o.standoff_mm)
    if o.pattern not in PATTERNS:
        raise InputError(f"pattern must be one of {', '.join(PATTERNS)}, found {o.pattern!r}", parameters=("pattern",))
    if o.order not in ORDERS:
        raise InputError(f"order must be one of {', '.join(ORDERS)}, found {o.order!r}", parameters=("order",))
    if o.spacing_mm is not None and o.ripple_pct is not None:
        raise InputError("give spacing_mm or ripple_pct, not both", parameters=("spacing_mm", "ripple_pct"))
    if o.step_direction is not None:
        if o.pattern != "raster":
            raise InputError("step_direction applies to the raster pattern", parameters=("step_direction", "pattern"))
        unit_vector(o.step_direction, "step_direction", "step_direction")
    if not isinstance(o.start, FromBoundary) and o.pattern != "geodesic":
        raise InputError("start applies to the geodesic pattern", parameters=("start", "pattern"))
    check_region(o.region)
    if len(o.pose) != 6 or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in o.pose):
        raise InputError("pose must be six finite numbers x, y, z (mm), o, a, t (deg)", parameters=("pose",))
    if o.spacing_mm is not None:
        spacing = _positive("spacing_mm", o.spacing_mm)
    elif o.ripple_pct is not None:
        spacing = spacing_for_ripple(o.ripple_pct, sigma)
    else:
        spacing = defaults.PLAN_SPACING_SIGMAS * sigma
    margin = defaults.PLAN_MARGIN_SIGMAS * sigma if o.margin_mm is None else _positive("margin_mm", o.margin_mm, True)
    _positive("edge_band_mm", o.edge_band_mm, True)
    max_edge = (spacing / defaults.PLAN_EDGES_PER_SPACING if o.max_edge_mm is None
                else _positive("max_edge_mm", o.max_edge_mm))
    return _Settings(spacing, margin, max_edge, sigma)


class _Clock:
    """CPU time of this process per stage (reported on stderr by the command, never written to
    the file)."""

    def __init__(self) -> None:
        self.marks: list[tuple[str, float]] = []
        self._last = time.process_time()

    def lap(self, name: str) -> None:
        now = time.process_time()
        self.marks.append((name, now - self._last))
        self._last = now


def _region_mesh(part: Part, o: PlanOptions, s: _Settings,
                 notes: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray, Facets]:
    """The coated region: vertices, faces (oriented outward, refined to ``max_edge_mm``, made
    manifold and cut along sharp edges) and unit vertex normals (smoothed within each feature
    region, over the region and the surface running on past it); and the part's own facets
    wound outward."""
    oriented, toward, why = oriented_for(part, o.region)
    if isinstance(o.region, Box):
        notes.append(f"box region: the gun comes from ({', '.join(f'{round(x, 6) + 0.0:.3g}' for x in toward)}), {why}")
    notes.extend(oriented.notes)
    if oriented.flipped:
        notes.append(f"turned {oriented.flipped} of {len(part.faces)} triangles to a consistent outward winding")
    coarse = max(s.smoothing_mm, part.extent_mm / SELECTION_CELLS)
    # a part read at a guessed unit too large for its budget was most likely guessed wrong: say so
    guessed = f", or give the units ({part.units_guess})" if part.units_guess else ""
    v, f, _ = refined(part.vertices_mm, oriented.faces, coarse, part.file,
                      f"use a wider footprint or decimate the part{guessed}", parameters=("units",) if guessed else ())
    mask = select_faces(v, f, selection_normals(v, f, s.smoothing_mm), o.region, toward, s.smoothing_mm)
    if not mask.any():
        raise EmptyRegionOfInterest(f"no face of the part that the gun sees lies in the region "
                                    f"{describe_region(o.region, toward)}; choose another region",
                                    parameters=("region",))
    both = mask | smoothing_ring(v, f, mask, RING_SMOOTHING_LENGTHS * s.smoothing_mm, s.smoothing_mm)
    sv, sf, _ = submesh(v, f, both)
    sv, sf, inside = refined(sv, sf, s.max_edge_mm, "the region", "use a larger spacing_mm or max_edge_mm, or a "
                             f"smaller region{guessed}", labels=mask[both],
                             parameters=("spacing_mm", "max_edge_mm") + (("units",) if guessed else ()))
    inside = inside.astype(bool)
    # from here on the surface is manifold: a bow-tie vertex or a non-manifold edge is split
    split, copies = manifold_split(sf)
    added = len(np.unique(split[inside])) - len(np.unique(sf[inside]))
    if added:
        notes.append(f"split {added} vertices where the region is not manifold (bow-tie vertices, edges with more "
                     "than two triangles); the region's border runs along them")
    sv, sf = sv[copies], split
    pairs, sharp = sharp_at_scale(sv, sf, s.smoothing_mm)
    if (sharp_mm := edge_length_mm(sv, sf, pairs[sharp & inside[pairs].all(axis=1)])) > 0:
        notes.append(f"the region has {sharp_mm:.4g} mm of sharp edges (faces meeting at more than {SHARP_EDGE_DEG:g} "
                     "deg): normals are smoothed on either side, never across, and passes stop at them")
    sf, copies = manifold_split(sf, pairs[~sharp])
    sv, facets = sv[copies], Facets.of(part.vertices_mm, oriented.faces, s.smoothing_mm)
    normals = smooth_normals(sv, sf, s.smoothing_mm, facets.normals(sv, vertex_normals(sv, sf)))
    rv, rf, parent = submesh(sv, sf, inside)
    return rv, rf, normals[parent], facets


def describe_region(region: RegionSpec, toward: np.ndarray) -> str:
    """The region in words, for messages."""
    if isinstance(region, Everything):
        return "all"
    if isinstance(region, Facing):
        return f"facing ({', '.join(f'{x:.3g}' for x in toward)}) within {region.max_angle_deg:g} deg"
    return f"box {tuple(region.low_mm)} .. {tuple(region.high_mm)}"


def _pieces(rv: np.ndarray, rf: np.ndarray, normals: np.ndarray, s: _Settings,
            notes: list[str]) -> tuple[list[Piece], float, float]:
    """The region's connected pieces (largest first, small islands dropped), with their normals
    and border distances; also the region's area and the largest normal angle."""
    face_n, face_area = face_normals(rv, rf)
    angle = largest_angle_deg(normals, rf, face_n)
    edges = mesh_edges(rf)
    on_border = border_vertices(len(rv), edges)
    count, label = face_components(len(rf), face_pairs(rf, edges)[0])
    area = np.bincount(label, weights=face_area, minlength=count)
    small = area < s.spacing_mm**2
    if small.any():
        notes.append(f"left out {int(small.sum())} island(s) of the region smaller than a spacing squared "
                     f"({float(area[small].sum()):.4g} mm2 in all)")
    pieces = []
    for k in sorted(np.flatnonzero(~small), key=lambda k: (-area[k], k)):
        v, f, parent = submesh(rv, rf, label == k)
        marching = Marching(v, f)
        border = marching.distance(source_vertices=np.flatnonzero(on_border[parent]))
        pieces.append(Piece(v, f, normals[parent], border, marching=marching, surface=SmallTriangles(v, f)))
    if not pieces:
        raise EmptyRegionOfInterest(f"every piece of the region is smaller than a spacing squared (the largest "
                                    f"{float(area.max()):.4g} mm2, the spacing {s.spacing_mm:g} mm); use a smaller "
                                    "spacing_mm or a larger region, or check the mesh's units",
                                    parameters=("spacing_mm", "region"))
    return pieces, float(face_area.sum()), angle


def _patterned(pieces: list[Piece], o: PlanOptions, s: _Settings, step: np.ndarray | None,
               notes: list[str]) -> list[Piece]:
    """Each piece with its pattern's field and levels. A piece a geodesic plane or points miss
    (a face behind a sharp edge, an island) takes its passes from its own border, with a note;
    a closed one is left out."""
    band = o.edge_band_mm
    if o.pattern == "raster":
        steps = [raster_step(p.vertices, p.faces, p.inside(band), step, s.spacing_mm) for p in pieces]
        own = [k for k, st in enumerate(steps) if st is not step]
        if own:
            notes.append(f"{len(own)} piece(s) of the region that the raster planes cross edge-on (facing the step "
                         f"direction; {sum(pieces[k].area_mm2 for k in own):.4g} mm2) are rastered along their own "
                         "longest axis")
        return [p.with_field(p.vertices @ st, raster_levels(p.vertices, p.faces, p.normals, st, p.inside(band),
                                                           s.spacing_mm, p.surface)) for p, st in zip(pieces, steps)]
    if o.pattern == "boundary":
        return [boundary_piece(p, s.spacing_mm, band) for p in pieces]
    points = (assign_points(pieces, o.start, s.spacing_mm) if isinstance(o.start, FromPoints)
              else [None] * len(pieces))
    done = [geodesic_piece(p, o.start, s.spacing_mm, band, pts) for p, pts in zip(pieces, points)]
    if all(p is None for p in done):
        raise EmptyRegionOfInterest("the start does not touch the region; give a plane that cuts it or points on it "
                                    "as the start", parameters=("start",))
    missed = [k for k, p in enumerate(done) if p is None and pieces[k].on_border.any()]
    for k in missed:
        done[k] = geodesic_piece(pieces[k], FromBoundary(), s.spacing_mm, band)
    if missed:
        notes.append(f"{len(missed)} piece(s) of the region that the start does not reach (beyond a sharp edge, "
                     f"islands; {sum(pieces[k].area_mm2 for k in missed):.4g} mm2) take passes from their own border")
    return [p for p in done if p is not None]


def _traces(piece: Piece, index: int, band: float) -> list[Trace]:
    """The piece's level curves without the edge band, tagged with their level's rank."""
    return [Trace(part, rank, index) for rank, level in enumerate(piece.levels)
            for curve in level_curves(piece.vertices, piece.faces, piece.field, float(level))
            for part in clip(curve, piece.border_mm, band, piece.vertices, piece.faces)]


def _standoff_note(part: Part, passes: tuple[Pass, ...], standoff_mm: float, lift_mm: float) -> list[str]:
    """A note where the part lies between a pass point and its tool centre point (standoff.py)."""
    blocked = blocked_standoff(part.vertices_mm, part.faces, passes, standoff_mm,
                               lift_mm + STANDOFF_CLEAR_FRACTION * part.extent_mm)
    if not blocked:
        return []
    first = blocked[0]
    return [f"the part lies within the stand-off ({standoff_mm:g} mm) along the normal of "
            f"{sum(b.points for b in blocked)} points of {len(blocked)} passes: the gun cannot spray them from there and "
            f"the twin stops on the collision (first: pass {first.pass_index + 1} point {first.first_point + 1}, the "
            f"part {first.distance_mm:.3g} mm out); use a smaller standoff_mm or a region without them"]


def _long_enough(traces: list[Trace], spacing_mm: float, notes: list[str]) -> list[Trace]:
    """The level curves no shorter than fill.py keeps a pass: a level just below a peak or ridge
    of the field is a loop round it a fraction of a millimetre long (a dome's flange gave 141
    passes under 5 mm, each a gun-on pass with its leads), which the passes beside it cover;
    what they leave is filled (_filling) and measured."""
    kept = [t for t in traces if t.curve.length_mm >= MIN_LENGTH_FRACTION * spacing_mm]
    if len(kept) < len(traces):
        shortest = min(t.curve.length_mm for t in traces)
        notes.append(f"left out {len(traces) - len(kept)} level curves shorter than half a spacing (the shortest "
                     f"{shortest:.3g} mm: loops round a peak or ridge of the field), covered by the passes beside them")
    return kept


def _filling(pieces: list[Piece], traces: list[Trace], band: float, spacing_mm: float, notes: list[str]) -> list[Trace]:
    """Passes where the levels leave a patch uncovered (fill.py), sprayed after each piece's
    levels; what the edge band leaves of one is dropped when shorter than fill.py drops a pass."""
    added = [Trace(part, len(p.levels), k) for k, p in enumerate(pieces)
             for curve in filled(p, [t.curve for t in traces if t.piece == k], spacing_mm)
             for part in clip(curve, p.border_mm, band, p.vertices, p.faces)
             if part.length_mm >= MIN_LENGTH_FRACTION * spacing_mm]
    if added:
        notes.append(f"added {len(added)} pass(es) where the levels leave patches more than half a spacing from every "
                     "pass (strips narrower than a spacing, ridges short of the next level)")
    return added


def _passes(pieces: list[Piece], traces: list[Trace], part: Part, facets: Facets, o: PlanOptions,
            s: _Settings, notes: list[str]) -> tuple[Pass, ...]:
    """Passes in spraying order with their normals (kept out of the part's faces at their points,
    normals.kept_outward) and leads; the points lifted off the part's facets onto the smooth
    surface their corner normals describe, along their normals (Facets.lifted: a cylinder's pass
    is a circle, not a polygon's chords)."""
    passes, turned = [], 0
    folded = facets.folded(SLIVER_SHARE * s.smoothing_mm)
    for curve, index in spraying_order(traces, o.order):
        piece = pieces[index]
        normals = curve.sample(piece.faces, piece.normals)
        normals, changed = kept_outward(curve.points, unit_rows(normals), facets.boxes, facets.face_n,
                                        TOUCH_FRACTION * part.extent_mm, folded)
        turned += changed
        points = facets.lifted(curve.points, normals)
        if curve.closed:
            lead_in = lead_out = np.zeros((0, 3))
        else:
            lead_in, lead_out = leads(points, normals, s.margin_mm, 0.5 * s.spacing_mm)
        passes.append(Pass(points, normals, bool(curve.closed), lead_in, lead_out))
    if turned:
        notes.append(f"{turned} normal(s) that leaned into a face at their point (a crease sharper than the smoothing "
                     "can follow, the foot of an overhanging wall) turned to the mean of the faces there")
    return tuple(passes)


def plan(part: Part, options: PlanOptions) -> SurfacePaths:
    """Passes covering the region of ``part`` (see the module docstring).

    Args:
        part: the mesh (load_part).
        options: pattern, spacing or ripple, stand-off, region, margins, order (PlanOptions).

    Returns:
        The SurfacePaths: passes on the surface with their normals, leads and statistics,
        checked independently (every point on the mesh, every normal near its faces).

    Raises:
        InputError: an empty region, options that contradict each other, or a plan that fails
            its own check.
        BudgetExceeded: more triangles or passes than the plan budgets.
    """
    s = _settings(options)
    clock, notes = _Clock(), list(part.notes)
    rv, rf, normals, facets = _region_mesh(part, options, s, notes)
    clock.lap("region and normals")
    pieces, region_area, angle = _pieces(rv, rf, normals, s, notes)
    clock.lap("border")
    step = None
    if options.pattern == "raster":
        given = options.step_direction
        step = (unit_vector(given, "step_direction", "step_direction") if given is not None
                else sign_fixed(principal_axes(rv, rf)[1]))
    pieces = _patterned(pieces, options, s, step, notes)
    clock.lap(options.pattern)
    traces = _long_enough([t for k, p in enumerate(pieces) for t in _traces(p, k, options.edge_band_mm)],
                          s.spacing_mm, notes)
    traces += _filling(pieces, traces, options.edge_band_mm, s.spacing_mm, notes)
    clock.lap("fill")
    gaps, ends, covered = [np.zeros(0)], [np.zeros(0, dtype=bool)], 0.0
    for k, p in enumerate(pieces):
        measured = measure(p, [t for t in traces if t.piece == k], s.spacing_mm, options.pattern != "raster")
        gaps.append(measured.gaps_mm)
        ends.append(measured.at_end)
        covered += measured.covered_mm2
    note = band_note(np.concatenate(gaps), np.concatenate(ends), s.spacing_mm)
    notes.extend([note] if note else [])
    clock.lap("measure")
    passes = _passes(pieces, traces, part, facets, options, s, notes)
    if not passes:
        raise EmptyRegionOfInterest("no pass fits in the region (the edge band covers it); use a smaller edge_band_mm",
                                    parameters=("edge_band_mm",))
    notes.extend(_standoff_note(part, passes, options.standoff_mm, facets.largest_lift_mm()))
    clock.lap("stand-off")
    gap = np.concatenate(gaps)
    spacing_stats = (float(gap.min()), float(np.median(gap)), float(gap.max())) if len(gap) else (None,) * 3
    stats = PlanStats(len(passes), region_area, min(1.0, covered / region_area), *spacing_stats, s.smoothing_mm, angle)
    info = MeshInfo(part.file, part.sha256, len(part.vertices_mm), len(part.faces), tuple(map(float, options.pose)))
    paths = SurfacePaths(info, options.pattern, s.spacing_mm, options.standoff_mm,
                         ripple_pct(s.spacing_mm, options.footprint_sigma_mm), passes, stats, tuple(notes))
    stats = replace(stats, normal_off_faces_deg=verify(part, paths))
    clock.lap("verify")
    return SurfacePaths(paths.mesh, paths.pattern, paths.spacing_mm, paths.standoff_mm, paths.ripple_pct,
                        paths.passes, stats, paths.notes, tuple(clock.marks))

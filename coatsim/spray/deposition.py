"""Deposition kernel: integrate the sprayed thickness on every surface vertex over a trajectory.

The nozzle is a point source at the logged tool centre point (the TCP sits at the nozzle) and
sprays along the logged unit axis a. A vertex x with unit normal n, seen from the nozzle along
d = x − p, receives the thickness rate (the surface projection model of Conner, Atkar, Rizzi
and Choset, IEEE T-ASE 2005: the footprint measured on a plane, projected onto the surface)

    Q · g(u, v) · (h0/|d|)² · cos γ / cos³ θ · DE(γ) · vis  =  Q · g(u, v) · h0² (−d·n) / (d·a)³ · DE(γ) · vis

where (u, v) = h0/(d·a) · (d·e1, d·e2) is the central projection of x onto the reference plane
at stand-off h0, cos θ = d·a/|d|, cos γ = −d·n/|d| (γ: incidence angle; the spray angle is
90° − γ), DE the optional deposition efficiency (coatsim.spray.efficiency) and vis ∈ {0, 1}
whether the nozzle sees x (coatsim.spray.visibility). Back faces (cos γ ≤ 0) and points behind
the nozzle get nothing. The footprint axis e1 is a fixed reference direction (base +x by
default) projected onto the plane normal to a; e2 = a × e1.

Time integration: row k of the log holds the spray signal for [t_k, t_k+1) (zero-order hold);
each sprayed interval is split into equal sub-steps so that the footprint centre moves at most
``substep_mm`` per sub-step (position linear, axis normalised-linear), each evaluated at its
midpoint and weighted by its duration, so slowdowns and dwells weigh exactly by time.

Culling (coatsim.spray.culling): per sub-step only the KD-tree leaves whose bounding sphere
meets the footprint's cut-off cone are evaluated, leaf block by leaf block, and only the pairs
within the cut-off radius get the full terms (coatsim.spray.pair_terms); contributions are
summed per vertex with ``np.bincount`` (deterministic order). Shadows cost one ray per
(sub-step, vertex) pair that receives spray, and none for vertices nothing can hide.
"""

from __future__ import annotations

import math
import warnings
import weakref
from dataclasses import dataclass
from functools import cached_property
from typing import Callable

import numpy as np

from coatsim.core.numeric import ROUND_OFF
from coatsim.core import defaults
from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, check_budget
from coatsim.core.errors import CoatsimWarning, InputError
from coatsim.robot.trajectory_log import TrajectoryLog
from coatsim.spray.culling import VertexTree, cone_pairs, vertex_tree
from coatsim.spray.efficiency import Efficiency
from coatsim.spray.footprints import Footprint
from coatsim.spray.pair_terms import LeafBlocks, NearPairs, PairBuffer, leaf_blocks, near_pairs
from coatsim.spray.surfaces import Surface
from coatsim.geometry.rays import RayCaster
from coatsim.spray.visibility import ClearCosines, Visibility, check_shadow_mode, visibility

MAX_RATE_MM3_S = 1e12  # a cubic metre per millisecond: far beyond any gun, far below float overflow
_LEAF_TESTS_PER_BATCH = 400_000
_MIN_STEPS_PER_SEARCH = 64
_PAIRS_PER_BATCH = 1_000_000


@dataclass(frozen=True)
class SprayModel:
    """Gun and numerics: footprint at reference stand-off h0 (mm), deposited rate Q (mm³/s) of
    material landing on a surface, deposition efficiency (None: all that lands sticks) and
    shadows: ``auto`` and ``on`` cast rays for the vertices the surface can hide (none on a
    surface that cannot shadow itself); without the Embree binding ``on`` is an error and
    ``auto`` warns and coats without shadows; ``off`` never casts (see coatsim.spray.visibility)."""

    footprint: Footprint
    rate_mm3_s: float = 40.0
    standoff_mm: float = 100.0
    efficiency: Efficiency | None = None
    shadows: str = defaults.SHADOWS
    substep_mm: float | None = None
    major_axis: tuple[float, float, float] = (1.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        checks = (("rate", self.rate_mm3_s, "rate_mm3_s", MAX_RATE_MM3_S),
                  ("stand-off", self.standoff_mm, "standoff_mm", MAX_ABS_COORDINATE_MM))
        for name, value, key, most in checks:
            if not (0 < value <= most):
                raise InputError(f"spray {name} must be positive and at most {most:g}, found {value:g} ({key})")
        if self.substep_mm is not None and not (math.isfinite(self.substep_mm) and self.substep_mm > 0):
            raise InputError(f"sub-step must be positive, found {self.substep_mm:g} mm")
        check_shadow_mode(self.shadows)
        if self.footprint.cutoff_mm >= 10 * self.standoff_mm:
            raise InputError(f"footprint radius {self.footprint.cutoff_mm:g} mm is too wide for stand-off {self.standoff_mm:g} mm")
        if np.linalg.norm(self.major_axis) == 0:
            raise InputError("footprint major axis must be a non-zero vector")

    @property
    def step_mm(self) -> float:
        return self.substep_mm if self.substep_mm is not None else self.footprint.substep_mm


@dataclass(frozen=True, eq=False)
class SubSteps:
    """Sprayed integration sub-steps: m midpoints with nozzle position (m, 3) mm, unit axis
    (m, 3), footprint axes e1 and e2 = axis × e1 (m, 3), duration dt (m,) s, and the spray-on
    stretch (m,) each belongs to (consecutive sprayed log rows form one stretch)."""

    position: np.ndarray
    axis: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    dt: np.ndarray
    stretch: np.ndarray

    @property
    def spray_time_s(self) -> float:
        return float(self.dt.sum())

    @cached_property
    def columns(self) -> np.ndarray:
        """Position, axis, e1 and e2 one above the other (12, m), gathered in one take per leaf."""
        return np.ascontiguousarray(np.hstack([self.position, self.axis, self.e1, self.e2]).T)

    def __len__(self) -> int:
        return len(self.dt)


def _unit_axes(axis: np.ndarray) -> np.ndarray:
    norm = np.linalg.norm(axis, axis=1)
    bad = np.flatnonzero(~(norm > 1e-6))
    if len(bad):
        raise InputError(f"trajectory row {bad[0] + 1} (CSV line {bad[0] + 2}): spray axis (ax, ay, az) is zero")
    return axis / norm[:, None]


def _footprint_axes(axis: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """e1: ``reference`` projected onto the plane normal to each axis (base y if parallel)."""
    ref = reference / np.linalg.norm(reference)
    e1 = ref - (axis @ ref)[:, None] * axis
    weak = np.linalg.norm(e1, axis=1) < 1e-6
    if np.any(weak):
        alt = np.array([0.0, 1.0, 0.0]) if abs(ref[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
        e1[weak] = alt - (axis[weak] @ alt)[:, None] * axis[weak]
    return e1 / np.linalg.norm(e1, axis=1)[:, None]


def substeps(log: TrajectoryLog, model: SprayModel) -> SubSteps:
    """Split every sprayed log interval so the footprint moves at most ``model.step_mm``."""
    p = np.asarray(log.position, dtype=float)
    a = _unit_axes(np.asarray(log.axis, dtype=float))
    t = np.asarray(log.t, dtype=float)
    k = np.flatnonzero(np.asarray(log.spray[:-1], dtype=bool))
    if len(k) == 0:
        empty = np.zeros((0, 3))
        return SubSteps(empty, empty, empty, empty, np.zeros(0), np.zeros(0, dtype=np.int64))
    dp = p[k + 1] - p[k]
    turn = np.arccos(np.clip(np.sum(a[k] * a[k + 1], axis=1), -1.0, 1.0))
    travel = np.maximum(np.linalg.norm(dp, axis=1), model.standoff_mm * turn)
    steps = np.maximum(1.0, np.ceil(travel / model.step_mm - ROUND_OFF))  # inf for a step of no length
    check_budget(f"coating sub-steps of {model.step_mm:g} mm along {float(travel.sum()):.6g} mm of sprayed path",
                 float(steps.sum()), "spray_substeps", "use a wider footprint or a longer sub-step")
    n = steps.astype(np.int64)
    rep = np.repeat(np.arange(len(k)), n)
    j = np.arange(len(rep)) - np.repeat(np.cumsum(n) - n, n)
    f = ((j + 0.5) / n[rep])[:, None]
    kk = k[rep]
    position = p[kk] + f * dp[rep]
    axis = (1 - f) * a[kk] + f * a[kk + 1]
    norm = np.linalg.norm(axis, axis=1)
    if np.any(norm < 1e-6):
        row = int(kk[np.argmax(norm < 1e-6)])
        raise InputError(f"trajectory row {row + 1} (CSV line {row + 2}): spray axis reverses within one step")
    axis /= norm[:, None]
    dt = (t[kk + 1] - t[kk]) / n[rep]
    starts = np.ones(len(k), dtype=bool)
    starts[1:] = k[1:] != k[:-1] + 1
    stretch = (np.cumsum(starts) - 1)[rep]
    e1 = _footprint_axes(axis, np.asarray(model.major_axis, float))
    return SubSteps(position, axis, e1, np.cross(axis, e1), dt, stretch)



@dataclass(frozen=True, eq=False)
class Deposit:
    """Per-vertex result, all (n,): thickness (mm), exposure (s with a non-zero rate), and the
    smallest footprint radius (mm) at which the vertex was seen while spraying (inf if never):
    its distance, on the reference plane, from the nearest sprayed sub-step centre (within
    (step/2)²/(2·distance) of the distance from the continuous track). Where the spray went
    besides: ``shadowed_mm``, the thickness that reached the vertex's direction while it was
    hidden (it landed on the faces in front instead), ``lost_mm`` what bounced off (deposition
    efficiency). Deposit-weighted means: ``spray_angle_deg`` (90 = normal incidence) and
    ``standoff_mm`` (distance from the nozzle along the spray axis), NaN where nothing landed.
    ``rays``: occlusion queries cast; ``shadows``: whether visibility was computed at all."""

    thickness_mm: np.ndarray
    exposure_s: np.ndarray
    track_distance_mm: np.ndarray
    steps: SubSteps
    evaluations: int
    shadowed_mm: np.ndarray
    lost_mm: np.ndarray
    spray_angle_deg: np.ndarray
    standoff_mm: np.ndarray
    rays: int = 0
    shadows: bool = False

    @property
    def thickness_um(self) -> np.ndarray:
        return self.thickness_mm * 1000.0


@dataclass(frozen=True, eq=False)
class _Shadows:
    """The ray caster, the vertices it never needs to test, the incidence cosine above which a
    vertex needs no ray, and the gun-position group of every sub-step (consecutive sub-steps at
    one position share their visibility)."""

    caster: RayCaster
    exposed: np.ndarray
    clear: ClearCosines
    group: np.ndarray


#: Each surface's Visibility (its hull and Embree scene), kept while the surface lives: the
#: variants of a run and the report's partial coats share one.
_VISIBILITY: weakref.WeakKeyDictionary[Surface, Visibility] = weakref.WeakKeyDictionary()


@dataclass(frozen=True, eq=False)
class _Mesh:
    """What the deposition reads of a surface, built once per surface: its vertices' KD-tree and
    its leaves' blocks of vertex positions and unit normals."""

    tree: VertexTree
    blocks: LeafBlocks


#: Each surface's _Mesh, kept while the surface lives (the variants of a run coat one surface).
_MESHES: weakref.WeakKeyDictionary[Surface, _Mesh] = weakref.WeakKeyDictionary()


def _mesh(surface: Surface) -> _Mesh:
    mesh = _MESHES.get(surface)
    if mesh is None:
        tree = vertex_tree(surface.vertices)
        mesh = _Mesh(tree, leaf_blocks(tree, surface.vertices, surface.normals))
        _MESHES[surface] = mesh
    return mesh


def _shadows(surface: Surface, model: SprayModel, steps: SubSteps) -> _Shadows | None:
    """What visibility needs, or None when no vertex can be hidden or shadows are off."""
    if model.shadows == "off":
        return None
    seen = _VISIBILITY.get(surface)
    if seen is None:
        seen = visibility(surface.vertices, surface.normals, surface.faces, model.shadows)
        if not seen.unavailable:
            _VISIBILITY[surface] = seen
    if seen.unavailable:
        warnings.warn(f"{surface.name} can shadow itself but the embreex package (Embree ray casting) cannot be "
                      f"imported: coating without shadows; install it with pip install embreex", CoatsimWarning)
    if seen.caster is None:
        return None
    moved = np.r_[True, np.any(steps.position[1:] != steps.position[:-1], axis=1)]
    return _Shadows(seen.caster, seen.exposed, seen.clear, np.cumsum(moved) - 1)


def _blocked(shadows: _Shadows, steps: SubSteps, s: np.ndarray, i: np.ndarray, d: np.ndarray,
             dist: np.ndarray, n: int) -> tuple[np.ndarray, int]:
    """Which of the pairs (s, i) with offsets d = x − p the part hides; one ray per vertex and
    gun position. Returns (blocked flags, rays cast)."""
    group = shadows.group[s]
    if len(s) and group[-1] - group[0] < s[-1] - s[0]:  # a gun position repeats: one ray for its pairs
        _, first, back = np.unique(group * n + i, return_index=True, return_inverse=True)
        hit = shadows.caster.blocked(steps.position[s[first]], d[first], dist[first])
        return hit[back.ravel()], len(first)
    return shadows.caster.blocked(steps.position[s], d, dist), len(s)


def _offsets(surface: Surface, steps: SubSteps, s: np.ndarray, i: np.ndarray) -> np.ndarray:
    """d = x − p (mm) for the pairs (s, i)."""
    return np.take(surface.vertices, i, axis=0) - np.take(steps.position, s, axis=0)


class _Totals:
    """Per-vertex sums over the batches: each batch's sums (bincount in pair order) over the
    vertices it touches, added to them."""

    def __init__(self, n: int):
        # separate arrays, as numpy allocates them: a row of one block may be aligned differently,
        # and BLAS sums (the volumes) round differently with the alignment
        self.thickness, self.exposure, self.shadowed, self.lost, self.angle, self.standoff = (np.zeros(n) for _ in range(6))
        self.r2_min = np.full(n, np.inf)
        self.evaluations = self.rays = 0
        self.buffer = PairBuffer()


def _batch(surface: Surface, steps: SubSteps, near: NearPairs, touched: np.ndarray, model: SprayModel,
           shadows: _Shadows | None, totals: _Totals) -> None:
    """Add the near pairs of one batch to ``totals`` (sums over the vertices ``touched``);
    incidence, rays and deposition efficiency only for the pairs that receive spray (``on``)."""
    s, i, slot, rate = near.step, near.vertex, near.slot, near.rate
    add = lambda where, w: np.bincount(slot[where], weights=w, minlength=len(touched))  # noqa: E731
    dt = steps.dt[s]
    every = slice(None)
    on = np.flatnonzero(rate > 0)
    on = every if len(on) == len(rate) else on  # usually all of them: views, not copies
    dist = near.dist[on]
    if shadows is not None:
        hideable = np.flatnonzero(~shadows.exposed[i])
        i_on = i[on]
        aim = np.flatnonzero(~shadows.exposed[i_on])
        # a pair seen more steeply than its vertex's clear cosine needs no ray
        aim = aim[near.facing[on][aim] <= shadows.clear(i_on[aim]) * dist[aim]]
        on_aim = np.arange(len(rate))[on][aim]
        s_aim, i_aim = s[on_aim], i[on_aim]
        hidden, rays = _blocked(shadows, steps, s_aim, i_aim, _offsets(surface, steps, s_aim, i_aim), dist[aim],
                                len(totals.thickness))
        totals.rays += rays
        blocked = on_aim[hidden]
        totals.shadowed[touched] += add(blocked, rate[blocked] * dt[blocked])
        rate[blocked] = 0.0
        near.r2[blocked] = np.inf
        np.minimum.at(totals.r2_min, i[hideable], near.r2[hideable])  # near_pairs left them out
    cos_gamma = near.facing[on] / dist
    stuck = rate
    if model.efficiency is not None:
        stuck = rate.copy()
        stuck[on] = rate[on] * model.efficiency.factor(cos_gamma)
        totals.lost[touched] += add(on, (rate[on] - stuck[on]) * dt[on])
    weight = stuck * dt
    totals.thickness[touched] += add(every, weight)
    totals.exposure[touched] += add(every, np.where(stuck > 0, dt, 0.0))
    angle = np.degrees(np.arcsin(np.minimum(cos_gamma, 1.0)))
    totals.angle[touched] += add(on, weight[on] * angle)
    totals.standoff[touched] += add(on, weight[on] * near.da[on])


def _deposit(totals: _Totals, steps: SubSteps, shadows: bool) -> Deposit:
    landed = totals.thickness > 0
    mean = lambda field: np.where(landed, field / np.where(landed, totals.thickness, 1.0), np.nan)
    return Deposit(totals.thickness, totals.exposure, np.sqrt(totals.r2_min), steps, totals.evaluations,
                   totals.shadowed, totals.lost, mean(totals.angle), mean(totals.standoff), totals.rays, shadows)


def deposit(surface: Surface, log: TrajectoryLog, model: SprayModel,
            progress: Callable[[float], None] | None = None) -> Deposit:
    """Accumulate thickness on ``surface`` over the sprayed part of ``log``."""
    steps = substeps(log, model)
    totals = _Totals(surface.n_vertices)
    if len(steps) == 0 or surface.n_vertices == 0:
        return _deposit(totals, steps, False)
    mesh = _mesh(surface)
    tree = mesh.tree
    shadows = _shadows(surface, model, steps)
    slope = model.footprint.cutoff_mm / model.standoff_mm
    hideable = None if shadows is None else ~shadows.exposed
    gun = (model.footprint, model.rate_mm3_s, model.standoff_mm)
    # sub-steps per search (the batches' sums are grouped by it, so it stays what it was for meshes
    # of up to 6250 leaves: the same thickness to the last bit)
    chunk = max(_MIN_STEPS_PER_SEARCH, _LEAF_TESTS_PER_BATCH // tree.n_leaves)
    for lo in range(0, len(steps), chunk):
        pairs = cone_pairs(tree, steps.position, steps.axis, slope, np.arange(lo, min(lo + chunk, len(steps))))
        totals.evaluations += pairs.size
        # batches of the pairs as they are numbered, far ones included: the sums are grouped as they were
        for start in range(0, pairs.size, _PAIRS_PER_BATCH):
            span = (start, min(start + _PAIRS_PER_BATCH, pairs.size))
            near = near_pairs(mesh.blocks, steps.columns, pairs, span, gun, hideable, totals.r2_min, totals.buffer)
            _batch(surface, steps, near, pairs.touched, model, shadows, totals)
        if progress is not None:
            progress(min(lo + chunk, len(steps)) / len(steps))
    return _deposit(totals, steps, shadows is not None)

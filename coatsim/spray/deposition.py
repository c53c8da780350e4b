"""Deposition kernel: integrate the sprayed thickness on every surface vertex over a trajectory.

The nozzle is a point source at the logged tool centre point (the TCP sits at the nozzle) and
sprays along the logged unit axis a. A vertex x with unit normal n, seen from the nozzle along
d = x − p, receives the thickness rate (point-source projection of the reference footprint)

    Q · g(u, v) · (h0/|d|)² · cos γ / cos³ θ · DE(γ)  =  Q · g(u, v) · h0² (−d·n) / (d·a)³ · DE(γ)

where (u, v) = h0/(d·a) · (d·e1, d·e2) is the central projection of x onto the reference plane
at stand-off h0, cos θ = d·a/|d|, cos γ = −d·n/|d| (γ: incidence angle), DE(γ) = cos^(n−1) γ.
Back faces (cos γ ≤ 0) and points behind the nozzle get nothing; with occlusion on, a vertex
counts only if a ray from the nozzle reaches it first. The footprint axis e1 is a fixed
reference direction (base +x by default) projected onto the plane normal to a; e2 = a × e1.

Time integration: row k of the log holds the spray signal for [t_k, t_k+1) (zero-order hold);
each sprayed interval is split into equal sub-steps so that the footprint centre moves at most
``substep_mm`` per sub-step (position linear, axis normalised-linear), each evaluated at its
midpoint and weighted by its duration, so slowdowns and dwells weigh exactly by time.

Culling: the vertices are grouped into the leaves of a KD-tree; per sub-step only leaves whose
bounding sphere meets the footprint's cut-off cone are evaluated, in vectorised batches, and
contributions are summed per vertex with ``np.bincount`` (deterministic order).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.spatial import cKDTree

from coatsim.core.budgets import MAX_ABS_COORDINATE_MM, check_budget
from coatsim.core.errors import InputError
from coatsim.robot.trajectory_log import TrajectoryLog
from coatsim.spray.footprints import Footprint
from coatsim.spray.surfaces import Surface

MAX_RATE_MM3_S = 1e12  # a cubic metre per millisecond: far beyond any gun, far below float overflow
LEAF_SIZE = 48
_LEAF_TESTS_PER_BATCH = 400_000
_PAIRS_PER_BATCH = 1_000_000


@dataclass(frozen=True)
class SprayModel:
    """Gun and numerics: footprint at reference stand-off h0 (mm), deposited rate Q (mm³/s)."""

    footprint: Footprint
    rate_mm3_s: float = 40.0
    standoff_mm: float = 100.0
    de_exponent: float = 1.0
    occlusion: bool = False
    substep_mm: float | None = None
    major_axis: tuple[float, float, float] = (1.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        checks = (("rate", self.rate_mm3_s, "--rate (mm3/s)", MAX_RATE_MM3_S),
                  ("stand-off", self.standoff_mm, "--standoff (mm)", MAX_ABS_COORDINATE_MM))
        for name, value, flag, most in checks:
            if not (0 < value <= most):
                raise InputError(f"spray {name} must be positive and at most {most:g}, found {value:g}; set {flag}")
        if self.substep_mm is not None and not (math.isfinite(self.substep_mm) and self.substep_mm > 0):
            raise InputError(f"sub-step must be positive, found {self.substep_mm:g} mm")
        if not (math.isfinite(self.de_exponent) and self.de_exponent >= 1):
            raise InputError(f"deposition-efficiency exponent must be >= 1, found {self.de_exponent:g}")
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
    n = np.maximum(1, np.ceil(travel / model.step_mm - 1e-9)).astype(np.int64)
    check_budget(f"coating sub-steps of {model.step_mm:g} mm along {float(travel.sum()):.6g} mm of sprayed path",
                 float(n.sum()), "spray_substeps", "use a wider footprint or a longer sub-step")
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
    """Per-vertex result: thickness (n,) mm, exposure (n,) s with a non-zero rate, and the
    smallest footprint radius (n,) mm at which the vertex was seen while spraying (inf if
    never): its distance, on the reference plane, from the nearest sprayed sub-step centre
    (within (step/2)²/(2·distance) of the distance from the continuous track)."""

    thickness_mm: np.ndarray
    exposure_s: np.ndarray
    track_distance_mm: np.ndarray
    steps: SubSteps
    evaluations: int

    @property
    def thickness_um(self) -> np.ndarray:
        return self.thickness_mm * 1000.0


@dataclass(frozen=True, eq=False)
class _Leaves:
    order: np.ndarray
    start: np.ndarray
    count: np.ndarray
    centre: np.ndarray
    radius: np.ndarray


def _kd_leaves(points: np.ndarray) -> _Leaves:
    """Leaves of a scipy KD-tree: contiguous ranges of ``order`` with bounding spheres."""
    tree = cKDTree(points, leafsize=LEAF_SIZE, balanced_tree=False, compact_nodes=False)
    ranges, stack = [], [tree.tree]
    while stack:
        node = stack.pop()
        if node.split_dim == -1:
            ranges.append((node.start_idx, node.end_idx))
        else:
            stack.extend((node.greater, node.lesser))
    ranges.sort()
    start = np.array([r[0] for r in ranges], dtype=np.int64)
    count = np.array([r[1] - r[0] for r in ranges], dtype=np.int64)
    order = np.asarray(tree.indices, dtype=np.int64)
    leaf = np.repeat(np.arange(len(start)), count)
    pts = points[order]
    lo = np.full((len(start), 3), np.inf)
    hi = np.full((len(start), 3), -np.inf)
    np.minimum.at(lo, leaf, pts)
    np.maximum.at(hi, leaf, pts)
    centre = 0.5 * (lo + hi)
    radius = np.zeros(len(start))
    np.maximum.at(radius, leaf, np.linalg.norm(pts - centre[leaf], axis=1))
    return _Leaves(order, start, count, centre, radius * (1 + 1e-9) + 1e-9)


def _candidate_pairs(leaves: _Leaves, steps: SubSteps, sel: slice, slope: float) -> tuple[np.ndarray, np.ndarray]:
    """(sub-step, vertex) pairs of the sub-steps ``sel`` whose leaf sphere may meet the cut-off
    cone (apex at the nozzle, lateral/axial = ``slope``). Conservative: the distance from a
    centre at axial w, lateral l to the cone's boundary line, (l − slope·w)/√(1 + slope²),
    never exceeds its distance to the cone."""
    v = leaves.centre[None, :, :] - steps.position[sel, None, :]
    w = np.einsum("slk,sk->sl", v, steps.axis[sel])
    lateral = np.sqrt(np.maximum(np.einsum("slk,slk->sl", v, v) - w * w, 0.0))
    r = leaves.radius[None, :]
    hit = (w >= -r) & (lateral - slope * w <= r * math.sqrt(1 + slope * slope))
    step, leaf = np.nonzero(hit)
    counts = leaves.count[leaf]
    total = int(counts.sum())
    offset = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    vertex = leaves.order[np.repeat(leaves.start[leaf], counts) + offset]
    return np.repeat(step + sel.start, counts), vertex


def _rates(surface: Surface, steps: SubSteps, s: np.ndarray, i: np.ndarray, model: SprayModel,
           ) -> tuple[np.ndarray, np.ndarray]:
    """Thickness rate (mm/s) and squared reference-plane radius (mm², inf where unseen) of pairs."""
    h0 = model.standoff_mm
    d = surface.vertices[i] - steps.position[s]
    a = steps.axis[s]
    da = np.einsum("ij,ij->i", d, a)
    dn = -np.einsum("ij,ij->i", d, surface.normals[i])
    seen = (da > 1e-9) & (dn > 0)
    scale = np.where(seen, h0 / np.where(seen, da, 1.0), 0.0)
    u = np.einsum("ij,ij->i", d, steps.e1[s]) * scale
    v = np.einsum("ij,ij->i", d, steps.e2[s]) * scale
    g = model.footprint.density(u, v)
    rate = model.rate_mm3_s * g * scale**3 * np.where(seen, dn, 0.0) / h0
    if model.de_exponent != 1.0:
        cos_gamma = np.where(seen, dn, 0.0) / np.linalg.norm(d, axis=1)
        rate *= cos_gamma ** (model.de_exponent - 1.0)
    r2 = np.where(seen, u * u + v * v, np.inf)
    return rate, r2


def _visible(mesh, origins: np.ndarray, targets: np.ndarray, tolerance: float) -> np.ndarray:
    """True where a ray from ``origins`` reaches ``targets`` without hitting the mesh earlier."""
    direction = targets - origins
    length = np.linalg.norm(direction, axis=1)
    locations, ray, _ = mesh.ray.intersects_location(origins, direction / length[:, None], multiple_hits=False)
    first = np.full(len(origins), np.inf)
    if len(ray):
        np.minimum.at(first, ray, np.linalg.norm(locations - origins[ray], axis=1))
    return first >= length - tolerance


def deposit(surface: Surface, log: TrajectoryLog, model: SprayModel,
            progress: Callable[[float], None] | None = None) -> Deposit:
    """Accumulate thickness on ``surface`` over the sprayed part of ``log``."""
    steps = substeps(log, model)
    n = surface.n_vertices
    thickness = np.zeros(n)
    exposure = np.zeros(n)
    r2_min = np.full(n, np.inf)
    evaluations = 0
    if len(steps) == 0 or n == 0:
        return Deposit(thickness, exposure, np.sqrt(r2_min), steps, 0)
    leaves = _kd_leaves(surface.vertices)
    slope = model.footprint.cutoff_mm / model.standoff_mm
    mesh = None
    if model.occlusion:
        import trimesh

        mesh = trimesh.Trimesh(surface.vertices, surface.faces, process=False)
    chunk = max(1, _LEAF_TESTS_PER_BATCH // len(leaves.start))
    for lo in range(0, len(steps), chunk):
        s_all, i_all = _candidate_pairs(leaves, steps, slice(lo, min(lo + chunk, len(steps))), slope)
        for b in range(0, len(s_all), _PAIRS_PER_BATCH):
            s, i = s_all[b:b + _PAIRS_PER_BATCH], i_all[b:b + _PAIRS_PER_BATCH]
            rate, r2 = _rates(surface, steps, s, i, model)
            evaluations += len(s)
            if mesh is not None:
                hit = np.flatnonzero(rate > 0)
                blocked = hit[~_visible(mesh, steps.position[s[hit]], surface.vertices[i[hit]],
                                        0.01 * model.standoff_mm)]
                rate[blocked] = 0.0
                r2[blocked] = np.inf
            dt = steps.dt[s]
            thickness += np.bincount(i, weights=rate * dt, minlength=n)
            exposure += np.bincount(i, weights=np.where(rate > 0, dt, 0.0), minlength=n)
            np.minimum.at(r2_min, i, r2)
        if progress is not None:
            progress(min(lo + chunk, len(steps)) / len(steps))
    return Deposit(thickness, exposure, np.sqrt(r2_min), steps, evaluations)

"""Region of interest and area-weighted coating metrics.

ROI kinds: ``part`` is the part minus an edge band along its border (default 3σ); ``band`` is
the strip the spray actually traced (vertices that came within a half-width, default 2σ, of
the footprint centre while spraying), minus the same edge band and minus the run-in and
run-out (within the edge band of the first and last footprint centre of every spray-on
stretch that does not close on itself); ``field`` is that band without the edge band along its
own border as well: the area a raster of passes coats evenly, its outer passes' falling flanks
left out (a run on a 3-D part measures its region so). Every statistic is weighted by vertex area, so it
does not depend on how the mesh is tessellated.

Where the sprayed material went: sprayed = deposited + lost (bounced off, deposition
efficiency) + missed (landed on no face turned towards the nozzle: past the part's edges).
Shadowed is reported beside it, not in the sum: the material aimed at faces the part hides,
which landed on the faces in front of them (and is counted there).
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.core.numeric import TINY
from coatsim.core import defaults
from coatsim.core.errors import EmptyRegionOfInterest, InputError
from coatsim.spray.deposition import Deposit, SprayModel
from coatsim.spray.efficiency import LOW_SPRAY_ANGLE_DEG
from coatsim.spray.surfaces import Surface, merged_vertices, border_distance

ROI_KINDS = ("band", "field", "part")
COVERAGE_FRACTION = 0.8
THICK_SPOT_FRACTION = 1.2


def _stretch_ends(deposit: Deposit, closing_mm: float) -> list[int]:
    """Indices of the first and last sub-step of every spray-on stretch that does not close."""
    steps = deposit.steps
    ends: list[int] = []
    for k in np.unique(steps.stretch):
        idx = np.flatnonzero(steps.stretch == k)
        first, last = int(idx[0]), int(idx[-1])
        if np.linalg.norm(steps.position[first] - steps.position[last]) > closing_mm:
            ends += [first, last]
    return ends


def _footprint_radius(surface: Surface, deposit: Deposit, model: SprayModel, step: int) -> np.ndarray:
    """Reference-plane radius (mm) of every vertex seen from sub-step ``step`` (inf if unseen)."""
    steps = deposit.steps
    d = surface.vertices - steps.position[step]
    a = steps.axis[step]
    da = d @ a
    seen = (da > TINY) & (-np.einsum("ij,ij->i", d, surface.normals) > 0)
    lateral = np.linalg.norm(d - da[:, None] * a, axis=1)
    return np.where(seen, lateral * model.standoff_mm / np.where(seen, da, 1.0), np.inf)


def edge_band_width(model: SprayModel, edge_band_mm: float | None = None) -> float:
    """The edge band left out of the ROI (mm): 3σ of the footprint unless given."""
    return 3 * model.footprint.sigma_mm if edge_band_mm is None else edge_band_mm


def away_from_border(surface: Surface, edge_band_mm: float, spacing: float | None = None) -> np.ndarray:
    """Vertices at least ``edge_band_mm`` from the part border (the ``part`` ROI). It depends on
    the surface alone: compute it once per surface and pass it to every variant's ROI."""
    if not edge_band_mm >= 0:
        raise InputError(f"the edge band must be >= 0 mm, found {edge_band_mm:g} mm")
    return border_distance(surface, spacing, within_mm=edge_band_mm) >= edge_band_mm


def region_of_interest(surface: Surface, deposit: Deposit, model: SprayModel, kind: str = "band",
                       edge_band_mm: float | None = None, band_halfwidth_mm: float | None = None,
                       spacing: float | None = None, away: np.ndarray | None = None) -> np.ndarray:
    """Boolean vertex mask of the ROI (see module docstring); widths default to 3σ and 2σ.
    ``away`` is ``away_from_border(surface, edge band, spacing)`` when already known."""
    if kind not in ROI_KINDS:
        raise InputError(f"ROI must be one of {', '.join(ROI_KINDS)}, found {kind!r}")
    sigma = model.footprint.sigma_mm
    edge = edge_band_width(model, edge_band_mm)
    half = 2 * sigma if band_halfwidth_mm is None else band_halfwidth_mm
    if not (edge >= 0 and half > 0 and np.isfinite(edge) and np.isfinite(half)):
        raise InputError(f"ROI widths must be finite, >= 0 (edge band) and > 0 (band half-width), found {edge:g}, {half:g} mm")
    mask = (away_from_border(surface, edge, spacing) if away is None else away).copy()
    if kind != "part":
        band = deposit.track_distance_mm <= half
        mask &= band
        for step in _stretch_ends(deposit, closing_mm=model.step_mm):
            mask &= _footprint_radius(surface, deposit, model, step) >= edge
        if kind == "field":
            mask &= inside(surface, band, edge)
    return mask


def inside(surface: Surface, mask: np.ndarray, margin_mm: float) -> np.ndarray:
    """Vertices of ``mask`` at least ``margin_mm`` from every vertex outside it, measured along
    the surface (shortest paths over the mesh's edges, coincident vertices merged: never through
    the air, so the far side of a thin part does not count; a path along edges is at most about
    8 % longer than the geodesic on a well-shaped mesh)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra

    if mask.all() or margin_mm <= 0:
        return mask.copy()
    ids = merged_vertices(surface.vertices)
    faces = ids[surface.faces]
    edges = np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
    edges = edges[edges[:, 0] != edges[:, 1]]
    n = int(ids.max()) + 1
    merged_in = np.zeros(n, dtype=bool)
    merged_in[ids[mask]] = True
    merged_out = np.zeros(n, dtype=bool)
    merged_out[ids[~mask]] = True
    border = np.unique(edges[merged_out[edges[:, 0]] != merged_out[edges[:, 1]]])
    sources = border[merged_out[border]]
    if not len(sources):
        return mask.copy()
    first = np.zeros(n, dtype=np.int64)
    first[ids] = np.arange(len(ids))
    length = np.linalg.norm(surface.vertices[first[edges[:, 0]]] - surface.vertices[first[edges[:, 1]]], axis=1)
    graph = coo_matrix((length, (edges[:, 0], edges[:, 1])), shape=(n, n)).tocsr()
    distance = dijkstra(graph, directed=False, indices=sources, min_only=True, limit=margin_mm * (1 + 1e-9))
    return mask & ~merged_out[ids] & (distance[ids] >= margin_mm)


def weighted_quantile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    """Smallest value whose cumulative weight fraction reaches q (area-weighted inverse CDF;
    splitting a vertex into pieces of the same value does not change it)."""
    order = np.argsort(values, kind="stable")
    v, cum = values[order], np.cumsum(weights[order])
    return float(v[min(int(np.searchsorted(cum, q * cum[-1], side="left")), len(v) - 1)])


def thickness_statistics(thickness_um: np.ndarray, areas: np.ndarray, mask: np.ndarray,
                         target_um: float, tolerance_pct: float = defaults.TOLERANCE_PCT) -> dict[str, float]:
    """Area-weighted mean, std, CV, extremes, P05/P95, coverage, thick-spot, coated and
    within-specification (target ± tolerance_pct %) fractions."""
    t, w = thickness_um[mask], areas[mask]
    area = float(w.sum())
    mean = float(np.sum(w * t) / area)
    std = float(np.sqrt(np.sum(w * (t - mean) ** 2) / area))
    band = tolerance_pct / 100.0 * target_um
    return {
        "roi_area_mm2": area,
        "roi_vertices": int(mask.sum()),
        "thickness_mean_um": mean,
        "thickness_std_um": std,
        "thickness_cv": std / mean if mean > 0 else 0.0,
        "thickness_min_um": float(t.min()),
        "thickness_max_um": float(t.max()),
        "thickness_p05_um": weighted_quantile(t, w, 0.05),
        "thickness_p95_um": weighted_quantile(t, w, 0.95),
        "target_um": float(target_um),
        "coverage_fraction": float(np.sum(w[t >= COVERAGE_FRACTION * target_um]) / area),
        "thick_spot_fraction": float(np.sum(w[t > THICK_SPOT_FRACTION * target_um]) / area),
        "coated_fraction": float(np.sum(w[t > 0]) / area),
        "tolerance_pct": float(tolerance_pct),
        "within_spec_fraction": float(np.sum(w[np.abs(t - target_um) <= band]) / area),
    }


def spray_conditions(deposit: Deposit, areas: np.ndarray, mask: np.ndarray) -> dict[str, float]:
    """How the region was sprayed: the area fraction whose (deposit-weighted) spray angle is
    below LOW_SPRAY_ANGLE_DEG, and the range of the stand-off at which coating landed."""
    angle, standoff = deposit.spray_angle_deg[mask], deposit.standoff_mm[mask]
    landed = ~np.isnan(standoff)
    flat = np.zeros(len(angle), dtype=bool)
    flat[landed] = angle[landed] < LOW_SPRAY_ANGLE_DEG
    return {
        "low_angle_fraction": float(np.sum(areas[mask][flat]) / areas[mask].sum()),
        "standoff_min_mm": float(standoff[landed].min()) if landed.any() else math.nan,
        "standoff_max_mm": float(standoff[landed].max()) if landed.any() else math.nan,
    }


def coating_metrics(surface: Surface, deposit: Deposit, model: SprayModel, roi: np.ndarray,
                    target_um: float | None = None, tolerance_pct: float = defaults.TOLERANCE_PCT) -> dict[str, float]:
    """All coating metrics; the target defaults to the ROI mean (coverage then measures evenness)."""
    spray_time = deposit.steps.spray_time_s
    if spray_time <= 0:
        raise InputError("trajectory never sprays (spray column is 0 on every row); nothing to coat")
    if not np.any(roi):
        raise EmptyRegionOfInterest("region of interest is empty: the spray misses the part or the edge band "
                                    "(edge_band_mm) covers it")
    if target_um is not None and not (np.isfinite(target_um) and target_um > 0):
        raise InputError(f"target thickness must be positive, found {target_um:g} um")
    if not (np.isfinite(tolerance_pct) and tolerance_pct >= 0):
        raise InputError(f"tolerance_pct: the thickness tolerance must be a percentage >= 0, found {tolerance_pct:g}",
                         parameters=("tolerance_pct",))
    thickness = deposit.thickness_um
    mean = float(np.sum(surface.areas[roi] * thickness[roi]) / surface.areas[roi].sum())
    if not mean > 0:
        raise InputError("no coating landed in the region of interest; check the surface placement "
                         "(--surface ...@x,y,z) and that the spray axis points at it")
    metrics = thickness_statistics(thickness, surface.areas, roi, mean if target_um is None else target_um,
                                   tolerance_pct)
    metrics.update(spray_conditions(deposit, surface.areas, roi))
    deposited = float(surface.areas @ deposit.thickness_mm)
    lost = float(surface.areas @ deposit.lost_mm)
    sprayed = model.rate_mm3_s * spray_time
    metrics.update({
        "part_thickness_max_um": float(thickness.max()),
        "deposited_volume_mm3": deposited,
        "roi_volume_mm3": float(surface.areas[roi] @ deposit.thickness_mm[roi]),
        "sprayed_volume_mm3": sprayed,
        "lost_volume_mm3": lost,
        "missed_volume_mm3": sprayed - deposited - lost,
        "shadowed_volume_mm3": float(surface.areas @ deposit.shadowed_mm),
        "on_part_efficiency": (deposited + lost) / sprayed,
        "deposition_efficiency": deposited / sprayed,
        "spray_time_s": spray_time,
    })
    return metrics

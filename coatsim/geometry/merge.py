"""Whether a junction of a G1 chain can be given up: the merged chain bent back onto the rest.

Two neighbouring segments become one of their length and mean curvature: the heading after
them is kept, but their end point moves, by about (κ₁ − κ₂)·ℓ₁·ℓ₂/2, and everything after
them with it, often by many times the tolerance, so the deviation of that chain says nothing
about whether a refinement will bring it back within σ. Here the merged segment and its
neighbours (up to three segments) are bent, by least-norm Newton steps on their curvatures
and lengths, until they end where the two segments' right-hand neighbour ended, with its
heading: the chain before and after that window is untouched, and what deviates is what the
merge itself costs. On the taught polygons measured (scripts/bench_sparse.py), every merge
the refinement brought within σ deviated at most 3.2 σ bent so; most that it did not, far more.
"""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.refine import ChainParams

NEWTON_STEPS = 12
SHORTEST = 0.25  # a bent segment is at least this share of its length before bending


def _pose(heading: float, kappa: np.ndarray, length: np.ndarray) -> np.ndarray:
    """End point (relative to the start) and end heading of arcs from ``heading``: (3,)."""
    sweep = kappa * length
    small = np.abs(sweep) < 1e-9
    half = np.where(small, 1.0, sweep / 2)
    chord = length * np.where(small, 1.0 - sweep**2 / 24, np.sin(half) / half)
    turn = heading + np.concatenate(([0.0], np.cumsum(sweep)))
    mid = (turn[:-1] + turn[1:]) / 2
    return np.array([float(np.sum(chord * np.cos(mid))), float(np.sum(chord * np.sin(mid))), float(turn[-1])])


def plain_merge(params: ChainParams, j: int) -> ChainParams:
    """``params`` with segments j and j + 1 one segment of their length and mean curvature."""
    kappa, length = params.kappa, params.length
    total = length[j] + length[j + 1]
    mean = (kappa[j] * length[j] + kappa[j + 1] * length[j + 1]) / total
    return ChainParams(params.heading, np.concatenate((kappa[:j], [mean], kappa[j + 2:])),
                       np.concatenate((length[:j], [total], length[j + 2:])), params.shift)


def bent_merge(params: ChainParams, j: int) -> ChainParams | None:
    """plain_merge with the window of the merged segment and its neighbours bent to end as
    segments j - 1 .. j + 2 did; None where no bending that keeps every length a quarter of
    what it was converges, or where the chain has no neighbour to bend."""
    kappa, length = params.kappa, params.length
    plain = plain_merge(params, j)
    new_kappa, new_length = plain.kappa.copy(), plain.length.copy()
    lo, hi = max(j - 1, 0), min(j + 1, len(new_kappa) - 1)  # the window, in the merged chain
    if hi - lo < 1:
        return None  # one segment left in the window: no freedom to keep both ends
    heading = params.heading + float(np.sum(kappa[:lo] * length[:lo]))
    target = _pose(heading, kappa[lo:hi + 2], length[lo:hi + 2])
    bent = _bend(heading, new_kappa[lo:hi + 1], new_length[lo:hi + 1], target)
    if bent is None:
        return None
    new_kappa[lo:hi + 1], new_length[lo:hi + 1] = bent
    return ChainParams(params.heading, new_kappa, new_length, params.shift)


def _bend(heading: float, kappa: np.ndarray, length: np.ndarray,
          target: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Curvatures and lengths near these that end at ``target`` (relative end point and
    heading), by least-norm Newton steps; None if they do not converge."""
    span = float(length.sum())
    scale = np.concatenate((np.full(len(kappa), 1.0 / span), np.full(len(length), span)))  # unit steps
    x = np.concatenate((kappa, length))
    m = len(kappa)

    def gap(v: np.ndarray) -> np.ndarray:
        g = _pose(heading, v[:m], v[m:]) - target
        g[2] = math.remainder(float(g[2]), 2 * math.pi) * span
        return g

    for _ in range(NEWTON_STEPS):
        g = gap(x)
        if np.abs(g).max() < 1e-9 * span:
            break
        eps = 1e-7
        jac = np.column_stack([(gap(x + eps * sc * e) - g) / eps for sc, e in zip(scale, np.eye(2 * m))])
        x = x + scale * np.linalg.lstsq(jac, -g, rcond=None)[0]
    if np.abs(gap(x)).max() > 1e-6 * span or np.any(x[m:] < SHORTEST * length):
        return None
    return x[:m], x[m:]

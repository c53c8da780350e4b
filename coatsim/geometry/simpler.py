"""A sparse run's chain made simpler where it stays within σ: junctions given up, and arcs
along straight stretches of the taught points made lines.

A chain found within σ of taught points is as simple as the band fit left it: two of its
segments may do as one (fewer), and a long side taught with collinear points comes back as
an arc of metres of radius bowing across the tolerance, where the robot should move on a
line (straightened). Either change is kept only where the chain, refined again, stays
within σ and under its caps, so neither ever costs the tolerance or a segment.
"""

from __future__ import annotations

import math
from typing import Protocol

import numpy as np

from coatsim.geometry.merge import bent_merge, plain_merge
from coatsim.geometry.primitives import Line, Segment
from coatsim.geometry.refine import ChainParams

HOPELESS = 1.02  # a merged chain whose sampled deviation is above this share of σ is not checked exactly
SCREEN = 5.0  # a merge bent back onto the rest that strays this many σ is not refined (see fewer)
STRAIGHT_SHARE = 0.5  # an arc is tried as a line where the taught points it passes are this share of σ off a line
STRAIGHT_TRIM = 0.15  # ... leaving out this share of the arc's stretch at either end (the pairing is by length)
STRAIGHT_FAILS = 2  # after all at once failed, lines are tried one by one (the gentlest arc first) until this many fail


class Settles(Protocol):
    """What a run's chain is refined against and checked on (fit._Target)."""

    measured: np.ndarray
    tolerance: float

    def settle(self, params: ChainParams, target: float, hopeless: float = ...,
               lines: np.ndarray | None = None) -> tuple[ChainParams, float, tuple[Segment, ...], bool, float]: ...

    def sampled(self, params: ChainParams) -> float: ...


Chain = tuple[ChainParams, tuple[Segment, ...], float]


def fewer(tgt: Settles, params: ChainParams, segs: tuple[Segment, ...], dev: float, target: float) -> Chain:
    """The chain with junctions given up, the calmest first (two segments become one of their
    length and turn, refined again to ``target``), while the chain stays within the tolerance
    and caps; a junction whose merge, bent back onto the rest of the chain
    (coatsim.geometry.merge), still strays SCREEN σ from the input is not refined.
    A junction that could not be given up is not tried again until a neighbouring one is
    (the segments next to it are then new)."""
    failed: set[int] = set()  # junction k: between segments k and k + 1
    while len(params.kappa) > 1:
        for j in np.argsort(np.abs(np.diff(params.kappa)), kind="stable"):
            if j in failed:
                continue
            bent = bent_merge(params, int(j))
            if bent is not None and tgt.sampled(bent) > SCREEN * tgt.tolerance:
                failed.add(int(j))  # (bent back onto the rest, the merge still strays far: not refined)
                continue
            merged, _, merged_segs, honest, merged_dev = tgt.settle(plain_merge(params, int(j)), target,
                                                                    HOPELESS * tgt.tolerance)
            if honest and merged_dev <= tgt.tolerance:
                params, segs, dev = merged, merged_segs, merged_dev
                failed = {k - (k > j) for k in failed if abs(k - j) > 1}
                break
            failed.add(int(j))
        else:
            break
    return params, segs, dev


def straight_arcs(measured: np.ndarray, params: ChainParams, tolerance: float) -> np.ndarray:
    """Indices of the arcs whose stretch of the taught polyline ``measured`` (paired by share
    of length, as the refinement pairs them, less STRAIGHT_TRIM at either end, where the pairing
    may reach into a bend) lies within STRAIGHT_SHARE σ of the line through its ends, the
    gentlest first."""
    seg = np.linalg.norm(np.diff(measured, axis=0), axis=1)
    frac = np.concatenate(([0.0], np.cumsum(seg))) / seg.sum()
    ends = np.concatenate(([0.0], np.cumsum(params.length))) / params.length.sum()
    found: list[tuple[float, int]] = []
    for k in np.flatnonzero(params.kappa != 0):
        trim = STRAIGHT_TRIM * (ends[k + 1] - ends[k])
        part = measured[(frac >= ends[k] + trim) & (frac <= ends[k + 1] - trim)]
        if len(part) < 2:
            continue
        chord = part[-1] - part[0]
        norm = float(np.hypot(*chord))
        if norm == 0.0:
            continue
        off = float(np.abs((part - part[0]) @ np.array([-chord[1], chord[0]])).max()) / norm
        if off <= STRAIGHT_SHARE * tolerance:
            found.append((abs(float(params.kappa[k])), int(k)))
    return np.array([k for _, k in sorted(found)], dtype=int)


def straightened(tgt: Settles, chain: Chain, target: float) -> Chain:
    """The chain with its arcs along straight stretches of the taught points (straight_arcs)
    made lines, all at once, else one by one (until STRAIGHT_FAILS fail), the rest refined
    again to ``target``; each kept where the chain stays within the tolerance and caps.
    Lines that end up next to each other are one line."""
    params, segs, dev = chain
    candidates = straight_arcs(tgt.measured, params, tgt.tolerance)
    tries = [candidates] + ([[k] for k in candidates] if len(candidates) > 1 else [])
    failed = 0
    for chosen in tries:
        if len(chosen) == 0 or failed >= STRAIGHT_FAILS or np.all(params.kappa[chosen] == 0):
            continue
        lines = params.kappa == 0
        lines[chosen] = True
        flat = ChainParams(params.heading, np.where(lines, 0.0, params.kappa), params.length.copy(), params.shift)
        straight, _, straight_segs, honest, straight_dev = tgt.settle(flat, target, math.inf, lines)
        if honest and straight_dev <= tgt.tolerance:
            params, segs, dev = straight, straight_segs, straight_dev
        else:
            failed += len(chosen) == 1
    return _joined(params), _joined_segments(segs), dev


def _joined(params: ChainParams) -> ChainParams:
    """``params`` with each run of consecutive lines one line (the same chain)."""
    keep = np.ones(len(params.kappa), dtype=bool)
    keep[1:] = (params.kappa[1:] != 0) | (params.kappa[:-1] != 0)
    group = np.cumsum(keep) - 1
    return ChainParams(params.heading, params.kappa[keep], np.bincount(group, weights=params.length), params.shift)


def _joined_segments(segs: tuple[Segment, ...]) -> tuple[Segment, ...]:
    """``segs`` with each run of consecutive lines one line (the same path)."""
    out: list[Segment] = []
    for seg in segs:
        if out and isinstance(seg, Line) and isinstance(out[-1], Line):
            out[-1] = Line(out[-1].start, seg.end)
        else:
            out.append(seg)
    return tuple(out)

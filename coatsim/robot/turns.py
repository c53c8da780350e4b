"""A revolute joint's whole-turn equivalents: the same arm pose with a joint turned by 360°.

A local IK solver can end a joint a turn (or several) away from where the arm stands; a joint
move may reach the same pose with the joint the other way round, inside its range.
"""

from __future__ import annotations

import math

import numpy as np


def turns_near(q: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """Each joint of ``q`` a whole number of turns off, nearest ``ref`` (the same arm pose)."""
    return q - 2 * math.pi * np.round((q - ref) / (2 * math.pi))


def within_turns(q: np.ndarray, ref: np.ndarray, q_min: np.ndarray, q_max: np.ndarray) -> np.ndarray | None:
    """Each joint of ``q`` the whole number of turns off that puts it inside [q_min, q_max],
    nearest ``ref`` where two do; None if a joint has none."""
    out = np.empty_like(q)
    for j, (value, near) in enumerate(zip(q, ref)):
        lo, hi = math.ceil((q_min[j] - value) / (2 * math.pi)), math.floor((q_max[j] - value) / (2 * math.pi))
        if lo > hi:
            return None
        out[j] = min((value + 2 * math.pi * k for k in range(lo, hi + 1)), key=lambda v: abs(v - near))
    return out

"""Cross products and lengths of 3-vectors along the last axis, for the fit's inner loops.

Each gives the very floats of its numpy counterpart (the same products, sums and square roots
in the same order) without that function's argument handling, which costs more than the
arithmetic on the few vectors the fit evaluates at a time.
"""

from __future__ import annotations

import numpy as np


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross(a, b)`` of vectors (..., 3)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=-1)


def norm3(v: np.ndarray, keepdims: bool = False) -> np.ndarray:
    """``np.linalg.norm(v, axis=-1, keepdims=keepdims)`` of vectors (..., 3)."""
    return np.sqrt(np.add.reduce(v * v, axis=-1, keepdims=keepdims))

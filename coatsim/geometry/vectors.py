"""Unit vectors of rows: the one normalisation the surface and space modules share."""

from __future__ import annotations

import numpy as np


def unit_rows(vectors: np.ndarray) -> np.ndarray:
    """Each vector along the last axis scaled to length 1 (a zero vector gives nan)."""
    return vectors / np.linalg.norm(vectors, axis=-1, keepdims=True)

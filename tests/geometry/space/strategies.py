"""Hypothesis strategies shared by the 3-D geometry tests: rotations, poses, unit vectors."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from coatsim.geometry.space.pose import Pose, exp_rotation

coord = st.floats(-500.0, 500.0, allow_nan=False)
unit_component = st.floats(-1.0, 1.0, allow_nan=False)


@st.composite
def unit_vectors(draw) -> np.ndarray:
    v = np.array([draw(unit_component) for _ in range(3)])
    n = np.linalg.norm(v)
    return v / n if n > 1e-3 else np.array([0.0, 0.0, 1.0])


@st.composite
def rotations(draw) -> np.ndarray:
    return exp_rotation(draw(unit_vectors()) * draw(st.floats(0.0, np.pi)))


@st.composite
def poses(draw) -> Pose:
    return Pose(draw(rotations()), np.array([draw(coord) for _ in range(3)]))


@st.composite
def points3(draw, n: int) -> np.ndarray:
    return np.array([[draw(coord) for _ in range(3)] for _ in range(n)])

"""Orientation-aware fit of a surface pass: the interpolated tool axis stays within the angle
tolerance of the surface normal along a torus section (measured here independently)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.orient import fit_surface_pass, slerp_axes
from coatsim.geometry.space.polysegment_json import chain_document, chain_from_document

R_MAJOR, R_TUBE, STANDOFF = 80.0, 30.0, 100.0


def torus_pass(n: int = 1500) -> tuple[np.ndarray, np.ndarray]:
    """TCP points 100 mm off a (2, 3) torus-knot section of the torus, and the spray axes
    (minus the outward normal)."""
    t = np.linspace(0.0, 4 * math.pi / 3, n)
    phi = 1.5 * t
    ring = np.column_stack((R_MAJOR * np.cos(t), R_MAJOR * np.sin(t), np.zeros_like(t)))
    normal = np.column_stack((np.cos(phi) * np.cos(t), np.cos(phi) * np.sin(t), np.sin(phi)))
    surface = ring + R_TUBE * normal
    return surface + STANDOFF * normal, -normal


def true_axis(x: np.ndarray) -> np.ndarray:
    """Minus the torus normal at the pass parameter nearest to the TCP point x (from a pass
    sampled 200 times more densely than the input)."""
    from scipy.spatial import cKDTree

    dense, axes = torus_pass(300_000)
    return axes[cKDTree(dense).query(x)[1]]


@pytest.mark.parametrize("angle_tol_deg", [2.0, 0.5])
def test_orientation_bound_holds_on_a_torus_section(angle_tol_deg):
    points, axes = torus_pass()
    fit = fit_surface_pass(points, axes, 0.1, angle_tol_deg)
    chain = fit.chain
    assert fit.segmentation.max_deviation_mm <= 0.1 and len(chain.axes) == chain.n_segments
    assert fit.max_axis_error_rad <= math.radians(angle_tol_deg)
    worst = 0.0
    for seg, (a0, av, a1) in zip(chain.segments, chain.axes):
        a0, av, a1 = (np.array(a) for a in (a0, av, a1))
        s = np.linspace(0.0, seg.length, 201)
        got = (slerp_axes(a0, a1, s / seg.length) if seg.kind == "line" else
               np.vstack((slerp_axes(a0, av, s[:101] / (seg.length / 2)), slerp_axes(av, a1, (s[101:] - seg.length / 2) / (seg.length / 2)))))
        want = true_axis(seg.points(s))
        worst = max(worst, float(np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", got, want), -1, 1))).max()))
    # the wanted axis is the sampled normal interpolated along the input (within 0.01 degree of the torus's)
    assert worst <= angle_tol_deg + 0.01
    tighter = fit_surface_pass(points, axes, 0.1, 0.05)  # 24 arcs keep 0.5 degrees; 0.05 needs more poses
    assert tighter.chain.n_segments > chain.n_segments and tighter.max_axis_error_rad <= math.radians(0.05)
    for a, b in zip(chain.segments[:-1], chain.segments[1:]):
        assert np.array_equal(a.end, b.start)
    assert max(chain.junction_breaks()) < 1e-9
    doc = chain_document(chain, 0.1, {})
    assert "axes" in doc["segments"][0] and chain_from_document(doc, "t.json").axes == chain.axes


def test_bad_axes_are_refused():
    points, axes = torus_pass(200)
    flipped = axes.copy()
    flipped[100:] *= -1
    with pytest.raises(InputError, match="turns .* between points 100 and 101"):
        fit_surface_pass(points, flipped, 0.1)
    with pytest.raises(InputError, match="spray axis 3 is zero"):
        fit_surface_pass(points, np.where(np.arange(200)[:, None] == 2, 0.0, axes), 0.1)
    with pytest.raises(InputError, match="angle_tol_deg"):
        fit_surface_pass(points, axes, 0.1, 0.0)


def test_a_pass_the_fit_cannot_follow_is_named_with_its_length():
    # a sliver loop of four points 0.4 mm across (a planner's level just below a ridge), offset
    # 100 mm along its normals: the planar fit of its tool path collapses the loop; the error
    # names the pass and its length, not only "the fit produced an unusable arc"
    surface = np.array([[16.768393, -54.767831, -2.46213], [16.89317, -55.103887, -2.526675],
                        [17.106368, -55.105692, -2.547391], [17.16158, -54.835536, -2.509824]])
    normals = np.array([[0.087792453, -0.145463837, 0.985460683], [0.088898061, -0.144860468, 0.985450445],
                        [0.087073241, -0.146050829, 0.985437672], [0.085163858, -0.147534092, 0.985383585]])
    tcp = surface + 100.0 * normals
    loop, axes = np.vstack((tcp, tcp[:1])), -np.vstack((normals, normals[:1]))
    with pytest.raises(InputError, match=r"^plan\.json: passes\[3\] \(its tool path 0\.9\d+ mm long\): "):
        fit_surface_pass(loop, axes, 0.1, name="plan.json: passes[3]")

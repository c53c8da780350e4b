"""A scanned part's noise: normals smoothed in steps, noisy passes not taken for taught points,
and a program that says its arcs follow noise."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh

from cli_helpers import cli
from coatsim.geometry.space import taught
from coatsim.geometry.space.curve import make_space_curve
from coatsim.geometry.space.families import FAMILIES, HELD_OUT
from coatsim.geometry.space.segment import segment_space_curve
from coatsim.geometry.surface.normals import smooth_normals, vertex_normals
from coatsim.path.pass_fits import place_passes
from coatsim.path.surface_program import SurfaceOptions, _noise_notes, surface_fit_settings
from coatsim.path.surfacepaths import read_surfacepaths


def grid(heights: np.ndarray, step_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """A height field on a square grid as a triangle mesh (vertices, faces)."""
    nu, nv = heights.shape
    u, v = np.meshgrid(np.arange(nu) * step_mm, np.arange(nv) * step_mm, indexing="ij")
    i, j = np.meshgrid(np.arange(nu - 1), np.arange(nv - 1), indexing="ij")
    a = (i * nv + j).ravel()
    faces = np.vstack([np.column_stack((a, a + nv, a + nv + 1)), np.column_stack((a, a + nv + 1, a + 1))])
    return np.column_stack((u.ravel(), v.ravel(), heights.ravel())), faces


def hump(noise_mm: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A bump 25 mm high on an 80 x 50 mm patch in 1.7 mm facets, its heights scattered by ``noise_mm``."""
    u, v = np.meshgrid(np.linspace(-40, 40, 48), np.linspace(-25, 25, 30), indexing="ij")
    heights = 25 * np.exp(-(u**2 + v**2) / 1500) + np.random.default_rng(seed).normal(0, noise_mm, u.shape)
    vertices, faces = grid(heights, 80 / 47)
    vertices[:, 0] -= 40
    vertices[:, 1] = v.ravel()
    return vertices, faces


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_normals_of_a_noisy_flat_scan_are_smoothed_in_steps(seed):
    """A flat scan with 0.2 mm of noise on 1.7 mm facets (raw normals 5.5 deg rms off the plane):
    smoothed over 5 mm in two implicit steps, the normals inside stay within 0.45 deg rms of
    the plane's (one step of the same time left 0.58 deg: a 100 mm stand-off scattered the tool
    points by twice as much)."""
    vertices, faces = grid(np.random.default_rng(seed).normal(0, 0.2, (60, 60)), 100 / 59)
    smoothed = smooth_normals(vertices, faces, 5.0, vertex_normals(vertices, faces))
    inner = np.all((vertices[:, :2] > 15) & (vertices[:, :2] < 85), axis=1)
    angle = np.arccos(np.clip(smoothed[inner, 2], -1, 1))
    assert math.degrees(math.sqrt(np.mean(angle**2))) < 0.45


def test_noisy_tells_measured_points_from_taught_ones():
    """Dense points whose noise (0.05 mm) outweighs their bend between neighbours (1 000 points
    along each family) turn back at random; a taught polygon of a smooth curve turns one way
    between its inflections, at 15, 30 and 60 vertices of every family."""
    rng = np.random.default_rng(7)
    for name, make in {**FAMILIES, **HELD_OUT}.items():
        for n in (15, 30, 60):
            assert not taught.noisy(make(n)), (name, n)
        dense = make(1000)
        assert taught.noisy(dense + rng.normal(0, 0.05, dense.shape)), name


def test_a_noisy_pass_is_not_fitted_along_a_taught_guide(monkeypatch):
    """A pass of points 1 mm apart with 0.05 mm of noise at σ 0.1 is sparse by its edges, but
    no taught polygon: the taught guide is not tried (it cost ten times the fit for nothing)."""
    def no_guide(*args, **kwargs):
        raise AssertionError("guide3 called on measured noise")

    monkeypatch.setattr(taught, "guide3", no_guide)
    t = np.linspace(0, 1, 120)
    points = np.column_stack((120 * t, 20 * np.sin(3 * t), 10 * t**2))
    points += np.random.default_rng(2).normal(0, 0.05, points.shape)
    fit = segment_space_curve(make_space_curve(points, "noisy pass"), 0.1)
    assert fit.max_deviation_mm <= 0.1


def _paths(tmp_path: Path, noise_mm: float) -> Path:
    vertices, faces = hump(noise_mm, 1)
    stl = tmp_path / f"hump_{noise_mm}.stl"
    trimesh.Trimesh(vertices, faces).export(stl)
    out = tmp_path / f"hump_{noise_mm}.json"
    code, _, err = cli("plan", stl, "-o", out, "--spacing", 15, "--units", "mm")
    assert code == 0, err
    return out


@pytest.mark.parametrize("noise_mm, said", [(0.0, False), (0.2, True)])
def test_the_noise_note_judges_the_tool_points(tmp_path, noise_mm, said):
    """The note is said for a scan whose tool points scatter (0.2 mm of noise: 0.03-0.05 mm at
    the stand-off, over a quarter of σ 0.1), not for the same bump without noise."""
    paths = read_surfacepaths(_paths(tmp_path, noise_mm))
    surface = SurfaceOptions()
    notes = _noise_notes(place_passes(paths, surface_fit_settings(paths, surface, 300.0)), surface)
    assert bool(notes) is said
    if said:
        assert "scatter" in notes[0] and "tolerance_mm 0.1" in notes[0]


@pytest.mark.slow
def test_program_of_a_noisy_scan_says_its_arcs_follow_noise(tmp_path):
    """End to end: the program of a noisy scan is written within σ and says why it has many
    short moves, and from which tolerance the surface itself is fitted; that tolerance fits
    with fewer segments."""
    paths = _paths(tmp_path, 0.2)
    code, out, err = cli("program", paths, "-o", tmp_path / "hump.as")
    assert code == 0, err
    assert "note: the tool points scatter" in out
    suggested = float(out.split("a tolerance of ")[1].split(" mm")[0])
    code, coarse, err = cli("program", paths, "--tol", suggested, "-o", tmp_path / "coarse.as")
    assert code == 0, err

    def segments(text: str) -> int:
        head = text.split(" in 3-D")[0].split(": polysegment, ")[1]
        return sum(int(word) for word in head.replace("+", " ").split() if word.isdigit())

    assert segments(coarse) < segments(out) / 2

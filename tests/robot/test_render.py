"""Offscreen pictures of the cell, headless: the backend chosen automatically (EGL, else OSMesa),
the part coloured by a field, a clear error when no backend works."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from coatsim.robot.cell import load_cell
from coatsim.spray.surfaces import plate

CHOICE = """
import os, sys
os.environ.pop("MUJOCO_GL", None) if sys.argv[1] == "auto" else os.environ.__setitem__("MUJOCO_GL", sys.argv[1])
from coatsim.robot.render import RenderUnavailable, gl_backend
try:
    print(gl_backend()[0])
except RenderUnavailable as exc:
    print("unavailable:", exc)
"""


def _choose(setting: str) -> str:
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM", "DISPLAY")}
    done = subprocess.run([sys.executable, "-c", CHOICE, setting], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_the_backend_is_chosen_without_a_display():
    auto = _choose("auto")
    assert auto in ("egl", "osmesa"), auto
    assert _choose(auto) == auto  # asked for by name, the same one


def test_when_egl_fails_osmesa_is_tried_and_the_error_names_both():
    """EGL made to fail (a device that does not exist): OSMesa is tried in the same process
    (PyOpenGL reloaded for it); where the machine has no libOSMesa, one line names both."""
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM", "DISPLAY")}
    env["MUJOCO_EGL_DEVICE_ID"] = "99"
    done = subprocess.run([sys.executable, "-c", CHOICE, "auto"], capture_output=True, text=True, env=env, timeout=120)
    answer = done.stdout.strip()
    assert done.returncode == 0, done.stderr
    if answer != "osmesa":
        assert answer.startswith("unavailable: no offscreen OpenGL backend works (egl: RuntimeError: ")
        assert "; osmesa: " in answer and "libosmesa6" in answer and "\n" not in answer


def test_the_part_is_drawn_in_the_colours_of_its_field():
    from coatsim.robot.render import Camera, CellRenderer, RenderUnavailable

    surface = plate(200.0, 200.0, 5.0, np.array([[1, 0, 0, 700.0], [0, 1, 0, 0], [0, 0, 1, 200.0], [0, 0, 0, 1]]))
    colours = np.zeros((256, 3), np.uint8)
    colours[:, 0] = np.arange(256)          # fraction 0: black, 1: pure red
    try:
        renderer = CellRenderer(load_cell(), surface.vertices, surface.faces, surface.normals, colours, 320, 240)
    except RenderUnavailable as exc:
        pytest.fail(str(exc))
    cell = load_cell()
    camera = Camera((700.0, 0.0, 200.0), 450.0, 90.0, -89.0)  # straight down onto the part
    left = (surface.vertices[:, 1] > 0).astype(float)         # one half red, the other black
    try:
        image = renderer.frame(cell.home, left, camera).astype(int)
        flat = renderer.frame(cell.home, np.zeros(surface.n_vertices), camera).astype(int)
    finally:
        renderer.close()
    assert image.shape == (240, 320, 3) and renderer.backend in ("egl", "osmesa")
    red = (image[..., 0] > image[..., 1] + 60) & (image[..., 0] > image[..., 2] + 60)
    dark = image.max(axis=2) < 40
    assert red.mean() > 0.05 and dark.mean() > 0.05  # both halves of the part are seen
    assert abs(red.mean() - dark.mean()) < 0.3 * max(red.mean(), dark.mean())
    assert not ((flat[..., 0] > flat[..., 1] + 60) & (flat[..., 0] > flat[..., 2] + 60)).any()
    # the two halves lie on either side of a line through the middle of the part
    red_rows, dark_rows = np.flatnonzero(red.any(axis=1)), np.flatnonzero(dark.any(axis=1))
    red_cols, dark_cols = np.flatnonzero(red.any(axis=0)), np.flatnonzero(dark.any(axis=0))
    assert red_rows.max() <= dark_rows.min() + 3 or dark_rows.max() <= red_rows.min() + 3 \
        or red_cols.max() <= dark_cols.min() + 3 or dark_cols.max() <= red_cols.min() + 3

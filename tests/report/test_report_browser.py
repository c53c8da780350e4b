"""report.html opened in a real headless Chromium: no script error, the 3-D viewer draws, the
page renders (the screenshot is not blank); and the GLB and PLY files of the run."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (.ci/run installs it)")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync"]


def chromium(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    profile = tmp_path / "profile"
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0", *args],
                          capture_output=True, text=True, timeout=180)


@needs_chromium
def test_the_report_loads_without_script_errors_and_the_viewer_draws(small_report, tmp_path: Path) -> None:
    *_, outdir = small_report
    page = (outdir / "report.html").resolve().as_uri()
    done = chromium(tmp_path, "--virtual-time-budget=5000", "--dump-dom", page)
    dom = done.stdout
    assert '<section id="view3d">' in dom, done.stderr[-2000:]
    errors = re.search(r'<html[^>]*data-script-errors="([^"]*)"', dom)
    assert errors is None, errors.group(1)
    assert re.search(r'id="coatsim-viewer"[^>]*data-viewer="ready"', dom)
    console = [line for line in done.stderr.splitlines() if "CONSOLE" in line and "Uncaught" in line]
    assert console == []


@needs_chromium
def test_the_report_renders_a_page_that_is_not_blank(small_report, tmp_path: Path) -> None:
    from PIL import Image

    *_, outdir = small_report
    shot = tmp_path / "shot.png"
    chromium(tmp_path, f"--screenshot={shot}", "--window-size=1200,2400", "--virtual-time-budget=5000",
             (outdir / "report.html").resolve().as_uri())
    pixels = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    assert pixels.shape[:2] == (2400, 1200)
    assert pixels.std() > 20.0                      # text, figures: not one flat colour
    assert (pixels.reshape(-1, 3) < 100).all(axis=1).mean() > 0.005  # dark ink somewhere
    assert len(np.unique(pixels.reshape(-1, 3)[::97], axis=0)) > 200  # figures' colours, not only text


def _ply(path: Path) -> tuple[str, np.ndarray]:
    """Header and vertex RGB of a coatsim PLY (x y z nx ny nz thickness exposure, rgb)."""
    data = path.read_bytes()
    head, body = data.split(b"end_header\n", 1)
    n = int(re.search(rb"element vertex (\d+)", head).group(1))
    vertex = np.frombuffer(body[: n * 35], dtype=[("f", "<f4", 8), ("rgb", "u1", 3)])
    return head.decode("ascii"), vertex


def test_glbs_load_in_trimesh_with_the_plys_colours_on_one_scale(small_report) -> None:
    import trimesh

    *_, outdir = small_report
    scales = set()
    for variant in ("polysegment", "polyline-stop", "polyline-blend"):
        scene = trimesh.load(outdir / f"{variant}.thickness.glb", process=False)
        mesh = scene.geometry["thickness"]
        head, vertex = _ply(outdir / f"{variant}.thickness.ply")
        assert "property float thickness\nproperty float exposure\n" in head
        scales.add(re.search(r"colours viridis from (\S+) to (\S+) um", head).groups())
        assert mesh.visual.kind == "vertex"
        colours = np.asarray(mesh.visual.vertex_colors)[:, :3]
        assert len(colours) == len(vertex) and (colours == vertex["rgb"]).all()
        thickness = np.asarray(mesh.vertex_attributes["_THICKNESS_UM"]).ravel()
        assert np.allclose(thickness, vertex["f"][:, 6])
        assert np.allclose(mesh.vertices * 1000.0, vertex["f"][:, :3], atol=1e-3)  # glTF metres
        assert any(name.startswith("tool_path_") for name in scene.geometry)
    assert len(scales) == 1  # every variant on the same colour scale

"""The report of a run on a 3-D part opened in a real headless Chromium: no script error, the 3-D
viewer ready, and the view showing the part in its thickness colours (a screenshot of the view3d
section alone: coloured pixels where the part is, none when the part's mesh is taken out)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from test_report_browser import chromium, needs_chromium


def view_only(html: str) -> str:
    """The report with every section but view3d taken out (the view then sits at the page's top)."""
    return re.sub(r'<section id="(?!view3d")[^"]+">.*?</section>', "", html, flags=re.S)


def coloured_share(tmp_path: Path, html: str, name: str) -> float:
    """Share of the screenshot's pixels that are clearly coloured (the viridis part, not text)."""
    from PIL import Image

    page, shot = tmp_path / f"{name}.html", tmp_path / f"{name}.png"
    page.write_text(html, encoding="utf-8")
    chromium(tmp_path, f"--screenshot={shot}", "--window-size=1000,900", "--virtual-time-budget=5000", page.as_uri())
    rgb = np.asarray(Image.open(shot).convert("RGB"), dtype=float)
    saturation = rgb.max(axis=2) - rgb.min(axis=2)
    return float((saturation > 60).mean())


@needs_chromium
def test_the_part_report_loads_without_script_errors(tube_run, tmp_path: Path) -> None:
    result, _ = tube_run
    done = chromium(tmp_path, "--virtual-time-budget=5000", "--dump-dom", (result.outdir / "report.html").as_uri())
    dom = done.stdout
    for section in ("verdict", "speed", "histogram", "maps", "view3d"):
        assert f'<section id="{section}">' in dom, done.stderr[-2000:]
    assert re.search(r'<html[^>]*data-script-errors="([^"]*)"', dom) is None
    assert re.search(r'id="coatsim-viewer"[^>]*data-viewer="ready"', dom)


@needs_chromium
def test_the_3d_view_shows_the_part(tube_run, tmp_path: Path) -> None:
    result, _ = tube_run
    html = view_only((result.outdir / "report.html").read_text(encoding="utf-8"))
    with_part = coloured_share(tmp_path, html, "part")
    # the same page with the part's triangles taken out of the viewer's data: only the passes remain
    empty = re.sub(r'"faces":"[^"]*"', '"faces":""', html)
    without = coloured_share(tmp_path, empty, "empty")
    assert with_part > 0.05, with_part
    assert with_part > 3 * without, (with_part, without)

"""The fitter's memory at large N, measured in a fresh process (not wall time): the peak
resident size it adds, and the peak of what numpy allocates, per input point."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from coatsim.geometry import builtin_curve

BUDGET_BYTES_PER_POINT = 512  # issue 15: at most 0.5 KiB per input point

CHILD = """
import json, resource, sys, tracemalloc
import numpy as np
from coatsim.geometry import make_curve, read_curve_file, segment_curve
segment_curve(make_curve(np.column_stack((np.cos(np.linspace(0, 6, 500)), np.sin(np.linspace(0, 6, 500)))) * 50,
                         "warm-up"), 0.05)  # every module the fitter imports, before the baseline
curve = read_curve_file(sys.argv[1])
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
segment_curve(curve, 0.05)
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base
tracemalloc.start()
segment_curve(curve, 0.05)
peak = tracemalloc.get_traced_memory()[1]
print(json.dumps({"n": len(curve.points), "rss_bytes": rss * 1024, "traced_bytes": peak}))
"""


@pytest.mark.parametrize("name,points", [("ellipse", 200_000), pytest.param("paper-spiral", 1_000_000, marks=pytest.mark.slow)])
def test_fitter_memory_per_input_point(tmp_path, name, points):
    path = tmp_path / f"{name}.npy"
    np.save(path, builtin_curve(name, points=points).points)
    out = subprocess.run([sys.executable, "-c", CHILD, str(path)], capture_output=True, text=True, check=True, timeout=900)
    figures = json.loads(out.stdout.strip().splitlines()[-1])
    assert figures["n"] == points
    assert figures["rss_bytes"] <= BUDGET_BYTES_PER_POINT * points, figures
    assert figures["traced_bytes"] <= BUDGET_BYTES_PER_POINT * points, figures


@pytest.mark.parametrize("points", [10, 100_000, 100_001, 250_000])
def test_the_band_fit_sees_a_bounded_subsample_with_both_ends(points):
    """Past BAND_KNOTS points the band fit works on every k-th point (its cost stays linear;
    the refinement and the exact check see every point)."""
    from coatsim.geometry.fit import BAND_KNOTS, _band_knots

    pts = np.column_stack((np.arange(points, dtype=float), np.zeros(points)))
    knots = _band_knots(pts)
    assert len(knots) <= BAND_KNOTS + 1
    assert (knots[0] == pts[0]).all() and (knots[-1] == pts[-1]).all()
    assert np.all(np.diff(knots[:, 0]) > 0)
    if points <= BAND_KNOTS:
        assert knots is pts


def test_a_subsampled_band_fit_keeps_the_contract():
    """250 000 points of the paper's spiral: the fit from a subsampled band still meets σ
    (exactly verified on every point), G1, and the limits."""
    from coatsim.geometry import segment_curve

    seg = segment_curve(builtin_curve("paper-spiral", points=250_000), 0.05)
    assert seg.max_deviation_mm <= 0.05 and seg.limits_kept
    assert seg.polysegment.max_tangent_break() <= 1e-9

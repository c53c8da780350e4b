"""Closed contours end to end with the real stack (mink, toppra, MuJoCo, trimesh): one lap at
process speed, the gun switched on the fly at the seam, no double coat there."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from coatsim.report.results import RunResult, VariantRun
from coatsim.run.pipeline import run_scenario

SIGMA_MM = 5.0
SCENARIO = """\
name: {name}
curve: {{builtin: {curve}, params: {params}}}
segmentation: {{tolerance_mm: 0.1}}
workpiece: {{kind: plate, size_mm: [240.0, 180.0]}}
gun: {{footprint: "gaussian:sigma={sigma}", target_thickness_um: 10.6}}
motion: {{speed_mm_s: 300.0, accuracy_mm: 1.0, lead_in_mm: 20.0, lead_out_mm: 20.0}}
coating: {{spacing_mm: 1.5, band_halfwidth_mm: 2.5}}
fast: {{coating_spacing_mm: 1.5, sample_step_mm: 1.0}}
"""
CASES = {
    "ellipse": ("ellipse", "{a: 80.0, b: 50.0}"),
    "rounded": ("rounded-rectangle", "{width: 160.0, height: 100.0, radius: 25.0}"),
}


class _Laps(dict):
    """Runs by case, each made on first use (selecting one test runs one case)."""

    def __init__(self, factory: pytest.TempPathFactory) -> None:
        super().__init__()
        self.factory = factory

    def __missing__(self, name: str) -> RunResult:
        curve, params = CASES[name]
        folder = self.factory.mktemp(name)
        scenario = folder / "lap.yaml"
        scenario.write_text(SCENARIO.format(name=name, curve=curve, params=params, sigma=SIGMA_MM), encoding="utf-8")
        self[name] = run_scenario(scenario, folder / "out", fast=True, progress=False)
        return self[name]


@pytest.fixture(scope="module")
def laps(tmp_path_factory: pytest.TempPathFactory) -> _Laps:
    return _Laps(tmp_path_factory)


def centre_line(run: VariantRun) -> tuple[np.ndarray, np.ndarray, float]:
    """Arc length from the seam (mm) and centre-line thickness (µm) at the mesh vertices within
    1 mm of the programmed curve (the Gaussian cross-profile of the pass divided out), and the
    curve's length."""
    curve = [s for s in run.program.path.segments if s.part == "curve"]
    pts = np.vstack([s.point_tangent(np.linspace(0.0, 1.0, 400))[0] for s in curve])
    along = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))))
    surface = run.coating.surface
    dist, nearest = cKDTree(pts[:, :2]).query(surface.vertices[:, :2])
    on = dist < 1.0
    profile = np.exp(-dist[on] ** 2 / (2 * SIGMA_MM**2))
    return along[nearest[on]], run.coating.thickness_um[on] / profile, float(along[-1])


@pytest.mark.slow
@pytest.mark.parametrize("case,variant", [("ellipse", "polysegment"), ("rounded", "polysegment"),
                                          ("rounded", "polyline-blend")])
def test_the_seam_is_coated_like_the_rest_of_the_lap(laps, case: str, variant: str):
    """Where the tool runs at constant speed through the seam (the ellipse's seam is at its
    tightest point, where the blended polyline slows down, so it is not a case for it)."""
    run = next(r for r in laps[case].variants if r.name == variant)
    s, thickness, length = centre_line(run)
    from_seam = np.minimum(s, length - s)
    seam, rest = from_seam < 2 * SIGMA_MM, from_seam > 4 * SIGMA_MM
    assert seam.sum() >= 4 and rest.sum() > 50
    lap_mm = float(np.median(thickness[rest]))
    assert np.all(np.abs(thickness[seam] / lap_mm - 1.0) <= 0.10), (thickness[seam] / lap_mm).round(3)


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(CASES))
def test_the_gun_is_open_for_exactly_one_lap_switching_at_speed(laps, case: str):
    for run in laps[case].variants:
        log, (a, b) = run.execution.log, run.execution.curve
        on = np.flatnonzero(log.spray)
        assert np.all(np.diff(on) == 1)  # one stretch
        speed = float(run.program.plan.speed_mm_s)
        row_mm = speed * float(np.median(np.diff(log.t)))
        assert abs(log.progress[on[0]] - a) <= row_mm + 0.05 and abs(log.progress[on[-1] + 1] - b) <= row_mm + 0.05
        assert np.allclose(log.position[on[0]], log.position[on[-1] + 1], atol=row_mm + 0.05)
        if run.name == "polysegment":  # the polylines stop (stop) or may slow (blend) at their vertices
            assert log.speed[on[0]] > 0.95 * speed and log.speed[on[-1]] > 0.95 * speed


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(CASES))
def test_the_polysegment_keeps_the_speed_on_the_whole_lap(laps, case: str):
    motion = next(r for r in laps[case].variants if r.name == "polysegment").groups["motion"]
    assert motion["min_speed_ratio"] >= 0.95
    assert motion["min_speed_mm_s"] >= 0.95 * motion["programmed_speed_mm_s"]

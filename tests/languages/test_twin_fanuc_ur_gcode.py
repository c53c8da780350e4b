"""The twin runs the Fanuc TP, URScript and G-code programs of a plan as it runs the Kawasaki AS
program of the same plan: the same sprayed path within the blending each language allows, the
same sprayed length, a similar cycle."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from coatsim.languages.fanuc_tp.blend import cnt_accuracy_mm, cnt_for
from coatsim.languages.registry import language
from coatsim.path.language import ReadOptions

from language_plans import planned

ACCURACY_MM, SPEED_MM_S = 0.5, 300.0
#: The corner rounding each language's program asks for when the plan asks for 0.5 mm at 300 mm/s.
BLEND_MM = {"kawasaki-as": ACCURACY_MM, "urscript": ACCURACY_MM, "gcode": ACCURACY_MM,
            "fanuc-tp": cnt_accuracy_mm(cnt_for(ACCURACY_MM, SPEED_MM_S), SPEED_MM_S)}


@pytest.fixture(scope="module")
def cell():
    from coatsim.robot.cell import load_cell

    return load_cell()


def _run(name, variant, cell, tmp_path):
    from coatsim.robot.execute import execute
    from coatsim.robot.kinematics import CellKinematics

    lang = language(name)
    path = tmp_path / f"{name}-{variant}{lang.suffixes[0]}"
    path.write_text(planned(name, variant=variant, speed_mm_s=SPEED_MM_S, accuracy_mm=ACCURACY_MM).text)
    toolpath = lang.read([path], ReadOptions(kinematics=CellKinematics(cell), needs_spray=True))
    return execute(toolpath, cell, step_mm=1.0)


@pytest.mark.parametrize("variant", ["polysegment", "polyline-blend", "polyline-stop"])
@pytest.mark.parametrize("name", ["fanuc-tp", "urscript", "gcode"])
def test_the_twin_runs_each_language_as_the_as_program(name, variant, cell, tmp_path):
    reference = _run("kawasaki-as", variant, cell, tmp_path)
    other = _run(name, variant, cell, tmp_path)
    a, b = reference.log, other.log
    pa, pb = np.asarray(a.position)[np.asarray(a.spray, bool)], np.asarray(b.position)[np.asarray(b.spray, bool)]
    tolerance = max(BLEND_MM[name], BLEND_MM["kawasaki-as"]) + 2e-3  # + the digits each language writes
    assert cKDTree(pa).query(pb)[0].max() < tolerance
    assert cKDTree(pb).query(pa)[0].max() < tolerance
    ma, mb = reference.metrics, other.metrics
    assert mb.curve_length_mm == pytest.approx(ma.curve_length_mm, abs=0.05)
    # (G61, exact path, runs straight through the tangent junction of the lead-in and the curve, where
    # AS's CP OFF stops; that stop is at the curve's first row, which the count leaves out)
    assert ma.stops == mb.stops
    assert mb.mean_speed_mm_s == pytest.approx(ma.mean_speed_mm_s, rel=0.03)
    assert mb.cycle_time_s == pytest.approx(ma.cycle_time_s, rel=0.15)

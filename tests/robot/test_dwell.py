"""Dwells (TWAIT, DELAY): the simulated arm stands still, the gun state held, and the coat
shows the thick spot (real stack: interpreter, MuJoCo playback, deposition)."""

from __future__ import annotations

import numpy as np
import pytest

from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.robot.cell import load_cell
from coatsim.robot.execute import execute

PROGRAM = """.PROGRAM dwell()
  SPEED 200 MM/S ALWAYS
  ACCURACY 1 ALWAYS
  JMOVE a
  BREAK
  SIGNAL 1
  LMOVE b
  {wait}
  LMOVE c
  BREAK
  SIGNAL -1
.END
.TRANS
a 700 -60 300 0 180 0
b 700 0 300 0 180 0
c 700 60 300 0 180 0
.END
"""


@pytest.fixture(scope="module")
def cell():
    return load_cell()


def run(cell, wait: str):
    toolpath = interpret(parse_as(PROGRAM.format(wait=wait), "dwell.as"))
    return toolpath, execute(toolpath, cell, step_mm=2.0)


def _rest_at(log, point, radius=0.5):
    near = np.linalg.norm(log.position - point, axis=1) < radius
    return float(np.count_nonzero(near & (log.speed < 1.0)) * (log.t[1] - log.t[0])), log.spray[near & (log.speed < 1.0)]


def test_delay_rests_at_the_point_with_the_gun_on(cell):
    tp, ex = run(cell, "DELAY 0.6")
    assert [(d.after, d.seconds, d.spray) for d in tp.dwells] == [(1, 0.6, True)]
    rest, spray = _rest_at(ex.log, np.array([700.0, 0.0, 300.0]))
    assert rest == pytest.approx(0.6, abs=0.05) and spray.all()
    _, plain = run(cell, "")
    assert ex.log.t[-1] - plain.log.t[-1] == pytest.approx(0.6, abs=0.2)
    assert ex.metrics.stops == plain.metrics.stops + 1


def test_twait_shorter_than_the_motion_leaves_no_rest(cell):
    tp, ex = run(cell, "TWAIT 0.1")
    assert tp.dwells == ()
    rest, _ = _rest_at(ex.log, np.array([700.0, 0.0, 300.0]))
    assert rest < 0.05


def test_the_coat_sees_the_dwell_as_a_thick_spot(cell):
    from coatsim.spray.coat import coat
    from coatsim.spray.deposition import SprayModel
    from coatsim.spray.footprints import parse_footprint_spec
    from coatsim.spray.surfaces import plate

    pose = np.eye(4)
    pose[:3, 3] = [700.0, 0.0, 200.0]
    surface = plate(60.0, 160.0, 2.0, pose)
    model = SprayModel(parse_footprint_spec("gaussian:sigma=5"), 40.0, 100.0)
    thick = {}
    for wait in ("", "TWAIT 1"):
        _, ex = run(cell, f"BREAK\n  {wait}" if wait else "")
        result = coat(ex.log, surface, model)
        at_b = np.linalg.norm(surface.vertices[:, :2] - [700.0, 0.0], axis=1) < 2.0
        thick[wait] = float(result.thickness_um[at_b].mean())
    assert thick["TWAIT 1"] > 3.0 * thick[""]

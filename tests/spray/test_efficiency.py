"""Deposition efficiency by spray angle: the laws, their specs and files, and the mass balance
with material bouncing off."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings

from coatsim.core.errors import InputError
from coatsim.spray.coating_metrics import coating_metrics
from coatsim.spray.deposition import deposit
from coatsim.spray.efficiency import DEFAULT_ANGLE_KNOTS, AngleTable, CosinePower, parse_efficiency_spec
from coatsim.spray.footprints import Gaussian
from coatsim.spray.surfaces import plate
from spray_helpers import H0, PLATE, Q, SIGMA, gun, random_paths, stationary_log, volume


def at_spray_angle(law, degrees):
    return law.factor(np.sin(np.radians(np.atleast_1d(np.asarray(degrees, float)))))


def test_the_default_curve_is_flat_down_to_60_degrees_then_falls():
    law = parse_efficiency_spec("angle")
    np.testing.assert_allclose(at_spray_angle(law, [90, 75, 60, 52.5, 45, 37.5, 30, 15, 0]),
                               [1, 1, 1, 0.95, 0.9, 0.825, 0.75, 0.375, 0], rtol=1e-12, atol=1e-12)
    assert law.knots == DEFAULT_ANGLE_KNOTS and law.spec == "angle"


@pytest.mark.parametrize("spec", ["angle", "angle:60=1,45=0.8,20=0.3", "cosine:n=2", "cosine:n=1.5"])
def test_specs_round_trip(spec):
    law = parse_efficiency_spec(spec)
    assert parse_efficiency_spec(law.spec) == law
    assert parse_efficiency_spec("none") is None


def test_knots_hold_their_end_values_beyond_the_outermost():
    law = parse_efficiency_spec("angle:70=1,40=0.6")
    np.testing.assert_allclose(at_spray_angle(law, [90, 70, 55, 40, 10]), [1, 1, 0.8, 0.6, 0.6], rtol=1e-12)


def test_the_cosine_law_is_cos_to_the_n_minus_1(tmp_path):
    law = CosinePower(2.5)
    cos = np.array([1.0, 0.5, 0.1])
    np.testing.assert_allclose(law.factor(cos), cos**1.5, rtol=1e-15)


def test_a_table_file(tmp_path):
    path = tmp_path / "de.csv"
    path.write_text("spray_angle_deg,efficiency\n30,0.5\n90,1\n60,0.95\n")
    law = parse_efficiency_spec(f"table:{path}")
    assert isinstance(law, AngleTable) and law.knots == ((30.0, 0.5), (60.0, 0.95), (90.0, 1.0))
    assert law.spec == f"table:{path}" and parse_efficiency_spec(law.spec) == law
    np.testing.assert_allclose(at_spray_angle(law, 45), 0.725, rtol=1e-12)


@pytest.mark.parametrize("text, words", [
    ("angle,eff\n30,1\n", "header must be 'spray_angle_deg,efficiency'"),
    ("spray_angle_deg,efficiency\n30\n", ":2: expected two numbers"),
    ("spray_angle_deg,efficiency\n30,x\n", ":2: expected two numbers"),
    ("spray_angle_deg,efficiency\n30,1.5\n", "efficiency must be between 0 and 1"),
    ("spray_angle_deg,efficiency\n95,1\n", "spray angle must be between 0 and 90"),
    ("spray_angle_deg,efficiency\n30,1\n30,0.5\n", "give each spray angle once"),
    ("spray_angle_deg,efficiency\n", "give each spray angle once"),
])
def test_bad_tables_name_the_file_and_line(tmp_path, text, words):
    path = tmp_path / "de.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=words) as info:
        parse_efficiency_spec(f"table:{path}")
    assert str(path) in str(info.value)


@pytest.mark.parametrize("spec, words", [
    ("sometimes", "unknown law 'sometimes'"), ("angle:60", "knots are spray_angle_deg=efficiency"),
    ("angle:60=2", "efficiency must be between 0 and 1"), ("cosine:n=0.5", "cosine:n=N with N >= 1"),
    ("cosine", "cosine:n=N"), ("table:", "give the table file"), ("table:/nonexistent/de.csv", "no such file"),
])
def test_bad_specs(spec, words):
    with pytest.raises(InputError, match=words):
        parse_efficiency_spec(spec)


def flux_weighted(law, tilt: float) -> float:
    """Independent quadrature on the reference plane: the footprint times DE at the spray angle
    of each ray on a plate tilted by ``tilt`` about y under a nozzle looking down."""
    x = np.linspace(-6 * SIGMA, 6 * SIGMA, 1201)
    u, v = np.meshgrid(x, x)
    g = Gaussian(SIGMA).density(u, v) * (x[1] - x[0]) ** 2
    rays = np.stack([u, -v, -np.full_like(u, H0)], axis=-1)
    rays /= np.linalg.norm(rays, axis=-1, keepdims=True)
    cos_gamma = -(rays @ np.array([math.sin(tilt), 0.0, math.cos(tilt)]))
    return float(np.sum(g * law.factor(cos_gamma.ravel()).reshape(cos_gamma.shape)))


@pytest.mark.parametrize("degrees", [35, 50])
def test_what_bounces_off_a_tilted_plate(degrees):
    """Spray angles around 90 - tilt: DE below 1 on all the plate at 50 deg, on part of it at 35."""
    tilt = math.radians(degrees)
    pose = np.eye(4)
    pose[:3, :3] = [[math.cos(tilt), 0, math.sin(tilt)], [0, 1, 0], [-math.sin(tilt), 0, math.cos(tilt)]]
    surface = plate(400, 200, SIGMA / 3, pose)
    log = stationary_log((0, 0, H0), 1.0)
    law = parse_efficiency_spec("angle")
    plain, bounced = deposit(surface, log, gun()), deposit(surface, log, gun(efficiency=law))
    np.testing.assert_allclose(bounced.thickness_mm + bounced.lost_mm, plain.thickness_mm, rtol=1e-12, atol=0)
    assert volume(surface, bounced.thickness_mm) == pytest.approx(Q * flux_weighted(law, tilt), rel=1e-4)
    m = coating_metrics(surface, bounced, gun(efficiency=law), np.ones(surface.n_vertices, bool))
    assert m["deposition_efficiency"] == pytest.approx(flux_weighted(law, tilt), rel=1e-4) and m["deposition_efficiency"] < 0.97
    assert m["on_part_efficiency"] == pytest.approx(1.0, rel=1e-4)
    assert m["lost_volume_mm3"] == pytest.approx(Q * (1 - flux_weighted(law, tilt)), rel=2e-3)


@given(random_paths())
@settings(max_examples=15, deadline=None)
def test_mass_balance_with_bouncing(log):
    """Everything lands on the plate (see spray_helpers.PLATE): sprayed = deposited + lost to
    1e-6 of the sprayed volume, missed ~ 0."""
    law = parse_efficiency_spec("angle")
    result = deposit(PLATE, log, gun(efficiency=law))
    sprayed = Q * result.steps.spray_time_s
    if sprayed == 0:
        return
    deposited, lost = volume(PLATE, result.thickness_mm), volume(PLATE, result.lost_mm)
    assert deposited + lost == pytest.approx(sprayed, rel=1e-6)
    assert lost >= 0 and deposited <= sprayed * (1 + 1e-6)


SCENARIO = """\
name: demo
curve:
  builtin: raster
  params: {passes: 3, pitch: 20}
workpiece: {kind: plate, size_mm: [300, 200]}
gun:
  efficiency: EFFICIENCY
"""


def test_a_scenario_gun_carries_its_efficiency(tmp_path):
    from coatsim.run.scenario import load_scenario
    from coatsim.run.scenario_inputs import input_files, spray_model

    (tmp_path / "guns").mkdir()
    (tmp_path / "guns" / "de.csv").write_text("spray_angle_deg,efficiency\n30,0.6\n90,1\n")
    job = tmp_path / "job.yaml"
    job.write_text(SCENARIO.replace("EFFICIENCY", "table:guns/de.csv"))
    loaded = load_scenario(job)
    assert spray_model(loaded).efficiency == parse_efficiency_spec(f"table:{tmp_path / 'guns' / 'de.csv'}")
    assert ("gun.efficiency", tmp_path / "guns" / "de.csv") in input_files(loaded)
    job.write_text(SCENARIO.replace("EFFICIENCY", "angle"))
    assert spray_model(load_scenario(job)).efficiency == parse_efficiency_spec("angle")
    job.write_text(SCENARIO.replace("EFFICIENCY", "angle:45=1.5"))
    with pytest.raises(InputError, match=r"job.yaml:7: gun.efficiency: .*efficiency must be between 0 and 1"):
        load_scenario(job)

"""A scenario's built-in variant written in Fanuc TP, URScript and G-code runs end to end (program,
twin, coating) as the Kawasaki AS program of the same plan: the same curve length, cycle time and
speed within the blending each language writes, and each program saved with its suffix."""

from __future__ import annotations

import json

import pytest
import yaml

from small_scenario import SMALL

LANGUAGES = {"fanuc-tp": ".ls", "urscript": ".script", "gcode": ".ngc"}


@pytest.mark.slow
def test_a_variant_in_each_language_runs_as_the_as_one(tmp_path, run_cli):
    spec = yaml.safe_load(SMALL)
    spec["variants"] = ["polysegment"] + [{"variant": "polysegment", "language": name} for name in LANGUAGES]
    spec["gates"] = spec["gates"][:3]
    scenario = tmp_path / "small.yaml"
    scenario.write_text(yaml.safe_dump(spec))
    code, _, err = run_cli(["run", str(scenario), "--fast", "-o", str(tmp_path / "out")])
    assert code == 0, err
    runs = json.loads((tmp_path / "out" / "metrics.json").read_text())["variants"]
    reference = runs["polysegment"]["motion"]  # in Kawasaki AS, the default language
    assert (tmp_path / "out" / "polysegment.as").exists()
    for name, suffix in LANGUAGES.items():
        assert (tmp_path / "out" / f"polysegment-{name}{suffix}").exists()
        motion = runs[f"polysegment-{name}"]["motion"]
        assert motion["curve_length_mm"] == pytest.approx(reference["curve_length_mm"], abs=0.01)
        assert motion["cycle_time_s"] == pytest.approx(reference["cycle_time_s"], rel=0.01)
        assert motion["min_speed_ratio"] == pytest.approx(reference["min_speed_ratio"], abs=0.01)
        assert motion["stops"] == reference["stops"]

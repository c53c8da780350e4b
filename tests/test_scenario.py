"""Scenario schema: strict loading, one-line errors naming file, line and key path."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.run.scenario import VARIANTS, Scenario, json_schema, load_scenario

BASE = """\
name: demo
curve:
  builtin: raster
  params: {passes: 3, pitch: 20}
workpiece:
  kind: plate
  size_mm: [300, 200]
"""


def write(tmp_path: Path, text: str, name: str = "job.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def load_error(tmp_path: Path, text: str) -> str:
    with pytest.raises(InputError) as info:
        load_scenario(write(tmp_path, text))
    message = str(info.value)
    assert "\n" not in message
    return message


def test_minimal_scenario_gets_documented_defaults(tmp_path: Path) -> None:
    loaded = load_scenario(write(tmp_path, BASE))
    spec = loaded.spec
    assert spec.variants == list(VARIANTS)
    assert spec.curve.params == {"passes": 3, "pitch": 20}
    assert isinstance(spec.curve.params["passes"], int)
    assert spec.segmentation.tolerance_mm == 0.1
    assert spec.workpiece.kind == "plate" and spec.workpiece.size_mm == [300.0, 200.0]
    assert spec.gates == []
    assert loaded.where("workpiece", "size_mm") == f"{loaded.path}:7"
    assert loaded.where("gun", "standoff_mm") == f"{loaded.path}:1"  # not spelled out: top


def test_yaml_exponent_without_dot_is_a_float(tmp_path: Path) -> None:
    spec = load_scenario(write(tmp_path, BASE + "segmentation:\n  tolerance_mm: 5e-2\n")).spec
    assert spec.segmentation.tolerance_mm == pytest.approx(0.05)


def test_relative_files_resolve_against_the_scenario_folder(tmp_path: Path) -> None:
    text = BASE.replace("builtin: raster\n  params: {passes: 3, pitch: 20}", "file: curves/c.csv")
    sub = tmp_path / "jobs"
    sub.mkdir()
    loaded = load_scenario(write(sub, text))
    assert loaded.resolve(loaded.spec.curve.file) == sub / "curves" / "c.csv"


MALFORMED = [
    # (name, appended or replaced text, line, fragments the message must contain)
    ("unknown top-level key", BASE + "colour: red\n", 8, ["colour", "unknown key"]),
    ("misspelt nested key", BASE + "gun:\n  standoff: 100\n", 9, ["gun.standoff", "did you mean 'standoff_mm'"]),
    ("negative stand-off", BASE + "gun:\n  standoff_mm: -5\n", 9, ["gun.standoff_mm", "greater than 0", "-5"]),
    ("word for a number", BASE + "motion:\n  speed_mm_s: fast\n", 9, ["motion.speed_mm_s", "valid number", "'fast'"]),
    ("quoted number", BASE + "motion:\n  speed_mm_s: '200'\n", 9, ["motion.speed_mm_s", "valid number"]),
    ("boolean for a number", BASE + "gun:\n  flow_mm3_s: true\n", 9, ["gun.flow_mm3_s", "valid number"]),
    ("not-a-number", BASE + "gun:\n  standoff_mm: .nan\n", 9, ["gun.standoff_mm", "finite"]),
    ("unknown workpiece kind", BASE.replace("kind: plate", "kind: cube"), 5, ["workpiece", "plate, cylinder, mesh".replace(", ", "', '"), "'cube'"]),
    ("workpiece without kind", BASE.replace("  kind: plate\n", ""), 5, ["workpiece", "missing key 'kind'", "plate, cylinder, mesh"]),
    ("missing curve", "name: demo\nworkpiece:\n  kind: plate\n  size_mm: [300, 200]\n", 1, ["curve", "program variant"]),
    ("key of another workpiece kind", BASE + "  radius_mm: 4\n", 8, ["workpiece.radius_mm", "unknown key"]),
    ("short vector", BASE.replace("[300, 200]", "[300]"), 7, ["workpiece.size_mm", "at least 2 items"]),
    ("unknown variant", BASE + "variants: [polysegment, spline]\n", 8, ["variants[1]", "'spline'"]),
    ("variant twice", BASE + "variants: [polysegment, polysegment]\n", 8, ["variants", "listed twice"]),
    ("bad gate operator", BASE + "gates:\n  - metric: coating.thickness_cv\n    op: '<<'\n    threshold: 0.1\n", 10, ["gates[0].op", "'<<'"]),
    ("gate with two references", BASE + "gates:\n  - metric: coating.thickness_cv\n    op: '<'\n    threshold: 0.1\n    compare_to: polyline-stop\n", 9, ["gates[0]", "exactly one of 'threshold' or 'compare_to'"]),
    ("gate metric without group", BASE + "gates:\n  - metric: thickness_cv\n    op: '<'\n    threshold: 0.1\n", 9, ["gates[0].metric", "'thickness_cv'"]),
    ("gate on a variant not run", BASE + "variants: [polysegment]\ngates:\n  - metric: coating.thickness_cv\n    op: '<'\n    compare_to: polyline-stop\n", 12, ["gates[0].compare_to", "not run"]),
    ("best of a variant not run", BASE + "variants: [polysegment, polyline-stop]\ngates:\n  - metric: coating.thickness_cv\n    op: '<'\n    compare_to: [polyline-stop, polyline-blend]\n", 12, ["gates[0].compare_to", "'polyline-blend' is not run"]),
    ("best of itself", BASE + "gates:\n  - metric: coating.thickness_cv\n    op: '<'\n    compare_to: [polyline-stop, polysegment]\n", 9, ["gates[0]", "other variants than 'polysegment'"]),
    ("best of one variant twice", BASE + "gates:\n  - metric: coating.thickness_cv\n    op: '<'\n    compare_to: [polyline-stop, polyline-stop]\n", 9, ["gates[0]", "lists a variant twice"]),
    ("best of nothing", BASE + "gates:\n  - metric: coating.thickness_cv\n    op: '<'\n    compare_to: []\n", 11, ["gates[0].compare_to", "at least one variant, got []"]),
    ("unknown built-in curve", BASE.replace("builtin: raster", "builtin: hexagon"), 3, ["curve.builtin", "'hexagon'"]),
    ("unknown built-in parameter", BASE.replace("passes: 3", "passez: 3"), 2, ["curve", "no parameter 'passez'", "passes"]),
    ("two curve sources", BASE.replace("builtin: raster", "builtin: raster\n  file: c.csv"), 2, ["curve", "exactly one of 'builtin' or 'file'"]),
    ("duplicate key", BASE + "name: again\n", 8, ["duplicate key 'name'", "line 1"]),
    ("broken YAML", BASE + "gun: [\n", 9, ["invalid YAML"]),
    ("a list, not a mapping", "- a\n- b\n", 1, ["a scenario is a mapping"]),
]


@pytest.mark.parametrize("text,line,fragments", [m[1:] for m in MALFORMED], ids=[m[0] for m in MALFORMED])
def test_malformed_scenario_names_line_and_key(tmp_path: Path, text: str, line: int, fragments: list[str]) -> None:
    message = load_error(tmp_path, text)
    assert message.startswith(f"{tmp_path / 'job.yaml'}:{line}: "), message
    for fragment in fragments:
        assert fragment in message, message


def test_empty_and_missing_files(tmp_path: Path) -> None:
    assert "empty file" in load_error(tmp_path, "")
    with pytest.raises(InputError, match="no such file"):
        load_scenario(tmp_path / "absent.yaml")
    with pytest.raises(InputError, match="is a folder"):
        load_scenario(tmp_path)


# Keys YAML 1.1 reads as booleans or null, not as strings.
YAML_WORDS = {"yes", "no", "on", "off", "true", "false", "null"}
SECTION_KEYS = {
    "gun": ["standoff_mm", "flow_mm3_s", "target_thickness_um"],
    "motion": ["speed_mm_s", "accuracy_mm", "lead_in_mm", "lead_out_mm"],
    "coating": ["spacing_mm"],
    "segmentation": ["tolerance_mm"],
}


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    section=st.sampled_from(sorted(SECTION_KEYS)),
    key=st.from_regex(r"[a-z][a-z_]{0,12}", fullmatch=True),
    padding=st.integers(0, 5),
)
def test_any_unknown_key_is_named_with_its_line(tmp_path: Path, section: str, key: str, padding: int) -> None:
    if key in Scenario.model_fields[section].annotation.model_fields or key in YAML_WORDS:
        return
    text = BASE + "#\n" * padding + f"{section}:\n  {key}: 1\n"
    message = load_error(tmp_path, text)
    where = f"{tmp_path / 'job.yaml'}:{8 + padding + 1}: "
    if not isinstance(next(iter(yaml.safe_load(f"{key}: 1"))), str):
        assert message.startswith(f"{where}key {key!r} is read by YAML as"), message  # on, no, null, ...
    else:
        assert message.startswith(f"{where}{section}.{key}: unknown key"), message


YAML11_KEYS = ["on", "off", "yes", "no", "true", "false", "On", "OFF", "Yes", "NO", "True", "FALSE"]


@pytest.mark.parametrize("key", YAML11_KEYS)
@pytest.mark.parametrize("where", ["top", "nested", "flow", "list"])
def test_keys_yaml_reads_as_booleans_are_named_at_their_line(tmp_path: Path, key: str, where: str) -> None:
    snippet, line = {
        "top": (f"{key}: 1\n", 8),
        "nested": (f"gun:\n  standoff_mm: 90\n  {key}: 2\n", 10),
        "flow": (f"motion: {{speed_mm_s: 100, {key}: 3}}\n", 8),
        "list": (f"gates:\n  - metric: motion.stops\n    op: '=='\n    threshold: 0\n  - op: '<'\n    {key}: 1\n", 13),
    }[where]
    message = load_error(tmp_path, BASE + snippet)
    value = str(next(iter(yaml.safe_load(f"{key}: 1")))).lower()
    assert message.startswith(f"{tmp_path / 'job.yaml'}:{line}: key {key!r} is read by YAML as the boolean {value}"), message
    assert f"quote it: '{key}':" in message


@pytest.mark.parametrize("key, what", [("~", "null"), ("null", "null"), ("12", "the number 12"), ("1.5", "the number 1.5")])
def test_keys_yaml_reads_as_null_or_numbers_are_named_at_their_line(tmp_path: Path, key: str, what: str) -> None:
    message = load_error(tmp_path, BASE + f"coating:\n  {key}: 1\n")
    assert message.startswith(f"{tmp_path / 'job.yaml'}:9: key {key!r} is read by YAML as {what}, not as a name"), message


def test_quoted_yaml11_words_are_ordinary_keys(tmp_path: Path) -> None:
    message = load_error(tmp_path, BASE + "gun:\n  'on': 1\n")
    assert message.startswith(f"{tmp_path / 'job.yaml'}:9: gun.on: unknown key"), message
    spec = load_scenario(write(tmp_path, BASE + "gun:\n  follow_tangent: yes\n")).spec
    assert spec.gun.follow_tangent is True  # YAML 1.1 boolean values stay as they are


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    values=st.fixed_dictionaries({
        section: st.fixed_dictionaries({k: st.floats(1e-3, 1e4, allow_nan=False) for k in keys})
        for section, keys in SECTION_KEYS.items()
    })
)
def test_valid_numbers_round_trip_exactly(tmp_path: Path, values: dict) -> None:
    data = yaml.safe_load(BASE) | values
    spec = load_scenario(write(tmp_path, yaml.safe_dump(data))).spec
    for section, fields in values.items():
        for key, value in fields.items():
            assert getattr(getattr(spec, section), key) == value


def test_json_schema_is_strict_and_lists_the_choices() -> None:
    schema = json.loads(json_schema())
    assert schema["additionalProperties"] is False
    assert all(d.get("additionalProperties") is False for d in schema["$defs"].values() if d.get("type") == "object")
    assert set(schema["required"]) == {"name"}  # and exactly one of workpiece or part (checked on loading)
    items = schema["properties"]["variants"]["items"]
    choices = items.get("anyOf") or items["oneOf"]
    assert choices[0]["enum"] == list(VARIANTS) and choices[1]["$ref"].endswith("ProgramVariantSpec")
    assert "raster" in schema["$defs"]["CurveSpec"]["properties"]["builtin"]["anyOf"][0]["enum"]


def test_shipped_scenarios_load() -> None:
    folder = Path(__file__).resolve().parents[1] / "scenarios"
    files = sorted(folder.glob("*.yaml"))
    assert files, "no shipped scenarios"
    for path in files:
        assert load_scenario(path).spec.name == path.stem


PROGRAM_VARIANT = """\
name: mine
workpiece: {kind: plate, size_mm: [300, 200]}
variants:
  - {name: mine, program: cell.as, main: trace, inputs: [1001, -1002]}
  - polysegment
  - name: split
    program: [prog.as, poses.as]
gates:
  - {metric: motion.stops, variant: mine, op: "<=", compare_to: polysegment, factor: 2}
"""


def test_program_variants(tmp_path: Path) -> None:
    spec = load_scenario(write(tmp_path, PROGRAM_VARIANT)).spec
    assert spec.curve is None and spec.variant_names == ["mine", "polysegment", "split"]
    mine, split = spec.programs
    assert mine.files == ["cell.as"] and mine.main == "trace" and mine.input_states == {1001: True, 1002: False}
    assert split.files == ["prog.as", "poses.as"] and spec.gates[0].variant == "mine"


@pytest.mark.parametrize("change,words", [
    (("{name: mine, program: cell.as, main: trace, inputs: [1001, -1002]}", "{name: polysegment, program: cell.as}"),
     "name of a built-in variant"),
    (("name: split", "name: mine"), "listed twice"),
    (("name: split", "name: 9lives"), "variants[2]"),
    (("program: [prog.as, poses.as]", "program: []"), "at least 1 item"),
    (("variant: mine", "variant: yours"), "variant 'yours' is not run"),
    (("inputs: [1001, -1002]", "inputs: [0]"), "signal 0 does not exist"),
])
def test_program_variant_errors(tmp_path: Path, change, words) -> None:
    assert words in load_error(tmp_path, PROGRAM_VARIANT.replace(*change))


def test_every_shipped_scenario_gates_the_polysegment_against_both_polylines() -> None:
    """Thickness CV and lowest speed, each against the best of the two polylines, within a small
    margin (at most 5 %); a shipped scenario at process speed closes on itself."""
    folder = Path(__file__).resolve().parents[1] / "scenarios"
    from coatsim.run.scenario_inputs import load_input_curve

    closed_at_process_speed = 0
    for path in sorted(folder.glob("*.yaml")):
        loaded = load_scenario(path)
        spec = loaded.spec
        if spec.part is not None:  # a 3-D part: docs/scenarios-3d.md says what each one gates
            assert any(g.compare_to for g in spec.gates) and spec.gates, path.name
            continue
        against = {(g.metric, g.op): g for g in spec.gates if set(g.compared) == {"polyline-stop", "polyline-blend"}}
        cv, speed = against[("coating.thickness_cv", "<=")], against[("motion.min_speed_ratio", ">=")]
        assert cv.variant == speed.variant == "polysegment", path.name
        assert 1.0 <= cv.factor <= 1.05 and 0.95 <= speed.factor <= 1.0, path.name
        if spec.curve is not None and spec.motion.speed_mm_s >= 300.0 and load_input_curve(loaded).closed:
            closed_at_process_speed += 1
    assert closed_at_process_speed >= 1


def test_a_builtin_variant_may_have_its_own_speed(tmp_path: Path) -> None:
    text = BASE + "motion: {speed_mm_s: 250}\nvariants: [polysegment, {variant: polyline-stop, speed_mm_s: 120}]\n"
    spec = load_scenario(write(tmp_path, text)).spec
    assert spec.variant_names == ["polysegment", "polyline-stop"]
    assert (spec.speed_of("polysegment"), spec.speed_of("polyline-stop")) == (250.0, 120.0)
    assert "speed_mm_s" in load_error(tmp_path, text.replace("speed_mm_s: 120", "speed_mm_s: 0"))

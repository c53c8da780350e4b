"""The hostile examples of the second hardening round, each a regression test: a one-line error
with exit 2 (or a result), never an internal error, a traceback, a hang or a memory bomb."""

from __future__ import annotations

import time

import ezdxf
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from cli_helpers import cli

SVG_HEAD = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="200mm" '
            'height="200mm" viewBox="0 0 200 200">')
RECT = '<rect x="10" y="10" width="100" height="50" fill="none" stroke="black"/>'


def _one_line(code: int, err: str, expected: tuple[int, ...] = (2,)) -> None:
    assert code in expected, err
    if code:
        assert err.count("\n") == 1 and err.startswith("coatsim: error: "), err
    assert "Traceback" not in err and "Warning:" not in err and len(err) <= 1100, err


def _svg(tmp_path, body: str):
    path = tmp_path / "d.svg"
    path.write_text(SVG_HEAD + body + "</svg>\n")
    return path


def _use_bomb(levels: int = 10, fan: int = 10) -> str:
    defs = ['<path id="a0" d="M0 0 L1 0"/>'] + [f'<g id="a{k}">' + f'<use xlink:href="#a{k - 1}"/>' * fan + "</g>"
                                               for k in range(1, levels)]
    return "<defs>" + "".join(defs) + f'</defs><use xlink:href="#a{levels - 1}"/>'


@pytest.mark.parametrize("body, words", [
    ('<g id="a"><use xlink:href="#a"/></g>', "cycle"),
    ('<g id="a"><use href="#b"/></g><g id="b"><use href="#a"/></g>', "cycle"),
    ("<g>" * 5000 + RECT + "</g>" * 5000, "drawing_depth"),
    (_use_bomb(), "drawing_entities"),
    ('<path d="M10 10 A1e-300 1e-300 0 0 1 20 10"/>', ""),
])
def test_svg_cycles_nesting_and_use_bombs_are_refused_quickly(tmp_path, body, words):
    started = time.monotonic()
    code, _, err = cli("segment", _svg(tmp_path, body), "--tol", "0.1")
    _one_line(code, err, (0, 2) if not words else (2,))
    assert words in err
    assert time.monotonic() - started < 60  # (the use bomb took past 120 s before)


def _dxf(tmp_path, build) -> str:
    doc = ezdxf.new("R2010")
    build(doc, doc.modelspace())
    path = tmp_path / "d.dxf"
    doc.saveas(path)
    return path


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "1e308", "1e400"])
def test_dxf_numbers_that_are_not_finite_or_beyond_any_drawing(tmp_path, value):
    path = _dxf(tmp_path, lambda doc, msp: msp.add_line((0, 0), (777.125, 0)))
    path.write_text(path.read_text().replace("777.125", value))
    code, _, err = cli("segment", path, "--tol", "0.1")
    _one_line(code, err)


def test_dxf_ellipse_of_ratio_zero(tmp_path):
    path = _dxf(tmp_path, lambda doc, msp: msp.add_ellipse((0, 0), (50, 0, 0), 0.625125))
    path.write_text(path.read_text().replace("0.625125", "0.0"))
    code, _, err = cli("segment", path, "--tol", "0.1")
    _one_line(code, err)
    assert "ratio" in err


def test_dxf_nested_minsert_arrays_are_counted_before_expansion(tmp_path):
    def build(doc, msp):
        doc.blocks.new("B0").add_line((0, 0), (1, 0))
        for k in range(1, 4):
            doc.blocks.new(f"B{k}").add_blockref(f"B{k - 1}", (0, 0)).grid(size=(100, 100), spacing=(1, 1))
        msp.add_blockref("B3", (0, 0)).grid(size=(100, 100), spacing=(1, 1))
    started = time.monotonic()
    code, _, err = cli("segment", _dxf(tmp_path, build), "--tol", "0.1")
    _one_line(code, err)
    assert "drawing_entities" in err and time.monotonic() - started < 60


def test_dxf_block_inserting_itself_is_named(tmp_path):
    def build(doc, msp):
        a, b = doc.blocks.new("A"), doc.blocks.new("B")
        a.add_line((0, 0), (1, 0))
        a.add_blockref("B", (0, 0))
        b.add_blockref("A", (1, 0))
        msp.add_blockref("A", (0, 0))
    code, _, err = cli("segment", _dxf(tmp_path, build), "--tol", "0.1")
    _one_line(code, err)
    assert "inserts itself" in err


def _as(tmp_path, body: str):
    path = tmp_path / "t.as"
    path.write_text(f".PROGRAM t()\n{body}\n  LMOVE TRANS(600,0,300,0,180,0)\n  LMOVE TRANS(650,0,300,0,180,0)\n.END\n")
    return path


@pytest.mark.parametrize("body", [
    "  x = " + "+".join(["1"] * 600),
    "  x = " + "(" * 3000 + "1" + ")" * 3000,
    "  x = " + "-" * 3000 + "1",
    '  $s = "ab"\n  FOR i = 1 TO 40\n    $s = $s + $s\n  END',
    '  $s = $ENCODE(/F999999999.0, 1)',
])
def test_as_expressions_and_strings_never_exhaust_the_stack_or_memory(tmp_path, body):
    code, _, err = cli("check-program", _as(tmp_path, body))
    _one_line(code, err, (0, 2, 3))


@pytest.mark.parametrize("command", ["segment", "program"])
@pytest.mark.parametrize("speed", ["1e-200", "1e308"])
def test_extreme_speeds_are_input_errors(tmp_path, command, speed):
    out = ["-o", tmp_path / "p.as"] if command == "program" else []
    code, _, err = cli(command, "builtin:ellipse:a=40,b=20", "--tol", "0.1", "--speed", speed, *out)
    _one_line(code, err)
    assert "--speed" in err


def test_a_symlink_loop_as_the_curve_file(tmp_path):
    (tmp_path / "c.csv").symlink_to(tmp_path / "c.csv")
    code, _, err = cli("segment", tmp_path / "c.csv", "--tol", "0.1")
    _one_line(code, err)


def test_json_nested_100000_deep(tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000)
    code, _, err = cli("program", path, "-o", tmp_path / "p.as")
    _one_line(code, err)


def test_a_sweep_grid_of_a_million_points_is_refused_before_it_is_built(tmp_path):
    (tmp_path / "base.yaml").write_text(
        "name: b\ncurve: {builtin: ellipse, params: {a: 40, b: 20}}\nworkpiece: {kind: plate, size_mm: [130.0, 90.0]}\n"
        "variants: [polysegment]\n")
    grid = "".join(f"  motion.{k}: [{', '.join(str(v) for v in range(1, 11))}]\n"
                   for k in ("speed_mm_s", "accuracy_mm", "lead_in_mm", "lead_out_mm"))
    grid += "  segmentation.tolerance_mm: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]\n"
    grid += "  gun.standoff_mm: [10, 20, 30, 40, 50, 60, 70, 80, 90, 100]\n"
    (tmp_path / "s.yaml").write_text(f"base: base.yaml\nfast: true\ngrid:\n{grid}")
    started = time.monotonic()
    code, _, err = cli("sweep", tmp_path / "s.yaml", "-o", tmp_path / "out", "--workers", "1")
    _one_line(code, err)
    assert "sweep points" in err and "1,000,000 needed" in err and time.monotonic() - started < 60
    assert not (tmp_path / "out").exists()


def test_progress_and_a_time_budget_bound_a_long_fit(tmp_path, monkeypatch):
    """Random points ask the fitter for one piece per point: the budget seconds stops it. The
    command's clock is set an hour back, so the test does not depend on how fast the machine is."""
    import numpy as np

    from coatsim.core import progress

    monkeypatch.setenv("COATSIM_BUDGET", "")  # the in-process command sets it: restored afterwards
    monkeypatch.setattr(progress, "_clock", [])
    monkeypatch.setattr(progress, "start_clock", lambda: progress._clock.__setitem__(
        slice(None), [time.monotonic() - 3600.0]))

    path = tmp_path / "r.csv"
    np.savetxt(path, np.random.default_rng(1).uniform(0, 100, (300, 2)), delimiter=",")
    code, _, err = cli("--budget", "seconds=1", "segment", path, "--tol", "0.1")
    _one_line(code, err)
    assert "--budget seconds=N" in err


curve_text = st.lists(st.lists(st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr), st.integers().map(str),
    st.sampled_from(["", "x", "1,5", "\u22121", "1e400", "0x1", "1_0", "nan", " ", "\"3\"", "1.2.3", "\x00"])),
    min_size=1, max_size=4), min_size=1, max_size=6)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(curve_text, st.sampled_from([",", ";", "\t", " "]))
def test_fuzz_curve_files_end_in_a_result_or_one_line(tmp_path, rows, sep):
    path = tmp_path / "fuzz.csv"
    path.write_text("\n".join(sep.join(r) for r in rows) + "\n", encoding="utf-8", errors="surrogatepass")
    code, _, err = cli("segment", path, "--tol", "0.5")
    _one_line(code, err, (0, 2))


svg_tree = st.recursive(st.sampled_from([RECT, '<use href="#a"/>', '<use href="#b"/>', '<circle r="5" cx="50" cy="50"/>']),
                        lambda inner: st.tuples(st.sampled_from(['<g>', '<g id="a">', '<g id="b">', '<svg>']),
                                                st.lists(inner, max_size=3)).map(
                            lambda t: t[0] + "".join(t[1]) + "</" + t[0][1:].split()[0].rstrip(">") + ">"),
                        max_leaves=12)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(svg_tree)
def test_fuzz_svg_structures_end_in_a_result_or_one_line(tmp_path, body):
    code, _, err = cli("segment", _svg(tmp_path, body), "--tol", "0.5")
    _one_line(code, err, (0, 2))


def test_a_mesh_vertex_beyond_the_coordinate_bound_is_refused_in_one_line(tmp_path):
    """1e308 mm overflowed the degenerate-triangle test (internal error): refused by name now."""
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1e308 0 0\nv 100 100 0\nv 0 100 0\nf 1 2 3\nf 1 3 4\n")
    code, _, err = cli("plan", tmp_path / "m.obj", "-o", tmp_path / "paths.json")
    _one_line(code, err)
    assert "from the origin" in err and not (tmp_path / "paths.json").exists()

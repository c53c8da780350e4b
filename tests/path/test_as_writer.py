"""Kawasaki AS writer: golden file, format rules, variants, arc splitting."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.languages.kawasaki_as import interpret, parse_as
from coatsim.languages.kawasaki_as.names import MAX_NAME_LENGTH, program_name
from coatsim.languages.kawasaki_as.writer import fmt, fmt_short
from coatsim.path.build import ProgramOptions, build_program, polyline_of
from coatsim.path.placement import Placement

from program_helpers import roundrect

GOLDEN = Path(__file__).parent / "data" / "roundrect_polysegment.as"
pytestmark = pytest.mark.golden


def golden_text() -> str:
    return build_program(roundrect(), Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="builtin:roundrect").text


NUMBER = re.compile(r"-?\d+\.\d+")


def same_program(found: str, expected: str) -> None:
    """The text the same everywhere but its decimal numbers, and each number within one unit of
    its last printed digit of the golden one: the poses come from sines and cosines, whose last
    bits may differ between machines and library versions (byte identity holds on one machine)."""
    assert NUMBER.split(found) == NUMBER.split(expected)
    for a, b in zip(NUMBER.findall(found), NUMBER.findall(expected)):
        unit = 10.0 ** -len(b.split(".")[1])
        assert abs(float(a) - float(b)) <= unit * (1 + 1e-6), (a, b)


def test_golden_rounded_rectangle():
    """The rounded-rectangle program against its golden file (regenerate with
    ``python tests/path/test_as_writer.py`` after an intended format change)."""
    same_program(golden_text(), GOLDEN.read_text(encoding="ascii"))


def test_deterministic_and_well_formed(rr):
    a = golden_text()
    assert a == golden_text()
    a.encode("ascii")
    assert "\r" not in a and a.endswith(".END\n")
    lines = a.split("\n")[:-1]
    body = lines[1:lines.index(".END")]
    assert lines[0] == ".PROGRAM roundrect()"
    assert all(line.startswith("  ") and not line.startswith("   ") for line in body)
    keywords = [line.split()[0] for line in body if not line.strip().startswith(";")]
    assert all(k == k.upper() for k in keywords)
    trans = lines[lines.index(".TRANS") + 1:-1]
    for row in trans:
        name, *values = row.split(" ")
        assert len(name) <= MAX_NAME_LENGTH and len(values) == 6
        assert all(re.fullmatch(r"-?\d+\.\d{8}", v) for v in values[:3])
        assert all(re.fullmatch(r"-?\d+\.\d{6}", v) for v in values[3:])


def test_program_structure_and_metadata(rr):
    text = golden_text()
    order = ["BASE NULL", "TOOL TRANS", "SPEED 500 MM/S ALWAYS", "ACCURACY 1 ALWAYS", "CP ON", "JAPPRO p0000, 50",
             "LMOVE p0000", "BREAK", "LMOVE p0001", "LMOVE p0002", "SIGNAL 1", "C1MOVE p0003", "C2MOVE p0004"]
    statements = [line.strip() for line in text.splitlines() if line.startswith("  ") and not line.strip().startswith(";")]
    assert len(statements) > len(order) and all(s.startswith(o) for s, o in zip(statements, order))
    assert [s.split(" ;")[0].strip() for s in statements[-4:]] == ["LMOVE p0014", "SIGNAL -1", "BREAK", "LDEPART 50"]
    assert sum(s.startswith("C1MOVE") for s in statements) == 4
    assert sum(s.startswith("C2MOVE") for s in statements) == 4
    meta = dict(re.findall(r"; coatsim: (\w+)=(.*)", text))
    for key in ("lead_in_mm", "lead_out_mm", "curve_length_mm", "variant", "tolerance_mm", "standoff_mm"):
        assert key in meta
    assert float(meta["curve_length_mm"]) == pytest.approx(rr.length, abs=1e-6)
    assert meta["variant"] == "polysegment" and meta["n_arcs"] == "4" and meta["sprayed"] == "curve"


def test_arcs_above_the_sweep_limit_are_split():
    circle = Polysegment(chain((0.0, 0.0), 0.0, [0.02], [2 * math.pi * 50.0]), closed=True)
    text = build_program(circle, Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="circle").text
    assert text.count("C1MOVE") == 3 and text.count("C2MOVE") == 3
    quarter = Polysegment(chain((0.0, 0.0), 0.0, [0.02], [math.radians(170.0) * 50.0]))
    assert build_program(quarter, Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="q").text.count("C1MOVE") == 1


def test_arc_flatter_than_the_pose_resolution_becomes_a_line():
    # Sagitta 1e-9 mm: the rounded via point lies on the chord.
    flat = Polysegment(chain((0.0, 0.0), 0.0, [1e-11], [20.0]))
    text = build_program(flat, Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="flat").text
    assert "C1MOVE" not in text
    interpret(parse_as(text))


def test_polyline_variants(rr):
    pts = rr.sample(0.5)[0]
    stop = build_program(rr, Placement(), ProgramOptions(variant="polyline-stop"), language=KAWASAKI_AS, tolerance_mm=0.1,
                         source="rr", points=pts)
    blend = build_program(rr, Placement(), ProgramOptions(variant="polyline-blend", accuracy_mm=2.0),
                          language=KAWASAKI_AS, tolerance_mm=0.1, source="rr", points=pts)
    assert "CP OFF" in stop.text and "CP ON" not in stop.text
    assert "CP ON" in blend.text and "ACCURACY 2 ALWAYS" in blend.text
    for built in (stop, blend):
        assert "C1MOVE" not in built.text
        n_vertices = built.curve.n_segments
        assert built.text.count("\n  LMOVE p") == n_vertices + 1 + 2   # down, lead-in, lead-out
    tp = interpret(parse_as(stop.text))
    assert all(m.settings.stop_at_end for m in tp.moves)
    assert not any(m.settings.stop_at_end for m in interpret(parse_as(blend.text)).spray_moves[:-1])


def test_polyline_stays_within_tolerance(rr):
    pts = rr.sample(0.2)[0]
    for tol in (0.01, 0.1, 1.0):
        poly = polyline_of(pts, True, tol)
        verts = np.array([s.start for s in poly.segments])
        # distance of every input point to the polyline
        d = np.full(len(pts), np.inf)
        for a, b in zip(verts, np.roll(verts, -1, axis=0)):
            ab = b - a
            u = np.clip((pts - a) @ ab / (ab @ ab), 0, 1)
            d = np.minimum(d, np.linalg.norm(pts - (a + u[:, None] * ab), axis=1))
        assert d.max() <= tol
        assert poly.closed and poly.end == poly.start


def test_number_formatting():
    assert fmt(-0.00000001, 4) == "0.0000"
    assert fmt(-1.23456, 2) == "-1.23"
    assert fmt_short(50.0) == "50" and fmt_short(0.5) == "0.5" and fmt_short(-0.0) == "0"


@pytest.mark.parametrize("text,name", [("roundrect", "roundrect"), ("NACA 0012", "naca_0012"),
                                        ("0spiral", "c0spiral"), ("a-very-long-curve-name-indeed", "a_very_long_cur"),
                                        ("", "c"), ("___", "c")])
def test_program_names(text, name):
    assert program_name(text) == name
    assert len(program_name(text)) <= MAX_NAME_LENGTH


if __name__ == "__main__":
    GOLDEN.write_text(golden_text(), encoding="ascii")


@pytest.mark.parametrize("n_teeth", [8, 40])
def test_a_header_field_longer_than_a_comment_is_written_whole(n_teeth):
    """A curve with many corners has a long ``speed_limits`` field; it was cut at 200 characters
    like a comment, and the program's own reader refused '4...' (a scenario with a zigzag)."""
    from coatsim.geometry.primitives import Line
    from coatsim.path.process_record import SPEED_LIMITS_KEY as HEADER_KEY, parse_limits

    pts = [(10.0 * i, 20.0 * (i % 2)) for i in range(n_teeth + 1)]
    poly = Polysegment(tuple(Line(a, b) for a, b in zip(pts, pts[1:])), corners=frozenset(range(n_teeth - 1)))
    text = build_program(poly, Placement(), ProgramOptions(), language=KAWASAKI_AS, tolerance_mm=0.1, source="zigzag").text
    (raw,) = re.findall(rf"; coatsim: {HEADER_KEY}=(.*)", text)
    limits = parse_limits(raw, "zigzag")
    assert len(limits) == n_teeth - 1 and all(lim.v_max_mm_s == 0.0 for lim in limits)
    assert interpret(parse_as(text)).process.contours[0].speed_limits == limits

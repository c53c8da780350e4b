"""coatsim convert keeps the arcs a program already has and never rewrites it for nothing: a
circle taught as a few circular moves comes back exact in no more arcs, and a program the arcs
cannot shorten is not written at all, in every language."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.languages.registry import LANGUAGES, language
from coatsim.path.convert import ConvertOptions, convert_program
from coatsim.path.edit import EditsInPlace
from coatsim.path.language import ReadOptions
from coatsim.path.process_path import spray_runs
from coatsim.path.toolpath import CircularMove

from language_plans import planned

TOL = 0.5


def _as_circle(centre: np.ndarray, radius: float, e1: np.ndarray, e2: np.ndarray, n_arcs: int, lead: int) -> str:
    """An AS program spraying ``lead`` short LMOVEs along a tangent, then the circle they reach
    taught as ``n_arcs`` C1MOVE/C2MOVE pairs (poses to 1e-8 mm)."""
    at = lambda a: centre + radius * (math.cos(a) * e1 + math.sin(a) * e2)  # noqa: E731
    start = at(0.0)
    poses = [("s0", start - 10.0 * lead * e2)] + [(f"s{k}", start - 10.0 * (lead - k) * e2) for k in range(1, lead)]
    poses.append(("c0", start))
    body = [f"  LMOVE s{k}" for k in range(1, lead)] + ["  LMOVE c0"]
    for k in range(n_arcs):
        a, b = 2 * math.pi * k / n_arcs, 2 * math.pi * (k + 1) / n_arcs
        poses += [(f"v{k}", at((a + b) / 2))] + ([(f"c{k + 1}", at(b))] if k + 1 < n_arcs else [])
        body += [f"  C1MOVE v{k}", f"  C2MOVE c{(k + 1) % n_arcs}"]
    trans = "".join(f"{name} {p[0]:.8f} {p[1]:.8f} {p[2]:.8f} 0 180 0\n" for name, p in poses)
    return (".PROGRAM circ()\n  SPEED 200 MM/S ALWAYS\n  JMOVE s0\n  BREAK\n  SIGNAL 1\n" + "\n".join(body)
            + "\n  BREAK\n  SIGNAL -1\n.END\n.TRANS\n" + trans + ".END\n")


def _sprayed(conversion, name: str, tmp_path, suffix: str = ".as"):
    """The sprayed moves of the program ``conversion`` wrote, read back."""
    lang = language(name)
    paths = []
    for k, (sfx, text) in enumerate(lang.files(conversion.text) if conversion.replaces is None
                                    else ((suffix, conversion.text),)):
        paths.append(tmp_path / f"converted{sfx}")
        paths[-1].write_text(text)
    tp = lang.read(paths[:1] if len(paths) == 1 else paths, ReadOptions())
    return [tp.moves[i] for run in spray_runs(tp) for i in run]


def _standalone(lang) -> bool:
    """Whether convert writes ``lang`` standalone only (it does not edit it in place)."""
    return not isinstance(lang, EditsInPlace)


unit = st.floats(-1.0, 1.0, allow_nan=False)


@settings(max_examples=8, deadline=None)
@given(centre=st.tuples(st.floats(500, 800), st.floats(-200, 200), st.floats(200, 500)),
       radius=st.floats(20.0, 200.0), axis=st.tuples(unit, unit, unit), n_arcs=st.sampled_from([2, 3]))
def test_a_taught_circle_comes_back_exact_in_no_more_arcs(tmp_path_factory, centre, radius, axis, n_arcs):
    normal = np.array(axis) + np.array([0.0, 0.0, 2.0])  # tilted up to ~30 deg: the gun still points at it
    normal /= np.linalg.norm(normal)
    e1 = np.cross(normal, [0.0, 1.0, 0.0] if abs(normal[1]) < 0.9 else [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    tmp_path = tmp_path_factory.mktemp("circle")
    src = tmp_path / "circle.as"
    src.write_text(_as_circle(np.array(centre), radius, e1, e2, n_arcs, lead=12))
    result = convert_program(src, ConvertOptions(TOL), language=language("kawasaki-as"))
    (report,) = result.paths
    assert result.written and report.moves_after == 1 + n_arcs  # the 12 LMOVEs one line, the circle as taught
    assert report.deviation_mm < 1e-6 * radius
    arcs = [m for m in _sprayed(result, "kawasaki-as", tmp_path) if isinstance(m, CircularMove)]
    assert len(arcs) <= n_arcs


def _lead_and_circle(n_arcs: int) -> Polysegment:
    """A straight lead of 10 pieces, then a full circle of radius 40 in ``n_arcs`` arcs."""
    return Polysegment(chain((0.0, 0.0), 0.0, [0.0] * 10 + [1 / 40.0] * n_arcs,
                             [6.0] * 10 + [2 * math.pi * 40.0 / n_arcs] * n_arcs))


@pytest.mark.parametrize("name", sorted(LANGUAGES))
def test_every_language_keeps_its_circular_moves(tmp_path, name):
    lang = language(name)
    text = planned(name, [_lead_and_circle(3)]).text
    paths = []
    for sfx, body in lang.files(text):
        paths.append(tmp_path / f"prog{sfx}")
        paths[-1].write_text(body)
    before = lang.reading(paths, ReadOptions()).toolpath
    n_in = sum(isinstance(m, CircularMove) for m in before.moves)
    result = convert_program(paths, ConvertOptions(TOL, standalone=_standalone(lang)), language=lang)
    (report,) = result.paths
    assert result.written and report.moves_after <= report.moves_before - 9 and report.deviation_mm <= TOL
    after = _sprayed(result, name, tmp_path, lang.suffixes[0])
    assert sum(isinstance(m, CircularMove) for m in after) <= n_in


RAPID_CIRCLE = """MODULE Ring
  PERS tooldata tGun := [TRUE,[[0,0,150],[1,0,0,0]],[2,[0,0,100],[1,0,0,0],0,0,0]];
  PROC main()
    MoveJ [[650,0,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v1000, fine, tGun;
    SetDO do1, 1;
    MoveC [[600,50,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], [[550,0,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v200, z1, tGun;
    MoveC [[600,-50,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], [[650,0,300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v200, fine, tGun;
    SetDO do1, 0;
  ENDPROC
ENDMODULE
"""
GCODE_CIRCLE = "%\n(ring)\nG21 G90 G17\nG0 X50 Y0 Z10\nG1 Z0 F600\nM3\nG3 X50 Y0 I-50 J0\nM5\nG0 Z10\nM2\n%\n"
AS_CIRCLE = (".PROGRAM circ()\n  SPEED 200 MM/S ALWAYS\n  JMOVE c0\n  BREAK\n  SIGNAL 1\n  C1MOVE c1\n  C2MOVE c2\n"
             "  C1MOVE c3\n  C2MOVE c0\n  BREAK\n  SIGNAL -1\n.END\n.TRANS\nc0 750 0 300 0 180 0\n"
             "c1 700 50 300 0 180 0\nc2 650 0 300 0 180 0\nc3 700 -50 300 0 180 0\n.END\n")


@pytest.mark.parametrize("name,suffix,text", [("kawasaki-as", ".as", AS_CIRCLE), ("abb-rapid", ".mod", RAPID_CIRCLE),
                                              ("gcode", ".nc", GCODE_CIRCLE)])
def test_a_hand_taught_circle_is_not_rewritten(tmp_path, run_cli, name, suffix, text):
    src = tmp_path / f"ring{suffix}"
    src.write_text(text)
    standalone = _standalone(language(name))
    result = convert_program(src, ConvertOptions(TOL, standalone=standalone), language=language(name))
    (report,) = result.paths
    assert not result.written and report.kept and report.moves_after == report.moves_before == 2
    out = tmp_path / f"out{suffix}"
    flags = ["--standalone"] if standalone else []
    code, stdout, stderr = run_cli(["convert", str(src), "--tol", str(TOL), *flags, "-o", str(out)])
    assert code == 0 and not out.exists() and src.read_text() == text
    assert "nothing gained: no program written" in stdout

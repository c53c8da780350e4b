"""RAPID and KRL as written: an independent mini-parser in this test (not the product's reader)
finds the plan's path and poses in the text; any bytes give a result or a one-line InputError;
the twin runs each program along the AS program of the same plan within the blending."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from scipy.spatial.transform import Rotation

from coatsim.core.errors import CoatsimError
from coatsim.languages.registry import language
from coatsim.path.build import ProgramOptions
from coatsim.path.language import ReadOptions
from coatsim.path.part_program import build_part_program
from coatsim.path.placement import Placement, centering_offset
from coatsim.path.program_files import program_suffixes, write_program

from program_helpers import roundrect

NUM = r"-?\d+(?:\.\d+)?(?:E[+-]?\d+)?"


def _plan(name: str, variant: str = "polysegment"):
    curve = roundrect()
    placement = Placement(lead_in_mm=20.0, lead_out_mm=15.0, offset_xy=centering_offset(curve))
    return build_part_program([curve], placement, ProgramOptions(variant=variant, speed_mm_s=300.0, accuracy_mm=0.5),
                              tolerance_mm=0.1, source="rr", language=language(name))


def _plan_points(built) -> list[np.ndarray]:
    """Every line end, arc via and arc end of the plan, in the order written, base frame."""
    out = []
    for path in built.plan.paths:
        for seg in path.segments:
            if seg.is_arc:
                for piece in seg.split(math.radians(170.0)):
                    out += [piece.via, piece.end]
            else:
                out.append(seg.end)
    return out


def _rapid_points(text: str):
    """Mini-parser: the robtargets named by MoveL/MoveC in PROC main, with the wobj's uframe."""
    targets = {m[0]: m[1:] for m in re.findall(
        rf"CONST robtarget (\w+) := \[\[({NUM}),({NUM}),({NUM})\],\[({NUM}),({NUM}),({NUM}),({NUM})\]", text)}
    w = re.search(rf'wobjdata \w+ := \[FALSE,TRUE,"",\[\[({NUM}),({NUM}),({NUM})\],\[({NUM}),({NUM}),({NUM}),({NUM})\]\]',
                  text).groups()
    frame_r = Rotation.from_quat([float(w[4]), float(w[5]), float(w[6]), float(w[3])])
    body = text.split("PROC main()")[1]
    names = []
    for kind, args in re.findall(r"^\s*(MoveL|MoveC) ([^;]*);", body, re.MULTILINE):
        parts = [p.strip() for p in args.split(",")]
        names += parts[:2] if kind == "MoveC" else parts[:1]
    poses = []
    for name in names:
        if name.startswith("RelTool"):
            continue
        x, y, z, q1, q2, q3, q4 = (float(v) for v in targets[name])
        position = frame_r.apply([x, y, z]) + np.array([float(v) for v in w[:3]])
        rotation = (frame_r * Rotation.from_quat([q2, q3, q4, q1])).as_matrix()
        poses.append((position, rotation, q1))
    return poses


def _krl_points(text: str):
    """Mini-parser: the E6POS of the .dat named by LIN/CIRC, in $BASE (A-B-C: Rz Ry Rx)."""
    def frame(m):
        x, y, z, a, b, c = (float(v) for v in m)
        return np.array([x, y, z]), Rotation.from_euler("ZYX", [a, b, c], degrees=True)

    data = {m[0]: frame(m[1:]) for m in re.findall(
        rf"DECL E6POS (\w+)=\{{X ({NUM}),Y ({NUM}),Z ({NUM}),A ({NUM}),B ({NUM}),C ({NUM})", text)}
    base_t, base_r = frame(re.search(rf"\$BASE=\{{X ({NUM}),Y ({NUM}),Z ({NUM}),A ({NUM}),B ({NUM}),C ({NUM})\}}",
                                     text).groups())
    names = []
    for kind, args in re.findall(r"^\s*(LIN|CIRC) ([^;\n]*?)(?: C_DIS)?\s*(?:;.*)?$", text, re.MULTILINE):
        parts = [p.strip() for p in re.sub(r"\{[^}]*\}", "", args).split(",")]
        names += [p for p in parts if ":" not in p]
    poses = []
    for name in names:
        t, r = data[name]
        poses.append((base_r.apply(t) + base_t, (base_r * r).as_matrix(), 1.0))
    return poses


@pytest.mark.parametrize("name, mini", [("abb-rapid", _rapid_points), ("kuka-krl", _krl_points)])
def test_a_parser_written_here_finds_the_plan(name, mini):
    built = _plan(name)
    found = mini(built.text)
    # the mini-parser sees the stand-off point first (MoveL/LIN down), then the path's moves
    planned = _plan_points(built)
    assert len(found) == len(planned) + 1
    for (position, rotation, q1), pose in zip(found[1:], planned):
        assert np.allclose(position, pose.translation_mm, atol=1e-6)
        assert np.allclose(rotation, pose.rotation, atol=1e-6)
        assert q1 >= 0.0


@pytest.mark.parametrize("name", ["abb-rapid", "kuka-krl"])
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_any_bytes_or_mixes_give_a_result_or_one_line(name, data, tmp_path_factory):
    lang = language(name)
    words = (["MODULE m", "PROC main()", "MoveL", "MoveC", "p10", ",", ";", "v500", "z10", "fine", "tool0", "\\WObj:=",
              "[", "]", "{", "}", "ENDPROC", "ENDMODULE", "IF", "THEN", "ENDIF", "FOR", "i", "FROM", "TO", "DO",
              "ENDFOR", "SetDO", "do1", "1", "Offs(", ")", ":=", "\n", "!", "%%%"] if name == "abb-rapid" else
             ["DEF p( )", "END", "DEFDAT p", "ENDDAT", "LIN", "CIRC", "PTP", "{X 1,Y 2}", "C_DIS", "$OUT[1]=TRUE",
              "$VEL.CP=", "0.2", "IF", "THEN", "ENDIF", "FOR", "i", "=", "TO", "ENDFOR", "DECL", "E6POS", "P1", ":",
              "\n", ";FOLD", "BAS(#INITMOV,0)", "TRIGGER WHEN DISTANCE=0 DELAY=0 DO", "GOTO", "x"])
    raw = data.draw(st.one_of(st.binary(max_size=300),
                              st.lists(st.sampled_from(words), max_size=60).map(lambda w: " ".join(w).encode())))
    path = tmp_path_factory.mktemp("fuzz") / f"p{lang.suffixes[0]}"
    path.write_bytes(raw)
    try:
        lang.reading([path], ReadOptions())
    except CoatsimError as exc:
        assert "\n" not in str(exc)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["abb-rapid", "kuka-krl"])
def test_the_twin_runs_each_language_as_the_as_program(name, tmp_path):
    """The same plan in AS and in each language: the same sprayed path, within the blend."""
    from coatsim.robot.cell import load_cell
    from coatsim.robot.execute import execute
    from coatsim.robot.kinematics import CellKinematics

    cell = load_cell()
    runs = {}
    for lang_name in ("kawasaki-as", name):
        lang = language(lang_name)
        built = _plan(lang_name)
        paths = write_program(lang, built.text, tmp_path / f"{lang_name}{program_suffixes(lang)[0]}")
        toolpath = lang.read(list(paths), ReadOptions(kinematics=CellKinematics(cell)))
        runs[lang_name] = execute(toolpath, cell, step_mm=1.0).log
    a, b = runs["kawasaki-as"], runs[name]
    sa = np.asarray(a.spray, bool)
    sb = np.asarray(b.spray, bool)
    pa, pb = np.asarray(a.position)[sa], np.asarray(b.position)[sb]
    from scipy.spatial import cKDTree

    assert cKDTree(pa).query(pb)[0].max() < 0.5 + 1e-3  # the blend zone is 0.5 mm
    assert abs(len(pa) - len(pb)) <= 0.02 * len(pa)

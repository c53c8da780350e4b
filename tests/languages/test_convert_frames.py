"""``convert`` keeps the user frame a program gives its poses in: a URScript program whose
waypoints are ``pose_trans(Plane_1, p[…])`` (a Polyscope feature, tilted and turned) becomes a
program in each language whose frame (wobjdata, $BASE, UFRAME, the UR ``frame``) is that feature,
and whose TCP path in the robot base is where the original's is: the same as converting the same
path written in base coordinates, within 1e-6 mm."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import rot_x, rot_z
from coatsim.languages.registry import language
from coatsim.languages.urscript.values import PoseValue
from coatsim.path.convert import ConvertOptions, convert_program
from coatsim.path.language import ReadOptions

FEATURE = Pose(rot_z(math.radians(30.0)) @ rot_x(math.radians(10.0)), np.array([450.0, -120.0, 300.0]))
DOWN = rot_x(math.pi)
# a stroke, a quarter circle of 60 mm as 12 chords, a stroke: in the feature's x-y plane (mm)
CURVE = [(0.0, 0.0), (40.0, 0.0)] + [(40.0 + 60.0 * math.sin(t), 60.0 - 60.0 * math.cos(t))
                                     for t in np.linspace(0.0, math.pi / 2, 13)[1:]] + [(100.0, 160.0)]
# a raster of straight strokes, each written as 10 mm steps, turning at true corners
CORNERS = [(0.0, 0.0), (100.0, 0.0), (100.0, 20.0), (0.0, 20.0), (0.0, 40.0), (100.0, 40.0)]
RASTER = [CORNERS[0]] + [tuple(np.array(a) + (np.array(b) - np.array(a)) * k / n)
                         for a, b in zip(CORNERS, CORNERS[1:])
                         for n in [int(round(math.dist(a, b) / 10.0))] for k in range(1, n + 1)]


def _literal(pose: Pose) -> str:
    return "p[" + ", ".join(f"{v:.12f}" for v in PoseValue.of(pose)) + "]"


def _script(in_feature: bool, points=CURVE) -> str:
    """The program, its waypoints relative to the feature or (False) the same in base coordinates."""
    def target(x: float, y: float, z: float) -> str:
        local = Pose(DOWN, np.array([x, y, z]))
        return f"pose_trans(Plane_1, {_literal(local)})" if in_feature else _literal(FEATURE @ local)

    lines = ["def coat():", "  set_tcp(p[0, 0, 0.25, 0, 0, 0])", f"  Plane_1 = {_literal(FEATURE)}",
             f"  movej({target(0, 0, 50)})", f"  movel({target(0, 0, 0)}, v=0.1)", "  set_digital_out(1, True)"]
    lines += [f"  movel({target(x, y, 0)}, v=0.1, r=0.0005)" for x, y in points[1:]]
    lines += ["  set_digital_out(1, False)", f"  movel({target(*points[-1], 50)}, v=0.1)", "end"]
    return "\n".join(lines) + "\n"


def _convert(tmp_path, in_feature: bool, to: str, points=CURVE):
    source = tmp_path / f"{'feature' if in_feature else 'base'}-{len(points)}.script"
    source.write_text(_script(in_feature, points))
    conversion = convert_program([source], ConvertOptions(tolerance_mm=0.2, standalone=True),
                                 language=language("urscript"), target=language(to))
    folder = tmp_path / f"{to}-{in_feature}-{len(points)}"
    folder.mkdir()
    files = []
    for suffix, text in language(to).files(conversion.text):
        files.append(folder / f"coat{suffix}")
        files[-1].write_text(text)
    return conversion, language(to).reading(files, ReadOptions())


def _ends(reading) -> np.ndarray:
    return np.array([(getattr(m, "end", None) or m.target).translation_mm for m in reading.toolpath.moves])


def test_the_reading_gives_each_move_the_feature_it_is_written_in(tmp_path):
    source = tmp_path / "feature.script"
    source.write_text(_script(True))
    reading = language("urscript").reading([source], ReadOptions())
    for frame in reading.move_frames:
        assert np.allclose(frame.as_matrix4(), FEATURE.as_matrix4(), atol=1e-9)
    base = tmp_path / "base.script"
    base.write_text(_script(False))
    assert all(np.allclose(f.as_matrix4(), np.eye(4)) for f in language("urscript").reading([base], ReadOptions()).move_frames)


LANGUAGES = ["urscript", "abb-rapid", "kuka-krl", "fanuc-tp"]


@pytest.mark.parametrize("to", LANGUAGES)
def test_convert_keeps_the_feature_as_the_frame_within_the_tolerance(tmp_path, to):
    conversion, converted = _convert(tmp_path, True, to)
    sprayed = [k for k, m in enumerate(converted.toolpath.moves) if m.spray]
    for k in sprayed:
        assert np.allclose(converted.move_frames[k].as_matrix4(), FEATURE.as_matrix4(), atol=1e-6)
    assert conversion.paths[0].n_arcs >= 1 and conversion.paths[0].deviation_mm <= 0.2
    ends = _ends(converted)
    assert np.linalg.norm(converted.toolpath.moves[sprayed[0]].start.translation_mm - FEATURE.translation_mm) < 1e-6
    assert np.linalg.norm(ends[sprayed[-1]] - FEATURE.apply(np.array([100.0, 160.0, 0.0]))) < 1e-6


@pytest.mark.parametrize("to", LANGUAGES)
def test_a_converted_raster_keeps_its_corners_in_the_base_within_a_micrometre(tmp_path, to):
    _, converted = _convert(tmp_path, True, to, RASTER)
    sprayed = [m for m in converted.toolpath.moves if m.spray]
    path = [sprayed[0].start.translation_mm] + [m.end.translation_mm for m in sprayed]
    corners = FEATURE.apply(np.array([(x, y, 0.0) for x, y in CORNERS]))
    assert len(path) == len(corners) and np.abs(np.array(path) - corners).max() < 1e-6
    _, from_base = _convert(tmp_path, False, to, RASTER)
    # the same moves as converted from base coordinates, which Fanuc's /POS holds to 3 decimals
    rounding = 0.5e-3 * math.sqrt(3) if to == "fanuc-tp" else 1e-6
    assert np.abs(_ends(converted) - _ends(from_base)).max() < rounding


RAPID_LAL = ("MODULE LAL\n  PERS tooldata tGun:=[TRUE,[[0,0,250],[1,0,0,0]],[1,[0,0,1],[1,0,0,0],0,0,0]];\n"
             + "".join(f"  CONST robtarget {n}:=[[{x},{y},300],[0,0,1,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
                       for n, x, y in (("a", 600, -50), ("b", 800, -50), ("c", 850, 0), ("d", 800, 50), ("e", 600, 50)))
             + "  PROC main()\n    MoveJ Offs(a,0,0,50),v300,fine,tGun;\n    MoveL a,v300,fine,tGun;\n"
             "    SetDO do1,1;\n    MoveL b,v300,z1,tGun;\n    MoveC c,d,v300,z1,tGun;\n    MoveL e,v300,fine,tGun;\n"
             "    SetDO do1,0;\n  ENDPROC\nENDMODULE\n")


@pytest.mark.parametrize("to", ["abb-rapid", "kawasaki-as"])
def test_an_exact_line_beside_an_arc_is_written_as_a_line_not_a_flat_circle(tmp_path, to):
    """A line, a half circle and a line: the taught lines come back as lines (a fitted arc turning
    less than a degree is written as its chord where the tolerance allows), never as circles
    through three nearly collinear points, which a controller refuses."""
    source = tmp_path / "lal.mod"
    source.write_text(RAPID_LAL)
    conversion = convert_program([source], ConvertOptions(tolerance_mm=0.1, standalone=True),
                                 language=language("abb-rapid"), target=language(to))
    if to == "abb-rapid":  # three moves, no fewer as arcs: nothing gained in its own language, nothing written
        assert not conversion.written and conversion.paths[0].kept
        return
    folder = tmp_path / to
    folder.mkdir()
    files = []
    for suffix, text in language(to).files(conversion.text):
        files.append(folder / f"coat{suffix}")
        files[-1].write_text(text)
    moves = [m for m in language(to).reading(files, ReadOptions()).toolpath.moves if m.spray]
    for m in moves:
        if m.kind == "arc":
            a, v, b = (np.asarray(p.translation_mm) for p in (m.start, m.via, m.end))
            chord = b - a
            off = np.linalg.norm(np.cross(chord, v - a)) / np.linalg.norm(chord)
            assert off > 1.0, f"a circle through nearly collinear points (via {off:.4f} mm off the chord)"
    lines = [m for m in moves if m.kind == "line"]
    assert len(lines) == 2 and all(abs(np.linalg.norm(m.end.translation_mm - m.start.translation_mm) - 200) < 0.2
                                   for m in lines)
    # its own three moves are the fewest: written move for move, the taught half circle kept exact
    assert any("written move for move" in n for n in conversion.notes)

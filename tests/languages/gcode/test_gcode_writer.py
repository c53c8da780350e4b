"""The G-code writer, checked by a small G-code reader written here (not the product's): the
written moves are the plan's path (points within 1e-3 mm, ends within the 4 decimals written),
arcs in G17/G18/G19 are G2/G3, other arcs lines, a tilted gun is refused."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.primitives import Arc3, Line3
from coatsim.geometry.space.rotations import rot_x, rot_y, rot_z
from coatsim.languages.gcode.gun import GunCodes
from coatsim.languages.gcode.language import GCODE, GCode
from coatsim.path.placement import PlacedMove, PlacedPath, placed_line
from coatsim.path.plan import ProgramPlan
from coatsim.path.process import ProcessInfo
from coatsim.geometry.space.xyzoat import pose_from_xyzoat

from language_plans import arc_spiral, distance_to_plan, planned, roundrect, sprayed_points

WORD = re.compile(r"([A-Z])([-+]?(?:\d+\.?\d*|\.\d+))")


def mini_read(text: str, gun_on: str = "M3", gun_off: str = "M5"):
    """(primitive, sprayed) of every feed move of a program coatsim wrote, in the base frame."""
    offset, turn = np.zeros(3), 0.0
    here, mode, plane, spray, out = None, None, 17, False, []
    for raw in text.splitlines():
        code = re.sub(r"\([^)]*\)", "", raw).split(";")[0].upper().replace(" ", "")
        words = WORD.findall(code)
        g = [float(v) for k, v in words if k == "G"]
        m = [f"M{int(float(v))}" for k, v in words if k == "M"]
        vals = {k: float(v) for k, v in words if k not in "GM"}
        if 10.0 in g:
            offset, turn = np.array([vals["X"], vals["Y"], vals["Z"]]), math.radians(vals.get("R", 0.0))
            continue
        spray = True if gun_on in m else False if gun_off in m else spray
        mode = next((x for x in g if x in (0.0, 1.0, 2.0, 3.0)), mode)
        plane = next((int(x) for x in g if x in (17.0, 18.0, 19.0)), plane)
        if not any(k in vals for k in "XYZ"):
            continue
        local_here = None if here is None else rot_z(-turn) @ (here - offset)
        target = np.array([vals.get(a, local_here[i] if local_here is not None else 0.0) for i, a in enumerate("XYZ")])
        end = offset + rot_z(turn) @ target
        if mode in (1.0,) and here is not None:
            out.append((Line3(here, end), spray))
        elif mode in (2.0, 3.0):
            axis = {17: 2, 18: 1, 19: 0}[plane]
            centre = local_here + np.array([vals.get(a, 0.0) for a in "IJK"])
            r = float(np.linalg.norm(local_here - centre))
            u, v = local_here - centre, target - centre
            normal = np.zeros(3)
            normal[axis] = 1.0 if mode == 3.0 else -1.0
            sweep = math.atan2(np.cross(u, v) @ normal, u @ v) % (2 * math.pi)
            out.append((Arc3(here, end, offset + rot_z(turn) @ centre, rot_z(turn) @ normal, r, sweep), spray))
        here = end
    return out


@pytest.mark.parametrize("contour", ["roundrect", "spiral"])
@pytest.mark.parametrize("frame", ["default", "turned"])
def test_the_written_moves_are_the_plans_path(contour, frame):
    curve = roundrect() if contour == "roundrect" else arc_spiral()
    place = {"frame": pose_from_xyzoat((650.0, -40.0, 180.0, 30.0, 0.0, 0.0))} if frame == "turned" else {}
    built = planned("gcode", [curve], **place)
    moves = mini_read(built.text)
    sprayed = [prim for prim, on in moves if on]
    assert distance_to_plan(sprayed_points(sprayed), built.plan.paths) < 1e-3
    plan_ends = np.array([s.geometry.end for s in built.plan.paths[0].segments])
    for e in plan_ends:  # every junction of the curve is the end of a written move
        assert np.linalg.norm(np.array([p.end for p, _ in moves]) - e, axis=1).min() < 1e-4
    curve_length = built.plan.paths[0].curve_length_mm
    leads = 0.0 if curve.closed else 35.0
    assert sum(p.length for p in sprayed) == pytest.approx(curve_length + leads, abs=2e-3)
    assert ("G3" in built.text or "G2" in built.text) and "G64 P0.5" in built.text and "G21" in built.text


def test_the_polyline_stop_variant_is_an_exact_stop_program():
    built = planned("gcode", variant="polyline-stop")
    assert "G61 (exact stop" in built.text and "G64" not in built.text and "G2 " not in built.text
    assert all(isinstance(p, Line3) for p, _ in mini_read(built.text))


def _plan(segments, frame=None, name="VERT"):
    path = PlacedPath(tuple(segments), np.array([0.0, 0.0, 1.0]), 100.0, 0.0, 0.0,
                      float(sum(s.length for s in segments)))
    return ProgramPlan(name, (path,), 200.0, 0.5, False, 50.0, 1, Pose.identity(), ProcessInfo(frame=frame))


def _down(point):
    return Pose(rot_y(math.pi), np.asarray(point, float))


def test_vertical_arcs_are_g18_g19_and_a_slanted_one_becomes_lines():
    a, b, c = np.array([700.0, 0, 300]), np.array([720.0, 0, 320]), np.array([720.0, 20, 340])
    about_y = Arc3(a, b, np.array([720.0, 0, 300]), np.array([0.0, 1.0, 0.0]), 20.0, math.pi / 2)
    about_x = Arc3(b, c, np.array([720.0, 0, 340]), np.array([1.0, 0.0, 0.0]), 20.0, math.pi / 2)
    slant_normal = np.array([1.0, 1.0, 1.0]) / math.sqrt(3)
    radial = np.cross(slant_normal, [0, 0, 1.0])
    radial *= 15.0 / np.linalg.norm(radial)
    slant = Arc3(c, c, c - radial, slant_normal, 15.0, math.pi / 2)
    slant = Arc3(c, slant.at_angles(np.array([math.pi / 2]))[0], c - radial, slant_normal, 15.0, math.pi / 2)
    segs = [PlacedMove(arc, _down(arc.start), _down(arc.end)) for arc in (about_y, about_x, slant)]
    text = GCODE.write(_plan(segs))
    assert "G18 G3" in text and "G19 G3" in text
    assert "arc outside G17/G18/G19 as" in text
    moves = mini_read(text)
    points = sprayed_points([p for p, on in moves if on])
    assert distance_to_plan(points, _plan(segs).paths) < 0.011  # chords within 0.01 mm (+ the written digits)


def test_a_tilted_gun_is_refused():
    tilted = Pose(rot_x(0.3) @ rot_y(math.pi), np.array([700.0, 0, 300]))
    seg = PlacedMove(Line3(tilted.translation_mm, tilted.translation_mm + [10, 0, 0]), tilted,
                     Pose(tilted.rotation, tilted.translation_mm + [10, 0, 0]))
    with pytest.raises(InputError, match=r"G-code has no tool orientation.*tilts it by 17.2 deg"):
        GCODE.write(_plan([seg]))
    with pytest.raises(InputError, match="tilts it"):
        planned("gcode", frame=pose_from_xyzoat((700.0, 0.0, 200.0, 0.0, 30.0, 0.0)))


def test_the_gun_codes_are_an_option():
    text = GCode(GunCodes(7, 9)).write(planned("gcode").plan)
    assert "\nM7 " in text and "\nM9 " in text and "\nM3" not in text
    with pytest.raises(InputError):
        GunCodes(5, 5)


def test_names_and_ranges():
    assert GCODE.program_name("paper spiral (v2)") == "PAPER_SPIRAL_V2"
    assert len(GCODE.program_name("x" * 40)) == 16 and GCODE.program_name("3d") == "C3D"
    with pytest.raises(InputError, match="not a valid G-code program name"):
        GCODE.check_name("has space", "name")
    far = [placed_line(_down([9000.0, 0, 300]), _down([10001.0, 0, 300]))]
    with pytest.raises(InputError, match="beyond the 9999.9999 mm"):
        GCODE.write(_plan(far))


def test_writing_is_deterministic():
    plan = planned("gcode", [arc_spiral()]).plan
    assert GCODE.write(plan) == GCODE.write(plan)

"""The URScript writer, checked by a small URScript reader written here (not the product's): the
targets are the plan's poses within 1e-6 mm and 1e-9 rad, the moves its path, blends never
overlap, the file keeps the controller's limits."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.primitives import Line3, arc_through
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.languages.urscript.language import URSCRIPT
from coatsim.path.build import ProgramOptions

from language_plans import arc_spiral, distance_to_plan, planned, roundrect, sprayed_points

NUM = r"-?\d+(?:\.\d+)?(?:e-?\d+)?"
POSE = re.compile(rf"p\[({NUM}), ({NUM}), ({NUM}), ({NUM}), ({NUM}), ({NUM})\]")


def _matrix(values):
    """4x4 of p[x, y, z, rx, ry, rz] (m, rad) by Rodrigues' formula, in mm."""
    x, y, z, *r = (float(v) for v in values)
    angle = math.sqrt(sum(v * v for v in r))
    m = np.eye(4)
    if angle > 0:
        k = np.array(r) / angle
        kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        m[:3, :3] = np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx
    m[:3, 3] = [1000 * x, 1000 * y, 1000 * z]
    return m


def mini_read(text: str):
    frame = _matrix(POSE.search(text.split("frame = ")[1]).groups())
    tool = _matrix(POSE.search(text.split("set_tcp(")[1]).groups())
    gun, out = False, []
    for line in text.splitlines():
        line = line.split("#")[0].strip()
        if line.startswith("set_standard_digital_out(1,"):
            gun = "True" in line
        elif line.startswith(("movel(", "movec(", "movej(")):
            poses = [frame @ _matrix(g) for g in POSE.findall(line)]
            keys = dict(re.findall(rf"(\w)=({NUM})", line))
            out.append((line[:5], poses, float(keys["v"]), float(keys.get("r", 0)), gun))
    return out, frame, tool


def primitives(motions):
    here, prims = None, []
    for kind, poses, _, _, gun in motions:
        end = poses[-1][:3, 3]
        if kind == "movel":
            prims.append((Line3(here, end), gun))
        elif kind == "movec":
            prims.append((arc_through(here, poses[0][:3, 3], end), gun))
        here = end
    return prims


@pytest.mark.parametrize("contour", ["roundrect", "spiral"])
@pytest.mark.parametrize("frame", [(700.0, 0.0, 200.0, 0.0, 0.0, 0.0), (650.0, -40.0, 320.0, 30.0, 35.0, -10.0)])
def test_the_targets_are_the_plans_poses(contour, frame):
    built = planned("urscript", [roundrect() if contour == "roundrect" else arc_spiral()], frame=pose_from_xyzoat(frame))
    motions, written_frame, tool = mini_read(built.text)
    assert np.allclose(written_frame, pose_from_xyzoat(frame).as_matrix4(), atol=1e-8)
    assert np.allclose(tool[:3, 3], [0, 0, 250])
    ends = [m for _, poses, _, _, _ in motions for m in poses[-1:]]
    for seg in built.plan.paths[0].segments:
        pose = seg.end
        best = min(ends, key=lambda m: np.linalg.norm(m[:3, 3] - pose.translation_mm))
        assert np.linalg.norm(best[:3, 3] - pose.translation_mm) < 1e-6
        assert np.abs(best[:3, :3] - pose.rotation).max() < 1e-9
    sprayed = [p for p, on in primitives(motions) if on]
    assert distance_to_plan(sprayed_points(sprayed), built.plan.paths) < 1e-6
    assert {v for kind, _, v, _, _ in motions} == {0.3}


def test_blends_are_the_accuracy_within_forty_percent_of_each_move_and_never_overlap():
    built = planned("urscript", variant="polyline-blend", accuracy_mm=2.0)
    motions, _, _ = mini_read(built.text)
    cartesian = [m for m in motions if m[0] != "movej"]
    lengths = [np.linalg.norm(b[1][-1][:3, 3] - a[1][-1][:3, 3]) for a, b in zip(cartesian, cartesian[1:])]
    radii = [1000 * m[3] for m in cartesian]
    for k in range(1, len(cartesian) - 1):
        assert radii[k - 1] + radii[k] <= lengths[k - 1] + 1e-9
        assert radii[k] <= 2.0 + 1e-12
    assert max(radii) == pytest.approx(2.0)


def test_the_polyline_stop_variant_stops_everywhere():
    motions, _, _ = mini_read(planned("urscript", variant="polyline-stop").text)
    assert {r for *_, r, _ in motions} == {0.0} and "movec" not in {m[0] for m in motions}


def test_names_and_the_gun_output():
    assert URSCRIPT.program_name("Paper Spiral (v2)") == "paper_spiral_v2"
    assert URSCRIPT.program_name("def") == "def_prog" and URSCRIPT.program_name("3d") == "p_3d"
    for bad in ("while", "has space", "9x", "x" * 32):
        with pytest.raises(InputError, match="not a valid URScript name"):
            URSCRIPT.check_name(bad, "name")
    from coatsim.path.part_program import build_part_program
    from coatsim.path.placement import Placement

    with pytest.raises(InputError, match="standard digital outputs 0 to 7"):
        build_part_program([roundrect()], Placement(), ProgramOptions(gun_signal=9), tolerance_mm=0.1, source="s",
                           language=URSCRIPT)


def test_writing_is_deterministic():
    plan = planned("urscript", [arc_spiral()]).plan
    assert URSCRIPT.write(plan) == URSCRIPT.write(plan)

"""The .LS writer, checked by a small .LS reader written here (not the product's): the positions
and motions are the plan's path (points within 2e-3 mm of it at the 3 decimals written, tool axes
within 2e-5 rad), CNT is the plan's accuracy at its speed, the file keeps Fanuc's limits."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.geometry.space.primitives import Line3, arc_through
from coatsim.geometry.space.xyzoat import pose_from_xyzoat
from coatsim.languages.fanuc_tp.blend import cnt_for
from coatsim.languages.fanuc_tp.language import FANUC_TP, FanucTp

from language_plans import arc_spiral, distance_to_plan, planned, roundrect, sprayed_points


def _matrix(w, p, r):
    """Fanuc W-P-R (deg) as the vendor states it: turn W about the fixed x, then P about y, then R about z."""
    def turn(axis, deg):
        c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        m = np.eye(3)
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m
    return turn(2, r) @ turn(1, p) @ turn(0, w)


def mini_read(text: str):
    """(kind, [base-frame 4x4 poses], speed text, termination, sprayed) of every motion."""
    mn = text.split("/MN\n")[1].split("/POS\n")[0]
    pos_text = text.split("/POS\n")[1]
    positions = {}
    for index, body in re.findall(r"P\[(\d+)\]\{(.*?)\};", pos_text, re.S):
        vals = dict(re.findall(r"([XYZWPR]) =\s*([-\d.]+)", body))
        m = np.eye(4)
        m[:3, :3] = _matrix(*(float(vals[k]) for k in "WPR"))
        m[:3, 3] = [float(vals[k]) for k in "XYZ"]
        positions[int(index)] = m
    pr, frames, gun, out = {}, {}, False, []
    instructions = re.findall(r"^\s*\d+:(.*?);", re.sub(r" \n\s*:\s*", " ", mn), re.M)
    for instr in instructions:
        instr = instr.strip()
        if m := re.match(r"PR\[9,(\d)\]=(\S+)", instr):
            pr[int(m.group(1))] = float(m.group(2))
        elif m := re.match(r"(UFRAME|UTOOL)\[9\]=PR\[9\]", instr):
            f = np.eye(4)
            f[:3, :3] = _matrix(pr[4], pr[5], pr[6])
            f[:3, 3] = [pr[1], pr[2], pr[3]]
            frames[m.group(1)] = f
        elif m := re.match(r"DO\[1\]=(ON|OFF)", instr):
            gun = m.group(1) == "ON"
        elif m := re.match(r"([JLC]) ((?:P\[\d+\] )+)(\S+) (FINE|CNT\d+)", instr):
            targets = [frames["UFRAME"] @ positions[int(i)] for i in re.findall(r"P\[(\d+)\]", m.group(2))]
            out.append((m.group(1), targets, m.group(3), m.group(4), gun))
    return out, frames


def primitives(motions):
    here, prims = None, []
    for kind, targets, _, _, sprayed in motions:
        end = targets[-1][:3, 3]
        if kind == "L":
            prims.append((Line3(here, end), sprayed))
        elif kind == "C":
            prims.append((arc_through(here, targets[0][:3, 3], end), sprayed))
        here = end
    return prims


@pytest.mark.parametrize("contour", ["roundrect", "spiral"])
@pytest.mark.parametrize("frame", [(700.0, 0.0, 200.0, 0.0, 0.0, 0.0), (650.0, -40.0, 320.0, 30.0, 35.0, -10.0)])
def test_the_positions_and_motions_are_the_plans_path(contour, frame):
    built = planned("fanuc-tp", [roundrect() if contour == "roundrect" else arc_spiral()],
                    frame=pose_from_xyzoat(frame))
    motions, frames = mini_read(built.text)
    assert np.allclose(frames["UTOOL"][:3, 3], [0, 0, 250]) and np.allclose(frames["UFRAME"][:3, 3], frame[:3])
    sprayed = [p for p, on in primitives(motions) if on]
    assert distance_to_plan(sprayed_points(sprayed), built.plan.paths) < 2e-3
    plan_poses = [pose for seg in built.plan.paths[0].segments for pose in (seg.start, seg.end)]
    written = [t for _, targets, _, _, _ in motions for t in targets]
    for pose in plan_poses:  # every planned pose is written, position and tool axes
        best = min(written, key=lambda m: np.linalg.norm(m[:3, 3] - pose.translation_mm))
        assert np.linalg.norm(best[:3, 3] - pose.translation_mm) < 2e-3
        assert np.abs(best[:3, :3] - pose.rotation).max() < 2e-5
    cnt = f"CNT{cnt_for(0.5, 300.0)}"
    assert {term for kind, _, speed, term, on in motions if on and kind != "J"} <= {cnt, "FINE"}
    assert {speed for kind, _, speed, _, _ in motions if kind != "J"} == {"300mm/sec"}


def test_the_polyline_stop_variant_stops_everywhere():
    motions, _ = mini_read(planned("fanuc-tp", variant="polyline-stop").text)
    assert {term for _, _, _, term, _ in motions} == {"FINE"} and {k for k, *_ in motions} == {"J", "L"}


def test_the_file_keeps_fanucs_limits():
    text = planned("fanuc-tp", [arc_spiral()]).text
    mn = text.split("/MN\n")[1].split("/POS")[0]
    remarks = re.findall(r":\s+!(.*) ;", mn)
    assert remarks and max(len(r) for r in remarks) <= 32 and not any(";" in r for r in remarks)
    count = int(re.search(r"LINE_COUNT\t= (\d+);", text).group(1))
    assert count == len(re.findall(r"^\s*\d+:", mn, re.M))
    numbers = [float(v) for v in re.findall(r"[XYZWPR] =\s*([-\d.]+)", text)]
    assert all(len(v.split(".")[1]) == 3 for v in re.findall(r"[XYZWPR] =\s*([-\d.]+)", text))
    assert max(abs(v) for v in numbers) < 1e5
    assert text.startswith("/PROG  SHAPES\n/ATTR\n") and text.endswith("/END\n")


def test_names():
    assert FANUC_TP.program_name("paper spiral (v2)") == "PAPER_SPIRAL_V2"
    assert FANUC_TP.program_name("3d") == "C3D" and len(FANUC_TP.program_name("x" * 50)) == 36
    for bad in ("lower", "HAS SPACE", "9START", "X" * 37):
        with pytest.raises(InputError, match="not a valid Fanuc program name"):
            FANUC_TP.check_name(bad, "name")


def test_the_cnt_model_is_an_option_and_writing_is_deterministic():
    plan = planned("fanuc-tp").plan
    assert FANUC_TP.write(plan) == FANUC_TP.write(plan)
    soft = FanucTp(decel_mm_s2=1000.0).write(plan)  # a softer brake rounds more at the same CNT: a smaller CNT
    assert f"CNT{cnt_for(0.5, 300.0, 1000.0)}" in soft and cnt_for(0.5, 300.0, 1000.0) < cnt_for(0.5, 300.0)

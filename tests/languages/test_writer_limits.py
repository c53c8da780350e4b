"""What a real controller enforces on loading, checked on the written text by patterns written
here (not the product's readers), for plans in tilted and turned work frames: RAPID unit
quaternions with q1 >= 0 (RAPID Reference: orient must be normalised); KRL A, C in [-180, 180] and
B in [-90, 90], every position of the .src declared in the .dat, names <= 24 characters; Fanuc W,
R in [-180, 180] and P in [-90, 90] with 3 decimals, LINE_COUNT equal to the /MN lines, numbered
from 1, every P[n] in /POS, remarks <= 32 characters; URScript rotation vectors of angle <= pi,
metres and m/s; G-code lines within LinuxCNC's 256 characters, 4 decimals; AS names <= 15."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.rotations import rot_x, rot_y, rot_z
from coatsim.languages.registry import language

from language_plans import planned

FRAMES = [Pose(rot_z(math.radians(a)) @ rot_y(math.radians(b)) @ rot_x(math.radians(c)), np.array(t))
          for a, b, c, t in [(0, 0, 0, (600.0, 0.0, 200.0)), (179.9, 0, 0, (500.0, 100.0, 300.0)),
                             (-135, 30, 10, (450.0, -120.0, 300.0)), (90, -89.99, 45, (700.0, 50.0, 400.0)),
                             (30, 0, 180, (600.0, 0.0, 900.0))]]
NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"


def _text(name: str, frame: Pose) -> str:
    return planned(name, frame=frame).text


@pytest.mark.parametrize("frame", FRAMES)
def test_rapid_orientations_are_unit_quaternions_with_q1_not_negative(frame):
    text = _text("abb-rapid", frame)
    quaternions = re.findall(rf"\[\[{NUMBER},{NUMBER},{NUMBER}\],\[({NUMBER}),({NUMBER}),({NUMBER}),({NUMBER})\]", text)
    assert len(quaternions) > 10
    for q in quaternions:
        q = np.array([float(v) for v in q])
        assert abs(np.linalg.norm(q) - 1.0) < 1e-9 and q[0] >= 0.0


@pytest.mark.parametrize("frame", FRAMES)
def test_krl_angles_in_range_and_every_position_declared(frame):
    program = planned("kuka-krl", frame=frame)
    files = dict(language("kuka-krl").files(program.text))
    src, dat = files[".src"], files[".dat"]
    for a, b, c in re.findall(rf"A ({NUMBER}),B ({NUMBER}),C ({NUMBER})", program.text):
        assert -180.0 <= float(a) <= 180.0 and -90.0 <= float(b) <= 90.0 and -180.0 <= float(c) <= 180.0
    declared = set(re.findall(r"^\s*DECL\s+E6POS\s+(\w+)\s*=", dat, re.M))
    used = set(re.findall(r"^\s*(?:LIN|PTP|CIRC)\s+(\w+)", src, re.M)) | set(re.findall(r"^\s*CIRC\s+\w+\s*,\s*(\w+)", src, re.M))
    assert used and used <= declared
    assert all(len(name) <= 24 for name in declared | set(re.findall(r"^\s*DEF(?:DAT)?\s+(\w+)", program.text, re.M)))


@pytest.mark.parametrize("frame", FRAMES)
def test_fanuc_positions_lines_and_remarks_within_the_controllers_format(frame):
    text = _text("fanuc-tp", frame)
    mn = text.split("/MN\n")[1].split("/POS")[0].splitlines()
    numbered = [line for line in mn if not re.match(r"\s*:", line)]  # "    :  P[6] …" goes on a C line
    assert all(re.match(r"\s*\d+:C ", before) for before, line in zip(mn, mn[1:]) if re.match(r"\s*:", line))
    numbers = [int(re.match(r"\s*(\d+):", line).group(1)) for line in numbered]
    assert numbers == list(range(1, len(numbered) + 1))
    assert int(re.search(r"LINE_COUNT\s*=\s*(\d+);", text).group(1)) == len(numbered)
    for remark in re.findall(r"^\s*\d+:\s*!(.*) ;$", text, re.M):
        assert len(remark) <= 32
    used = {int(n) for n in re.findall(r"\bP\[(\d+)", "\n".join(mn))}
    positions = re.findall(r"P\[(\d+)\]\{\s*GP1:\s*UF : \d+, UT : \d+,\s*CONFIG : '[NF] [UD] [TB], -?\d+, -?\d+, -?\d+',"
                           rf"\s*X =\s*({NUMBER})\s+mm,\s*Y =\s*({NUMBER})\s+mm,\s*Z =\s*({NUMBER})\s+mm,"
                           rf"\s*W =\s*({NUMBER}) deg,\s*P =\s*({NUMBER}) deg,\s*R =\s*({NUMBER}) deg", text)
    assert used and used == {int(p[0]) for p in positions}
    for _, *values in positions:
        assert all(re.fullmatch(r"-?\d+\.\d{3}", v) for v in values)
        w, p, r = (float(v) for v in values[3:])
        assert -180.0 <= w <= 180.0 and -90.0 <= p <= 90.0 and -180.0 <= r <= 180.0


@pytest.mark.parametrize("frame", FRAMES)
def test_urscript_poses_are_metres_and_rotation_vectors_of_at_most_a_half_turn(frame):
    text = _text("urscript", frame)
    poses = re.findall(rf"p\[({NUMBER}), ({NUMBER}), ({NUMBER}), ({NUMBER}), ({NUMBER}), ({NUMBER})\]", text)
    assert len(poses) > 10
    for pose in poses:
        values = [float(v) for v in pose]
        assert max(abs(v) for v in values[:3]) < 5.0  # metres: no cell reaches 5 m
        assert np.linalg.norm(values[3:]) <= math.pi + 1e-9
    for v in re.findall(rf"\bv=({NUMBER})", text):
        assert 0.0 < float(v) <= 1.0  # m/s (the plan's 300 mm/s)
    for r in re.findall(rf"\br=({NUMBER})", text):
        assert 0.0 <= float(r) < 0.01  # m (the plan's 0.5 mm accuracy)


def test_gcode_lines_and_numbers_within_the_controllers_format():
    text = _text("gcode", FRAMES[1])
    assert max(len(line) for line in text.splitlines()) <= 256
    for letter, value in re.findall(rf"\b([XYZIJKF])({NUMBER})", text):
        assert len(value.split(".")[1]) <= 4 if "." in value else True


def test_kawasaki_names_within_fifteen_characters():
    text = _text("kawasaki-as", FRAMES[2])
    names = re.findall(r"^\.PROGRAM\s+([^\s(]+)", text, re.M) + re.findall(r"^\s*([A-Za-z][\w.]*)\s+" + NUMBER, text, re.M)
    assert names and all(len(n) <= 15 for n in names)

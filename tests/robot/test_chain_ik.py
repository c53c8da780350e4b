"""Vectorised kinematics against MuJoCo, batched Newton IK, and the tracker's knot path against
its sample-by-sample path."""

from __future__ import annotations

import math

import mink
import mujoco
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from coatsim.core.errors import ExecutionError
from coatsim.robot import ik
from coatsim.robot.cell import M_TO_MM, load_cell
from coatsim.robot.ik_batch import continuity_ok, refine, rotation_vectors
from coatsim.robot.chain import Chain

DOWN = np.diag([-1.0, 1.0, -1.0])
CELL = load_cell()
CHAIN = Chain.build(CELL.model, CELL.tcp_site, (CELL.wrist_site,))
HYP = settings(max_examples=60, deadline=None, derandomize=True)


def configurations(away_from_wrist_singularity: bool = False):
    def build(u):
        q = CELL.q_min + np.asarray(u) * (CELL.q_max - CELL.q_min)
        if away_from_wrist_singularity:
            q[4] = math.copysign(max(abs(q[4]), 0.4), q[4] or 1.0)
        return q
    return st.lists(st.floats(0.02, 0.98), min_size=6, max_size=6).map(build)


def test_default_cell_has_a_chain():
    assert CHAIN is not None


@HYP
@given(configurations())
def test_poses_and_jacobian_equal_mujoco(q):
    data = mujoco.MjData(CELL.model)
    data.qpos[:] = q
    mujoco.mj_kinematics(CELL.model, data)
    mujoco.mj_comPos(CELL.model, data)
    jp, jr = np.zeros((3, 6)), np.zeros((3, 6))
    mujoco.mj_jacSite(CELL.model, data, jp, jr, CELL.tcp_site)
    poses = CHAIN.poses(np.vstack((q, q)))
    np.testing.assert_allclose(poses.tcp[1], data.site_xpos[CELL.tcp_site], atol=1e-12)
    np.testing.assert_allclose(poses.rotation[1], data.site_xmat[CELL.tcp_site].reshape(3, 3), atol=1e-12)
    np.testing.assert_allclose(poses.sites[CELL.wrist_site][0], data.site_xpos[CELL.wrist_site], atol=1e-12)
    np.testing.assert_allclose(poses.jacobian()[0], np.vstack((jp, jr)), atol=1e-12)
    np.testing.assert_allclose(poses.jacobian(np.array([False, True]))[0], np.vstack((jp, jr)), atol=1e-12)


def test_a_chain_with_a_slide_joint_is_not_built(tmp_path):
    bodies = ""
    for k in range(6):
        kind = 'type="slide"' if k == 3 else ""
        bodies += f'<body pos="0 0 0.1"><joint name="j{k}" {kind} axis="0 1 0" range="-1 1"/><geom size="0.02"/>'
    xml = f'<mujoco><worldbody>{bodies}<site name="tcp"/>{"</body>" * 6}</worldbody></mujoco>'
    model = mujoco.MjModel.from_xml_string(xml)
    assert Chain.build(model, 0) is None
    assert Chain.build(mujoco.MjModel.from_xml_string(xml.replace('type="slide"', "")), 0) is not None


@HYP
@given(st.floats(-3.0, 3.0), st.lists(st.floats(-1, 1), min_size=3, max_size=3).filter(lambda v: np.linalg.norm(v) > 0.1))
def test_rotation_vectors_invert_axis_rotations(angle, axis):
    axis = np.asarray(axis) / np.linalg.norm(axis)
    quat, turn = np.empty(4), np.empty(9)
    mujoco.mju_axisAngle2Quat(quat, axis, angle)
    mujoco.mju_quat2Mat(turn, quat)
    np.testing.assert_allclose(rotation_vectors(turn.reshape(1, 3, 3), np.eye(3)[None]), [angle * axis], atol=1e-9)


@HYP
@given(configurations(away_from_wrist_singularity=True), st.integers(0, 2**32 - 1))
def test_newton_refines_a_perturbed_guess_to_the_target(q_true, seed):
    poses = CHAIN.poses(q_true[None])
    assume(np.linalg.cond(poses.jacobian()[0]) < 200.0)  # near a singularity another solution is as close
    guess = q_true + np.random.default_rng(seed).uniform(-0.01, 0.01, 6)
    q, dp, dr, wrist = refine(CHAIN, guess[None], poses.tcp * M_TO_MM, poses.rotation, 1e-6, 1e-6, 8, CELL.wrist_site)
    assert dp[0] <= 1e-6 and dr[0] <= 1e-6
    assert np.abs(q[0] - q_true).max() < 1e-6
    np.testing.assert_allclose(wrist, poses.sites[CELL.wrist_site] * M_TO_MM, atol=1e-6)


def test_continuity_flags_a_jump_no_speed_bounded_step_makes():
    s = np.arange(5.0)
    q = np.outer(s, np.full(6, 1e-3))
    dt = np.full(5, 0.005)
    v = np.full(6, 2.0)
    assert continuity_ok(s, q, dt, v)
    q[3, 2] += 0.02  # 0.02 rad in 5 ms is twice the 2 rad/s limit
    assert not continuity_ok(s, q, dt, v)


def arc_path(n: int = 241, radius: float = 60.0):
    """Samples of a line then a half circle at z = 300 mm with the tool pointing down."""
    line = np.column_stack((np.full(n // 2, 700.0), np.linspace(-150.0, 0.0, n // 2), np.full(n // 2, 300.0)))
    a = np.linspace(0.0, math.pi, n - n // 2 + 1)[1:]
    arc = np.column_stack((700.0 - radius + radius * np.cos(a), radius * np.sin(a), np.full(len(a), 300.0)))
    p = np.vstack((line, arc))
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))
    return s, p, np.repeat(DOWN[None], len(p), axis=0)


def start_on(tracker, p, r):
    return tracker.solve_pose(CELL.home, p, r, "start")


def test_knot_path_equals_the_sample_by_sample_path_with_fewer_qp_solves(monkeypatch):
    s, p, r = arc_path()
    dt = np.concatenate(([0.0], np.diff(s))) / 200.0
    fast = ik.Tracker(CELL)
    q0 = start_on(fast, p[0], r[0])
    calls = []
    real = mink.solve_ik
    monkeypatch.setattr(ik.mink, "solve_ik", lambda *a, **k: calls.append(1) or real(*a, **k))
    q_fast, wrist_fast, res_fast = fast.track(q0, s, p, r, dt, lambda i: f"sample {i}")
    assert 0 < len(calls) < len(s) / 5
    slow = ik.Tracker(CELL)
    slow.chain = None
    q_slow, wrist_slow, res_slow = slow.track(q0, s, p, r, dt, lambda i: f"sample {i}")
    assert res_fast.position_mm <= 1e-6 and res_fast.rotation_deg <= 1e-6
    assert res_slow.position_mm <= 1e-3
    np.testing.assert_allclose(q_fast, q_slow, atol=1e-5)
    np.testing.assert_allclose(wrist_fast, wrist_slow, atol=1e-3)


def test_out_of_reach_midway_gives_the_sample_by_sample_error():
    s, p, r = arc_path()
    p = p.copy()
    p[150:, 0] += np.linspace(0.0, 2000.0, len(p) - 150)  # runs off out of reach
    s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))
    dt = np.concatenate(([0.0], np.diff(s))) / 200.0
    messages = []
    for chain in (CHAIN, None):
        tracker = ik.Tracker(CELL)
        tracker.chain = chain
        with pytest.raises(ExecutionError) as info:
            tracker.track(start_on(tracker, p[0], r[0]), s, p, r, dt, lambda i: f"sample {i}")
        messages.append(str(info.value))
    assert messages[0] == messages[1] and "cannot follow the path" in messages[0]


@HYP
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 3.1))
def test_slerp_turns_at_a_constant_rate_from_one_orientation_to_the_other(seed, angle):
    from coatsim.robot.sampling import _slerp

    rng = np.random.default_rng(seed)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    quat, turn = np.empty(4), np.empty(9)
    mujoco.mju_axisAngle2Quat(quat, axis, angle)
    mujoco.mju_quat2Mat(turn, quat)
    mujoco.mju_axisAngle2Quat(quat, rng.normal(size=3) / 2.0, 1.0)
    r0 = np.empty(9)
    mujoco.mju_quat2Mat(r0, quat / np.linalg.norm(quat))
    r0 = r0.reshape(3, 3)
    r1 = r0 @ turn.reshape(3, 3)
    f = np.linspace(0.0, 1.0, 5)
    out = _slerp(r0, r1, f)
    np.testing.assert_allclose(out[0], r0, atol=1e-12)
    np.testing.assert_allclose(out[-1], r1, atol=1e-9)
    np.testing.assert_allclose(out @ np.swapaxes(out, 1, 2), np.broadcast_to(np.eye(3), (5, 3, 3)), atol=1e-12)
    steps = rotation_vectors(out[1:], out[:-1])
    np.testing.assert_allclose(np.linalg.norm(steps, axis=1), angle / 4.0, atol=1e-9)


@HYP
@given(configurations(away_from_wrist_singularity=True), st.integers(0, 2**32 - 1))
def test_first_order_prediction_errs_by_the_square_of_the_step(q0, seed):
    from coatsim.robot.ik_batch import first_order

    poses = CHAIN.poses(q0[None])
    assume(np.linalg.cond(poses.jacobian()[0]) < 200.0)
    direction = np.random.default_rng(seed).uniform(-1.0, 1.0, 6)
    errors = []
    for h in (1e-3, 2e-3):
        target = CHAIN.poses((q0 + h * direction)[None])
        guess = first_order(q0, poses.tcp[0], poses.rotation[0], poses.jacobian()[0], target.tcp * M_TO_MM,
                            target.rotation)
        errors.append(np.abs(guess[0] - (q0 + h * direction)).max())
    assert errors[0] < 1e-4 and errors[1] / max(errors[0], 1e-15) == pytest.approx(4.0, rel=0.2)


def polygon_pieces(seed: int, sides: int, radius: float, tilt: float):
    """The rest-to-rest pieces of an exact-stop polygon (1 mm samples, the tool tilting about x
    by up to ``tilt`` rad, a different angle at every corner): (s, positions, rotations, step
    times)."""
    rng = np.random.default_rng(seed)
    corners = np.column_stack((700.0 + radius * np.cos(np.linspace(0, 2 * math.pi, sides + 1)),
                               radius * np.sin(np.linspace(0, 2 * math.pi, sides + 1)), np.full(sides + 1, 300.0)))
    corners[:, :2] += rng.uniform(-2.0, 2.0, (sides + 1, 2))
    tilts = tilt * np.sin(np.linspace(0.0, 2 * math.pi, sides + 1))
    pieces = []
    for a, b, t0, t1 in zip(corners[:-1], corners[1:], tilts[:-1], tilts[1:]):
        n = max(3, int(math.ceil(np.linalg.norm(b - a))) + 1)
        f = np.linspace(0.0, 1.0, n)
        p = a + f[:, None] * (b - a)
        angle = t0 + f * (t1 - t0)
        turn = np.array([[[1, 0, 0], [0, math.cos(t), -math.sin(t)], [0, math.sin(t), math.cos(t)]] for t in angle])
        s = np.concatenate(([0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))))
        pieces.append((s, p, DOWN @ turn, np.concatenate(([0.0], np.diff(s))) / 200.0))
    return pieces


@settings(max_examples=10, deadline=None, derandomize=True)
@given(st.integers(0, 2**32 - 1), st.integers(3, 24), st.floats(10.0, 120.0), st.floats(0.0, 0.3))
@example(seed=1, sides=20, radius=60.0, tilt=0.2)
def test_a_run_of_short_pieces_solves_as_each_piece_alone(seed, sides, radius, tilt):
    """track_run gives what track gives piece after piece (to the Newton tolerance), for the
    leading pieces its batched polish converges on (the rest are left to track: where a piece
    lands just at the convergence threshold, the last bits of the BLAS in use decide)."""
    pieces = polygon_pieces(seed, sides, radius, tilt)
    tracker = ik.Tracker(CELL)
    assume(all(tracker.batchable(piece[0]) for piece in pieces))
    q0 = start_on(tracker, pieces[0][1][0], pieces[0][2][0])
    together = tracker.track_run(q0, pieces)
    q = q0
    if (seed, sides, radius, tilt) == (1, 20, 60.0, 0.2):  # the explicit example: the batch covers every piece
        assert len(together) == len(pieces)
    for (s, p, r, dt), (q_run, wrist_run, res_run) in zip(pieces, together):
        q_one, wrist_one, res_one = tracker.track(q, s, p, r, dt, lambda i: f"sample {i}")
        np.testing.assert_allclose(q_run, q_one, atol=1e-8)
        np.testing.assert_allclose(wrist_run, wrist_one, atol=1e-6)
        assert res_run.position_mm <= 1e-6 and res_run.rotation_deg <= 1e-6
        q = q_one[-1]


def test_a_run_stops_before_a_piece_out_of_reach():
    pieces = polygon_pieces(0, 12, 80.0, 0.0)
    s, p, r, dt = pieces[5]
    pieces[5] = (s, p + np.array([0.0, 0.0, 3000.0]) * (s / s[-1])[:, None], r, dt)  # climbs out of reach
    tracker = ik.Tracker(CELL)
    q0 = start_on(tracker, pieces[0][1][0], pieces[0][2][0])
    assert len(tracker.track_run(q0, pieces)) == 5

import mujoco
import numpy as np
import pytest

from coatsim.core.errors import InputError
from coatsim.robot.cell import DEFAULT_MODEL, MODELS, load_cell


def test_default_cell_limits_and_home():
    cell = load_cell()
    # RS013N spec-sheet speeds (deg/s) and the 2 ms implicitfast integration
    assert np.allclose(np.degrees(cell.v_max), [265, 250, 265, 475, 475, 730], atol=0.01)
    assert cell.timestep == pytest.approx(0.002)
    assert cell.model.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    data = mujoco.MjData(cell.model)
    p, r = cell.forward(data, cell.home)
    assert np.allclose(r[:, 2], [0, 0, -1], atol=1e-6)  # home: tool points down
    assert 300 < p[2] < 800  # above the table, clear of the work plane


def test_workspace_reach_about_1_4_m():
    cell = load_cell()
    data = mujoco.MjData(cell.model)
    q = np.zeros(6)
    q[2] = -np.arctan2(0.65, 0.11)  # forearm in line with the upper arm: arm stretched upwards
    data.qpos[:] = q
    mujoco.mj_kinematics(cell.model, data)
    shoulder = data.xanchor[1]
    reach = np.linalg.norm(data.site_xpos[mujoco.mj_name2id(cell.model, mujoco.mjtObj.mjOBJ_SITE, "flange")] - shoulder)
    assert 1.40 < reach < 1.47


def test_missing_model_is_input_error(tmp_path):
    with pytest.raises(InputError, match="not found"):
        load_cell(tmp_path / "nope.xml")


def test_model_without_limits_is_input_error(tmp_path):
    text = DEFAULT_MODEL.read_text().replace('name="joint_accel_limit"', 'name="other"')
    for name in ("rs013n_arm.xml", "plasma_gun.xml"):
        (tmp_path / name).write_text((MODELS / name).read_text())
    (tmp_path / "cell.xml").write_text(text)
    with pytest.raises(InputError, match="joint_accel_limit"):
        load_cell(tmp_path / "cell.xml")

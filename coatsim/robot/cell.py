"""The robot cell: the MuJoCo model, its names, limits and home configuration.

This is the only place where coatsim's millimetres meet MuJoCo's metres: everything the other
robot modules hand in or out of the model goes through ``MM`` / ``M_TO_MM``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from importlib.resources import as_file, files
from pathlib import Path

import mujoco
import numpy as np

from coatsim.core.errors import InputError
from coatsim.core.fileio import check_input

MM = 1e-3  # metres per millimetre
M_TO_MM = 1e3

# The shipped models are package data (the repository's top-level models/ links to this folder).
MODELS = files("coatsim") / "models"
DEFAULT_MODEL_NAME = "coating_cell.xml"
DEFAULT_MODEL = MODELS / DEFAULT_MODEL_NAME
JOINTS = ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6")
TCP_SITE = "tcp"
WRIST_SITE = "wrist_centre"
FLANGE_SITE = "flange"


@dataclass(frozen=True, eq=False)
class Cell:
    """A loaded cell model with everything the robot stage needs to know about the arm.

    Joint arrays are (6,) in joint order; limits in rad, rad/s, rad/s^2; the tool acceleration
    limit in mm/s^2; ``home`` is the start configuration of every program (rad). The physical
    gun's TCP (the ``tcp`` site) in the flange frame (the ``flange`` site, z out of the flange, as
    a controller's TOOL frame is given) is ``gun_rotation`` (3, 3) and ``gun_offset_mm`` (3,):
    what a TOOL statement must say for the controller's TCP to be the gun's.
    """

    path: Path
    model: mujoco.MjModel
    q_min: np.ndarray
    q_max: np.ndarray
    v_max: np.ndarray
    a_max: np.ndarray
    tool_accel_mm_s2: float
    home: np.ndarray
    tcp_site: int
    wrist_site: int
    gun_rotation: np.ndarray
    gun_offset_mm: np.ndarray

    @property
    def timestep(self) -> float:
        return float(self.model.opt.timestep)

    def forward(self, data: mujoco.MjData, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """TCP position (mm) and rotation (3, 3) for configuration ``q``, using ``data``."""
        data.qpos[:] = q
        mujoco.mj_kinematics(self.model, data)
        return data.site_xpos[self.tcp_site] * M_TO_MM, data.site_xmat[self.tcp_site].reshape(3, 3).copy()


def _numeric(model: mujoco.MjModel, name: str, size: int, path: Path) -> np.ndarray:
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_NUMERIC, name)
    if index < 0:
        raise InputError(f"{path}: model lacks <custom><numeric name=\"{name}\"> with {size} value(s)")
    adr, n = model.numeric_adr[index], model.numeric_size[index]
    values = np.array(model.numeric_data[adr:adr + n], dtype=float)
    if n != size or np.any(values <= 0):
        raise InputError(f"{path}: <numeric name=\"{name}\"> needs {size} positive value(s), found {values.tolist()}")
    return values


def load_cell(path: str | Path | None = None) -> Cell:
    """Load and check a cell model (default: the shipped ``coating_cell.xml``, package data).

    The model must define joints ``joint1``..``joint6`` (hinge, limited) as its only degrees of
    freedom, ``tcp``, ``flange`` and ``wrist_centre`` sites, a ``home`` keyframe, and the custom numerics
    ``joint_speed_limit``, ``joint_accel_limit`` and ``tool_accel_limit``, site sensors ``tcp_pos``,
    ``tcp_axis``, ``tcp_vel``, and one ``pid`` actuator per joint with inputs "pos vel ff".
    """
    if path is None:
        with as_file(MODELS) as folder:
            return _load(Path(folder) / DEFAULT_MODEL_NAME)
    path = Path(path)
    if not os.path.lexists(path):
        raise InputError(f"{path}: model file not found (give an MJCF cell model, or leave it out for the shipped one)")
    check_input(path, "cell model")
    return _load(path)


def _gun_frame(model: mujoco.MjModel, tcp: int, flange: int) -> tuple[np.ndarray, np.ndarray]:
    """The tcp site's pose in the flange site's frame (rotation, offset in mm)."""
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    r_flange = data.site_xmat[flange].reshape(3, 3)
    rotation = r_flange.T @ data.site_xmat[tcp].reshape(3, 3)
    offset = r_flange.T @ (data.site_xpos[tcp] - data.site_xpos[flange]) * M_TO_MM
    return rotation, offset


def _load(path: Path) -> Cell:
    try:
        model = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else "invalid MJCF"
        raise InputError(f"{path}: cannot load model: {first}") from None
    return cell_of(model, path)


def cell_of(model: mujoco.MjModel, path: Path) -> Cell:
    """The cell of a compiled model (``path`` names it in messages), checked as ``load_cell`` says."""
    if model.nq != 6 or model.nv != 6:
        raise InputError(f"{path}: expected a fixed-base six-axis arm (nq = nv = 6), found nq={model.nq}")
    for k, name in enumerate(JOINTS):
        jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if jid < 0 or model.jnt_qposadr[jid] != k:
            raise InputError(f"{path}: joint {name!r} missing or not the arm's joint {k + 1}")
        if not model.jnt_limited[jid]:
            raise InputError(f"{path}: joint {name!r} needs a range")
    sites = {}
    for name in (TCP_SITE, WRIST_SITE, FLANGE_SITE):
        sites[name] = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name)
        if sites[name] < 0:
            raise InputError(f"{path}: model lacks the site {name!r}")
    for name, dim in (("tcp_pos", 3), ("tcp_axis", 3), ("tcp_vel", 3)):
        sid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SENSOR, name)
        if sid < 0 or model.sensor_dim[sid] != dim:
            raise InputError(f"{path}: model lacks the {dim}-D sensor {name!r} on the tcp site")
    if model.nu != 18 or list(model.actuator_ctrlnum[:6]) != [3] * 6 or list(model.actuator_trnid[:6, 0]) != list(range(6)):
        raise InputError(f"{path}: expected one pid actuator per joint, in joint order, with input=\"pos vel ff\"")
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if key < 0:
        raise InputError(f"{path}: model lacks the keyframe 'home'")
    q_min, q_max = model.jnt_range[:6, 0].copy(), model.jnt_range[:6, 1].copy()
    home = model.key_qpos[key].copy()
    if np.any(home < q_min) or np.any(home > q_max):
        raise InputError(f"{path}: keyframe 'home' lies outside the joint ranges")
    gun_rotation, gun_offset = _gun_frame(model, sites[TCP_SITE], sites[FLANGE_SITE])
    return Cell(
        path=path,
        model=model,
        q_min=q_min,
        q_max=q_max,
        v_max=_numeric(model, "joint_speed_limit", 6, path),
        a_max=_numeric(model, "joint_accel_limit", 6, path),
        tool_accel_mm_s2=float(_numeric(model, "tool_accel_limit", 1, path)[0]) * M_TO_MM,
        home=home,
        tcp_site=sites[TCP_SITE],
        wrist_site=sites[WRIST_SITE],
        gun_rotation=gun_rotation,
        gun_offset_mm=gun_offset,
    )

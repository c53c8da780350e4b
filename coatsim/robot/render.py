"""Offscreen pictures of the cell: the arm at a configuration, the coated part coloured by a
per-vertex field (thickness), the tool path as a line, the spray as a ray from the nozzle.

The OpenGL backend is chosen once per process (:func:`gl_backend`): the one ``MUJOCO_GL`` names
(``egl`` or ``osmesa``), otherwise EGL (headless, GPU or Mesa's software device) and, failing
that, OSMesa (software). Both need no display. PyOpenGL fixes its platform on first use, so a
failed EGL attempt is forgotten (its modules unloaded) before OSMesa is tried.

The part is one mesh geom added to the cell's model (MjSpec), textured with the colour map as a
256 x 1 texture: each vertex's texture coordinate is its value on the colour scale, so a new
field is a new set of texture coordinates uploaded to the GPU, without recompiling the model.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from coatsim.core.errors import CoatsimError
from coatsim.robot.cell import M_TO_MM, Cell

_BACKENDS = ("egl", "osmesa")
_chosen: Optional[tuple[str, type]] = None
_failures: list[str] = []
LIFT_MM = 0.3  # the part is drawn this far above the surface along its normals (no z-fighting with the cell)


class RenderUnavailable(CoatsimError):
    """No offscreen OpenGL backend works on this machine."""

    exit_code = 3


def _load(name: str) -> type:
    if os.environ.get("PYOPENGL_PLATFORM", name) != name:
        for module in [m for m in sys.modules if m == "OpenGL" or m.startswith("OpenGL.")]:
            del sys.modules[module]
        os.environ.pop("PYOPENGL_PLATFORM")
    if name == "egl":
        from mujoco.egl import GLContext
    else:
        from mujoco.osmesa import GLContext
    return GLContext


def gl_backend() -> tuple[str, type]:
    """(name, GLContext class) of the offscreen backend: MUJOCO_GL's if it names egl or osmesa,
    else the first of EGL, OSMesa that opens a context. RenderUnavailable says why none did."""
    global _chosen
    if _chosen is not None:
        return _chosen
    wanted = os.environ.get("MUJOCO_GL", "").strip().lower()
    order = (wanted,) if wanted in _BACKENDS else _BACKENDS
    for name in order:
        try:
            cls = _load(name)
            context = cls(8, 8)
            context.make_current()
            context.free()
        except Exception as exc:  # any failure of a backend means: try the next one
            _failures.append(f"{name}: {type(exc).__name__}: {exc}".splitlines()[0])
            continue
        _chosen = (name, cls)
        return _chosen
    raise RenderUnavailable("no offscreen OpenGL backend works (" + "; ".join(_failures) + "); install Mesa's EGL "
                            "(libegl1) or OSMesa (libosmesa6), or set MUJOCO_GL=egl|osmesa")


@dataclass(frozen=True)
class Camera:
    """A free camera: the point looked at (mm, base frame), distance (mm), azimuth and
    elevation (deg, MuJoCo's convention)."""

    lookat_mm: tuple[float, float, float]
    distance_mm: float
    azimuth_deg: float = 150.0
    elevation_deg: float = -28.0


def framing(points_mm: np.ndarray, fovy_deg: float = 45.0, margin: float = 1.12, **angles: float) -> Camera:
    """A camera that shows every point (their bounding sphere fills the view)."""
    lo, hi = points_mm.min(axis=0), points_mm.max(axis=0)
    centre = 0.5 * (lo + hi)
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 1.0)
    distance = margin * radius / np.sin(np.radians(fovy_deg) / 2.0)
    return Camera(tuple(float(c) for c in centre), float(distance), **angles)


class CellRenderer:
    """Renders the cell with a coloured part; reuse one instance for many frames."""

    def __init__(self, cell: Cell, vertices_mm: np.ndarray, faces: np.ndarray, normals: np.ndarray,
                 colour_map: np.ndarray, width: int = 640, height: int = 420) -> None:
        import mujoco

        self.backend, context_class = gl_backend()
        spec = mujoco.MjSpec.from_file(str(cell.path))
        texture = spec.add_texture(name="coatsim_scale", type=mujoco.mjtTexture.mjTEXTURE_2D, width=len(colour_map),
                                   height=1, nchannel=3)
        texture.data = np.ascontiguousarray(colour_map, dtype=np.uint8).tobytes()
        material = spec.add_material(name="coatsim_part", emission=0.35, specular=0.1, shininess=0.1)
        material.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = "coatsim_scale"
        lifted = (np.asarray(vertices_mm, float) + LIFT_MM * np.asarray(normals, float)) / M_TO_MM
        self.n = len(lifted)
        spec.add_mesh(name="coatsim_part", uservert=lifted.ravel().tolist(), userface=np.asarray(faces).ravel().tolist(),
                      usertexcoord=self._texcoord(np.zeros(self.n)).ravel().tolist(),
                      inertia=mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL)
        spec.worldbody.add_geom(name="coatsim_part", type=mujoco.mjtGeom.mjGEOM_MESH, meshname="coatsim_part",
                                material="coatsim_part", contype=0, conaffinity=0, mass=0.0)
        spec.visual.global_.offwidth = max(width, spec.visual.global_.offwidth)
        spec.visual.global_.offheight = max(height, spec.visual.global_.offheight)
        self.model = spec.compile()
        self.mesh = self.model.nmesh - 1
        adr, num = int(self.model.mesh_texcoordadr[self.mesh]), int(self.model.mesh_texcoordnum[self.mesh])
        if num != self.n:
            raise RenderUnavailable(f"the part mesh was reordered by MuJoCo ({num} texture coordinates for {self.n} vertices)")
        self._texcoords = slice(adr, adr + num)
        self.data = mujoco.MjData(self.model)
        self.width, self.height = width, height
        self.context = context_class(width, height)
        self.context.make_current()
        self.scene = mujoco.MjvScene(self.model, maxgeom=4000)
        self.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = 0
        self.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = 0
        self.gl = mujoco.MjrContext(self.model, mujoco.mjtFontScale.mjFONTSCALE_100)
        mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN, self.gl)
        self.option = mujoco.MjvOption()
        self._mujoco = mujoco

    @staticmethod
    def _texcoord(fraction: np.ndarray) -> np.ndarray:
        u = 0.002 + 0.996 * np.clip(np.nan_to_num(fraction), 0.0, 1.0)
        return np.column_stack((u, np.full(len(u), 0.5)))

    def frame(self, q: np.ndarray, fraction: np.ndarray, camera: Camera, path_mm: Optional[np.ndarray] = None,
              spray_mm: Optional[Sequence[np.ndarray]] = None) -> np.ndarray:
        """An (height, width, 3) uint8 picture: the arm at ``q``, the part coloured by
        ``fraction`` (n,) of the colour scale, ``path_mm`` (k, 3) as a line, ``spray_mm`` (nozzle,
        aim point) as a ray."""
        mj = self._mujoco
        self.context.make_current()
        self.model.mesh_texcoord[self._texcoords] = self._texcoord(fraction)
        mj.mjr_uploadMesh(self.model, self.gl, self.mesh)
        self.data.qpos[:] = q
        mj.mj_forward(self.model, self.data)
        cam = mj.MjvCamera()
        cam.lookat[:] = np.asarray(camera.lookat_mm) / M_TO_MM
        cam.distance, cam.azimuth, cam.elevation = camera.distance_mm / M_TO_MM, camera.azimuth_deg, camera.elevation_deg
        mj.mjv_updateScene(self.model, self.data, self.option, mj.MjvPerturb(), cam, mj.mjtCatBit.mjCAT_ALL, self.scene)
        if path_mm is not None and len(path_mm) > 1:
            self._polyline(np.asarray(path_mm) / M_TO_MM, 2.5, np.array([1.0, 1.0, 1.0, 1.0], np.float32))
        if spray_mm is not None:
            self._polyline(np.asarray(spray_mm) / M_TO_MM, 4.0, np.array([1.0, 0.9, 0.3, 1.0], np.float32))
        viewport = mj.MjrRect(0, 0, self.width, self.height)
        mj.mjr_render(viewport, self.scene, self.gl)
        rgb = np.empty((self.height, self.width, 3), dtype=np.uint8)
        mj.mjr_readPixels(rgb, None, viewport, self.gl)
        return rgb[::-1].copy()

    def _polyline(self, points_m: np.ndarray, width_px: float, rgba: np.ndarray) -> None:
        mj, scene = self._mujoco, self.scene
        step = max(1, (len(points_m) - 1) // max(1, scene.maxgeom - scene.ngeom - 8))
        pts = points_m[::step]
        for a, b in zip(pts[:-1], pts[1:]):
            if scene.ngeom >= scene.maxgeom or np.allclose(a, b):
                continue
            geom = scene.geoms[scene.ngeom]
            mj.mjv_initGeom(geom, mj.mjtGeom.mjGEOM_LINE, np.zeros(3), np.zeros(3), np.eye(3).ravel(), rgba)
            mj.mjv_connector(geom, mj.mjtGeom.mjGEOM_LINE, width_px, a, b)
            scene.ngeom += 1

    def close(self) -> None:
        self.gl.free()
        self.context.free()

"""Batched Newton refinement of IK guesses at many path samples at once.

Between the samples the tracker solves with mink (the knots), the joint path is smooth: a cubic
through the knot solutions is already close, and a few Newton steps on the vectorised Jacobian
(:mod:`coatsim.robot.chain`) bring every sample to the same convergence as a mink solve.
``refine`` does those steps for all samples together; ``continuity_ok`` checks that the result
is a joint path the sample-by-sample tracker would have followed (no jump a QP step bounded by
the joint speed limits could not make), so the caller can fall back to it where it is not.
"""

from __future__ import annotations

import numpy as np

from coatsim.robot.cell import M_TO_MM, MM
from coatsim.robot.chain import Chain

DAMPING_M2 = 1e-12  # Levenberg-Marquardt term (m^2): keeps the 6x6 solves finite at a singularity


def row_norms(x: np.ndarray) -> np.ndarray:
    """Euclidean norm of each row of ``x`` (N, k): numpy.linalg.norm's arithmetic, without its
    per-call checks (called a few times per path piece)."""
    return np.sqrt(np.add.reduce(x * x, axis=1))


def rotation_vectors(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """World-frame rotation vectors (N, 3) rad taking ``current`` (N, 3, 3) onto ``target``."""
    err = target @ np.swapaxes(current, 1, 2)
    vee = 0.5 * np.stack((err[:, 2, 1] - err[:, 1, 2], err[:, 0, 2] - err[:, 2, 0], err[:, 1, 0] - err[:, 0, 1]), axis=1)
    sin = row_norms(vee)
    cos = np.clip((np.trace(err, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arctan2(sin, cos)
    scale = np.where(sin > 1e-12, angle / np.maximum(sin, 1e-300), 1.0)
    return vee * scale[:, None]


def pose_errors(chain: Chain, q: np.ndarray, p_mm: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position (mm) and rotation (deg) distance of the TCP from the targets, per configuration."""
    poses = chain.poses(q)
    dp = row_norms(poses.tcp * M_TO_MM - p_mm)
    cos = (np.einsum("nij,nij->n", poses.rotation, r) - 1.0) / 2.0
    return dp, np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def first_order(q0: np.ndarray, tcp_m: np.ndarray, rotation: np.ndarray, jac: np.ndarray, p_mm: np.ndarray,
                r: np.ndarray) -> np.ndarray:
    """Configurations (N, 6) predicted for the targets from q0 (6,) by the Jacobian ``jac``
    (6, 6) at q0, where the TCP is at ``tcp_m`` (3,) m with ``rotation`` (3, 3)."""
    e = np.hstack((p_mm * MM - tcp_m, rotation_vectors(r, np.broadcast_to(rotation, r.shape))))
    return q0 + np.linalg.solve(jac @ jac.T + DAMPING_M2 * np.eye(6), e.T).T @ jac


def refine(chain: Chain, q: np.ndarray, p_mm: np.ndarray, r: np.ndarray, converged_mm: float, converged_deg: float,
           max_iters: int, site: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """Newton steps on every configuration of ``q`` (N, 6) until its TCP is within
    ``converged_mm`` / ``converged_deg`` of its target (or ``max_iters`` steps); returns the
    configurations, their final position (mm) and rotation (deg) errors, and the positions (mm)
    of the chain's extra ``site`` at them (None without a site)."""
    q = np.array(q, float)
    target_m = p_mm * MM
    todo = np.arange(len(q))
    dp = np.zeros(len(q))
    dr = np.zeros(len(q))
    at_site = None if site is None else np.empty((len(q), 3))
    for it in range(max_iters + 1):
        poses = chain.poses(q[todo])
        e = np.hstack((target_m[todo] - poses.tcp, rotation_vectors(r[todo], poses.rotation)))
        dp[todo] = row_norms(e[:, :3]) * M_TO_MM
        dr[todo] = np.degrees(row_norms(e[:, 3:]))
        if at_site is not None:
            at_site[todo] = poses.sites[site] * M_TO_MM
        open_ = (dp[todo] > converged_mm) | (dr[todo] > converged_deg)
        if it == max_iters or not open_.any():
            break
        jac = poses.jacobian(open_)
        todo, e = todo[open_], e[open_]
        jjt = jac @ np.swapaxes(jac, 1, 2) + DAMPING_M2 * np.eye(6)
        q[todo] += np.einsum("nji,nj->ni", jac, np.linalg.solve(jjt, e[..., None])[..., 0])
    return q, dp, dr, at_site


def continuity_ok(s_mm: np.ndarray, q: np.ndarray, step_time: np.ndarray, v_max: np.ndarray) -> bool:
    """Whether every sample lies within one joint-speed-bounded QP step (v_max x its step time)
    of the sample-by-sample tracker's prediction from the two samples before it."""
    if len(q) < 2:
        return True
    pred = np.empty_like(q)
    pred[1] = q[0]
    if len(q) > 2:
        w = ((s_mm[2:] - s_mm[:-2]) / np.maximum(s_mm[1:-1] - s_mm[:-2], 1e-12))[:, None]
        pred[2:] = q[:-2] + w * (q[1:-1] - q[:-2])
    jump = np.abs(q[1:] - pred[1:])
    return bool(np.all(jump <= v_max * np.maximum(step_time[1:], 1e-4)[:, None]))

"""Ground states: the airplane at rest on its gear (the start of a takeoff run).

:func:`ground_equilibrium` solves, for every condition of a batch with a ground model, the height
h of the CG and the pitch attitude θ at which the gear legs carry the airplane at rest (vertical
acceleration and pitch acceleration zero, wings level, no motion), by Newton iteration with a
finite-difference 2 × 2 Jacobian per condition. Thrust (idle at throttle 0) and aerodynamic forces
at zero airspeed are included as the model gives them; the horizontal force is not balanced
(friction is zero at zero speed: the airplane starts rolling as soon as it is released).
"""

from __future__ import annotations

import numpy as np

from certkit.models.dynamics.eom import AircraftModel, euler_to_quat, quat_to_dcm


def gear_heights(model: AircraftModel, x12: np.ndarray, rows=None) -> np.ndarray:
    """Height (m) of each gear contact point above the runway, (n, n_legs), for Euler states (n, 12); ``rows`` says
    which condition of the batch each state belongs to (default: state i is condition i)."""
    if model.ground is None:
        raise ValueError("the model has no ground model")
    dcm = quat_to_dcm(euler_to_quat(x12[:, 9], x12[:, 10], x12[:, 11]))
    r_gear = model.r_gear if rows is None else model.r_gear[rows]
    r_ned = np.einsum("nij,nlj->nli", dcm, r_gear)
    return x12[:, 2:3] - model.ground.elevation - r_ned[:, :, 2]


def wheel_height(model: AircraftModel, x13: np.ndarray, elevation: float | None = None) -> np.ndarray:
    """Height (m) of the lowest gear contact point above the runway (``model.ground``'s elevation unless given), (n,),
    for quaternion states (n, 13): the wheels are on the runway where it is not positive."""
    q0, q1, q2, q3 = (x13[:, 9 + k, None] for k in range(4))
    rx, ry, rz = (model.r_gear[:, :, k] for k in range(3))
    down = 2 * (q1 * q3 - q0 * q2) * rx + 2 * (q2 * q3 + q0 * q1) * ry + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * rz
    if elevation is None:
        elevation = model.ground.elevation if model.ground is not None else 0.0
    return x13[:, 2] - elevation - down.max(axis=1)


def ground_equilibrium(model: AircraftModel, u: np.ndarray, tol: float = 1e-7, max_iter: int = 50) -> np.ndarray:
    """Euler states (n, 12) of the batch at rest on the runway with controls ``u`` (module docstring)."""
    if model.ground is None:
        raise ValueError("the model has no ground model")
    n = model.n
    u = np.broadcast_to(np.asarray(u, dtype=float), (n, len(model.control_names)))
    x = np.zeros((n, 12))
    # start level with every leg compressed by 0.1 m (at exactly touching the Jacobian is singular)
    x[:, 2] = model.ground.elevation + model.r_gear[:, :, 2].max(axis=1) - 0.1

    def residual(x):
        xd = model.derivatives_euler(x, u)
        theta = x[:, 10]
        hddot = -(-np.sin(theta) * xd[:, 3] + np.cos(theta) * xd[:, 5])
        return np.stack([hddot, xd[:, 7]], axis=1)

    steps = (1e-4, 1e-6)
    for _ in range(max_iter):
        r = residual(x)
        if np.all(np.abs(r) < tol):
            break
        J = np.empty((n, 2, 2))
        for k, (col, dz) in enumerate(zip((2, 10), steps)):
            xp = x.copy()
            xp[:, col] += dz
            J[:, :, k] = (residual(xp) - r) / dz
        dz = np.linalg.solve(J, -r[:, :, None])[:, :, 0]
        x[:, 2] += np.clip(dz[:, 0], -0.2, 0.2)  # damped steps: stay on the branch with every leg on the runway
        x[:, 10] += np.clip(dz[:, 1], -0.01, 0.01)
    return x


__all__ = ["ground_equilibrium", "gear_heights"]

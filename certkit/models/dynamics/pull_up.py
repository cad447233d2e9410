"""Instantaneous symmetric pull-up or push-over at a given load factor (no regulation content).

The classical elevator-per-g manoeuvre (Etkin & Reid, *Dynamics of Flight*, §2.9 "steady pull-up"; Nelson,
*Flight Stability and Automatic Control*, §3.x manoeuvring flight): wings level at the bottom (or top) of the
manoeuvre, flight path horizontal, speed V; the pitch rate that turns the flight path at load factor n is
q = (n − 1) g / V. The angle of attack α and the elevator δe are solved so that the normal acceleration ẇ and
the pitch acceleration q̇ vanish (the path curves at n g, the pitch rate is steady) with every other control
and the throttles held as given — e.g. a stabiliser mistrimmed and held, thrust for level flight at the trim.
The speed is not held (u̇ is whatever it is at that instant), as in the textbook manoeuvre point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.trim import assemble_state


@dataclass
class PullUp:
    """Solution per condition: α (rad), the pitch control's deflection (rad), the pitch rate (rad/s), convergence."""

    alpha: np.ndarray
    elevator: np.ndarray
    pitch_rate: np.ndarray
    converged: np.ndarray
    residual: np.ndarray


def symmetric_pull_up(
    model: AircraftModel,
    V,
    h,
    n,
    u: np.ndarray,
    pitch: str = "elevator",
    alpha0=0.03,
    tol: float = 1e-8,
    max_iter: int = 30,
) -> PullUp:
    """Solve the manoeuvre point of every condition of ``model`` at true airspeed ``V`` (m/s), altitude ``h`` (m) and
    load factor ``n`` (scalars or (n,) arrays); ``u`` (conditions, controls) gives every control and throttle, the
    ``pitch`` control's column being the first guess. Newton with a forward-difference Jacobian, steps limited to
    0.1 rad; a condition whose residual does not fall below ``tol`` (ẇ in g, q̇ in rad/s²) is reported unconverged."""
    count = model.n
    bc = lambda a: np.broadcast_to(np.asarray(a, dtype=float), (count,)).astype(float)  # noqa: E731
    V, h, n = bc(V), bc(h), bc(n)
    q = (n - 1.0) * model.g / V
    j = model.control_index(pitch)
    u = np.array(u, dtype=float)
    z = np.column_stack([bc(alpha0), u[:, j]])
    zero = np.zeros(count)

    def residual(z):
        x = assemble_state(V, h, z[:, 0], zero, zero, zero, zero)
        x[:, 7] = q
        uu = u.copy()
        uu[:, j] = z[:, 1]
        xd = model.derivatives_euler(x, uu)
        return np.column_stack([xd[:, 5] / model.g, xd[:, 7]])

    r = residual(z)
    step = 1e-6
    for _ in range(max_iter):
        norm = np.max(np.abs(r), axis=1)
        if np.all(norm <= tol):
            break
        J = np.empty((count, 2, 2))
        for k in range(2):
            zp = z.copy()
            zp[:, k] += step
            J[:, :, k] = (residual(zp) - r) / step
        with np.errstate(all="ignore"):
            dz = -np.linalg.solve(J, r[:, :, None])[:, :, 0]
        dz = np.where(np.isfinite(dz), dz, 0.0)
        dz /= np.maximum(np.max(np.abs(dz), axis=1) / 0.1, 1.0)[:, None]
        active = (norm > tol)[:, None]
        z = np.where(active, z + dz, z)
        r = residual(z)
    norm = np.max(np.abs(r), axis=1)
    return PullUp(alpha=z[:, 0], elevator=z[:, 1], pitch_rate=q, converged=norm <= tol, residual=norm)


__all__ = ["symmetric_pull_up", "PullUp"]

"""Linearisation of the batch equations of motion about trimmed states.

ẋ = f(x, u) with the Euler state (:data:`~certkit.models.dynamics.eom.EULER_STATE`) is
differentiated by central differences,
    A[:, j] = (f(x + δ_j e_j, u) − f(x − δ_j e_j, u)) / (2 δ_j),   B likewise with the controls,
all conditions of the batch perturbed at once (2 (12 + m) evaluations of the batch).

Steps δ_j (absolute, chosen so that the truncation error O(δ² f‴) and the round-off error
O(ε f / δ) are both below 1e-7 relative for transport-aircraft magnitudes):
    positions 1 m (only h matters, through the density), velocities 1e-3 m/s,
    rates 1e-5 rad/s, angles 1e-5 rad, surface deflections 1e-5 rad, throttles and brake 1e-5.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from certkit.models.dynamics.eom import EULER_STATE, AircraftModel

_STATE_STEP = np.array([1.0, 1.0, 1.0, 1e-3, 1e-3, 1e-3, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5, 1e-5])
_CONTROL_STEP = 1e-5

LONGITUDINAL = ("u", "w", "q", "theta")
LATERAL = ("v", "p", "r", "phi")


@dataclass
class Linearization:
    """A (n, 12, 12), B (n, 12, m) of a batch; state and control names."""

    A: np.ndarray
    B: np.ndarray
    x0: np.ndarray
    u0: np.ndarray
    state_names: tuple[str, ...]
    control_names: tuple[str, ...]

    def select(self, i: int, states: Sequence[str] | None = None, inputs: Sequence[str] | None = None):
        si = [self.state_names.index(s) for s in (states or self.state_names)]
        ci = [self.control_names.index(c) for c in (inputs or self.control_names)]
        return self.A[i][np.ix_(si, si)], self.B[i][np.ix_(si, ci)]

    def statespace(self, i: int, states: Sequence[str] | None = None, inputs: Sequence[str] | None = None):
        """A ``control.StateSpace`` of condition ``i`` (outputs: the selected states)."""
        import control  # deferred: python-control (0.4 s) only when a state-space object is asked for

        A, B = self.select(i, states, inputs)
        return control.ss(
            A,
            B,
            np.eye(A.shape[0]),
            np.zeros((A.shape[0], B.shape[1])),
            states=list(states or self.state_names),
            inputs=list(inputs or self.control_names),
            outputs=list(states or self.state_names),
        )

    def longitudinal(self, i: int, inputs: Sequence[str] | None = None):
        return self.statespace(i, LONGITUDINAL, inputs)

    def lateral(self, i: int, inputs: Sequence[str] | None = None):
        return self.statespace(i, LATERAL, inputs)


def _perturbed(x0: np.ndarray, u0: np.ndarray):
    """Every ± perturbation of every condition in one batch (2 (ns + m) states per condition): the states and
    controls (nb · n rows), the condition of each row, the steps and nb."""
    n, ns = x0.shape
    m = u0.shape[1]
    nb = 2 * (ns + m)
    X = np.repeat(x0[None], nb, axis=0)
    U = np.repeat(u0[None], nb, axis=0)
    for j in range(ns):
        X[2 * j, :, j] += _STATE_STEP[j]
        X[2 * j + 1, :, j] -= _STATE_STEP[j]
    for j in range(m):
        U[2 * (ns + j), :, j] += _CONTROL_STEP
        U[2 * (ns + j) + 1, :, j] -= _CONTROL_STEP
    steps = np.concatenate([np.asarray(_STATE_STEP, dtype=float)[:ns], np.full(m, _CONTROL_STEP)])
    return X.reshape(nb * n, ns), U.reshape(nb * n, m), np.tile(np.arange(n), nb), steps, nb


def linearize(model: AircraftModel, x0: np.ndarray, u0: np.ndarray) -> Linearization:
    """Central-difference A, B of every condition about (x0 (n, 12), u0 (n, m))."""
    x0 = np.asarray(x0, dtype=float)
    u0 = np.asarray(u0, dtype=float)
    n, ns = x0.shape
    X, U, rows, steps, nb = _perturbed(x0, u0)
    F = model.derivatives_euler(X, U, rows=rows).reshape(nb, n, ns)
    D = (F[0::2] - F[1::2]) / (2 * steps[:, None, None])  # (ns + m, n, ns)
    A = np.moveaxis(D[:ns], 0, -1)
    B = np.moveaxis(D[ns:], 0, -1)
    return Linearization(A=A, B=B, x0=x0, u0=u0, state_names=EULER_STATE, control_names=model.control_names)


def output_sensitivities(
    model: AircraftModel, x0: np.ndarray, u0: np.ndarray, outputs: Sequence[str]
) -> tuple[np.ndarray, np.ndarray]:
    """C (n, k, 12) and D (n, k, m): the derivatives of the model's ``outputs`` (``V``, ``alpha``, ``n_z``, ``qbar``,
    …, :meth:`AircraftModel.derivatives_euler`) with respect to the Euler state and the controls about (x0, u0), by
    the central differences and steps of :func:`linearize`."""
    x0 = np.asarray(x0, dtype=float)
    u0 = np.asarray(u0, dtype=float)
    n, ns = x0.shape
    X, U, rows, steps, nb = _perturbed(x0, u0)
    _, out = model.derivatives_euler(X, U, with_outputs=True, rows=rows)
    Y = np.stack([np.asarray(getattr(out, k), dtype=float).reshape(nb, n) for k in outputs], axis=-1)  # (nb, n, k)
    dY = (Y[0::2] - Y[1::2]) / (2 * steps[:, None, None])  # (ns + m, n, k)
    return np.moveaxis(dY[:ns], 0, -1), np.moveaxis(dY[ns:], 0, -1)


__all__ = ["linearize", "output_sensitivities", "Linearization", "LONGITUDINAL", "LATERAL"]

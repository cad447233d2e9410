"""Ground effect on a wing's lift and induced drag, from the image of its trailing vortex wake.

Near the ground the wing's wake and its mirror image in the ground plane form a biplane-like
system (Prandtl; Wieselsberger, NACA TM 77, 1922): the image's upwash reduces the downwash at the
wing. For an elliptic load the downwash stays uniform across the span and is multiplied by

    φ(h/b) = D_i(ground) / D_i(free air)

(h height of the wing above the ground, b span), computed here in the Trefftz plane: the elliptic
load's trailing vortex sheet and its image (opposite strength, 2h below), induced drag
−ρ/2 ∫ Γ w dy with the image's downwash added. Wieselsberger's closed form
σ = (1 − 1.32 h/b)/(1.05 + 7.4 h/b), φ = 1 − σ (his range 0.033 ≤ h/b ≤ 0.25) is the test reference.

Consequences used by the equations of motion (:mod:`certkit.models.dynamics.kernel`):

* induced drag at a given CL is φ times its free-air value (the polar's ``k`` term);
* with the downwash reduced by φ, lifting-line theory gives the slope of a wing of effective aspect
  ratio A/φ: the lift at a given attitude is the free-air lift times a(A/φ)/a(A), a the DATCOM
  lift-curve slope (:func:`certkit.models.aero.planform.lift_curve_slope`).

The change of the downwash at the tail (a nose-down moment near the ground) is
:mod:`certkit.models.aero.tail_ground_effect`'s.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit

from certkit.models.aero.ground_effect_phi import PHI_TABLE

#: h/b beyond which the ground's effect is ignored (φ > 0.995 there)
H_OVER_B_MAX = 2.0
#: entries of the φ table (h/b = 0 … H_OVER_B_MAX)
N_TABLE = 201


#: the trailing vortices of the table the equations of motion use
N_SPAN = 400


@lru_cache(maxsize=None)
def induced_drag_factor_table(n_span: int = N_SPAN) -> np.ndarray:
    """φ at h/b = 0, 0.01, …, :data:`H_OVER_B_MAX` (module docstring) over ``n_span`` trailing vortices: for
    :data:`N_SPAN`, the sums of :func:`trefftz_induced_drag_factors` as stored in
    :mod:`certkit.models.aero.ground_effect_phi` (they take 0.3 s of every process that builds a flight model near the
    ground; tests/aero/test_ground_effect.py recomputes them and compares every bit)."""
    if n_span == N_SPAN:
        return np.array(PHI_TABLE, dtype=float)
    return trefftz_induced_drag_factors(n_span)


def trefftz_induced_drag_factors(n_span: int) -> np.ndarray:
    """φ at h/b = 0, 0.01, …, :data:`H_OVER_B_MAX`, Trefftz-plane sums over ``n_span`` cosine-spaced trailing
    vortices."""
    th = np.linspace(0.0, np.pi, n_span + 1)
    y = -np.cos(th)  # trailing vortices at the panel edges, semi-span 1
    yc = -np.cos(0.5 * (th[1:] + th[:-1]))
    gamma = np.sqrt(1.0 - yc**2)  # elliptic circulation at the control points
    padded = np.concatenate([[0.0], gamma, [0.0]])
    strength = padded[:-1] - padded[1:]
    width = np.diff(y)
    dy = yc[:, None] - y[None, :]

    def drag(dz):
        w = (strength[None, :] * dy / (2.0 * np.pi * (dy**2 + dz**2))).sum(axis=1)
        return float((gamma * w * width).sum())

    free = drag(0.0)
    h_over_b = np.linspace(0.0, H_OVER_B_MAX, N_TABLE)
    table = np.empty(N_TABLE)
    table[0] = 0.0
    for i, hb in enumerate(h_over_b[1:], start=1):
        table[i] = (free - drag(4.0 * hb)) / free  # image 2h below; span 2 → 2h = 4 h/b
    return table


@njit(cache=True, fastmath=True, inline="always")
def induced_drag_factor_at(table, h_over_b):
    """φ(h/b) interpolated in ``table`` (:func:`induced_drag_factor_table`); 1 above its range."""
    n = table.shape[0]
    x = max(h_over_b, 0.0) * (n - 1) / H_OVER_B_MAX
    if x >= n - 1:
        return 1.0
    i = int(x)
    f = x - i
    return table[i] * (1.0 - f) + table[i + 1] * f


@njit(cache=True, fastmath=True, inline="always")
def lift_ratio(phi, aspect_ratio, tan_sweep_half_chord, mach, airfoil_efficiency=0.95):
    """a(A/φ)/a(A): the DATCOM lift-curve slope at the effective aspect ratio over the free-air one."""
    beta2 = max(1.0 - mach * mach, 0.05)
    t = beta2 / (airfoil_efficiency * airfoil_efficiency) * (1.0 + tan_sweep_half_chord * tan_sweep_half_chord / beta2)
    a = aspect_ratio
    ae = aspect_ratio / max(phi, 1e-3)
    return ae * (2.0 + math.sqrt(4.0 + a * a * t)) / (a * (2.0 + math.sqrt(4.0 + ae * ae * t)))


__all__ = ["induced_drag_factor_table", "induced_drag_factor_at", "lift_ratio", "H_OVER_B_MAX", "N_TABLE"]

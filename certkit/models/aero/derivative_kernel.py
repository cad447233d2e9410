"""Compiled evaluation of a stability-derivative table (the equations of
:mod:`certkit.models.aero.derivative_model`, one state at a time).

This is the only implementation of those equations: :class:`StabilityDerivativeModel.coefficients`
loops it over a batch, and the equations of motion (:mod:`certkit.models.dynamics.kernel`) call it
inside their compiled step, so a simulation never leaves compiled code between the aerodynamics and
the rigid-body equations. Compiled with numba (cached on disk after the first use).

Table layout: one row per term, one column per Mach breakpoint. Rows 0–21 are the base terms in the
order of :data:`BASE_TERMS`; then six rows per control j (CL, CD, CY, Cl, Cm, Cn at 22 + 6 j + k).
``after_stall[j]`` marks controls whose lift is added after the stall model (and outside the induced
drag): pseudo-controls such as a gust angle whose lift must not be rounded by the airplane's stall.
``stall`` = (flag, rounding, break_delta, break_width, CD90); ``clmax`` one value per breakpoint.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

BASE_TERMS = (
    "CL0",
    "CL_alpha",
    "CL_q",
    "CL_alphadot",
    "CD0",
    "k",
    "CL_minD",
    "CD_alpha",
    "CD_alpha2",
    "CY_beta",
    "CY_p",
    "CY_r",
    "Cl_beta",
    "Cl_p",
    "Cl_r",
    "Cm0",
    "Cm_alpha",
    "Cm_q",
    "Cm_alphadot",
    "Cn_beta",
    "Cn_p",
    "Cn_r",
)
CONTROL_PREFIXES = ("CL", "CD", "CY", "Cl", "Cm", "Cn")
N_BASE = len(BASE_TERMS)

#: number of values :func:`coefficients_one` returns: CL, CD, CY, Cl, Cm, Cn (body-axis moments),
#: CL_alphadot, Cm_alphadot
N_OUT = 8


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def mach_weights(machs, mach):
    """Index i and weight w of the linear interpolation at ``mach`` (held at the end values)."""
    nm = machs.shape[0]
    if nm == 1:
        return 0, 0, 0.0
    x = min(max(mach, machs[0]), machs[nm - 1])
    i = 0
    while i < nm - 2 and x >= machs[i + 1]:
        i += 1
    return i, i + 1, (x - machs[i]) / (machs[i + 1] - machs[i])


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def _row(T, k, i0, i1, w):
    return T[k, i0] * (1.0 - w) + T[k, i1] * w


@njit(cache=True, error_model="numpy", fastmath=True, inline="always")
def coefficients_one(
    T, machs, clmax_row, stall, alpha_drag, after_stall, alpha, beta, p_hat, q_hat, r_hat, mach, ctrl, out
):
    """Coefficients of one state into ``out`` (length :data:`N_OUT`); ``ctrl`` the deflections
    (rad) in the table's control order."""
    i0, i1, w = mach_weights(machs, mach)
    ca, sa = math.cos(alpha), math.sin(alpha)
    ps = p_hat * ca + r_hat * sa
    rs = r_hat * ca - p_hat * sa
    CL = _row(T, 0, i0, i1, w) + _row(T, 1, i0, i1, w) * alpha + _row(T, 2, i0, i1, w) * q_hat
    CY = _row(T, 9, i0, i1, w) * beta + _row(T, 10, i0, i1, w) * ps + _row(T, 11, i0, i1, w) * rs
    Cl = _row(T, 12, i0, i1, w) * beta + _row(T, 13, i0, i1, w) * ps + _row(T, 14, i0, i1, w) * rs
    Cm = _row(T, 15, i0, i1, w) + _row(T, 16, i0, i1, w) * alpha + _row(T, 17, i0, i1, w) * q_hat
    Cn = _row(T, 19, i0, i1, w) * beta + _row(T, 20, i0, i1, w) * ps + _row(T, 21, i0, i1, w) * rs
    CDc = 0.0
    CL_late = 0.0
    for j in range(ctrl.shape[0]):
        d = ctrl[j]
        if d == 0.0:
            continue
        base = N_BASE + 6 * j
        if after_stall[j]:
            CL_late += _row(T, base, i0, i1, w) * d
        else:
            CL += _row(T, base, i0, i1, w) * d
        CDc += _row(T, base + 1, i0, i1, w) * d
        CY += _row(T, base + 2, i0, i1, w) * d
        Cl += _row(T, base + 3, i0, i1, w) * d
        Cm += _row(T, base + 4, i0, i1, w) * d
        Cn += _row(T, base + 5, i0, i1, w) * d
    CD_sep = 0.0
    if stall[0] != 0.0:
        clmax = clmax_row[i0] * (1.0 - w) + clmax_row[i1] * w
        wr = stall[1]
        x = (clmax - CL) / wr
        # smooth minimum of CL and CLmax: CLmax − w·softplus(x), softplus written stably
        cl_att = clmax - wr * (max(x, 0.0) + math.log1p(math.exp(-abs(x))))
        cla = _row(T, 1, i0, i1, w)
        if abs(cla) <= 1e-9:
            cla = 1e-9
        alpha_s = alpha + (clmax - CL) / cla
        z = (alpha - alpha_s - stall[2]) / stall[3]
        sig = 0.5 * (1.0 + math.tanh(0.5 * z))
        CL = (1.0 - sig) * cl_att + sig * stall[4] * sa * ca
        CD_sep = sig * stall[4] * sa * sa
    dcl = CL - _row(T, 6, i0, i1, w)
    CD = _row(T, 4, i0, i1, w) + _row(T, 5, i0, i1, w) * dcl * dcl + CDc + CD_sep
    if alpha_drag:
        CD += _row(T, 7, i0, i1, w) * alpha + _row(T, 8, i0, i1, w) * alpha * alpha
    out[0] = CL + CL_late
    out[1] = CD
    out[2] = CY
    out[3] = Cl * ca - Cn * sa
    out[4] = Cm
    out[5] = Cl * sa + Cn * ca
    out[6] = _row(T, 3, i0, i1, w)
    out[7] = _row(T, 18, i0, i1, w)


@njit(cache=True, error_model="numpy", fastmath=True)
def coefficients_batch(
    T, machs, clmax_row, stall, alpha_drag, after_stall, alpha, beta, p_hat, q_hat, r_hat, mach, ctrl
):
    """:func:`coefficients_one` over flat arrays of n states; ``ctrl`` (n, n_controls). Returns (n, 8)."""
    n = alpha.shape[0]
    out = np.empty((n, N_OUT))
    for i in range(n):
        coefficients_one(
            T,
            machs,
            clmax_row,
            stall,
            alpha_drag,
            after_stall,
            alpha[i],
            beta[i],
            p_hat[i],
            q_hat[i],
            r_hat[i],
            mach[i],
            ctrl[i],
            out[i],
        )
    return out

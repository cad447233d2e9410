"""Discrete gusts for the rigid-airplane loads response.

The gust enters as an angle-of-attack increment carried by two pseudo-controls added to the
airplane's derivative model (:func:`gust_aero`; the dynamics package is not changed): ``gust_wing`` (the gust angle at
the wing, U/V) and ``gust_tail`` (the same gust reaching the tail a tail-arm / V later). The model adds

    ΔCL = CL_g,wing(M) · α_g,wing + CL_g,tail(M) · α_g,tail,   ΔCm likewise (about the model's reference),

with the per-surface lift and moment of a unit uniform angle of attack taken from the strip loads model
(the tail's value includes the wing's downwash, which convects with the gust and reaches the tail at
the same time). The lift of the gust builds up as each surface penetrates it (Küssner's function in R. T. Jones'
approximation, ψ(σ) = 1 − 0.5 e^(−0.13 σ) − 0.5 e^(−σ), σ the distance travelled in semichords of the surface's mean
chord: Bisplinghoff, Ashley & Halfman, *Aeroelasticity*, 1955, §5-7; incompressible and two-dimensional): the
pseudo-controls carry the effective gust angle of :func:`penetration_lagged`, and a continuous gust the same lag in
the frequency domain (:func:`penetration_transfer`). The lift of the airplane's own motion is quasi-steady (no Wagner
lag). Inputs are held over each simulation step, so the step must resolve the gust (a few dozen per 2H/V).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

GUST_CONTROLS = ("gust_wing", "gust_tail")


def one_minus_cosine(s, H, Uds):
    """Gust velocity at penetration s (m, array) of a 1 − cos gust of gradient H (m), peak Uds."""
    s = np.asarray(s, dtype=float)
    half_peak = 0.5 * np.asarray(Uds, dtype=float)
    out = np.zeros(np.broadcast_shapes(s.shape, half_peak.shape))
    within = np.broadcast_to((s >= 0) & (s <= 2 * H), out.shape)  # the cosine only where the gust is
    out[within] = np.broadcast_to(half_peak, out.shape)[within] * (
        1 - np.cos(np.pi * np.broadcast_to(s, out.shape)[within] / H)
    )
    return out


#: R. T. Jones' approximation of Küssner's function: ψ(σ) = 1 − Σ A_k e^(−b_k σ), σ in semichords
KUSSNER = ((0.5, 0.13), (0.5, 1.0))


def penetration_lagged(s, H, Uds, chord):
    """The effective gust velocity (the lift it gives over the lift-curve slope) at penetration ``s`` (m, array) of a
    1 − cos gust of gradient ``H`` (m) and peak ``Uds`` for a surface of mean chord ``chord`` (m): the gust's slope
    convolved with Küssner's function :data:`KUSSNER`, in closed form (each exponential is a first-order lag of the
    slope, dy/dσ = −b y + dw/dσ, integrated exactly for the sine slope and decaying after the gust). Tends to
    :func:`one_minus_cosine` as the gust grows long against the chord. Element by element in one compiled pass
    (:func:`_penetration_lagged_into`)."""
    s = np.asarray(s, dtype=float)
    Uds = np.asarray(Uds, dtype=float)
    shape = np.broadcast_shapes(s.shape, Uds.shape)
    w = np.pi * chord / (2.0 * H)  # the gust's angular frequency per semichord
    lags = np.array([(a_k, b_k, b_k**2 + w**2) for a_k, b_k in KUSSNER], dtype=float)
    out = np.empty(shape)
    _penetration_lagged_into(
        np.array(np.broadcast_to(s, shape), order="C").ravel(),  # copies: writable, C-ordered (one compiled type)
        np.array(np.broadcast_to(Uds, shape), order="C").ravel(),
        float(H),
        float(chord),
        float(w),
        4.0 * H / chord,
        lags,
        out.reshape(-1),
    )
    return out


@njit(cache=True)
def _penetration_lagged_into(s, uds, H, chord, w, end, lags, out):
    """:func:`penetration_lagged` of the flat penetrations ``s`` and peaks ``uds`` into ``out``: the 1 − cos gust
    (zero outside 0 ≤ s ≤ 2H) less each lag of ``lags`` (rows A_k, b_k, b_k² + w²): the slope's lag at σ clipped to the
    gust (``end`` = 4H/c semichords), (b sin(wσ) − w cos(wσ) + w e^(−bσ)) / (b² + w²), decaying as e^(−b_k (σ − end))
    after the gust and nil before it. Within the gust the lags share the sine and cosine of wσ (and decay by
    e⁰ = 1, left out: exact); past it they share their value at the gust's end, computed once."""
    n_lag = lags.shape[0]
    at_end = np.empty(n_lag)
    sin_end, cos_end = math.sin(w * end), math.cos(w * end)
    for k in range(n_lag):
        b_k = lags[k, 1]
        at_end[k] = (b_k * sin_end - w * cos_end + w * math.exp(-b_k * end)) / lags[k, 2]
    for i in range(s.size):
        si = s[i]
        half_peak = 0.5 * uds[i]
        value = half_peak * (1 - math.cos(np.pi * si / H)) if (si >= 0) and (si <= 2 * H) else 0.0
        sigma = 2.0 * si / chord
        if sigma > 0.0 and sigma < end:  # within the gust
            sn, cs = math.sin(w * sigma), math.cos(w * sigma)
            for k in range(n_lag):
                a_k, b_k = lags[k, 0], lags[k, 1]
                lag = (b_k * sn - w * cs + w * math.exp(-b_k * sigma)) / lags[k, 2]
                value = value - a_k * (half_peak * w * lag)
        elif sigma > 0.0:  # past it (σ ≥ end)
            for k in range(n_lag):
                a_k, b_k = lags[k, 0], lags[k, 1]
                value = value - a_k * (half_peak * w * at_end[k] * math.exp(-b_k * (sigma - end)))
        else:  # before it (or σ not a number): no lag
            for k in range(n_lag):
                value = value - lags[k, 0] * 0.0
        out[i] = value


def penetration_transfer(omega, chord):
    """The same lag for a sinusoidal gust of spatial frequency ``omega`` (rad/m): the effective over the actual gust
    velocity, 1 − Σ A_k iκ / (iκ + b_k), κ = Ω c/2 the frequency per semichord (the Fourier transform of the
    derivative of Küssner's indicial response: a Sears-function approximation)."""
    ik = 1j * np.asarray(omega, dtype=float) * chord / 2.0
    return 1.0 - sum(a_k * ik / (ik + b_k) for a_k, b_k in KUSSNER)


def gust_aero(base, mach, cl_wing, cm_wing, cl_tail, cm_tail):
    """The airplane's derivative model (:class:`StabilityDerivativeModel`) with the gust
    pseudo-controls added as control terms: per radian of gust angle, lift and pitching moment of the
    wing (``cl_wing``, ``cm_wing``) and of the tail (``cl_tail``, ``cm_tail``), one value per ``mach``
    breakpoint (interpolated onto the model's breakpoints: exact when they coincide, as for the loads
    model built at the aerodynamic model's Mach numbers). The gust lift is added after the stall model
    and outside the induced drag: the gust lift is taken normal to the gust-free relative wind (small
    gust angles)."""
    m = np.asarray(base.mach, dtype=float)
    f = lambda table: np.interp(m, np.asarray(mach, dtype=float), np.asarray(table, dtype=float))  # noqa: E731
    return base.with_control_terms(
        {
            "CL_gust_wing": f(cl_wing),
            "Cm_gust_wing": f(cm_wing),
            "CL_gust_tail": f(cl_tail),
            "Cm_gust_tail": f(cm_tail),
        },
        after_stall=GUST_CONTROLS,
    )


def gust_tables(loads, reference) -> dict[str, np.ndarray]:
    """Per-surface lift and pitching-moment coefficients per radian of uniform angle of attack from
    the strip loads model (both halves; the root shear is the surface's normal force, the moment
    about the reference point follows from the root torsion's centre of pressure)."""
    out = {"mach": loads["wing"].mach}
    S, c, xref = reference.area, reference.chord, reference.x_ref
    for name, key in (("wing", "wing"), ("horizontal_tail", "tail")):
        s = loads[name]
        k = s.inputs.index("alpha")
        normal = 2 * s.aero[:, k, 0, 0]  # shear at the root, both halves, per unit q̄
        torsion = 2 * s.aero[:, k, 2, 0]
        x_axis = float(np.interp(0.0, s.strip_span, s.strip_x))
        x_cp = x_axis - torsion / np.where(np.abs(normal) > 1e-12, normal, 1.0)
        out[f"cl_{key}"] = normal / S
        out[f"cm_{key}"] = -normal * (x_cp - xref) / (S * c)  # lift aft of the reference point: nose down
    return out

"""Discrete gusts for the rigid-airplane loads response.

The gust enters as an angle-of-attack increment carried by two pseudo-controls added to the
airplane's derivative model (:func:`gust_aero`; the dynamics package is not changed): ``gust_wing`` (the gust angle at
the wing, U/V) and ``gust_tail`` (the same gust reaching the tail a tail-arm / V later). The model adds

    ΔCL = CL_g,wing(M) · α_g,wing + CL_g,tail(M) · α_g,tail,   ΔCm likewise (about the model's reference),

with the per-surface lift and moment of a unit uniform angle of attack taken from the strip loads model
(the tail's value includes the wing's downwash, which convects with the gust and reaches the tail at
the same time). Aerodynamics are quasi-steady (no Küssner/Wagner lag: conservative for short gusts).
Inputs are held over each simulation step, so the step must resolve the gust (a few dozen per 2H/V).
"""

from __future__ import annotations

import numpy as np

GUST_CONTROLS = ("gust_wing", "gust_tail")


def one_minus_cosine(s, H, Uds):
    """Gust velocity at penetration s (m, array) of a 1 − cos gust of gradient H (m), peak Uds."""
    s = np.asarray(s, dtype=float)
    return np.where((s >= 0) & (s <= 2 * H), 0.5 * Uds * (1 - np.cos(np.pi * s / H)), 0.0)


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

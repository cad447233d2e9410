"""Discrete gusts for the rigid-airplane loads response.

The gust enters as an angle-of-attack increment carried by two pseudo-controls of a wrapper around the
airplane's aerodynamic model (the dynamics package is not changed): ``gust_wing`` (the gust angle at
the wing, U/V) and ``gust_tail`` (the same gust reaching the tail a tail-arm / V later). The wrapper adds

    ΔCL = CL_g,wing(M) · α_g,wing + CL_g,tail(M) · α_g,tail,   ΔCm likewise (about the model's reference),

with the per-surface lift and moment of a unit uniform angle of attack taken from the strip loads model
(the tail's value includes the wing's downwash, which convects with the gust and reaches the tail at
the same time). Aerodynamics are quasi-steady (no Küssner/Wagner lag: conservative for short gusts).
Inputs are held over each simulation step, so the step must resolve the gust (a few dozen per 2H/V).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.aero.interface import AeroState, Coefficients

GUST_CONTROLS = ("gust_wing", "gust_tail")


def one_minus_cosine(s, H, Uds):
    """Gust velocity at penetration s (m, array) of a 1 − cos gust of gradient H (m), peak Uds."""
    s = np.asarray(s, dtype=float)
    return np.where((s >= 0) & (s <= 2 * H), 0.5 * Uds * (1 - np.cos(np.pi * s / H)), 0.0)


@dataclass
class GustAero:
    """AeroModel wrapper adding the gust pseudo-controls. ``mach`` breakpoints and per-surface
    (CL, Cm) per radian of gust angle: ``cl_wing``, ``cm_wing``, ``cl_tail``, ``cm_tail`` (arrays)."""

    base: object
    mach: np.ndarray
    cl_wing: np.ndarray
    cm_wing: np.ndarray
    cl_tail: np.ndarray
    cm_tail: np.ndarray

    def __post_init__(self):
        self.reference = self.base.reference
        self.control_names = tuple(self.base.control_names) + GUST_CONTROLS
        ad = getattr(self.base, "alpha_dot_derivatives", None)
        if callable(ad):
            self.alpha_dot_derivatives = ad

    def coefficients(self, state: AeroState) -> Coefficients:
        ctrl = dict(state.controls)
        gw = np.asarray(ctrl.pop("gust_wing", 0.0), dtype=float)
        gt = np.asarray(ctrl.pop("gust_tail", 0.0), dtype=float)
        c = self.base.coefficients(AeroState(state.alpha, state.beta, state.p_hat, state.q_hat, state.r_hat, state.mach,
                                             ctrl, state.reynolds_per_metre))
        m = np.asarray(state.mach, dtype=float)
        f = lambda table: np.interp(m, self.mach, table)  # noqa: E731
        dcl = f(self.cl_wing) * gw + f(self.cl_tail) * gt
        dcm = f(self.cm_wing) * gw + f(self.cm_tail) * gt
        # the gust lift is taken normal to the gust-free relative wind (small gust angles)
        return Coefficients(CL=c.CL + dcl, CD=c.CD, CY=c.CY, Cl=c.Cl, Cm=c.Cm + dcm, Cn=c.Cn)


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

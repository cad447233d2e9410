"""Rigid-airplane response to a discrete 1 − cos lateral gust on the vertical tail, batched over conditions, with the
strip loads of the fin.

The gust is a sideslip increment β_g = v_g / V felt by the fin (positive: wind from the right, like β), carried by a
pseudo-control ``gust_fin`` added to the airplane's derivative model: per radian of β_g the side force, rolling and
yawing moments of the fin's own unit-sideslip loading in the strip loads model (its root shear, with the centre of
pressure from the root torsion (X) and the root bending (height)). The airplane then responds in yaw, sideslip and
roll to the fin's force alone — the dynamic model of the classical fin gust formula (Pratt-type: the fin's load
alleviated by the airplane's yawing response, its mass ratio built with the yaw radius of gyration and the fin arm);
the fuselage's and the wing's share of the gust are not modelled; the gust's sideslip builds up on the fin with
Küssner's function on its mean chord (:func:`certkit.models.loads.gust.penetration_lagged`), the motion's
aerodynamics are quasi-steady. The gust front reaches the fin at t = 0; one simulation per gradient H, as for
the vertical gusts (:mod:`certkit.models.loads.gust_response`), then ``settle`` seconds of free response.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.dynamics.simulate import Function
from certkit.models.loads.gust import penetration_lagged
from certkit.models.loads.gust_response import phase_into, phase_records, phase_times, two_phase_run, with_aero
from certkit.models.loads.response import response_load_parts

FIN = "vertical_tail"
CONTROL = "gust_fin"


def fin_gust_tables(loads, reference) -> dict[str, np.ndarray]:
    """Side force, rolling and yawing moment coefficients of the fin per radian of sideslip felt by the fin alone, one
    value per Mach breakpoint of the strip model, about the reference point (body axes: Y right, moments positive
    right wing down and nose right)."""
    fin = loads[FIN]
    k = fin.inputs.index("beta")
    side = fin.aero[:, k, 0, 0]  # root shear per unit q̄ and β: force along +Y
    bending, torsion = fin.aero[:, k, 1, 0], fin.aero[:, k, 2, 0]
    x_axis = float(np.interp(0.0, fin.strip_span, fin.strip_x))
    safe = np.where(np.abs(side) > 1e-12, side, 1.0)
    x_cp = x_axis - torsion / safe
    z_cp = fin.station_y[0] + bending / safe  # the fin's span is upward from its root
    S, b = reference.area, reference.span
    return {
        "mach": fin.mach,
        "CY": side / S,
        "Cl": side * (z_cp - reference.z_ref) / (S * b),
        "Cn": -side * (x_cp - reference.x_ref) / (S * b),
    }


@dataclass
class LateralGustBatch:
    model: object
    x0: np.ndarray
    u0: np.ndarray
    v_tas: np.ndarray


def lateral_gust_batch(loads, base_model, x0, u0) -> LateralGustBatch:
    """Wrap a trimmed batch's flight model with the fin's gust pseudo-control (zero in the trim)."""
    t = fin_gust_tables(loads, base_model.aero.reference)
    m = np.asarray(base_model.aero.mach, dtype=float)
    terms = {f"{c}_{CONTROL}": np.interp(m, t["mach"], t[c]) for c in ("CY", "Cl", "Cn")}
    model, u = with_aero(base_model, base_model.aero.with_control_terms(terms), u0)
    v = np.linalg.norm(np.asarray(x0, dtype=float)[:, 3:6], axis=1)
    return LateralGustBatch(model, np.asarray(x0, dtype=float), u, v)


def simulate_lateral_gust(
    loads,
    lb: LateralGustBatch,
    H: float,
    beta_peak,
    steps_per_gust: float,
    settle: float,
    max_step: float = 0.05,
    settle_step: float = 0.04,
):
    """One gust gradient ``H`` (m) for the batch; ``beta_peak`` (n,) the peak gust sideslip U_ds/V (signed), in the
    two phases of :func:`certkit.models.loads.gust_response.two_phase_run`. Returns (simulation, fin station loads
    (nt, n, 3, S), gust sideslip felt (nt, n))."""
    a = np.asarray(beta_peak, dtype=float) * np.ones(lb.x0.shape[0])
    v = lb.v_tas
    chord = loads[FIN].mean_chord

    def felt(t):  # the fin's gust sideslip with Küssner's penetration lag
        return penetration_lagged(v * t, H, a, chord)

    parts, sim, _ = two_phase_run(
        lb.model,
        lb.x0,
        lb.u0,
        H,
        v,
        np.zeros_like(v),
        {CONTROL: Function(felt, time_grid=True)},
        steps_per_gust,
        settle,
        max_step,
        settle_step,
    )
    nt, slices = phase_records(parts)
    hist = None
    for k, (part, (keep, rows)) in enumerate(zip(parts, slices)):  # loads per phase (rate derivatives in its step)
        beta_g = felt(phase_times(parts, k))
        aero, inertia = response_load_parts(loads, part, lb.model, (FIN,), extra_beta={FIN: beta_g})[FIN]
        hist = phase_into(hist, nt, keep, rows, aero, inertia)
    return sim, hist, felt(phase_times([sim], 0))

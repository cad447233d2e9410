"""Unsymmetrical wing air load (§25.349(b)): a fraction of a symmetric condition's wing air load removed on one
side, the unbalanced forces and moments reacted by the rigid airplane's inertia.

The symmetric condition gives, for the right wing half, the aerodynamic station loads A and the inertial ones I
(:func:`certkit.models.loads.response.response_load_parts`); the left half carries the same by symmetry. With the
full fraction f₁ on one side and f₂ on the other (100 % and 80 % in §25.349(b)), the air load removed is
ΔA = (1 − f₂) A on the reduced side (and (1 − f₁) A on the full side, zero for f₁ = 1). Taking the full side on the
right, the root of the half wing on the plane of symmetry at (Y₀, Z₀), its shear S, bending B and torsion T
(about the reference axis at X_ax) from ΔA:

* vertical force lost  ΔF = −S_full − S_red (upward positive), Δn_z = ΔF / (m g);
* rolling moment about the X axis, body axes (positive right wing down):  ΔL = −(M_full − M_red) with
  M = B + S (Y₀ cos Γ + Z₀ sin Γ), the moment of a half wing's normal forces about the plane of symmetry
  (exact for a plane half wing of dihedral Γ; cos Γ ≈ 1 is used: the root station lies near Y₀ = 0);
* pitching moment (nose up positive) ΔM = ΔF (X_cg − X_cp), X_cp = X_ax − T/S the removed load's centre;

reacted by Δn_z, ṗ = ΔL / I_xx and q̇ = ΔM / I_yy applied to both halves' strip masses (the left half as the
right half of the mirror image, ṗ of opposite sign). Products of inertia and the aerodynamic damping of the
starting roll are neglected (the roll rate is zero at the instant). Signs of the inertial terms are those of
:class:`certkit.models.loads.model.SurfaceLoads`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.models.loads.model import SurfaceLoads
from certkit.units import G0


@dataclass
class UnsymmetricalLoads:
    """Station loads (…, 3, S) of the full and the reduced side, and the reacting accelerations (…)."""

    full: np.ndarray
    reduced: np.ndarray
    delta_n_z: np.ndarray  # load factor change from the air load removed
    pdot: np.ndarray  # rad/s², body axes, the full side being the right wing (negative: full side rises)
    qdot: np.ndarray  # rad/s², nose up positive
    rolling_moment: np.ndarray  # N·m, body axes, unbalanced aerodynamic rolling moment


def _require_root_station(loads: SurfaceLoads, name: str, what: str) -> None:
    """The unbalanced moments of an unsymmetrical loading are taken at the root: refuse a surface without a root
    station (``what``: "moment needs" or "moments need", for the message)."""
    if loads.station_span[0] > 1e-9:
        raise ValueError(
            f"the {name}'s first load station is {loads.station_span[0]:.3f} m from its root: the "
            f"unbalanced {what} the root station"
        )


def half_wing_moment(wing: SurfaceLoads, loads: np.ndarray) -> np.ndarray:
    """Moment (N·m) of a half wing's normal loads about the plane of symmetry: root bending + root shear × root Y."""
    return loads[..., 1, 0] + loads[..., 0, 0] * wing.station_y[0]


def unsymmetrical_wing(
    wing: SurfaceLoads,
    aero: np.ndarray,
    inertia: np.ndarray,
    mass,
    cg,
    inertia_tensor,
    full: float = 1.0,
    reduced: float = 0.8,
    trim_aero: np.ndarray | None = None,
) -> UnsymmetricalLoads:
    """The full- and reduced-side loads of one half wing from a symmetric condition.

    ``aero``, ``inertia``: (…, n, 3, S) aerodynamic and inertial station loads of the symmetric condition (any
    leading time axis); ``mass`` (n,) kg, ``cg`` (n, 3) airplane frame (X aft, Z up), ``inertia_tensor``
    (n, 3, 3) body axes. ``trim_aero`` (n, 3, S): when given, the fractions apply to the air load's increment
    over it (the gust increment) instead of the whole air load."""
    _require_root_station(wing, "wing", "moments need")
    base = 0.0 if trim_aero is None else trim_aero
    varying = aero - base
    removed_full = (1.0 - full) * varying
    removed_red = (1.0 - reduced) * varying
    s_lost = removed_full[..., 0, 0] + removed_red[..., 0, 0]
    d_force = -s_lost  # upward force change, N
    d_nz = d_force / (np.asarray(mass) * G0)
    roll = -(half_wing_moment(wing, removed_red) - half_wing_moment(wing, removed_full))
    # the removed load: shear S at the reference axis X_ax of the root, torsion T = Σ N (X_ax − X) → X_cp = X_ax − T/S
    x_axis = float(np.interp(0.0, wing.strip_span, wing.strip_x))
    t_lost = removed_full[..., 2, 0] + removed_red[..., 2, 0]
    x_cp = x_axis - np.divide(t_lost, s_lost, out=np.zeros_like(t_lost), where=np.abs(s_lost) > 1e-9)
    xcg, zcg = np.asarray(cg)[:, 0], np.asarray(cg)[:, 2]
    pitch = np.where(np.abs(s_lost) > 1e-9, d_force * (xcg - x_cp), 0.0)
    J = np.asarray(inertia_tensor)
    pdot = roll / J[:, 0, 0]
    qdot = pitch / J[:, 1, 1]

    def react(p):
        return wing.inertia_loads({"n_z": d_nz, "qdot": qdot, "qdot_xcg": qdot * xcg, "pdot": p, "pdot_zcg": p * zcg})

    full_side = aero - removed_full + inertia + react(pdot)
    reduced_side = aero - removed_red + inertia + react(-pdot)
    return UnsymmetricalLoads(full_side, reduced_side, d_nz, pdot, qdot, roll)


@dataclass
class UnsymmetricalTail:
    """Station loads (…, 3, S) of the two tailplane halves and the torsion they put into the fuselage (…)."""

    full: np.ndarray
    reduced: np.ndarray
    fuselage_torsion: np.ndarray  # N·m about the X axis, positive when the full side is the right half pushed up


def unsymmetrical_tail(
    tail: SurfaceLoads, aero: np.ndarray, inertia: np.ndarray, full: float = 1.0, reduced: float = 0.8
) -> UnsymmetricalTail:
    """A symmetric tail loading split ``full`` on one half and ``reduced`` on the other (§25.427(b)): each half's air
    load A scaled by its fraction, its inertial load I unchanged (the airplane's state is the symmetric one); the
    unbalanced rolling moment of the two halves' air loads about the plane of symmetry — each half's root bending +
    root shear × root Y (:func:`half_wing_moment`) — goes into the fuselage as torsion at the tail (the tail's own
    roll inertia relief neglected, conservative). ``aero``, ``inertia``: (…, 3, S) of the right half."""
    _require_root_station(tail, "tailplane", "moment needs")
    return UnsymmetricalTail(
        full * aero + inertia, reduced * aero + inertia, (full - reduced) * half_wing_moment(tail, aero)
    )


def unsymmetrical_tail_peaks(
    tail: SurfaceLoads, aero: np.ndarray, inertia: np.ndarray, full: float = 1.0, reduced: float = 0.8
):
    """The extremes over the leading (time) axis of :func:`unsymmetrical_tail`'s loads, NaN entries ignored:
    (full-side peaks (…, 2, 3, S) min then max, reduced-side peaks, fuselage torsion min (…), max (…)), without
    keeping the split histories (one work array)."""
    _require_root_station(tail, "tailplane", "moment needs")
    work = np.empty(np.broadcast_shapes(aero.shape, inertia.shape))
    peaks = []
    for fraction in (full, reduced):
        np.multiply(aero, fraction, out=work)
        work += inertia
        peaks.append(np.stack([np.fmin.reduce(work, axis=0), np.fmax.reduce(work, axis=0)], axis=-3))
    torsion = (full - reduced) * half_wing_moment(tail, aero)
    return peaks[0], peaks[1], np.fmin.reduce(torsion, axis=0), np.fmax.reduce(torsion, axis=0)

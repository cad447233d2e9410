"""The horizontal tail in the wing's downwash, from the vortex lattice: the downwash lag (C_Lα̇, C_mα̇) and the
tail's share of the flap increments.

Both come from splitting the lattice's Kutta–Joukowski forces by surface (bound legs, per unit dynamic pressure,
coefficients on the airplane's reference area and chord, moments about its moment point) and differentiating
them by central differences (the lattice is linear in α and δ; the forces are quadratic, so the central
difference is exact up to the trigonometry of α).

Downwash lag (Etkin & Reid, *Dynamics of Flight*, 3rd ed., 1996, ch. 5, the α̇ derivatives; Roskam, *Airplane
Flight Dynamics and Automatic Flight Controls*, Part I, 1995, ch. 4: C_Lα̇ = 2 a_t η V_H dε/dα,
C_mα̇ = −2 a_t η V_H (l_t/c̄) dε/dα). The downwash at the tail is that of the wing's vorticity shed
Δt = l/V earlier, l the path from the wing's lift centre to the tail's, so the tail sees
Δα_t = (dε/dα) α̇ l / V more than in steady flight at the same α:

    C_Lα̇ = 2 (l/c̄) (dε/dα) C_Lα,t      C_mα̇ = 2 (l/c̄) (dε/dα) C_mα,t        (per unit α̇ c̄/2V)

with C_Lα,t, C_mα,t the isolated tail's lift and moment slopes on the airplane's reference (a_t S_t/S and
−a_t S_t/S · l_t/c̄ about the moment point; the lattice has no wake loss, η = 1) and
dε/dα = 1 − C_Lα,t(with the wing)/C_Lα,t(isolated), the mean downwash gradient the lattice's tail feels.

The downwash gradient comes from a lattice finer across the wing's span than the airplane's (the tail sits close
to the wing's trailing-vortex sheet and its lift converges only with narrow wing strips: on the baseline, dε/dα
0.451 with 20 strips per half-wing, 0.387 with 40, 0.373 with 60, 0.369 with 120; the flap ratio below 0.188, 0.131,
0.120, 0.117), solved once at the lowest Mach number; at the others it scales with the wing's lift slope
(DATCOM §4.4.1: (dε/dα)_M = (dε/dα)_low C_Lα,w(M)/C_Lα,w,low).

Free-air downwash for the ground effect at the tail (:mod:`certkit.models.aero.tail_ground_effect`): ε = ε₀ + (dε/dα) α
from the same lattice, ε₀ = −(C_L,t(with the wing) − C_L,t(isolated))/C_Lα,t at α = 0 (:func:`free_air_downwash`).

Flap at the tail: the change of the tail's lift and moment per unit of the wing's flap lift increment,
(ΔC_L,t / ΔC_L,w, ΔC_m,t / ΔC_L,w) from the lattice with the flap deflected. The downwash is linear in the wing's
circulation, so this ratio carries the lattice's tail response to a flap increment estimated or declared by
another method (the lattice's own increment is linear theory and overestimates large deflections).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

#: central-difference step in α and in the flap angle (rad)
STEP = 1e-3
WING = ("wing",)
TAIL = ("horizontal_tail",)


def _vortex_mask(vl, names) -> np.ndarray:
    """Vortices of the named surfaces (their mirror images included)."""
    lat = vl.lattice
    strip_on = np.zeros(lat.n_strips, dtype=bool)
    for p in lat.patches:
        if p.name.removesuffix(" (YDUP)") in names:
            strip_on[p.strips] = True
    return strip_on[lat.vortex_strip]


def surface_coefficients(vl, names, alpha: float = 0.0, controls=None) -> tuple[float, float]:
    """(C_L, C_m) of the named surfaces' bound-leg forces at ``alpha`` (airplane reference area and chord,
    moment about the reference point)."""
    f = vl.vortex_forces(alpha=alpha, controls=controls)
    on = _vortex_mask(vl, names)
    ref = vl.reference
    r = vl.lattice.rv[on] - np.array([ref.x_ref, 0.0, ref.z_ref])
    fx, fz = f[on, 0].sum(), f[on, 2].sum()
    my = float(np.sum(r[:, 2] * f[on, 0] - r[:, 0] * f[on, 2]))
    lift = -fx * np.sin(alpha) + fz * np.cos(alpha)
    return float(lift) / ref.area, my / (ref.area * ref.chord)


def slopes(vl, names, controls_of=None) -> tuple[float, float]:
    """(∂C_L/∂x, ∂C_m/∂x) of the named surfaces at α = 0, x = α, or the flap angle when ``controls_of`` names
    the control."""
    if controls_of is None:
        plus, minus = surface_coefficients(vl, names, STEP), surface_coefficients(vl, names, -STEP)
    else:
        plus = surface_coefficients(vl, names, 0.0, {controls_of: STEP})
        minus = surface_coefficients(vl, names, 0.0, {controls_of: -STEP})
    return (plus[0] - minus[0]) / (2 * STEP), (plus[1] - minus[1]) / (2 * STEP)


def lift_centre(vl, names) -> float:
    """X (geometry frame, m) of the named surfaces' lift due to α: x_ref − c̄ C_mα/C_Lα."""
    cl_a, cm_a = slopes(vl, names)
    return vl.reference.x_ref - vl.reference.chord * cm_a / cl_a


def downwash_gradient(airplane_vl, tail_vl) -> float:
    """dε/dα: 1 − the tail's lift slope in the lattice with the wing over that of the isolated tail (same panels,
    same Mach)."""
    return 1.0 - slopes(airplane_vl, TAIL)[0] / slopes(tail_vl, TAIL)[0]


@dataclass(frozen=True)
class FreeAirDownwash:
    """The free-air downwash at the tail, ε = ``epsilon0`` + ``gradient`` α (rad, body α), and the isolated tail's lift
    and moment slopes (airplane reference, moment about its reference point, per rad): what the ground effect at the
    tail changes (:mod:`certkit.models.aero.tail_ground_effect`)."""

    epsilon0: float
    gradient: float
    lift_slope: float
    moment_slope: float

    def with_flap(self, tail_CL: float) -> "FreeAirDownwash":
        """The same with the downwash of a flap whose tail lift share is ``tail_CL`` (Δε = −ΔC_L,t/C_Lα,t)."""
        return replace(self, epsilon0=self.epsilon0 - tail_CL / self.lift_slope)


def free_air_downwash(airplane_vl, tail_vl) -> FreeAirDownwash:
    """:class:`FreeAirDownwash` of the wing-and-tail lattice and the isolated tail's (same Mach, same panels)."""
    cl_t, cm_t = slopes(tail_vl, TAIL)
    eps0 = -(surface_coefficients(airplane_vl, TAIL)[0] - surface_coefficients(tail_vl, TAIL)[0]) / cl_t
    return FreeAirDownwash(float(eps0), downwash_gradient(airplane_vl, tail_vl), cl_t, cm_t)


@dataclass(frozen=True)
class DownwashLag:
    """The α̇ derivatives (per unit α̇ c̄/2V) and what they are made of."""

    CL_alphadot: float
    Cm_alphadot: float
    downwash_gradient: float  # dε/dα at the tail
    tail_lift_slope: float  # isolated tail, airplane reference area, per rad
    lag_distance: float  # m, wing lift centre to tail lift centre


def downwash_lag(gradient: float, airplane_vl, tail_vl) -> DownwashLag:
    """The downwash-lag derivatives for the downwash gradient ``gradient`` at the tail, the wing's lift centre from
    the airplane's lattice and the isolated horizontal tail's slopes and lift centre (same Mach)."""
    cl_t, cm_t = slopes(tail_vl, TAIL)
    lag = lift_centre(tail_vl, TAIL) - lift_centre(airplane_vl, WING)
    k = 2.0 * lag / airplane_vl.reference.chord * gradient
    return DownwashLag(k * cl_t, k * cm_t, gradient, cl_t, lag)


@dataclass(frozen=True)
class FlapAtTail:
    """Per radian of flap (lattice, linear theory): the wing's lift increment, the tail's lift and moment
    increments; and their ratios to the wing's, which scale any flap lift increment."""

    wing_CL: float
    tail_CL: float
    tail_Cm: float
    tail_lift_slope: float  # isolated tail, airplane reference area, per rad

    @property
    def CL_per_wing_CL(self) -> float:
        return self.tail_CL / self.wing_CL

    @property
    def Cm_per_wing_CL(self) -> float:
        return self.tail_Cm / self.wing_CL

    @property
    def downwash_per_wing_CL(self) -> float:
        """Δε/ΔC_L,w: the mean downwash change at the tail per unit flap lift of the wing (rad)."""
        return -self.tail_CL / (self.tail_lift_slope * self.wing_CL)


def flap_at_tail(flapped_vl, tail_vl, flap: str) -> FlapAtTail:
    """The flap's effect at the tail from a lattice of the wing (with the flap as control ``flap``) and the tail,
    and the isolated tail's lattice (same Mach)."""
    wing_cl, _ = slopes(flapped_vl, WING, flap)
    tail_cl, tail_cm = slopes(flapped_vl, TAIL, flap)
    return FlapAtTail(wing_cl, tail_cl, tail_cm, slopes(tail_vl, TAIL)[0])

"""Boeing 747 at Mach 0.8, 40 000 ft from Etkin & Reid, *Dynamics of Flight: Stability and
Control*, 3rd ed., Wiley 1996, §6.2 (longitudinal, Table 6.2 p. 166) and §6.8 (lateral): the
dimensional stability derivatives in SI, converted here to the non-dimensional derivatives the
StabilityDerivativeModel takes (the conversions are Etkin's Table 4.4 formulas for stability axes,
θ0 = 0). The numbers were checked against the MIT 16.333 (J. P. How, 2004) and Stanford AA271a
course scripts that reproduce Etkin's example.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from certkit import atmosphere as isa
from certkit.models.aero.derivative_model import StabilityDerivativeModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel, Engine, inertia_tensor

# flight condition and airplane (Etkin & Reid Table 6.2 / §6.8)
RHO = 0.3045  # kg/m³
U0 = 235.9  # m/s
W = 2.83176e6  # N
G = 9.81  # Etkin's g
S, CBAR, B = 511.0, 8.324, 59.64
IX, IY, IZ, IZX = 0.247e8, 0.449e8, 0.673e8, -0.212e7  # kg m², stability axes
CD_TRIM = 0.043  # Etkin Table 6.1 (only the combinations below matter)

# dimensional derivatives, SI (Etkin & Reid Table 6.2 and §6.8)
XU, XW = -1.982e3, 4.025e3
ZU, ZW, ZQ, ZWD = -2.595e4, -9.030e4, -4.524e5, 1.909e3
MU, MW, MQ, MWD = 1.593e4, -1.563e5, -1.521e7, -1.702e4
YV, LV, LP, LR = -1.610e4, -3.062e5, -1.076e7, 9.925e6
NV, NP, NR = 2.131e5, -1.330e6, -8.934e6
# control derivatives (non-dimensional, Etkin & Reid §6.2, §7.x as used in the course scripts)
CL_DE, CM_DE = 0.3648, -1.444
CY_DR, CL_DA, CL_DR, CN_DA, CN_DR = 0.1146, -1.368e-2, 6.976e-3, -1.973e-4, -0.1257

# published eigenvalues
LON_SHORT_PERIOD = complex(-0.3719, 0.8875)  # Etkin & Reid §6.2
LON_PHUGOID = complex(-0.003289, 0.06723)  # Etkin & Reid §6.2
LAT_ROLL = -0.562  # Etkin & Reid §6.8 ("the true value −0.562")
LAT_SPIRAL_APPROX = -0.00734  # Etkin & Reid §6.8, McRuer approximation, "within about 1 %" of the true root
# Not quoted: the book's Dutch-roll pair and exact spiral root (§6.8). No reachable copy of §6.8 or faithful
# transcription was found (search of 2026-12-02: MIT 16.333 and other course scripts, GitHub transcriptions,
# web-page and documentation corpora); the Dutch roll is checked against Etkin's linear equations instead.


def altitude() -> float:
    """ISA altitude at which the density is Etkin's 0.3045 kg/m³ (≈ 12.19 km)."""
    return brentq(lambda h: float(isa.density(h)) - RHO, 10_000.0, 14_000.0)


def build(n: int = 1, mach_effects: bool = True, cd: float | None = None):
    """The 747 model; ``mach_effects=False`` drops the speed derivatives (CL_M, CD_M, Cm_M) and
    ``cd`` overrides the drag coefficient (for the Lanchester-phugoid check)."""
    h = altitude()
    a = float(isa.speed_of_sound(h))
    M0 = U0 / a
    Q = 0.5 * RHO * U0**2 * S
    K = Q / U0  # ½ ρ u0 S
    CL = W / Q
    d = {
        "CL_alpha": -ZW / K - CD_TRIM,
        "CD_alpha": CL - XW / K,
        "Cm_alpha": MW / (K * CBAR),
        "CL_q": -ZQ / (K * CBAR / 2),
        "Cm_q": MQ / (K * CBAR * CBAR / 2),
        "CL_alphadot": -ZWD * 2 * U0 / (K * CBAR),
        "Cm_alphadot": MWD * 2 * U0 / (K * CBAR * CBAR),
        "CY_beta": YV / K,
        "Cl_beta": LV / (K * B),
        "Cn_beta": NV / (K * B),
        "Cl_p": LP / (K * B * B / 2),
        "Cl_r": LR / (K * B * B / 2),
        "Cn_p": NP / (K * B * B / 2),
        "Cn_r": NR / (K * B * B / 2),
        "CL_elevator": CL_DE,
        "Cm_elevator": CM_DE,
        "Cl_aileron": CL_DA,
        "Cn_aileron": CN_DA,
        "CY_rudder": CY_DR,
        "Cl_rudder": CL_DR,
        "Cn_rudder": CN_DR,
    }
    # speed derivatives through the Mach dependence: X_u = K(−2 CD − M CD_M), Z_u = K(−2 CL − M CL_M),
    # M_u = K c M Cm_M (Cm = 0 in trim)
    CD_M = (-XU / K - 2 * CD_TRIM) / M0
    CL_M = (-ZU / K - 2 * CL) / M0
    Cm_M = MU / (K * CBAR) / M0
    if not mach_effects:
        CD_M = CL_M = Cm_M = 0.0
    mach = np.array([M0 - 0.05, M0 + 0.05])
    d["CL0"] = CL + CL_M * (mach - M0)
    d["CD0"] = (CD_TRIM if cd is None else cd) + CD_M * (mach - M0)
    d["Cm0"] = Cm_M * (mach - M0)
    aero = StabilityDerivativeModel(
        AeroReference(S, B, CBAR, x_ref=30.0), d, mach=mach, control_names=("elevator", "aileron", "rudder")
    )
    thrust_max = 4 * 2.0e5
    engine = Engine("all", thrust=lambda thr, hh, m: thr * thrust_max, position=(30.0, 0.0, 0.0))
    model = AircraftModel(
        aero, mass=W / G, cg=(30.0, 0.0, 0.0), inertia=inertia_tensor(IX, IY, IZ, IZX), engines=[engine], g=G, n=n
    )
    return model, h

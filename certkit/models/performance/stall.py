"""Stall speeds and stall-limited load factors (1-g, equivalent airspeed).

From the lift equation, n W = ½ ρ₀ V_E² S C_N: the 1-g stall speed V_S = √(2 W / (ρ₀ S C_Nmax))
and the stall-limited load factor n(V_E) = (V_E / V_S)². Arrays of weights and speeds broadcast.
"""

from __future__ import annotations

import numpy as np

from certkit.atmosphere import RHO0
from certkit.units import G0


def stall_speed_eas(mass, area, cn_max):
    """1-g stall speed (m/s EAS) for ``mass`` (kg), wing area (m²) and maximum normal-force coefficient."""
    cn_max = np.asarray(cn_max, dtype=float)
    if np.any(cn_max == 0):
        raise ValueError("maximum normal-force coefficient must not be zero")
    return np.sqrt(2.0 * np.asarray(mass, dtype=float) * G0 / (RHO0 * area * np.abs(cn_max)))


def stall_load_factor(speed_eas, mass, area, cn):
    """Load factor reachable at ``speed_eas`` with normal-force coefficient ``cn`` (signed)."""
    return (
        0.5
        * RHO0
        * np.asarray(speed_eas, dtype=float) ** 2
        * area
        * np.asarray(cn, dtype=float)
        / (np.asarray(mass, dtype=float) * G0)
    )

"""Gust criteria shared by §25.335(a), §25.335(d) and §25.341(a) (regulation content).

§25.341(a)(5)(i), Amdt. 25-141: reference gust velocity U_ref 56.0 ft/s EAS at sea level, reduced
linearly to 44.0 ft/s EAS at 15,000 ft and further to 20.86 ft/s EAS at 60,000 ft.
§25.341(a)(5)(ii): at VD, 0.5 × that value.
"""

from __future__ import annotations

import numpy as np

from certkit.units import FT

#: (altitude m, U_ref m/s EAS) break points of §25.341(a)(5)(i)
UREF_TABLE = ((0.0, 56.0 * FT), (15_000 * FT, 44.0 * FT), (60_000 * FT, 20.86 * FT))
SOURCE = "14 CFR 25.341(a)(5)(i), Amdt. 25-141"


def reference_gust_velocity(altitude, at_vd: bool = False):
    """U_ref (m/s EAS) at ``altitude`` (m); half of it at VD (§25.341(a)(5)(ii))."""
    h = np.asarray(altitude, dtype=float)
    if np.any(h < 0) or np.any(h > UREF_TABLE[-1][0]):
        raise ValueError("§25.341(a)(5) defines U_ref from sea level to 60,000 ft only")
    alt, u = zip(*UREF_TABLE)
    value = np.interp(h, alt, u)
    return 0.5 * value if at_vd else value

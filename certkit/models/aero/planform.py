"""Trapezoidal planform relations and the semi-empirical wing lift-curve slope.

References: Raymer, *Aircraft Design: A Conceptual Approach*, 6th ed., §12.4 (eq. 12.6, the
DATCOM/Polhamus lift-curve slope); USAF DATCOM §1.2.2 (mean aerodynamic chord and sweep relations).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike


def span(area: Any, aspect_ratio: Any) -> Any:
    """Span (or, for a fin, height when ``aspect_ratio`` = h²/S)."""
    return np.sqrt(aspect_ratio * area)


def root_chord(area: Any, aspect_ratio: Any, taper: Any) -> Any:
    return 2.0 * area / (span(area, aspect_ratio) * (1.0 + taper))


def mean_aerodynamic_chord(area: Any, aspect_ratio: Any, taper: Any) -> Any:
    """c̄ = 2/3 c_r (1 + λ + λ²)/(1 + λ)."""
    return 2.0 / 3.0 * root_chord(area, aspect_ratio, taper) * (1 + taper + taper**2) / (1 + taper)


def mac_spanwise_position(area: Any, aspect_ratio: Any, taper: Any) -> Any:
    """Spanwise station of the MAC from the root: y = b/6 (1 + 2λ)/(1 + λ)."""
    return span(area, aspect_ratio) / 6.0 * (1 + 2 * taper) / (1 + taper)


def sweep_at(fraction: float, sweep_quarter_chord: float, aspect_ratio: float, taper: float) -> float:
    """Sweep of the ``fraction``-chord line from the quarter-chord sweep (full-span aspect ratio):
    tan Λ_f = tan Λ_c/4 − 4/A (f − 1/4)(1 − λ)/(1 + λ)."""
    return float(
        np.arctan(np.tan(sweep_quarter_chord) - 4.0 / aspect_ratio * (fraction - 0.25) * (1 - taper) / (1 + taper))
    )


def lift_curve_slope(
    aspect_ratio: float, sweep_half_chord: float, mach: ArrayLike, airfoil_efficiency: float = 0.95
) -> Any:
    """Wing lift-curve slope per radian, DATCOM/Polhamus (Raymer eq. 12.6, without fuselage factor):
    a = 2πA / (2 + √(4 + A²β²/η² (1 + tan²Λ_½/β²))), β² = 1 − M²."""
    beta2 = 1.0 - np.asarray(mach, dtype=float) ** 2
    if np.any(beta2 <= 0):
        raise ValueError("the DATCOM lift-curve slope applies to subsonic Mach numbers only")
    a = aspect_ratio
    return (
        2
        * np.pi
        * a
        / (2 + np.sqrt(4 + a**2 * beta2 / airfoil_efficiency**2 * (1 + np.tan(sweep_half_chord) ** 2 / beta2)))
    )

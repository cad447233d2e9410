"""Fuselage contributions to the static stability derivatives Cm_α, Cn_β and CY_β (per radian).

Conventions of :mod:`certkit.conventions`: Cm nose up positive, Cn nose right positive, β positive
with the wind from the right; coefficients on the wing reference area, c̄ and span. A fuselage is
destabilising in both: ΔCm_α > 0 and ΔCn_β < 0.

Pitch — Gilruth & White (NACA Report 711, 1941) in the form of Raymer, *Aircraft Design: A
Conceptual Approach*, 6th ed., eq. 16.25:
    ΔCm_α = K_f W_f² L_f / (c̄ S)   per degree  (× 180/π here, per radian),
with K_f read from Raymer Fig. 16.14 against the station of the wing root quarter chord as a
fraction of the body length (the theoretical root chord on the centreline). The table below is
that figure as digitised in FAST-GA (ONERA/ISAE-SUPAERO, ``k_fus_regression.py``), every second
point, interpolated linearly; the figure covers 10 % to 62 % of the body length.

Yaw — Raymer eq. 16.50: ΔCn_β = −1.3 V_f/(S b) · (D_f/W_f) per radian, with D_f the depth and W_f
the width of the fuselage. The volume is not in the aircraft file; it is estimated for a cylinder
with a 1.5 D half-ellipsoid nose and a 3 D paraboloid tail cone, which gives
V_f = (π/4) W_f D_f L_f (1 − 2/λ), λ = L_f/√(W_f D_f).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from certkit.aircraft.model import Geometry, Reference
from certkit.models.aero import planform

#: Raymer Fig. 16.14: root quarter-chord station / body length → K_f (per degree).
K_F_STATION = np.array(
    [
        0.0976,
        0.1374,
        0.1910,
        0.2415,
        0.2919,
        0.3236,
        0.3496,
        0.3797,
        0.4049,
        0.4366,
        0.4683,
        0.5065,
        0.5537,
        0.5894,
        0.6211,
    ]
)
K_F_PER_DEG = np.array(
    [
        0.00492,
        0.00541,
        0.00631,
        0.00787,
        0.00992,
        0.01172,
        0.01361,
        0.01623,
        0.01869,
        0.02238,
        0.02656,
        0.03213,
        0.03992,
        0.04615,
        0.05230,
    ]
)


def pitching_moment_factor(station_fraction):
    """K_f (per degree) of Raymer Fig. 16.14; outside the figure's 10–62 % it is an error."""
    x = np.asarray(station_fraction, dtype=float)
    if np.any(x < K_F_STATION[0] - 1e-9) or np.any(x > K_F_STATION[-1] + 1e-9):
        raise ValueError(
            f"wing root quarter chord at {np.min(x):.3f}–{np.max(x):.3f} of the body length: "
            f"Raymer Fig. 16.14 covers {K_F_STATION[0]:.2f}–{K_F_STATION[-1]:.2f}"
        )
    return np.interp(x, K_F_STATION, K_F_PER_DEG)


def cm_alpha_fuselage(length, width, root_quarter_chord_station, reference_area, mean_chord):
    """ΔCm_α (per radian) = K_f W² L / (c̄ S) · 180/π, Raymer eq. 16.25 (Gilruth & White)."""
    k_f = pitching_moment_factor(np.asarray(root_quarter_chord_station, dtype=float) / length)
    return np.degrees(k_f * width**2 * length / (mean_chord * reference_area))


def fuselage_volume(length, width, depth):
    """(π/4) W D L (1 − 2/λ): cylinder with a 1.5 D half-ellipsoid nose and a 3 D paraboloid tail."""
    d = np.sqrt(width * depth)
    return np.pi / 4.0 * width * depth * length * (1.0 - 2.0 * d / length)


def cy_beta_fuselage(depth, width, reference_area, interference=1.0):
    """ΔCY_β (per radian) = −2 K_i S_0/S (USAF DATCOM §5.2.1.1, Roskam Part VI eq. 10.28), S_0 the
    body's maximum cross-section (an ellipse of the fuselage width and depth); K_i, the wing–body
    interference factor of the DATCOM figure (1 mid wing, larger for low and high wings), is 1 here:
    the figure is not digitised in certkit, so the side force of low- and high-wing bodies is on the
    small side."""
    return -2.0 * interference * (np.pi / 4.0 * width * depth) / reference_area


def cn_beta_fuselage(volume, depth, width, reference_area, span):
    """ΔCn_β (per radian) = −1.3 V/(S b) · D/W, Raymer eq. 16.50."""
    return -1.3 * volume / (reference_area * span) * depth / width


@dataclass(frozen=True)
class FuselageDerivatives:
    """Fuselage increments (per radian) and the intermediate values a report shows."""

    Cm_alpha: float
    Cn_beta: float
    CY_beta: float
    K_f: float
    root_quarter_chord_fraction: float
    volume: float


def wing_root_quarter_chord_station(geometry: Geometry) -> float:
    """X (m) of the quarter chord of the wing's theoretical root chord."""
    w = geometry.wing
    return w.root_leading_edge.x + 0.25 * float(planform.root_chord(w.area, w.aspect_ratio, w.taper))


def fuselage_derivatives(geometry: Geometry, reference: Reference) -> FuselageDerivatives:
    """ΔCm_α and ΔCn_β of the fuselage for the aircraft-file geometry and reference values."""
    f = geometry.fuselage
    x_qc = wing_root_quarter_chord_station(geometry)
    volume = float(fuselage_volume(f.length, f.width, f.height))
    return FuselageDerivatives(
        Cm_alpha=float(cm_alpha_fuselage(f.length, f.width, x_qc, reference.area, reference.mean_chord)),
        Cn_beta=float(cn_beta_fuselage(volume, f.height, f.width, reference.area, reference.span)),
        CY_beta=float(cy_beta_fuselage(f.height, f.width, reference.area)),
        K_f=float(pitching_moment_factor(x_qc / f.length)),
        root_quarter_chord_fraction=x_qc / f.length,
        volume=volume,
    )


__all__ = [
    "K_F_STATION",
    "K_F_PER_DEG",
    "pitching_moment_factor",
    "cm_alpha_fuselage",
    "fuselage_volume",
    "cn_beta_fuselage",
    "cy_beta_fuselage",
    "FuselageDerivatives",
    "wing_root_quarter_chord_station",
    "fuselage_derivatives",
]

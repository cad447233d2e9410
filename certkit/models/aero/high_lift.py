"""High-lift estimates when the aircraft file declares none (Raymer, *Aircraft Design*, 6th ed., §12.4.4).

* Maximum lift, clean: C_Lmax = 0.9 c_lmax cos Λ_c/4 (Raymer eq. 12.15 form for high-aspect-ratio
  swept wings), c_lmax of the section from its thickness (NACA 4-digit sections at Re ≈ 6·10⁶,
  Abbott & von Doenhoff: about 1.3 at t/c 0.09 rising to 1.6 at t/c 0.12-0.15).
* Flap and slat increment of maximum lift: ΔC_Lmax = 0.9 Δc_lmax (S_flapped / S_ref) cos Λ_HL
  (Raymer eq. 12.21) with Δc_lmax of Raymer Table 12.2 (plain/split 0.9, slotted 1.3, double
  slotted 1.6 c'/c, Fowler 1.3 c'/c, slat 0.4 c'/c, Krueger 0.3) at the landing setting; at a takeoff setting
  60–80 % of it (Raymer §12.4.7: 70 % taken).
* Zero-lift angle shift: Δα_L=0 = Δα_L=0,2D (S_flapped/S_ref) cos Λ_HL (Raymer eq. 12.22), the 2-D change about
  −15° at the landing setting and −10° at the takeoff setting (Raymer §12.4.7, 6th ed. p. 415), so
  ΔC_L0 = −C_Lα Δα_L=0.
* The settings are the airplane's own: the flap deflections of the aircraft file's ``takeoff`` and ``landing``
  configurations (:class:`FlapSettings`). Between them the increments go linearly from the takeoff value to the
  landing value (an approach setting); below the takeoff setting in proportion to the deflection; at and beyond the
  landing setting the landing value. Without a declared takeoff setting the increments scale with the deflection up
  to the landing setting (40° without a declared landing configuration).
* Flap pitching moment: the flap increment acts at half the local chord (thin-airfoil theory puts the
  centre of a trailing-edge flap's load between c/4 and c/2, Abbott & von Doenhoff §8.2), at the
  flapped span's centroid: ΔC_m0 = −ΔC_L0 (x_flap − x_ref)/c̄.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from certkit.models.aero import planform

if TYPE_CHECKING:
    from certkit.aircraft.model import Configuration, HighLiftDevice, LiftingSurface

DELTA_CLMAX_SECTION = {
    "plain": 0.9,
    "split": 0.9,
    "slotted": 1.3,
    "double_slotted": 1.6,
    "fowler": 1.3,
    "slat": 0.4,
    "krueger": 0.3,
}
#: types whose Δc_lmax multiplies the extended-chord ratio c'/c (Raymer Table 12.2)
CHORD_SCALED = {"double_slotted", "fowler", "slat"}
#: the landing setting when the aircraft file declares no ``landing`` configuration
LANDING_DEFLECTION = np.radians(40.0)
#: 2-D zero-lift angle change of a trailing-edge flap (Raymer §12.4.7, 6th ed. p. 415: "≈ −15 deg at landing setting,
#: −10 deg at takeoff setting")
ALPHA0_SHIFT_LANDING = np.radians(-15.0)
ALPHA0_SHIFT_TAKEOFF = np.radians(-10.0)
#: Δc_lmax at a takeoff setting as a share of the landing setting's (Raymer §12.4.7: "60–80 %"; the middle taken)
CLMAX_SHARE_TAKEOFF = 0.7


@dataclass(frozen=True)
class FlapSettings:
    """The airplane's takeoff and landing flap deflections (rad): Raymer's "takeoff setting" and "landing setting"
    (``takeoff`` None: none declared)."""

    takeoff: float | None = None
    landing: float = float(LANDING_DEFLECTION)

    @classmethod
    def of(cls, configurations: Mapping[str, Configuration]) -> FlapSettings:
        """The settings of an aircraft file's ``configurations`` (its ``takeoff`` and ``landing`` flap deflections;
        a takeoff deflection not below the landing one is not a separate setting)."""
        landing = configurations.get("landing")
        takeoff = configurations.get("takeoff")
        d_ldg = landing.flap if landing is not None and landing.flap > 0 else float(LANDING_DEFLECTION)
        d_to = takeoff.flap if takeoff is not None and 0 < takeoff.flap < d_ldg else None
        return cls(d_to, d_ldg)

    def share(self, deflection: float, takeoff_share: float) -> float:
        """The increment at ``deflection`` as a share of the landing setting's, ``takeoff_share`` at the takeoff
        setting: in proportion to the deflection below it, linear from it to the landing setting, 1 beyond."""
        d = max(float(deflection), 0.0)
        if d >= self.landing:
            return 1.0
        if self.takeoff is None:
            return d / self.landing
        if d <= self.takeoff:
            return takeoff_share * d / self.takeoff
        return takeoff_share + (1.0 - takeoff_share) * (d - self.takeoff) / (self.landing - self.takeoff)

    def zero_lift_shift_basis(self, deflection: float) -> str:
        """Which of Raymer's 2-D zero-lift angle changes the deflection takes, for the notes."""
        if deflection >= self.landing:
            return f"the landing setting's −{abs(np.degrees(ALPHA0_SHIFT_LANDING)):.0f}° 2-D zero-lift angle change"
        if self.takeoff is not None and abs(deflection - self.takeoff) < 1e-9:
            return f"the takeoff setting's −{abs(np.degrees(ALPHA0_SHIFT_TAKEOFF)):.0f}° 2-D zero-lift angle change"
        return "the 2-D zero-lift angle change interpolated between the takeoff and landing settings"


def section_clmax(thickness_ratio: float) -> float:
    """Section maximum lift of a NACA 4-digit-like section (Abbott & von Doenhoff, Re ≈ 6e6)."""
    return float(np.interp(thickness_ratio, [0.06, 0.09, 0.12, 0.15, 0.21], [1.0, 1.3, 1.6, 1.6, 1.4]))


def clean_clmax(wing: LiftingSurface) -> float:
    """Clean wing maximum lift, 0.9 c_lmax cos Λ_c/4 (Raymer eq. 12.15 form)."""
    return float(0.9 * section_clmax(wing.thickness_ratio) * np.cos(wing.sweep_quarter_chord))


def flapped_area_ratio(wing: LiftingSurface, device: HighLiftDevice) -> float:
    """S_flapped/S: the wing area between the device's spanwise ends (trapezoid, fractions of semispan)."""
    lam = wing.taper

    def area_inboard_of(eta: float) -> float:  # fraction of the half-wing area inboard of eta
        return float((eta - 0.5 * (1 - lam) * eta**2) / (0.5 * (1 + lam)))

    return area_inboard_of(device.span_end) - area_inboard_of(device.span_start)


def hinge_sweep(wing: LiftingSurface, device: HighLiftDevice, trailing: bool = True) -> float:
    """Sweep of the device's hinge line (rad): the trailing-edge device's at 1 − its chord ratio, a leading-edge
    device's at its chord ratio."""
    fraction = 1.0 - device.chord_ratio if trailing else device.chord_ratio
    return float(planform.sweep_at(fraction, wing.sweep_quarter_chord, wing.aspect_ratio, wing.taper))


def delta_clmax(wing: LiftingSurface, device: HighLiftDevice | None, share: float) -> float:
    """ΔC_Lmax of one device at ``share`` of its landing-setting value (:meth:`FlapSettings.share`), Raymer
    eq. 12.21."""
    if device is None or share <= 0:
        return 0.0
    base = DELTA_CLMAX_SECTION[device.type]
    if device.type in CHORD_SCALED:
        base *= 1.0 + device.chord_ratio  # c'/c with the extension about equal to the device chord
    trailing = device.type not in ("slat", "krueger")
    return float(0.9 * base * flapped_area_ratio(wing, device) * np.cos(hinge_sweep(wing, device, trailing)) * share)


def lift_and_moment_increment(
    wing: LiftingSurface,
    flaps: HighLiftDevice | None,
    flap_deflection: float,
    cl_alpha: float,
    x_ref: float,
    mean_chord: float,
    settings: FlapSettings = FlapSettings(),
) -> tuple[float, float]:
    """(ΔC_L0, ΔC_m0) of the trailing-edge flaps at ``flap_deflection`` (Raymer eq. 12.22 and the module notes)."""
    if flaps is None or flap_deflection <= 0:
        return 0.0, 0.0
    ratio = flapped_area_ratio(wing, flaps)
    shift_2d = ALPHA0_SHIFT_LANDING * settings.share(flap_deflection, ALPHA0_SHIFT_TAKEOFF / ALPHA0_SHIFT_LANDING)
    d_alpha0 = shift_2d * ratio * np.cos(hinge_sweep(wing, flaps))
    d_cl = -cl_alpha * d_alpha0
    semi = 0.5 * planform.span(wing.area, wing.aspect_ratio)
    c_root = planform.root_chord(wing.area, wing.aspect_ratio, wing.taper)
    eta = 0.5 * (flaps.span_start + flaps.span_end)
    y = eta * semi
    chord = c_root * (1 - (1 - wing.taper) * eta)
    x_le = wing.root_leading_edge.x + y * np.tan(
        planform.sweep_at(0.0, wing.sweep_quarter_chord, wing.aspect_ratio, wing.taper)
    )
    x_flap = x_le + 0.5 * chord
    return float(d_cl), float(-d_cl * (x_flap - x_ref) / mean_chord)


def estimated_clmax(
    wing: LiftingSurface, configuration: Configuration, settings: FlapSettings = FlapSettings()
) -> float:
    """C_Lmax of a configuration: clean estimate plus the flap and slat increments, both at the share of their
    landing value the configuration's flap setting gives (a slat alone: its deflection over the landing flap
    setting's)."""
    flap_share = settings.share(configuration.flap, CLMAX_SHARE_TAKEOFF)
    if configuration.slat <= 0:
        slat_share = 0.0
    elif configuration.flap > 0:
        slat_share = flap_share
    else:
        slat_share = min(configuration.slat / settings.landing, 1.0)
    return clean_clmax(wing) + delta_clmax(wing, wing.flaps, flap_share) + delta_clmax(wing, wing.slats, slat_share)

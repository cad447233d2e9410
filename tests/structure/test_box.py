"""Box sizing (certkit.models.structure.box) against closed-form results.

References: NACA 0012 ordinates of Abbott & von Doenhoff, *Theory of Wing Sections* (1959), App. I (y/c at
x = 0.15: 5.345 %, at 0.60: 4.563 %); a bending box with covers at a uniform stress (Megson, *Aircraft
Structures*, idealised two-boom/two-cover section: M = σ A (h − t)); Bredt–Batho shear flow of a single closed
cell q = T / (2 A) (Megson §18.1); minimum-gauge floor. Tolerances are stated per test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from certkit.models.structure.box import BoxMaterial, BoxStations, StructuralSizingError, UltimateLoads, size_box
from certkit.models.structure.section import depth_factors

MAT = BoxMaterial(
    density=1600.0,
    cover_stress=300e6,
    cover_shear=180e6,
    web_shear=250e6,
    skin_fraction=0.6,
    min_cover=1e-4,
    min_web=1e-4,
)


def rectangular(length=5.0, chord=4.0, tc=0.1, n=11, sweep=0.0):
    return BoxStations(np.linspace(0.0, length, n), np.full(n, chord), tc, sweep)


def uniform(stations, shear=0.0, bending=0.0, torsion=0.0):
    n = stations.span.size
    return UltimateLoads(stations.span, np.full(n, shear), np.full(n, bending), np.full(n, torsion))


def test_depth_factors_match_abbott_naca0012_ordinates():
    """Reference: Abbott & von Doenhoff App. I, NACA 0012 half-thickness 5.345 % at 15 % chord and 4.563 % at 60 %:
    spar-height factors 2 × 5.345 / 12 = 0.8908 and 2 × 4.563 / 12 = 0.7605 (tabulated to 4 digits: 2e-4)."""
    k = depth_factors(0.15, 0.60)
    assert k.front_spar == pytest.approx(0.8908, abs=2e-4)
    assert k.rear_spar == pytest.approx(0.7605, abs=2e-4)
    assert k.rear_spar < k.mean < 1.0  # the mean depth lies between the thinner spar and the maximum thickness


def test_rectangular_box_uniform_moment_hand_cover():
    """A straight rectangular box (no sweep, chord 4 m, t/c 0.1, spars 15/60 %) under a uniform 2 MN·m: hand
    arithmetic with the documented mean depth 0.931 t (docs/baseline-sources.md §10): h = 0.3724 m, w = 1.8 m,
    K = M/(σ w) = 3.704e-3 m², t = (h − √(h² − 4K))/2 = 10.24 mm; covers 2 ρ t w L. Tolerance 0.3 % (the
    depth factor is given to 3 digits)."""
    st = rectangular()
    box = size_box(st, uniform(st, bending=2.0e6), MAT, 0.15, 0.60)
    h, w = 0.931 * 0.4, 0.45 * 4.0
    k = 2.0e6 / (300e6 * w)
    t = (h - math.sqrt(h * h - 4 * k)) / 2
    assert t == pytest.approx(10.24e-3, rel=2e-3)
    assert np.allclose(box.t_cover, t, rtol=3e-3)
    assert set(box.cover_governs) == {"bending"}
    assert box.cover_mass == pytest.approx(2 * 1600.0 * t * w * 5.0, rel=3e-3)


def test_bredt_batho_torsion_shear_flow():
    """Pure torsion T = 1 MN·m on a box of mean depth h = 0.5 m (chord set from the depth factor) and width
    w = 0.45 c: the web carries q = T/(2 h w) (Bredt–Batho), t_web = q/τ; the cover skin q/τ_skin/0.6.
    Tolerance 1e-9 (exact arithmetic)."""
    k = depth_factors(0.15, 0.60)
    chord = 0.5 / (k.mean * 0.1)
    st = rectangular(chord=chord)
    box = size_box(st, uniform(st, torsion=1.0e6), MAT, 0.15, 0.60)
    q = 1.0e6 / (2 * 0.5 * 0.45 * chord)
    assert np.allclose(box.t_web, q / 250e6, rtol=1e-9)
    assert np.allclose(box.t_cover, q / (180e6 * 0.6), rtol=1e-9)
    assert set(box.web_governs) == {"shear and torsion"} and set(box.cover_governs) == {"torsion"}


def test_minimum_gauge_governs_at_low_load():
    """Loads 1000× below what the gauges carry: every thickness is its minimum and the mass is the gauge volume
    ρ (2 t_c w + t_w (h_fs + h_rs)) L. Tolerance 1e-9."""
    mat = BoxMaterial(1600.0, 300e6, 180e6, 250e6, 0.6, min_cover=2.5e-3, min_web=2.0e-3)
    st = rectangular()
    box = size_box(st, uniform(st, shear=1e3, bending=1e3, torsion=1e3), mat, 0.15, 0.60)
    assert set(box.cover_governs) == {"minimum gauge"} and set(box.web_governs) == {"minimum gauge"}
    k = depth_factors(0.15, 0.60)
    expected = 1600.0 * (2 * 2.5e-3 * 1.8 + 2.0e-3 * (k.front_spar + k.rear_spar) * 0.4) * 5.0
    assert box.cover_mass + box.web_mass == pytest.approx(expected, rel=1e-9)


def test_shear_web_hand_value():
    """Shear only, V = 1 MN: web shear flow V/(h_fs + h_rs) at τ = 250 MPa; with the Abbott NACA 0012 factors
    (0.8908 + 0.7605) × t, t = 0.4 m: t_web = 1e6 / (0.6605 × 250e6) = 6.056 mm. Tolerance 0.1 %."""
    st = rectangular()
    box = size_box(st, uniform(st, shear=1.0e6), MAT, 0.15, 0.60)
    assert np.allclose(box.t_web, 1.0e6 / ((0.8908 + 0.7605) * 0.4 * 250e6), rtol=1e-3)


def test_monotone_and_sweep():
    """Doubling the bending adds cover mass; the same loads on a box swept 35° need 1/cos²35° more bending
    material (normal section w cos Λ carrying M / cos Λ; hand: 1/cos² 35° = 1.490, tolerance 2 % from the
    lever's dependence on the thickness)."""
    st = rectangular()
    one = size_box(st, uniform(st, bending=1.0e6), MAT, 0.15, 0.60)
    two = size_box(st, uniform(st, bending=2.0e6), MAT, 0.15, 0.60)
    assert two.cover_mass > 1.9 * one.cover_mass
    swept = size_box(rectangular(sweep=math.radians(35.0)), uniform(st, bending=1.0e6), MAT, 0.15, 0.60)
    assert swept.cover_mass / one.cover_mass == pytest.approx(1 / math.cos(math.radians(35.0)) ** 2, rel=0.02)


def test_overloaded_box_is_an_error():
    """A moment above σ w h²/4 (the most a box of that depth carries) cannot be sized."""
    st = rectangular()
    with pytest.raises(StructuralSizingError, match="exceeds"):
        size_box(st, uniform(st, bending=20e6), MAT, 0.15, 0.60)


def test_envelope_from_limit_peaks_and_interpolation():
    """UltimateLoads: the largest magnitude of either sense over conditions × 1.5; PCHIP through the stations is
    monotone (no overshoot between them) and zero at the tip."""
    peaks = np.zeros((2, 2, 3, 3))
    peaks[0, 1, 1] = [100.0, 40.0, 10.0]
    peaks[1, 0, 1] = [-120.0, -20.0, -5.0]
    loads = UltimateLoads.from_limit_peaks([0.0, 1.0, 2.0], peaks)
    assert list(loads.bending) == [180.0, 60.0, 15.0]
    fine = loads.interpolate(np.linspace(0.0, 3.0, 31), tip=3.0)
    assert fine.bending[-1] == 0.0 and np.all(np.diff(fine.bending) <= 1e-12)

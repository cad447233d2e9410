"""Ground effect (certkit.models.aero.ground_effect) against references no one here wrote."""

import math

import numpy as np
import pytest

from certkit.models.aero.ground_effect import (
    N_SPAN,
    induced_drag_factor_at,
    induced_drag_factor_table,
    lift_ratio,
    trefftz_induced_drag_factors,
)


def wieselsberger_phi(h_over_b):
    """Wieselsberger (NACA TM 77, 1922), as quoted by Hoerner, Fluid-Dynamic Lift §10 and McCormick ch. 9:
    D_i(ground)/D_i(free) = 1 − (1 − 1.32 h/b)/(1.05 + 7.4 h/b), stated for 0.033 ≤ h/b ≤ 0.25."""
    return 1.0 - (1.0 - 1.32 * h_over_b) / (1.05 + 7.4 * h_over_b)


@pytest.mark.parametrize("h_over_b", [0.05, 0.1, 0.15, 0.2, 0.25])
def test_induced_drag_factor_against_wieselsberger(h_over_b):
    # tolerance 0.01 absolute: Wieselsberger's formula is his fit to the same image theory, good to ~1 %
    phi = induced_drag_factor_at(induced_drag_factor_table(), h_over_b)
    assert phi == pytest.approx(wieselsberger_phi(h_over_b), abs=0.01)


@pytest.mark.parametrize("h_over_b", [0.1, 0.2, 0.3, 0.5])
def test_induced_drag_factor_against_raymer(h_over_b):
    # Raymer, Aircraft Design: A Conceptual Approach, §12.6 (ground effect on the drag-due-to-lift factor):
    # K_eff/K = 33(h/b)^1.5/(1 + 33(h/b)^1.5), an empirical fit; tolerance 0.04 absolute (its scatter about theory).
    # McCormick's φ = (16h/b)²/(1 + (16h/b)²) is NOT used: 0.72 at h/b = 0.1 against Wieselsberger's 0.52.
    phi = induced_drag_factor_at(induced_drag_factor_table(), h_over_b)
    raymer = 33 * h_over_b**1.5 / (1 + 33 * h_over_b**1.5)
    assert phi == pytest.approx(raymer, abs=0.04)


def test_induced_drag_factor_limits():
    table = induced_drag_factor_table()
    # on the ground the image cancels the trailing vortices (φ → 0); far away no effect
    assert induced_drag_factor_at(table, 0.0) == 0.0
    assert induced_drag_factor_at(table, 3.0) == 1.0
    assert 0.99 < induced_drag_factor_at(table, 1.99) < 1.0
    # far-field decay: the image sheet's mutual drag falls as (b/h)² (two line vortices 2h apart); the
    # product (1 − φ)(h/b)² tends to a constant: within 5 % between h/b = 1.5 and 1.9
    c = [(1 - induced_drag_factor_at(table, hb)) * hb**2 for hb in (1.5, 1.9)]
    assert c[0] == pytest.approx(c[1], rel=0.05)
    assert np.all(np.diff(table) > 0.0)


@pytest.mark.parametrize("phi", [0.3, 0.5, 0.8])
def test_lift_ratio_against_prandtl_lifting_line(phi):
    # elliptic unswept wing, incompressible: Prandtl's a = 2π/(1 + 2/A) with the induced angle reduced by φ
    # gives a_ge/a = (1 + 2/A)/(1 + 2φ/A); the DATCOM/Helmbold form used tends to it at large A (κ = 1):
    # within 1.5 % at A = 30
    A = 30.0
    expected = (1 + 2 / A) / (1 + 2 * phi / A)
    assert lift_ratio(phi, A, 0.0, 0.0, 1.0) == pytest.approx(expected, rel=0.015)


def test_lift_ratio_free_air_and_transport_wing():
    # no ground effect, no change
    assert lift_ratio(1.0, 8.81, math.tan(0.5), 0.2) == pytest.approx(1.0, abs=1e-12)
    # on the ground (φ → 0, A_eff → ∞) the DATCOM slope tends to the swept 2-D limit 2πκ/(β√(1 + tan²Λ/β²)),
    # so the ratio tends to that over the free-air slope (κ = 0.95, A = 8.81, Λ½ = 0.5 rad, M = 0.2)
    beta = math.sqrt(1 - 0.2**2)
    t = math.tan(0.5)
    two_d = 2 * math.pi * 0.95 / (beta * math.sqrt(1 + t**2 / beta**2))
    free = 2 * math.pi * 8.81 / (2 + math.sqrt(4 + 8.81**2 * beta**2 / 0.95**2 * (1 + t**2 / beta**2)))
    assert lift_ratio(1e-3, 8.81, t, 0.2) == pytest.approx(two_d / free, rel=0.01)


def test_the_stored_table_is_the_trefftz_sums_bit_for_bit():
    # the equations of motion read the stored φ table (certkit.models.aero.ground_effect_phi); the sums recomputed
    # here must give every double as stored (a changed method regenerates the file)
    stored = induced_drag_factor_table()
    assert stored.shape == (201,)
    assert np.array_equal(trefftz_induced_drag_factors(N_SPAN), stored)
    # another resolution is computed, not stored, and agrees to the discretisation's order
    assert np.allclose(induced_drag_factor_table(200), stored, atol=2e-3)

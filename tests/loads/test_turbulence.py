"""Continuous-turbulence responses of the rigid airplane (certkit/models/loads/turbulence.py): the spectrum and the rms
integral against quadrature, and the linearised frequency response against the nonlinear time-domain simulation of a
discrete gust (a different code path: RK4 of the full equations of motion, the strip loads along the history)."""

import numpy as np
import pytest
from scipy.integrate import quad

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.loads.gust_response import gust_batch, simulate_gust
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.turbulence import (
    rms_per_unit,
    spatial_frequencies,
    steady_loads,
    turbulence_response,
    von_karman,
)
from certkit.units import FT

from ..conftest import BASELINE

L = 2500 * FT


def test_von_karman_spectrum_has_unit_variance_and_its_low_frequency_value():
    """Φ normalised to unit variance (Hoblit, Gust Loads on Aircraft, eq. 2.20): ∫₀^∞ Φ dΩ = 1 (to the rounding of
    von Kármán's 1.339 and the quadrature of the Ω^(−5/3) tail: 1e-4), Φ(0) = L/π."""
    total = sum(quad(lambda w: float(von_karman(w, L)), a, b, limit=200)[0] for a, b in [(0, 1 / L), (1 / L, np.inf)])
    assert total == pytest.approx(1.0, abs=1e-4)
    assert float(von_karman(0.0, L)) == pytest.approx(L / np.pi)


def test_the_rms_integral_of_a_unit_response_is_one():
    omega = spatial_frequencies(L)
    assert float(rms_per_unit(np.ones_like(omega), omega, L)) == pytest.approx(1.0, abs=0.005)


@pytest.mark.parametrize("lag_s", [0.5, 2.0, 8.0])
def test_the_rms_integral_of_a_plunging_airplane_against_quadrature(lag_s):
    """The load factor of an airplane free to plunge only (quasi-steady): H(ω) = K iωT / (1 + iωT), T = 2m/(ρ V S a):
    Ā² = ∫ K² (ωT)² / (1 + (ωT)²) Φ(Ω) dΩ with ω = Ω V, against scipy's adaptive quadrature within 1 %."""
    V, K = 230.0, 0.02
    omega = spatial_frequencies(L)

    def power(w_spatial):
        x = (w_spatial * V * lag_s) ** 2
        return K**2 * x / (1 + x)

    exact = np.sqrt(
        sum(
            quad(lambda w: power(w) * float(von_karman(w, L)), a, b, limit=400)[0]
            for a, b in [(0, 1e-3), (1e-3, np.inf)]
        )
    )
    assert float(rms_per_unit(power(omega), omega, L)) == pytest.approx(exact, rel=0.01)


@pytest.fixture(scope="module")
def batch():
    """fwd_mrw at VC (272 KEAS) at sea level and 20,000 ft, trimmed in level flight, with the gust pseudo-controls."""
    from certkit_rules.part25.support.gust_runs import GUST_CONDITIONS, gust_speeds
    from certkit_rules.part25.support.loads_conditions import trimmed_batch

    ctx = Context(load_aircraft(BASELINE))
    picks = [
        c
        for c in GUST_CONDITIONS.expand(ctx.aircraft)
        if c.loading == "fwd_mrw" and c.get("speed_point") == "VC" and c.get("gust") == "up"
    ]
    picks = [picks[0], min(picks, key=lambda c: abs(c.altitude - 20000 * FT))]
    entries = [
        c.with_(speed=gust_speeds(ctx, c.altitude)["VC"], speed_kind="EAS", speed_name=None, gust=None) for c in picks
    ]
    trimmed = trimmed_batch(ctx, entries)
    assert not trimmed.failed
    loads = airplane_loads(ctx)
    return loads, gust_batch(loads, trimmed.model, trimmed.x, trimmed.u)


def _one_minus_cosine_spectrum(w, U, T):
    """Fourier transform ∫ w(t) e^{−iωt} dt of the gust (U/2)(1 − cos 2πt/T), 0 ≤ t ≤ T."""

    def pulse(a):
        return (1 - np.exp(-1j * a * T)) / (1j * a)

    w0 = 2 * np.pi / T
    return 0.5 * U * (pulse(w) - 0.5 * (pulse(w - w0) + pulse(w + w0)))


@pytest.mark.parametrize("i", [0, 1])
def test_the_frequency_response_reproduces_a_simulated_discrete_gust(batch, i):
    """A small 1 − cos gust (H = 100 ft, 0.002 rad) simulated with the nonlinear equations of motion and the strip
    loads (certkit.models.loads.gust_response) against the same gust through the linearised frequency response,
    y(t) = (1/π) Re ∫₀^∞ H(ω) W(ω) e^{iωt} dω: the peak increments of the load factor, the wing's side-of-body bending
    and the tailplane's root shear within 2 %."""
    loads, gb = batch
    one = gb.subset([i])
    v = float(one.v_tas[0])
    gradient, angle = 100 * FT, 0.002
    T = 2 * gradient / v
    w = np.linspace(1e-3, 150.0, 8000)  # rad/s
    response = turbulence_response(loads, one, steady_loads(loads, one), w / v)
    W = _one_minus_cosine_spectrum(w, angle * v, T)
    run = simulate_gust(loads, one, gradient, angle, 40, 3.0)
    t = np.linspace(0.0, float(run.sim.t[-1]), 300)

    def linear(h):
        return np.array([np.trapezoid((h * W * np.exp(1j * w * x)).real, w) / np.pi for x in t])

    def extreme(y):
        return y[np.argmax(np.abs(y))]

    sob = list(loads["wing"].station_names).index("side of body")
    pairs = [
        (run.sim["n_z"][:, 0], response.n_z[:, 0]),
        (run.loads["wing"][:, 0, 1, sob], response.loads["wing"][:, 0, 1, sob]),
        (run.loads["horizontal_tail"][:, 0, 0, 0], response.loads["horizontal_tail"][:, 0, 0, 0]),
    ]
    for simulated, h in pairs:
        assert extreme(linear(h)) == pytest.approx(extreme(simulated - simulated[0]), rel=0.02)


@pytest.mark.parametrize("i", [0, 1])
def test_the_lateral_frequency_response_reproduces_a_simulated_lateral_gust(batch, i):
    """The same check in sideslip (certkit.models.loads.lateral_gust: the gust felt by the fin): a small 1 − cos
    lateral gust (H = 100 ft, 0.002 rad) simulated with the nonlinear equations of motion against the linearised
    response free in sideslip, roll and yaw — the peak lateral load factor and the fin's root shear and bending within
    3 % (the spiral mode, left out of the linear model, hardly moves in the 4 s simulated)."""
    from certkit.models.loads.lateral_gust import FIN, lateral_gust_batch, simulate_lateral_gust
    from certkit.models.loads.turbulence import lateral_turbulence_response

    loads, gb = batch
    one = gb.subset([i])
    base = lateral_gust_batch(loads, one.model, one.x0, one.u0)
    v = float(base.v_tas[0])
    gradient, angle = 100 * FT, 0.002
    w = np.linspace(1e-3, 150.0, 8000)
    response = lateral_turbulence_response(loads, base, steady_loads(loads, base, (FIN,)), w / v)
    W = _one_minus_cosine_spectrum(w, angle * v, 2 * gradient / v)
    sim, fin, _ = simulate_lateral_gust(loads, base, gradient, angle, 40, 3.0)
    t = np.linspace(0.0, float(sim.t[-1]), 300)

    def linear(h):
        return np.array([np.trapezoid((h * W * np.exp(1j * w * x)).real, w) / np.pi for x in t])

    def extreme(y):
        return y[np.argmax(np.abs(y))]

    pairs = [
        (sim["n_y"][:, 0], response.n_z[:, 0]),
        (fin[:, 0, 0, 0], response.loads[FIN][:, 0, 0, 0]),
        (fin[:, 0, 1, 0], response.loads[FIN][:, 0, 1, 0]),
    ]
    for simulated, h in pairs:
        assert extreme(linear(h)) == pytest.approx(extreme(simulated - simulated[0]), rel=0.03)


def test_the_default_frequency_grid_is_converged(batch):
    """Ā of the load factor, the wing's side-of-body bending and the tail's root shear on the default grid within
    0.5 % of a grid eight times finer, in vertical and (the fin's root bending) lateral turbulence."""
    from certkit.models.loads.lateral_gust import FIN, lateral_gust_batch
    from certkit.models.loads.turbulence import OMEGA_POINTS, lateral_turbulence_response

    loads, gb = batch
    steady = steady_loads(loads, gb)
    base = lateral_gust_batch(loads, gb.model, gb.x0, gb.u0)
    fin_steady = steady_loads(loads, base, (FIN,))
    sob = list(loads["wing"].station_names).index("side of body")
    values = []
    for points in (OMEGA_POINTS, 8 * OMEGA_POINTS):
        omega = spatial_frequencies(L, points)
        v = turbulence_response(loads, gb, steady, omega)
        lat = lateral_turbulence_response(loads, base, fin_steady, omega)
        picks = [
            v.n_z,
            v.loads["wing"][:, :, 1, sob],
            v.loads["horizontal_tail"][:, :, 0, 0],
            lat.loads[FIN][:, :, 1, 0],
        ]
        values.append(np.array([rms_per_unit(np.abs(h.T) ** 2, omega, L) for h in picks]))
    assert values[0] == pytest.approx(values[1], rel=0.005)

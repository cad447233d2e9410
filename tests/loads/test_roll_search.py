"""The aileron fraction search of the rolling conditions (:func:`certkit.models.loads.roll.aileron_for_roll_rate`):
each step flies again only the conditions whose fraction changed, and the run it returns — gathered from those runs
(:func:`certkit.models.dynamics.simulate.gather`) — is bit for bit the run of every condition at its final fraction."""

import numpy as np
import pytest

import certkit.models.loads.roll as roll

from ..conftest import clean_trims, count_conditions


@pytest.fixture(scope="module")
def trimmed(baseline):
    """Five clean conditions (:func:`tests.conftest.clean_trims`)."""
    model, batch = clean_trims(baseline, 5)
    return model, batch.x, batch.u


def test_the_search_flies_only_the_changed_fractions(trimmed, monkeypatch):
    """Two conditions at the whole deflection (not scaled), three scaled to 40–60 % of their full-deflection roll
    rate: the first step flies the three, the later steps those still outside the tolerance; the returned run, rates
    and fractions are those of one run of all five at the final fractions, bit for bit."""
    model, x0, u0 = trimmed
    timing = dict(duration=3.0, dt=0.02, ramp=0.1)
    amplitude = np.radians([-15.0, -15.0, -20.0, -20.0, -20.0])
    sim_full = roll.simulate_roll(model, x0, u0, amplitude, **timing)
    p_full = roll.peak_roll_rate(sim_full)[0]
    scaled = np.array([False, False, True, True, True])
    target = np.where(scaled, p_full * np.array([0.0, 0.0, 0.4, 0.5, 0.6]), 0.0)
    run = roll.simulate_roll
    flown = count_conditions(monkeypatch, roll, "simulate_roll")
    sim, p, frac = roll.aileron_for_roll_rate(
        model, x0, u0, amplitude, target, scaled, sim_full, tolerance=0.002, steps=6, **timing
    )
    assert flown and flown[0] == 3 and max(flown) == 3
    np.testing.assert_array_equal(frac[:2], 1.0)
    assert ((frac[2:] > 0.2) & (frac[2:] < 0.8)).all()
    whole = run(model, x0, u0, frac * amplitude, **timing)
    assert sim.t.tobytes() == whole.t.tobytes() and sim.controls.tobytes() == whole.controls.tobytes()
    for key in ("p", "phi", "n_z", "beta", "r"):
        assert sim[key].tobytes() == whole[key].tobytes(), key
    assert sim.final_state.tobytes() == whole.final_state.tobytes()
    assert p.tobytes() == roll.peak_roll_rate(whole)[0].tobytes()

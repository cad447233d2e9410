"""The steady rolling velocity read from a roll response (:func:`certkit.models.loads.roll.peak_roll_rate`) against
the first-order roll mode in closed form (Etkin & Reid, *Dynamics of Flight*, 3rd ed., the rolling-subsidence mode;
Nelson, *Flight Stability and Automatic Control*, 2nd ed., ch. 5 "pure rolling motion"): p = p_ss (1 − e^(−t/τ))."""

import numpy as np
import pytest

from certkit.models.loads.roll import STEADY_ROLL_ACCELERATION, peak_roll_rate

T = np.arange(0.0, 6.0 + 1e-9, 0.02)


def _record(p):
    return {"p": np.asarray(p, dtype=float)[:, None]}


@pytest.mark.parametrize("tau", [0.5, 1.4])
def test_a_first_order_roll_is_steady_within_two_percent(tau):
    """The response never stops growing: the rate is read where the roll acceleration has fallen to 2 % of its peak,
    i.e. at t = τ ln 50 with p within 2 % of p_ss."""
    p_ss = np.radians(30.0)
    rate, k = peak_roll_rate(_record(p_ss * (1 - np.exp(-T / tau))))
    assert rate[0] == pytest.approx(p_ss * (1 - STEADY_ROLL_ACCELERATION), rel=0.005)
    assert T[k[0]] == pytest.approx(tau * np.log(1 / STEADY_ROLL_ACCELERATION), abs=0.03)


def test_a_creeping_plateau_is_steady_and_an_overshoot_is_its_peak():
    """A plateau that keeps creeping up (0.2 °/s² as the sideslip builds, the zero-g roll at the ceiling) is the
    steady rate, not the end of the record; a response with an overshoot is read at its peak (the step before it
    at most, where the growth has already fallen under 2 % of its peak)."""
    tau, p_ss = 1.0, np.radians(35.0)
    creep = p_ss * (1 - np.exp(-T / tau)) + np.radians(0.2) * T
    rate, k = peak_roll_rate(_record(creep))
    assert T[k[0]] < 5.0 and rate[0] == pytest.approx(p_ss, rel=0.03)
    overshoot = p_ss * (1 - np.exp(-T / tau) * np.cos(2.0 * T))
    rate, k = peak_roll_rate(_record(overshoot))
    assert rate[0] == pytest.approx(overshoot.max(), rel=1e-3)  # a step before the peak at most

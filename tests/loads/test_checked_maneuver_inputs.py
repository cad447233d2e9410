"""The checked manoeuvre's input search (certkit.models.loads.checked_maneuver) on the two-surface airplane of
tests/loads/test_balanced.py: it finds the smallest sinusoid amplitude whose peak load factor reaches the target
(less half the tolerance, to the resolution) — 1 % less amplitude falls short — and holds the full deflection when
the full sinusoid does not reach it. The airplane's response is linear in the amplitude here (linear lift, no stall),
so the peak increment of the found amplitude is the target's share of the full-amplitude peak (superposition)."""

import numpy as np
import pytest

from certkit.models.dynamics.trim import assemble_state
from certkit.models.loads.balanced import balanced_states
from certkit.models.loads.checked_maneuver import checked_maneuver_inputs

from .test_balanced import two_surface

ARGS = dict(
    n_limit=2.5, max_hold=5.0, dt=0.02, periods=1.5, steps=30, tolerance=0.02, resolution=0.001, hold_resolution=0.005
)


def _run(target, available):
    model = two_surface(10.6)
    V = np.array([120.0, 120.0])
    x0 = assemble_state(V, np.zeros(2), 0.0, 0.0, 0.0, 0.0, 0.0)
    st = balanced_states(model, x0, np.zeros((2, 1)), 1.0)  # the 1 g trim
    return (
        model,
        st,
        checked_maneuver_inputs(
            model, st.x, st.u, [True, True], [2.0, 2.0], [available, available], [target, target], **ARGS
        ),
    )


def test_the_smallest_amplitude_that_reaches_the_load_factor():
    _, _, full = _run(1.5, np.radians(20.0))
    assert full.reach.all() and (full.amplitude < np.radians(20.0)).all() and (full.hold == 0).all()
    assert full.response == pytest.approx(1.5 - 0.01, abs=0.001)
    # 1 % less amplitude available: the sinusoid alone no longer reaches, the input is held at it
    _, _, less = _run(1.5, 0.99 * float(full.amplitude[0]))
    assert not less.reach.any() and (less.hold > 0).all()


def test_a_sinusoid_that_cannot_reach_is_held():
    _, _, small = _run(1.5, np.radians(0.5))
    assert not small.reach.any()
    assert small.amplitude == pytest.approx(np.radians(0.5))
    assert (small.hold > 0).all()


def test_a_full_sinusoid_within_the_tolerance_below_the_target_is_not_held():
    """The full sinusoid peaks between the search's aim (target − tolerance/2 = 1.49) and the target (1.50): it reaches
    the load factor within the tolerance, so its amplitude is searched and no hold is added. (Judged against the
    target itself, such a condition went to a hold search whose bracket did not hold the aim and ended at the longest
    hold, 5 s at full deflection — far beyond the load factor; a §25.331(c)(2) condition of the baseline's and one
    of a study design were flown so.)"""
    _, _, full = _run(1.5, np.radians(20.0))
    available = float(full.amplitude[0]) * 1.495 / float(full.response[0])  # linear: the full sinusoid peaks at 1.495
    _, _, near = _run(1.5, available)
    assert near.reach.all() and (near.hold == 0).all()
    assert near.response == pytest.approx(1.49, abs=0.001)


def test_the_minimum_hold_to_the_hold_resolution():
    """Δt is "the minimum period of time necessary to allow the prescribed limit load factor to be achieved"
    (§25.331(c)(2)(iii)): with 3 % less amplitude than the sinusoid needs, the hold found reaches the aim, and
    the hold 5 ms (``hold_resolution``) shorter does not. The load factor grows slowly in the hold, so a search
    stopped on the load factor's resolution alone would leave the hold loose by far more than that."""
    model, st, full = _run(1.5, np.radians(20.0))
    available = 0.97 * float(full.amplitude[0])
    _, _, held = _run(1.5, available)
    assert not held.reach.any() and (held.hold > 0).all()
    hold = float(held.hold[0])

    def peak(h):  # the response held for exactly h (target out of reach: the longest hold, set to h, is flown)
        return checked_maneuver_inputs(
            model, st.x, st.u, [True, True], [2.0, 2.0], [available] * 2, [9.0, 9.0], **{**ARGS, "max_hold": h}
        ).response[0]

    assert peak(hold) >= 1.49 - 1e-9
    assert peak(hold - 0.005) < 1.49


def test_a_repeated_condition_is_searched_once(baseline, monkeypatch):
    """A batch holding one flight point twice (three baseline conditions, two of them repeated; nose up and nose
    down): each distinct condition is searched and flown once, and the inputs, responses and recorded run are bit for
    bit those of the batch searched row by row (the repeats searched too)."""
    import certkit.models.loads.checked_maneuver as cm

    from ..conftest import clean_trims, count_conditions

    model, trims = clean_trims(baseline, 3)
    rows = np.array([0, 1, 2, 0, 2])
    up = np.array([True, True, False, True, False])
    args = (model.subset(rows), trims.x[rows], trims.u[rows], up, np.full(5, 1.5), np.full(5, np.radians(8.0)))
    target = np.where(up, 0.8, 1.0)
    kwargs = dict(ARGS, steps=10)
    flown = count_conditions(monkeypatch, cm, "simulate")
    once = cm.checked_maneuver_inputs(*args, target, **kwargs)
    assert max(flown) == 3
    monkeypatch.setattr(cm, "_repeats", lambda *a: None)
    each = cm.checked_maneuver_inputs(*args, target, **kwargs)
    assert max(flown) == 5
    for name in ("amplitude", "hold", "reach", "held_short", "response", "valid", "t_max"):
        assert getattr(once, name).tobytes() == getattr(each, name).tobytes(), name
    assert once.sim.t.tobytes() == each.sim.t.tobytes() and once.sim.controls.tobytes() == each.sim.controls.tobytes()
    for key in ("n_z", "q", "alpha", "theta"):
        assert once.sim[key].tobytes() == each.sim[key].tobytes(), key
    assert once.sim.stop_reason == each.sim.stop_reason and (once.sim.stop_time == each.sim.stop_time).all()

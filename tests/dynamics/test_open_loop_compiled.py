"""A fixed-step run whose controls are all scheduled (no controllers, no stop criteria) runs in one compiled loop
(:func:`certkit.models.dynamics.kernel.integrate_open_loop`); it must give the Python loop's run: the same grid and
controls, the states and outputs within round-off (1e-9 of each history's scale), one time step or one per
condition."""

import numpy as np
import pytest

from certkit.models.dynamics.simulate import Function, simulate

from ..conftest import clean_trims


def _assert_same_run(compiled, loop):
    """The same grid and controls; states, outputs and the final state within round-off (1e-9 of each scale)."""
    np.testing.assert_array_equal(compiled.t, loop.t)
    np.testing.assert_array_equal(compiled.controls, loop.controls)
    for key, ref in loop.history.items():
        np.testing.assert_allclose(
            compiled.history[key], ref, rtol=1e-9, atol=1e-9 * max(1.0, float(np.abs(ref).max())), err_msg=key
        )
    np.testing.assert_allclose(compiled.final_state, loop.final_state, rtol=1e-9, atol=1e-9)


@pytest.fixture(scope="module")
def batch(baseline):
    n = 6
    model, trims = clean_trims(baseline, n)
    return model, trims, {"elevator": Function(lambda t: 0.02 * np.sin(t) * np.ones(n))}


@pytest.mark.parametrize("dt", [0.01, np.linspace(0.008, 0.012, 6)], ids=["one step", "a step per condition"])
def test_compiled_run_equals_the_python_loop(batch, dt):
    model, trims, inputs = batch
    assert model._turbofan is not None  # the baseline's engines are parametric turbofans: the compiled path runs
    compiled = simulate(model, trims.x, trims.u, 3.0, dt, inputs=inputs)
    saved, model._turbofan = model._turbofan, None
    try:
        loop = simulate(model, trims.x, trims.u, 3.0, dt, inputs=inputs)
    finally:
        model._turbofan = saved
    _assert_same_run(compiled, loop)


def test_compiled_run_with_bound_stops_equals_the_python_loop(batch):
    """Stop criteria that are bounds (:class:`Bound`) run in the compiled loop: each condition stops at the same step
    for the same criterion as the Python loop (the first in order wins), keeps its last record and its state, and
    the run ends when every condition has stopped."""
    from certkit.models.dynamics.simulate import Bound

    model, trims, _ = batch
    n = trims.x.shape[0]
    pull = {"elevator": Function(lambda t: -0.08 * np.minimum(t, 1.0) * np.ones(n))}  # a pull: n_z rises
    nz_cap = np.array([1.3, 1.5, np.inf, 1.4, np.inf, 1.6])
    stops = [
        Bound("n_z cap", "n_z", upper=nz_cap),
        Bound("alpha floor", "alpha", lower=np.full(n, -1.0)),
        Bound("t_max", "t", upper=np.array([9.0, 9.0, 1.2, 9.0, 2.0, 9.0])),
    ]
    compiled = simulate(model, trims.x, trims.u, 3.0, 0.01, inputs=pull, stop=stops)
    saved, model._turbofan = model._turbofan, None
    try:
        loop = simulate(model, trims.x, trims.u, 3.0, 0.01, inputs=pull, stop=stops)
    finally:
        model._turbofan = saved
    assert set(loop.stop_reason) >= {"n_z cap", "t_max"}  # both kinds of bound stop some condition here
    assert compiled.stop_reason == loop.stop_reason
    np.testing.assert_array_equal(compiled.stop_time, loop.stop_time)
    _assert_same_run(compiled, loop)


def test_a_batch_gathered_from_runs_of_its_conditions_is_the_batch_run(batch):
    """:func:`gather`: the conditions of a batch flown in other runs — other batches, longer or shorter, the same
    inputs — gathered column by column give the batch's own run bit for bit (each condition's records up to its stop,
    its last after it; the run ending at the last stop), the Euler angles (converted from the gathered quaternions)
    and the final states included; a condition that did not stop ran to its run's end, and is gathered only into a
    run that ends there too."""
    from certkit.models.dynamics.simulate import Bound, gather

    model, trims, _ = batch
    n = trims.x.shape[0]
    amplitude = np.linspace(-0.02, -0.07, n)
    t_stop = np.array([1.0, 1.6, 0.7, 2.2, 1.3, 1.9])

    def run(rows, extra_time=0.0):
        """The conditions ``rows`` alone, pulled by their own amplitude and stopped at their own time."""
        sub = model.subset(rows)
        pull = {"elevator": Function(lambda t: amplitude[rows] * np.minimum(np.asarray(t), 1.0))}
        stops = [Bound("n_z cap", "n_z", upper=np.full(len(rows), 1.45)), Bound("t_max", "t", upper=t_stop[rows])]
        return simulate(
            sub,
            trims.x[rows],
            trims.u[rows],
            float(t_stop[rows].max()) + 0.02 + extra_time,
            0.02,
            inputs=pull,
            stop=stops,
        )

    whole = run(np.arange(n))
    a, b = run(np.array([3, 0, 5])), run(np.array([1, 4, 2]), extra_time=1.0)
    picks = [(a, 1), (b, 0), (b, 2), (a, 0), (b, 1), (a, 2)]
    got = gather(picks)
    assert got is not None and set(whole.stop_reason) == {"n_z cap", "t_max"}
    assert got.t.tobytes() == whole.t.tobytes() and got.controls.tobytes() == whole.controls.tobytes()
    for key in ("n_z", "alpha", "q", "theta", "phi", "V"):
        assert got.history[key].tobytes() == whole.history[key].tobytes(), key
    assert got.stop_time.tobytes() == whole.stop_time.tobytes() and got.stop_reason == whole.stop_reason
    assert got.final_state.tobytes() == whole.final_state.tobytes()

    def free(rows, t_end=0.5):
        """The conditions ``rows`` without a stop criterion: each runs to the end."""
        return simulate(model.subset(rows), trims.x[rows], trims.u[rows], t_end, 0.02)

    never = free(np.array([0]))
    assert gather([(never, 0)]) is never  # every condition of one run, in its order: that run
    latest = int(np.argmax(a.stop_time))
    assert a.stop_time[latest] > 0.5 and gather([(never, 0), (a, latest)]) is None  # its records end too early
    odd, even = free(np.array([1, 3, 5])), free(np.array([0, 2, 4]))
    together = gather([(even, 0), (odd, 0), (even, 1), (odd, 1), (even, 2), (odd, 2)])
    alone = free(np.arange(n))
    assert together is not None and together.t.tobytes() == alone.t.tobytes()
    for key in ("n_z", "q", "theta"):
        assert together.history[key].tobytes() == alone.history[key].tobytes(), key
    assert together.final_state.tobytes() == alone.final_state.tobytes() and together.stop_reason == [""] * n

"""The compiled thrust of :meth:`AircraftModel.evaluate` (:func:`certkit.models.dynamics.kernel.engine_forces`, used
when the engines are parametric turbofans) must be the Python engine path (:meth:`AircraftModel.thrust_forces`: the
engine model's own ``thrust_rows``, its :class:`WindmillDrag`, the spool-down blend) bit for bit — with running,
failed and spooling-down engines — and so must the trims built on it (an engine-out trim at a bank, a steady-heading
sideslip, a turn, a descent), whose residuals are then evaluated in one compiled call (``trim._residual_rows``). The
reference is the Python path of the same model; the tolerance is zero."""

import numpy as np
import pytest

from certkit.models.dynamics import kernel
from certkit.models.dynamics.trim import trim
from certkit.models.flight import ROLES, control_limits, flight_model


@pytest.fixture(scope="module")
def model(baseline):
    from certkit.engine.context import Context

    ctx = Context(baseline)
    n = 8
    rng = np.random.default_rng(3)
    loadings = [ctx.loading(float(baseline.model.mass.MTOW) * f, 29.5, "x") for f in rng.uniform(0.65, 1.0, n)]
    operative = np.array([[True, True], [True, False], [False, True], [True, False]] * 2)
    return flight_model(baseline.model, ctx.aero("clean").model, loadings, operative=operative)


def test_compiled_thrust_equals_the_python_engine_path(model):
    assert model.thrust_compiled  # the baseline's engines: parametric turbofans with the Torenbeek windmilling drag
    rng = np.random.default_rng(7)
    n, m = model.n, 300
    model.failed_thrust_fraction = np.where(rng.uniform(size=(n, 2)) > 0.5, rng.uniform(size=(n, 2)), 0.0)
    try:
        for quat in (False, True):
            X = np.zeros((m, 13 if quat else 12))
            X[:, 2] = rng.uniform(-100.0, 12000.0, m)
            X[:, 3] = rng.uniform(60.0, 250.0, m)
            X[:, 4:9] = rng.normal(0.0, [5.0, 10.0, 0.1, 0.1, 0.1], (m, 5))
            att = rng.normal(size=(m, 4)) if quat else rng.normal(0.0, 0.2, (m, 3))
            X[:, 9:] = att / np.linalg.norm(att, axis=1, keepdims=True) if quat else att
            U = rng.normal(0.0, 0.1, (m, len(model.control_names)))
            U[:, model.throttle_slice] = rng.uniform(-0.1, 1.1, (m, 2))  # beyond both ends of the throttle range
            rows = rng.integers(0, n, m)
            xd, out, _, thrust = model.evaluate(X, U, rows=rows)
            ref = model.thrust_forces(kernel.air_data(X), U, rows)
            assert (thrust < 0).any() and (thrust > 0).any()  # windmilling and running engines both present
            np.testing.assert_array_equal(thrust, ref)
            xd_ref, out_ref, _ = kernel.derivatives(X, rows, quat, U, ref, np.empty((m, 8)), *model._kernel_args)
            np.testing.assert_array_equal(xd, xd_ref)
            np.testing.assert_array_equal(out, out_ref)
    finally:
        model.failed_thrust_fraction = np.zeros((n, 2))


@pytest.mark.parametrize(
    "kind, extra",
    [
        ("oei", {"bank": np.radians(3.0)}),
        ("sideslip", {"beta": np.radians(4.0)}),
        ("turn", {"bank": np.radians(25.0)}),
        ("straight", {"gamma": np.radians(-1.0)}),
    ],
)
def test_trims_equal_with_the_python_engine_path(model, baseline, kind, extra):
    n = model.n
    args = dict(kind=kind, limits=control_limits(baseline.model), roles=ROLES, **extra)
    V, h = np.linspace(110.0, 220.0, n), np.linspace(0.0, 9000.0, n)
    fast = trim(model, V, h, **args)
    saved, model._windmill = model._windmill, None  # without its compiled windmilling drag: the Python path
    try:
        assert not model.thrust_compiled
        slow = trim(model, V, h, **args)
    finally:
        model._windmill = saved
    assert sum(r.converged for r in slow.results) >= n // 2
    np.testing.assert_array_equal(fast.x, slow.x)
    np.testing.assert_array_equal(fast.u, slow.u)
    for a, b in zip(fast.results, slow.results):
        assert (a.iterations, a.residual_norm, a.thrust, a.converged) == (
            b.iterations,
            b.residual_norm,
            b.thrust,
            b.converged,
        )

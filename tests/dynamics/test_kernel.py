"""The compiled equations of motion: the two aerodynamic paths agree, subsets and stacked rows
evaluate like the whole batch, after-stall controls bypass the stall model.

References are internal consistency checks of one implementation against another route through it
(tolerances: rounding only, 1e-10 relative), plus the closed form of the linear lift for the
after-stall control."""

import numpy as np
import pytest

from certkit.models.aero.derivative_model import StabilityDerivativeModel, StallModel
from certkit.models.aero.interface import AeroState
from certkit.models.dynamics.eom import AircraftModel, Engine, euler_state_to_quat_state
from certkit.models.dynamics.simulate import Doublet, simulate
from certkit.models.dynamics.trim import trim

from . import b747_etkin as ref


class Opaque:
    """The same derivative model seen only through the AeroModel protocol (no compiled table), so
    the equations of motion take their Python-coefficients path."""

    def __init__(self, model):
        self._m = model
        self.reference = model.reference
        self.control_names = model.control_names
        self.alpha_dot_derivatives = model.alpha_dot_derivatives

    def coefficients(self, state):
        return self._m.coefficients(state)


def _engine_747(model):
    return [
        Engine(name, lambda thr, h, m: 2.0e5 * thr, position=(20.0, y, -2.0)) for name, y in (("l", -12.0), ("r", 12.0))
    ]


def test_table_and_protocol_paths_agree():
    """Derivatives and outputs of the compiled-table path equal those of the protocol path (Python
    coefficients fed to the same kernel) for random states, one engine failed: 1e-10 relative."""
    base, h = ref.build(n=5)
    engines = _engine_747(base)
    kw = dict(mass=base.mass, cg=base.cg, inertia=base.inertia, engines=engines, operative=[[True, False]] * 5, n=5)
    fast = AircraftModel(base.aero, **kw)
    slow = AircraftModel(Opaque(base.aero), **kw)
    assert fast._use_table and not slow._use_table
    rng = np.random.default_rng(1)
    x = np.zeros((5, 12))
    x[:, 2] = h
    x[:, 3:6] = [230.0, 0.0, 10.0] + rng.normal(size=(5, 3)) * [5.0, 3.0, 4.0]
    x[:, 6:9] = rng.normal(size=(5, 3)) * 0.05
    x[:, 9:12] = rng.normal(size=(5, 3)) * 0.2
    u = rng.normal(size=(5, len(fast.control_names))) * 0.05 + 0.5 * np.isin(
        np.arange(len(fast.control_names)), np.arange(fast.throttle_slice.start, fast.throttle_slice.stop)
    )
    for state in (x, euler_state_to_quat_state(x)):
        a = fast.evaluate(state, u)
        b = slow.evaluate(state, u)
        for ka, kb in zip(a, b):
            np.testing.assert_allclose(ka, kb, rtol=1e-10, atol=1e-12)


def test_rows_evaluate_subsets_and_stacks():
    """``rows`` maps each state to its condition: a reversed subset and a stack of two copies give
    the rows of the whole-batch evaluation (exactly)."""
    model, h = ref.build(n=4)
    model.cg[:, 0] += np.array([-1.0, 0.0, 0.5, 1.0])
    model = AircraftModel(model.aero, model.mass, model.cg, model.inertia, n=4)
    tb = trim(model, np.full(4, ref.U0), h)
    full = model.derivatives_euler(tb.x + 0.01, tb.u)
    idx = np.array([3, 1])
    sub = model.derivatives_euler(tb.x[idx] + 0.01, tb.u[idx], rows=idx)
    np.testing.assert_array_equal(sub, full[idx])
    two = model.derivatives_euler(
        np.vstack([tb.x, tb.x]) + 0.01, np.vstack([tb.u, tb.u]), rows=np.tile(np.arange(4), 2)
    )
    np.testing.assert_array_equal(two, np.vstack([full, full]))


def test_fused_rk4_equals_python_stages():
    """The compiled RK4 step (table path) and the stage-by-stage Python RK4 (protocol path) fly the
    same elevator doublet: final states within 1e-9 relative after 5 s."""
    base, h = ref.build(n=2)
    tb = trim(base, [ref.U0, 220.0], h)
    slow = AircraftModel(Opaque(base.aero), base.mass, base.cg, base.inertia, base.engines, g=base.g, n=2)
    inputs = {"elevator": Doublet(0.5, 1.0, np.radians(1.0))}
    a = simulate(base, tb.x, tb.u, 5.0, dt=0.02, inputs=inputs)
    b = simulate(slow, tb.x, tb.u, 5.0, dt=0.02, inputs=inputs)
    np.testing.assert_allclose(a.final_state, b.final_state, rtol=1e-9, atol=1e-9)
    assert np.ptp(a["q"]) > 1e-3  # the doublet moved the airplane


def test_after_stall_control_lift_is_linear():
    """A control listed in ``after_stall`` adds CL_δ δ on top of the stalled lift (closed form: the
    lift difference with and without the deflection is exactly CL_δ δ, even beyond CLmax), and adds
    no induced drag; an ordinary control's lift is rounded by the stall model."""
    from certkit.models.aero.interface import AeroReference

    ref_ = AeroReference(100.0, 30.0, 4.0, 10.0)
    base = StabilityDerivativeModel(
        ref_, {"CL_alpha": 5.0, "CD0": 0.02, "k": 0.05, "CL_flap": 1.0}, stall=StallModel(CLmax=1.2)
    )
    gust = base.with_control_terms({"CL_gust": 5.0}, after_stall=("gust",))
    alpha = np.array([0.05, 0.2, 0.3])
    d = 0.1
    plain = gust.coefficients(AeroState(alpha=alpha))
    gusty = gust.coefficients(AeroState(alpha=alpha, controls={"gust": d}))
    np.testing.assert_allclose(gusty.CL - plain.CL, 5.0 * d, rtol=1e-12)
    np.testing.assert_allclose(gusty.CD, plain.CD, rtol=1e-12)
    flap = base.coefficients(AeroState(alpha=np.array([0.3]), controls={"flap": 0.5}))
    assert flap.CL[0] < 5.0 * 0.3 + 0.5 - 0.2  # rounded onto CLmax, not linear


def test_declared_clmax_is_the_peak_of_the_lift_curve():
    """The stall model's rounding and separated-flow blend start below CLmax; the model calibrates the CLmax it uses
    so that the maximum of the lift curve (controls neutral) equals the declared CLmax at every Mach breakpoint
    (reference: the definition of CLmax; tolerance 1e-3 on a 0.01° α grid), and keeps the declared value public."""
    from certkit.models.aero.interface import AeroReference

    ref_ = AeroReference(400.0, 60.0, 7.0, 30.0)
    m = StabilityDerivativeModel(
        ref_,
        {"CL0": 0.2, "CL_alpha": [5.5, 6.0, 7.5], "CD0": 0.02, "k": 0.04},
        mach=[0.2, 0.5, 0.8],
        stall=StallModel(CLmax=[1.5, 1.45, 1.3]),
    )
    alpha = np.radians(np.arange(0.0, 30.0, 0.01))
    for mach, clmax in zip((0.2, 0.5, 0.8), (1.5, 1.45, 1.3)):
        cl = m.coefficients(AeroState(alpha=alpha, mach=mach)).CL
        assert cl.max() == pytest.approx(clmax, abs=1e-3)
        assert cl[-1] < 0.9 * clmax  # lift falls after the break
        assert float(m.clmax(mach)) == clmax


def test_each_mach_breakpoint_calibrates_its_clmax_as_it_would_alone():
    """The breakpoints still iterating are evaluated in one batch: a breakpoint's calibrated CLmax must not depend on
    the others' (at a breakpoint the lift curve reads that breakpoint's CLmax alone), bit for bit — here the
    neighbours' declared CLmax and lift slopes are changed, so that they also take other numbers of iterations."""
    from certkit.models.aero.interface import AeroReference

    ref_ = AeroReference(400.0, 60.0, 7.0, 30.0)

    def internal(cl_alpha, clmax):
        m = StabilityDerivativeModel(
            ref_,
            {"CL0": 0.2, "CL_alpha": cl_alpha, "CD0": 0.02, "k": 0.04},
            mach=[0.2, 0.5, 0.8],
            stall=StallModel(CLmax=clmax),
        )
        return m.kernel_data[2]

    a = internal([5.5, 6.0, 7.5], [1.5, 1.45, 1.3])
    b = internal([4.0, 6.0, 9.0], [1.1, 1.45, 1.7])
    assert a[1] == b[1] and a[0] != b[0] and a[2] != b[2]
    alone = StabilityDerivativeModel(
        ref_, {"CL0": 0.2, "CL_alpha": 6.0, "CD0": 0.02, "k": 0.04}, mach=[0.5], stall=StallModel(CLmax=1.45)
    )
    assert alone.kernel_data[2][0] == a[1]


def test_a_copy_with_further_controls_keeps_the_calibrated_clmax():
    """A copy with more control terms (a gust pseudo-control) skips the CLmax calibration: it must hold exactly what
    calibrating it afresh gives (controls neutral see only the base terms)."""
    from certkit.models.aero.interface import AeroReference

    ref_ = AeroReference(400.0, 60.0, 7.0, 30.0)
    terms = {"CL0": 0.2, "CL_alpha": [5.5, 6.0, 7.5], "CD0": 0.02, "k": 0.04, "CL_flap": 0.8}
    m = StabilityDerivativeModel(ref_, terms, mach=[0.2, 0.5, 0.8], stall=StallModel(CLmax=[1.5, 1.45, 1.3]))
    copy = m.with_control_terms({"CL_gust": [4.0, 4.5, 5.0]}, after_stall=("gust",))
    fresh = StabilityDerivativeModel(
        ref_,
        {**terms, "CL_gust": [4.0, 4.5, 5.0]},
        mach=[0.2, 0.5, 0.8],
        stall=StallModel(CLmax=[1.5, 1.45, 1.3]),
        after_stall=("gust",),
    )
    np.testing.assert_array_equal(copy.kernel_data[2], fresh.kernel_data[2])
    assert not np.array_equal(copy.kernel_data[2], [1.5, 1.45, 1.3])  # calibrated above the declared values
    alpha = np.radians(np.arange(0.0, 30.0, 0.01))
    assert copy.coefficients(AeroState(alpha=alpha, mach=0.5)).CL.max() == pytest.approx(1.45, abs=1e-3)
    with pytest.raises(KeyError, match="CL_alpha"):  # a base term would change the lift curve the calibration holds
        m.with_control_terms({"CL_alpha": [4.0, 4.5, 5.0]})


def test_a_subset_is_the_model_of_its_rows(ctx):
    """``subset`` against a model built from those rows alone (the baseline's engines and ground model, four loadings
    with their own inertia): every per-row array and every compiled-kernel argument equal bit for bit, the failed
    engines' thrust not carried over, the engines that run kept."""
    from certkit.models.flight import flight_model, ground_model

    loadings = [ctx.loading(m, x) for m, x in ((2.0e5, 27.0), (2.5e5, 28.0), (2.9e5, 27.5), (1.8e5, 28.4))]
    ground = ground_model(ctx.aircraft)
    model = flight_model(ctx.aircraft, ctx.aero("takeoff").model, loadings, ground=ground)
    model.set_operative([[True, False], [True, True], [False, True], [True, True]])
    model.failed_thrust_fraction = np.full((4, 2), 0.3)
    idx = np.array([3, 0, 2])
    sub = model.subset(idx)
    fresh = AircraftModel(
        model.aero,
        model.mass[idx],
        model.cg[idx],
        model.inertia[idx],
        model.engines,
        model.operative[idx],
        ground,
        model.g,
    )
    assert sub.n == fresh.n == 3 and model.n == 4
    for name in (
        "mass",
        "cg",
        "inertia",
        "inertia_inv",
        "operative",
        "failed_thrust_fraction",
        "r_ref",
        "r_eng",
        "r_gear",
        "_all_operative",
    ):
        np.testing.assert_array_equal(getattr(sub, name), getattr(fresh, name), err_msg=name)
    assert not sub.failed_thrust_fraction.any() and model.failed_thrust_fraction.all()
    assert len(sub._kernel_args) == len(fresh._kernel_args)
    for a, b in zip(sub._kernel_args, fresh._kernel_args):
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b))
    np.testing.assert_array_equal(sub.subset([True, False, True]).mass, model.mass[[3, 2]])

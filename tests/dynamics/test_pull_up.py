"""Symmetric pull-up / push-over manoeuvre points against the trim and the linear elevator-per-g balance."""

import math

import numpy as np
import pytest

from certkit.engine.conditions import Condition
from certkit.engine.context import Context
from certkit.models.dynamics.pull_up import symmetric_pull_up
from certkit.units import FT, KN, LB


@pytest.fixture(scope="module")
def trimmed(baseline):
    ctx = Context(baseline)
    ref = ctx.aircraft.reference.moment_point.x  # CG on the moment point: the table's Cm needs no transfer
    cond = Condition(
        mass=500000 * LB, x_cg=ref, configuration="clean", altitude=10000 * FT, speed=300 * KN, speed_kind="CAS"
    )
    return ctx, ctx.trim([cond])


def test_one_g_point_is_the_level_trim(trimmed):
    """At n = 1 the manoeuvre point is the straight level trim (another solver, the same equations): α and elevator
    within 1e-6 rad."""
    _, batch = trimmed
    r = batch[0]
    p = symmetric_pull_up(batch.model, r.V, r.h, 1.0, batch.u)
    assert p.converged[0]
    assert p.alpha[0] == pytest.approx(r.alpha, abs=1e-6)
    assert p.elevator[0] == pytest.approx(r.controls["elevator"], abs=1e-6)


def test_elevator_per_g_matches_the_linear_balance(trimmed):
    """Elevator per g of the steady pull-up (Etkin & Reid §2.9; Nelson §3.x): with q̂ = (n − 1) g c̄/(2V²) and
    CW = W/(q̄S), the lift and moment increments balance,
        CL_α Δα + CL_δ Δδ = (n − 1) CW − CL_q q̂,   Cm_α Δα + Cm_δ Δδ = −Cm_q q̂,
    solved by hand with the model's derivatives at the flight Mach number. The 6-DOF point (thrust held, full
    nonlinear kinematics) within 5 % for n = 1.5 and n = 0; pulling needs trailing edge up (Δδ < 0)."""
    ctx, batch = trimmed
    r = batch[0]
    aero = ctx.aero("clean").model
    ref = ctx.aircraft.reference
    rho = 1.225 * (1 - 2.25577e-5 * r.h) ** 4.25588
    mach = r.V / (340.294 * math.sqrt(1 - 2.25577e-5 * r.h))
    d = lambda name: float(np.asarray(aero.derivative(name, mach)))  # noqa: E731
    qbar = 0.5 * rho * r.V**2
    cw = 500000 * LB * 9.80665 / (qbar * ref.area)
    A = np.array([[d("CL_alpha"), d("CL_elevator")], [d("Cm_alpha"), d("Cm_elevator")]])
    for n in (1.5, 0.0):
        qhat = (n - 1) * 9.80665 * ref.mean_chord / (2 * r.V**2)
        dalpha, ddelta = np.linalg.solve(A, [(n - 1) * cw - d("CL_q") * qhat, -d("Cm_q") * qhat])
        p = symmetric_pull_up(batch.model, r.V, r.h, n, batch.u)
        assert p.converged[0]
        assert p.elevator[0] - r.controls["elevator"] == pytest.approx(ddelta, rel=0.05)
        assert (p.elevator[0] < r.controls["elevator"]) == (n > 1)

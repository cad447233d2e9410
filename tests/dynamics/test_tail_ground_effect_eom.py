"""The tail's loss of downwash near the runway in the equations of motion (certkit.models.aero.tail_ground_effect via
certkit.models.dynamics.kernel), on the baseline: unchanged far from the runway, a nose-down moment on it, a flare
flown with more nose-up elevator. Elevator sign: certkit.conventions (trailing edge down positive, nose-down)."""

import numpy as np
import pytest

from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.context import Context
from certkit.models.dynamics.controllers import TECSApproach, WingsLevel
from certkit.models.dynamics.eom import euler_to_quat
from certkit.models.dynamics.ground import ground_equilibrium
from certkit.models.dynamics.simulate import simulate, stop_when
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN


def _without_tail(ac):
    gm = ground_model(ac)
    gm.wing.lines = None  # the wing's ground effect only (the model before the tail's)
    return gm


@pytest.fixture(scope="module")
def ctx(baseline):
    return Context(baseline)


def _models(ctx, configuration, loading_names, design_weight):
    ac = ctx.aircraft
    conds = ConditionSpace(loading=DesignWeight(design_weight, loading_names), configurations=(configuration,)).expand(
        ac
    )
    loadings = [ctx.loading(c.mass, c.x_cg) for c in conds]
    aero = ctx.aero(configuration).model
    return (
        conds,
        flight_model(ac, aero, loadings, ground=ground_model(ac)),
        flight_model(ac, aero, loadings, ground=_without_tail(ac)),
        flight_model(ac, aero, loadings),
    )


def _level(n, h, theta, speed):
    x = np.zeros((n, 13))
    x[:, 2] = h
    x[:, 3], x[:, 5] = speed * np.cos(theta), speed * np.sin(theta)  # level path at attitude θ
    x[:, 9:13] = euler_to_quat(np.zeros(n), np.full(n, theta), np.zeros(n)).reshape(4, n).T
    return x


def test_unchanged_far_from_the_runway(ctx):
    """At 2 spans and more above the runway (where the wing's ground effect also ends) the derivatives are
    bit-identical with the tail's ground effect, without it, and without any ground model."""
    _, with_tail, wing_only, free = _models(ctx, "takeoff", ("forward", "aft"), "MTOW")
    u = np.zeros((2, len(with_tail.control_names)))
    u[:, with_tail.control_index("elevator")] = np.radians(-5.0)
    for h in (2.05 * 63.51, 300.0, 3000.0):  # the wing point 2 spans above the runway at 8° and more
        x = _level(2, h, np.radians(8.0), 85.0)
        xd = with_tail.evaluate(x, u)[0]
        assert np.array_equal(xd, wing_only.evaluate(x, u)[0])
        assert np.array_equal(xd, free.evaluate(x, u[:, : len(free.control_names)])[0])


def test_nose_down_moment_on_the_runway_worth_several_degrees_of_elevator(ctx):
    """On the runway at VR (155 KCAS), at the ground attitude and at 8° (the rotation), the tail's reduced downwash
    pitches the airplane nose down (q̇ lower than with the wing's ground effect alone), and the nose-up elevator
    that restores the pitch acceleration (q̇ is linear in the elevator) is of the order of degrees, more at the
    rotation attitude (more lift, more downwash to lose, the tail lower in the wake). Sign and order only (1–15°):
    the textbook statement is qualitative (the downwash at the tail falls near the ground, a nose-down moment the
    elevator must hold in rotation and flare); the baseline's numbers (about 2° at the ground attitude, 8–9° at 8°)
    are a model result, docs/baseline-sources.md §14."""
    _, with_tail, wing_only, _ = _models(ctx, "takeoff", ("forward", "reference", "aft"), "MTOW")
    u = np.zeros((3, len(with_tail.control_names)))
    x12 = ground_equilibrium(with_tail, u)
    je = with_tail.control_index("elevator")
    extra = []
    for theta in (None, np.radians(8.0)):
        x = x12.copy()
        if theta is not None:
            x[:, 10] = theta
        x[:, 3], x[:, 5] = 155 * KN * np.cos(x[:, 10]), 155 * KN * np.sin(x[:, 10])
        qd = with_tail.derivatives_euler(x, u)[:, 7]
        qd_wing = wing_only.derivatives_euler(x, u)[:, 7]
        u1 = u.copy()
        u1[:, je] = np.radians(-1.0)
        per_deg = wing_only.derivatives_euler(x, u1)[:, 7] - qd_wing  # q̇ per degree of nose-up elevator
        assert np.all(qd < qd_wing)
        extra.append((qd_wing - qd) / per_deg)  # degrees of nose-up elevator the tail's ground effect costs
    assert np.all((np.array(extra) > 1.0) & (np.array(extra) < 15.0)), extra
    assert np.all(extra[1] > extra[0])


@pytest.fixture(scope="module")
def flares(ctx):
    """The −3° TECS approach and flare of tests/dynamics/test_flare.py (MLW, reference CG, VREF 136 KCAS) flown with
    and without the tail's ground effect."""
    ac = ctx.aircraft
    (cond,) = ConditionSpace(loading=DesignWeight("MLW", ("reference",)), configurations=("landing",)).expand(ac)
    tb = ctx.trim([cond.with_(altitude=150 * FT, speed=136 * KN, speed_kind="CAS")], gamma=np.radians(-3.0))
    out = {}
    for name, gm in (("with", ground_model(ac)), ("without", _without_tail(ac))):
        m = flight_model(ac, ctx.aero("landing").model, [ctx.loading(cond.mass, cond.x_cg)], ground=gm)
        u0 = np.zeros((1, len(m.control_names)))
        u0[:, : tb.u.shape[1]] = tb.u
        tecs = TECSApproach(m, tb.x, u0, limits=control_limits(ac, design=False)["elevator"])
        res = simulate(
            m,
            tb.x,
            u0,
            60.0,
            0.05,
            controllers=[tecs, WingsLevel(m, u0)],
            stop=[stop_when("touchdown", lambda t, x, o: o.gear_load.sum(axis=1) > 0.0)],
        )
        out[name] = (m, res)
    return out


def test_flare_needs_more_nose_up_elevator_near_the_runway(flares):
    """Both flares touch down, and the flare's most nose-up elevator (negative, certkit.conventions) is at least 2°
    more nose-up with the tail's ground effect (the baseline: −8.8° against −4.9°; the approach from 150 ft starts
    at h/b ≈ 0.72, inside both ground effects, so the two runs differ slightly from the start)."""
    (m, res), (_, res0) = flares["with"], flares["without"]
    je = m.control_index("elevator")
    assert res.stop_reason[0] == "touchdown" and res0.stop_reason[0] == "touchdown"
    de, de0 = np.degrees(res.controls[:, 0, je]), np.degrees(res0.controls[:, 0, je])
    assert de.min() < de0.min() - 2.0

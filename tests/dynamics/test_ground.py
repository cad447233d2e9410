"""Ground model of the baseline (gear legs from geometry.landing_gear) and a takeoff run.

Hand references (SI, from the aircraft file's numbers, independent of certkit's code path):
    gear stations x_nose = 22.1 ft, x_main = 107.0 ft (airplane frame, aft of the nose);
    lever rule at rest: N_nose = W (x_main − x_cg)/(x_main − x_nose), N_mains = W − N_nose;
    rolling friction μ = 0.02, braked mains + 0.4 at full brake: ẍ = −g (0.02 + 0.4 N_mains/W).
"""

import numpy as np
import pytest

from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.models.dynamics.controllers import PitchAttitudeHold
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.dynamics.ground import gear_heights, ground_equilibrium
from certkit.models.dynamics.simulate import airborne_above, simulate
from certkit.models.flight import flight_model, ground_model
from certkit.units import FT, KN, LB

G = 9.80665
X_NOSE, X_MAIN = 22.1 * FT, 107.0 * FT


@pytest.fixture(scope="module")
def setup(baseline):
    from certkit.engine.context import Context

    ctx = Context(baseline)
    ac = ctx.aircraft
    conds = ConditionSpace(
        loading=DesignWeight("MTOW", ("forward", "reference", "aft")), configurations=("takeoff",)
    ).expand(ac)
    loadings = [ctx.loading(c.mass, c.x_cg) for c in conds]
    return ctx, conds, loadings


def _glider(ctx, loadings, ground):
    """The baseline without engines (no idle thrust), so that only gear, weight and aero act."""
    mp = [ld.properties for ld in loadings]
    return AircraftModel(
        ctx.aero("takeoff").model, [p.mass for p in mp], [p.cg for p in mp], [p.inertia for p in mp], (), ground=ground
    )


def test_static_reactions_split_the_weight_by_the_lever_rule(setup):
    """At rest (MTOW 656,000 lb) the nose and the two main legs carry W by the lever rule about
    the CG's station: at the reference CG 97.25 ft, N_nose = W·(107.0 − 97.25)/(107.0 − 22.1)
    = 11.48 % of W (75,340 lb); within 0.1 % (the sizing loading: both legs at the same stroke, level).
    At the forward and aft CG corners the attitude is no longer exactly level; within 1 %."""
    ctx, conds, loadings = setup
    m = _glider(ctx, loadings, ground_model(ctx.aircraft))
    u = np.zeros((m.n, len(m.control_names)))
    x = ground_equilibrium(m, u)
    _, out = m.derivatives_euler(x, u, with_outputs=True)
    W = 656_000 * LB * G
    for i, ld in enumerate(loadings):
        x_cg = ld.properties.cg[0]
        nose = W * (X_MAIN - x_cg) / (X_MAIN - X_NOSE)
        tol = 1e-3 if i == 1 else 1e-2
        assert out.gear_load[i, 2] == pytest.approx(nose, rel=tol)
        assert out.gear_load[i, :2].sum() == pytest.approx(W - nose, rel=tol)
        assert out.gear_load[i, 0] == pytest.approx(out.gear_load[i, 1], rel=1e-9)  # symmetric mains
    ref = conds[1].x_cg
    assert out.gear_load[1, 2] / W == pytest.approx((107.0 - ref / FT) / (107.0 - 22.1), rel=1e-3)
    assert out.gear_load[1, 2] / LB / G == pytest.approx(75_340, rel=2e-3)
    # each leg compressed by its static stroke (0.30 m) at the sizing loading
    assert gear_heights(m, x)[1] == pytest.approx(-0.30, abs=1e-6)


def test_rolling_friction_and_braking_deceleration(setup):
    """Rolling at 5 m/s (aero forces below 0.2 % of the friction): ẍ = −0.02 g unbraked and
    −g (0.02 + 0.4·N_mains/W) at full brake, N_mains/W = (x_cg − 22.1 ft)/(84.9 ft); within 1 %."""
    ctx, conds, loadings = setup
    m = _glider(ctx, loadings, ground_model(ctx.aircraft))
    u = np.zeros((m.n, len(m.control_names)))
    x = ground_equilibrium(m, u)
    th = x[:, 10]
    x[:, 3], x[:, 5] = 5.0 * np.cos(th), 5.0 * np.sin(th)  # rolling horizontally at 5 m/s

    def horizontal(xd):  # earth-frame acceleration along the runway
        return np.cos(th) * xd[:, 3] + np.sin(th) * xd[:, 5]

    assert horizontal(m.derivatives_euler(x, u)) == pytest.approx(np.full(m.n, -0.02 * G), rel=1e-2)
    u[:, m.control_index("brake")] = 1.0
    share = (np.array([ld.properties.cg[0] for ld in loadings]) - X_NOSE) / (X_MAIN - X_NOSE)
    assert horizontal(m.derivatives_euler(x, u)) == pytest.approx(-G * (0.02 + 0.4 * share), rel=1e-2)


@pytest.fixture(scope="module")
def takeoff(setup):
    """All engines at full throttle from brake release at MTOW, reference CG; rotation at VR = 155 KCAS
    at 3°/s to the V2 attitude (the 1-g trim pitch attitude at V2 = 161 KCAS)."""
    ctx, conds, loadings = setup
    ac = ctx.aircraft
    ref = [conds[1]]
    trim_v2 = ctx.trim([ref[0].with_(altitude=0.0, speed=161 * KN, speed_kind="CAS")])[0]
    m = flight_model(ac, ctx.aero("takeoff").model, [loadings[1]], ground=ground_model(ac))
    u = np.zeros((1, len(m.control_names)))
    u[:, m.throttle_slice] = 1.0
    x0 = ground_equilibrium(m, u)
    pah = PitchAttitudeHold(m, u, 155 * KN, trim_v2.theta, limits=(-np.radians(30), np.radians(25)))
    h35 = x0[0, 2] + 35 * FT
    res = simulate(m, x0, u, 90.0, 0.05, controllers=[pah], stop=[airborne_above(h35)])
    return m, x0, res, trim_v2, h35


def test_takeoff_rotates_about_the_main_gear_lifts_off_and_reaches_35_ft(takeoff):
    """Ground roll, rotation and lift-off: the nose gear leaves the runway only once V ≥ VR; while the
    nose rises by more than 2 m the main-gear contact points stay on the runway (their struts extend
    by at most the 0.3 m static stroke as lift builds) and the nose rises relative to them by the
    wheelbase (84.9 ft) × (sin θ − sin θ₀) — a rotation about the main gear; lift-off (no gear load) at VLOF > VR; 35
    ft reached climbing and accelerating, the pitch rate
    below 5°/s (commanded 3°/s: no over-rotation), the attitude at most 3° short of (never above) the target."""
    m, x0, res, trim_v2, h35 = takeoff
    assert res.stop_reason[0].startswith("airborne")
    V, theta, h = res["V"][:, 0], res["theta"][:, 0], res["h"][:, 0]
    # contact heights along the run (recompute from the recorded attitude)
    x12 = np.zeros((V.size, 12))
    x12[:, 2], x12[:, 9], x12[:, 10] = h, res["phi"][:, 0], theta
    mm = m.subset(np.zeros(V.size, dtype=int))
    heights = gear_heights(mm, x12)
    nose_off = np.flatnonzero(heights[:, 2] > 0.0)[0]
    assert V[nose_off] >= 155 * KN
    rotating = np.arange(nose_off, V.size)
    rotating = rotating[heights[rotating, 0] < 0.0]  # mains still on the runway
    assert heights[rotating, 2].max() - heights[nose_off, 2] > 2.0
    static_main = gear_heights(m, x0)[0, 0]
    assert np.all((heights[rotating, 0] >= static_main - 0.05) & (heights[rotating, 0] <= 0.0))
    # the pivot is the main gear: nose rise relative to the mains = wheelbase × (sin θ − sin θ0), ±2 cm
    rel = (heights[rotating, 2] - heights[rotating, 0]) - (heights[0, 2] - heights[0, 0])
    assert rel == pytest.approx((X_MAIN - X_NOSE) * (np.sin(theta[rotating]) - np.sin(theta[0])), abs=0.02)
    lof = rotating[-1] + 1
    assert V[lof] > 155 * KN
    assert h[-1] >= h35 - 0.5 and h[-1] > h[lof] and V[-1] > V[lof]
    # still rotating at 3°/s toward the target at 35 ft: never above it, at most 3° short of it
    assert trim_v2.theta - np.radians(3.0) < theta[-1] <= trim_v2.theta + np.radians(0.5)
    assert res["q"][:, 0].max() < np.radians(5.0)

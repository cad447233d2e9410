"""Minimum unstick speed (certkit.models.dynamics.unstick) against the lift equation.

Reference (closed form, no one here wrote it): at the point of lift-off the flight path runs along the runway, so the
lift of the attitude's angle of attack α = θ and the thrust's vertical component carry the weight,

    ½ ρ₀ V² S C_L(θ, δe) + T sin θ = m g,   V = √(2 (m g − T sin θ) / (ρ₀ S C_L)),

with the elevator that zeroes the pitching moment about the CG, δe = −(Cm0 + Cm_α θ)/Cm_δe (moment reference at the
CG, thrust through it). The test airplane is a linear derivative table without ground effect (so C_L is the table's),
on a two-leg tricycle gear; ρ the ISA troposphere's, ρ₀ (1 − 2.25577e-5 h)^4.2559 (ρ₀ 1.225 kg/m³), at the CG's
height with the main wheels (1.5 m aft of and 3 m below the CG) touching the runway: h = 1.5 sin θ + 3 cos θ.
"""

import numpy as np
import pytest

from certkit.models.aero.derivative_model import StabilityDerivativeModel, StallModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel, Engine, GearLeg, GroundModel, inertia_tensor
from certkit.models.dynamics.unstick import minimum_unstick_speed, unstick_speeds

RHO0, G = 1.225, 9.80665
MASS, S = 60_000.0, 120.0
X_CG = 15.0
CL0, CL_A, CL_DE = 0.6, 5.0, 0.35
CM0, CM_A, CM_DE = 0.02, -1.1, -1.3
STRIKE = np.radians(12.0)
LIMITS = (np.radians(-30.0), np.radians(20.0))


def airplane(thrust=0.0, stall=None, n=1):
    d = {"CL0": CL0, "CL_alpha": CL_A, "CL_elevator": CL_DE, "Cm0": CM0, "Cm_alpha": CM_A, "Cm_elevator": CM_DE}
    d |= {"CD0": 0.08, "k": 0.045}
    aero = StabilityDerivativeModel(
        AeroReference(S, 34.0, 4.0, x_ref=X_CG), d, control_names=("elevator",), stall=stall
    )
    legs = [
        GearLeg("main", (X_CG + 1.5, 0.0, -3.0), 5e6, 2e5, braked=True),
        GearLeg("nose", (X_CG - 12.0, 0.0, -3.0), 2e6, 1e5),
    ]
    engine = Engine("both", thrust=lambda thr, h, m: thr * thrust + 0.0 * h, position=(X_CG, 0.0, 0.0))
    model = AircraftModel(
        aero, MASS, (X_CG, 0.0, 0.0), inertia_tensor(1e6, 3e6, 4e6), [engine], ground=GroundModel(legs), g=G, n=n
    )
    u = np.zeros((n, len(model.control_names)))
    u[:, model.control_index("throttle:both")] = 1.0
    return model, u


def by_hand(theta, thrust=0.0):
    de = -(CM0 + CM_A * theta) / CM_DE
    cl = CL0 + CL_A * theta + CL_DE * de
    rho = RHO0 * (1.0 - 2.25577e-5 * (1.5 * np.sin(theta) + 3.0 * np.cos(theta))) ** 4.2559
    return np.sqrt(2.0 * (MASS * G - thrust * np.sin(theta)) / (rho * S * cl)), de


@pytest.mark.parametrize("thrust", [0.0, 0.25 * MASS * G])
def test_the_unstick_speed_at_each_attitude_is_the_lift_equation(thrust):
    """At 4°, 8° and 12°, with and without a thrust of 0.25 W: speed within 1e-4, elevator within 1e-6 rad."""
    model, u = airplane(thrust)
    theta = np.radians([4.0, 8.0, 12.0])
    V, de, clipped, _ = unstick_speeds(model, u, theta, LIMITS)
    hand_v, hand_de = by_hand(theta, thrust)
    assert V[:, 0] == pytest.approx(hand_v, rel=1e-4)
    assert de[:, 0] == pytest.approx(hand_de, abs=1e-6)
    assert not clipped.any()


def test_lift_growing_up_to_the_tail_strike_makes_vmu_geometry_limited():
    """Linear lift: the least unstick speed is the tail-strike attitude's (12°)."""
    model, u = airplane()
    r = minimum_unstick_speed(model, u, STRIKE, LIMITS)
    assert r.limited_by == ("attitude limit",) and r.geometry_limited[0]
    assert r.attitude[0] == pytest.approx(STRIKE)
    assert r.speed[0] == pytest.approx(by_hand(STRIKE)[0], rel=1e-4)


def test_a_lift_maximum_below_the_tail_strike_makes_vmu_lift_limited():
    """A stall at C_Lmax 1.2 (the linear lift reaches it near 7° with the balancing elevator): VMU is reached at a
    lower attitude than 12° and within 1.5 % of √(2 m g/(ρ₀ S C_Lmax)) (the model rounds its lift onto C_Lmax and
    blends in the separated flow past the break)."""
    model, u = airplane(stall=StallModel(1.2, rounding=0.02))
    r = minimum_unstick_speed(model, u, STRIKE, LIMITS)
    assert r.limited_by == ("lift maximum",) and not r.geometry_limited[0]
    assert r.attitude[0] < STRIKE - np.radians(1.0)
    assert r.speed[0] == pytest.approx(np.sqrt(2.0 * MASS * G / (RHO0 * S * 1.2)), rel=0.015)
    assert r.speed[0] < r.speeds[0, 0] - 1.0  # 12° lifts off more than 1 m/s later: past the lift maximum


def test_an_elevator_that_cannot_hold_the_attitude_limits_vmu():
    """With the nose-up stop at −7.5° the elevator holds the attitude only up to θ = (Cm0 + Cm_δe·δ_stop)/(−Cm_α) =
    9.91°: VMU is the lift equation's at the highest attitude of the 0.25° grid below it (9.75°), flagged
    elevator-limited."""
    model, u = airplane()
    stop = np.radians(-7.5)
    r = minimum_unstick_speed(model, u, STRIKE, (stop, LIMITS[1]))
    held_max = (CM0 + CM_DE * stop) / -CM_A
    assert np.degrees(held_max) == pytest.approx(9.91, abs=0.01)
    assert r.limited_by == ("elevator",)
    assert r.attitude[0] == pytest.approx(np.radians(9.75))
    assert r.speed[0] == pytest.approx(by_hand(np.radians(9.75))[0], rel=1e-4)
    assert np.isnan(r.speeds[0, 0])  # 12°: beyond the elevator


def test_no_lift_off_within_the_speed_range_is_nan():
    """A weight the lift cannot carry below the search's upper speed gives no VMU (nan), never a number."""
    model, u = airplane()
    heavy = AircraftModel(model.aero, 40 * MASS, model.cg, model.inertia, model.engines, ground=model.ground, g=G)
    r = minimum_unstick_speed(heavy, u, STRIKE, LIMITS)
    assert np.isnan(r.speed[0]) and r.limited_by == ("none",)


def test_lift_beyond_the_free_air_maximum_is_not_credited():
    """Given C_Lmax 1.3 (the free-air maximum a ground-effect factor must not exceed), the linear airplane's VMU is
    the lift equation's at the highest attitude of the grid whose C_L(θ, δe(θ)) stays within 1.3, lift-limited."""
    model, u = airplane()
    r = minimum_unstick_speed(model, u, STRIKE, LIMITS, cl_max=1.3)
    grid = STRIKE - np.radians(0.25) * np.arange(33)
    cl = CL0 + CL_A * grid + CL_DE * (-(CM0 + CM_A * grid) / CM_DE)
    top = grid[np.argmax(cl <= 1.3)]
    assert r.limited_by == ("lift maximum",)
    assert r.attitude[0] == pytest.approx(top)
    assert r.speed[0] == pytest.approx(by_hand(top)[0], rel=1e-4)

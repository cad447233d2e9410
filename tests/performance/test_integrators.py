"""Mission integrators against closed forms no one here wrote.

* Cruise in weight with constant L/D, TSFC and speed is the Breguet range R = V (L/D)/(c g) ln(W0/W1)
  (Breguet 1923; Anderson, *Aircraft Performance and Design*, 1999, eq. 5.153). Tolerance 1e-6 relative: the
  spline of the specific air range 1/W is integrated exactly up to its interpolation error.
* Energy method (Rutowski 1954; Anderson §6.5): with a constant specific excess power P_s the time to gain the
  energy height ΔE = Δh + ΔV²/(2g) is ΔE/P_s exactly, whatever the split between altitude and speed.
"""

import numpy as np
import pytest

from certkit.models.performance.integrators import LevelCruise, breguet_range, fly_path
from certkit.units import G0

V, LD, C = 250.0, 18.0, 0.55 / 3600 / G0  # m/s, L/D, 0.55 lb/lbf/h in kg/(N s)


def constant_ld_cruise():
    w = np.linspace(150e3, 300e3, 12)
    return LevelCruise.from_fuel_flow(V, w, C * w * G0 / LD)  # fuel flow = c D = c W g / (L/D)


def test_cruise_integral_reproduces_breguet():
    cruise = constant_ld_cruise()
    for w0, w1 in ((290e3, 200e3), (280e3, 160e3), (210e3, 205e3)):
        assert cruise.distance(w0, w1) == pytest.approx(breguet_range(V, LD, C, w0, w1), rel=1e-6)


def test_breguet_closed_form_number():
    # V/(c g) (L/D) ln 1.5 with c in lb/lbf/h: 250 m/s × 3600 s/h / 0.55 × 18 × 0.405465 = 11,943 km
    assert breguet_range(V, LD, C, 300e3, 200e3) == pytest.approx(250 * 3600 / 0.55 * 18 * np.log(1.5), rel=1e-12)


def test_weight_after_inverts_the_breguet_distance():
    cruise = constant_ld_cruise()
    d = breguet_range(V, LD, C, 290e3, 210e3)
    assert cruise.weight_after(290e3, d) == pytest.approx(210e3, rel=1e-6)
    assert cruise.time(290e3, 210e3) == pytest.approx(d / V, rel=1e-6)


def constant_power_path(ps, h, v, thrust=2.0e5, ff=2.0):
    """Required thrust chosen so that (T − D) V / (W g) = ps at every point and weight."""

    def required(k, w):
        return thrust - ps * np.asarray(w) * G0 / v[k]

    K = len(h)
    return fly_path(h, v, [250e3, 180e3], required, np.full(K, thrust), np.full(K, ff))


def test_energy_method_constant_excess_power_climb_and_acceleration():
    h = np.array([500.0, 3000.0, 3000.0, 9000.0])
    v = np.array([130.0, 130.0, 160.0, 230.0])  # climb, level acceleration, climb while accelerating
    ps = 8.0
    res = constant_power_path(ps, h, v)
    de = np.diff(h) + np.diff(v**2) / (2 * G0)
    t_expected = np.concatenate([[0.0], np.cumsum(de / ps)])
    assert res.reached.all()
    for row in range(2):
        assert res.time[row] == pytest.approx(t_expected, rel=1e-9)
        assert res.fuel[row] == pytest.approx(2.0 * t_expected, rel=1e-9)
    # the level acceleration gains (160² − 130²)/(2 g) = 443.6 m of energy height at 8 m/s: 55.4 s
    assert res.time[0, 2] - res.time[0, 1] == pytest.approx((160**2 - 130**2) / (2 * G0) / 8.0, rel=1e-9)


def test_energy_method_descent_and_unreachable_climb():
    h = np.array([9000.0, 5000.0, 1000.0])
    v = np.array([220.0, 200.0, 150.0])
    down = constant_power_path(-12.0, h, v)
    de = np.diff(h) + np.diff(v**2) / (2 * G0)
    assert down.reached.all()
    assert down.time[0, -1] == pytest.approx(de.sum() / -12.0, rel=1e-9)
    up = constant_power_path(-3.0, h[::-1], v[::-1])  # drag above thrust: the climb never starts
    assert not up.reached[:, 1:].any() and np.isnan(up.time[:, -1]).all()


def test_a_climb_stops_where_the_excess_power_falls_below_the_minimum():
    """P_s = 2 m/s everywhere: with a minimum of 1.5 m/s the whole path is flown; with 2.5 m/s from the third point
    on, the path ends at the second (the segment into a point below the minimum is not flown)."""
    h = np.array([1000.0, 4000.0, 7000.0, 10000.0])
    v = np.full(4, 200.0)
    ps = 2.0

    def path(minimum):
        def required(k, w):
            return 2.0e5 - ps * np.asarray(w) * G0 / v[k]

        return fly_path(h, v, [250e3], required, np.full(4, 2.0e5), np.full(4, 2.0), np.asarray(minimum))

    assert path([1.5] * 4).reached.all()
    cut = path([0.0, 0.0, 2.5, 2.5])
    assert cut.reached[0].tolist() == [True, True, False, False]
    assert cut.time[0, 1] == pytest.approx(3000.0 / ps, rel=1e-9)

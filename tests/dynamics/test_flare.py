"""TECS −3° approach, exponential flare and touchdown of the baseline (landing configuration, MLW
460,000 lb, reference CG, VREF 136 KCAS), with the ground model from geometry.landing_gear.

References: the exponential flare ḣ = −(h + h_aim)/τ (Stevens & Lewis, *Aircraft Control and
Simulation*, 2nd ed., §4.7; McRuer, Ashkenas & Graham 1973, ch. 10) with τ = (h_f + h_aim)/ḣ_app,
ḣ_app = V sin 3°: at 136 kn (70.0 m/s) ḣ_app = 3.66 m/s = 12.0 ft/s, and with h_f = 15 m,
h_aim = 1 m, τ = 16/3.66 = 4.37 s and the commanded touchdown sink h_aim/τ = 0.23 m/s (0.75 ft/s).
"""

import numpy as np
import pytest

from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.context import Context
from certkit.models.dynamics.controllers import TECSApproach, WingsLevel
from certkit.models.dynamics.simulate import simulate, stop_when
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN


def sink_rate(x13):
    q0, q1, q2, q3 = x13[:, 9:13].T
    return (
        2 * (q1 * q3 - q0 * q2) * x13[:, 3]
        + 2 * (q2 * q3 + q0 * q1) * x13[:, 4]
        + (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * x13[:, 5]
    )


@pytest.fixture(scope="module")
def landing(baseline):
    ctx = Context(baseline)
    ac = ctx.aircraft
    (cond,) = ConditionSpace(loading=DesignWeight("MLW", ("reference",)), configurations=("landing",)).expand(ac)
    tb = ctx.trim([cond.with_(altitude=150 * FT, speed=136 * KN, speed_kind="CAS")], gamma=np.radians(-3.0))
    assert tb.converged.all()
    m = flight_model(ac, ctx.aero("landing").model, [ctx.loading(cond.mass, cond.x_cg)], ground=ground_model(ac))
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
        stop=[stop_when("touchdown", lambda t, x, out: out.gear_load.sum(axis=1) > 0.0)],
    )
    return m, tb, tecs, res


def test_flare_time_constant_from_the_approach_sink_rate(landing):
    """τ = (15 + 1)/(V sin 3°) = 4.36 s at 136 KCAS (70.12 m/s TAS at 150 ft, σ = 0.9956); commanded touchdown sink
    0.75 ft/s."""
    m, tb, tecs, res = landing
    V = np.linalg.norm(tb.x[0, 3:6])
    sigma = (1 - 2.25577e-5 * 150 * 0.3048) ** 4.25588  # ISA density ratio at 150 ft
    assert V == pytest.approx(136 * KN / np.sqrt(sigma), rel=1e-3)  # TAS = 70.12 m/s
    assert tecs.tau[0] == pytest.approx(16.0 / (70.12 * np.sin(np.radians(3.0))), rel=2e-3)
    assert tecs.aim / tecs.tau[0] / FT == pytest.approx(0.75, abs=0.02)


def test_approach_tracks_the_glide_path_then_flares_to_a_soft_touchdown(landing):
    """Above the flare height the −3° path is held (sink 12.0 ft/s within 0.6 ft/s after 3 s: the trim at 150 ft
    is a free-air trim, and ground effect at h/b ≈ 0.75 — lift +0.9 %, induced drag −5 % (Wieselsberger's image
    theory, certkit.models.aero.ground_effect) — slows the sink by about 0.5 ft/s before the TECS takes it out;
    0.3 ft/s without ground effect); below it
    the throttle is at idle; the airplane touches down (first gear load) with a sink rate below
    3 ft/s — half of the 6 ft/s landing-distance demonstration criterion — on its main gear first."""
    m, tb, tecs, res = landing
    assert res.stop_reason[0] == "touchdown"
    k3 = int(3.0 / 0.05)
    hdot3 = (res["h"][k3 + 1, 0] - res["h"][k3 - 1, 0]) / 0.1
    assert -hdot3 / FT == pytest.approx(136 * 1.68781 * np.sin(np.radians(3.0)), abs=0.6)
    thr = res.controls[:, 0, m.throttle_slice.start]
    assert np.all(
        thr[tecs.flaring[0] & (np.arange(res.t.size) > np.argmax(res["h"][:, 0] - tecs.h_gear[0] < 15.0))] == 0.0
    )
    td_sink = sink_rate(res.final_state)[0] / FT
    assert 0.0 < td_sink < 3.0
    _, out = m.derivatives_quat(res.final_state, res.controls[-1], with_outputs=True)
    assert out.gear_load[0, :2].sum() > 0.0 and out.gear_load[0, 2] == 0.0  # mains first
    assert res["theta"][-1, 0] > 0.0  # nose up at touchdown

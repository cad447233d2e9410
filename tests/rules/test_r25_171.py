"""§25.171 static margin and §25.173 speed stability.

Hand calculations in feet and knots (MAC 27.456 ft, reference point 97.25 ft):
* neutral point x_np = 97.25 − 27.456·Cm_α/CL_α (ft), static margin (x_np − x_cg)/27.456 (Etkin & Reid §2.3);
* elevator-fixed speed stability from the two trim equations Cm = 0, CL = W/(qS) (Etkin & Reid §2.4; McLean):
  dδe/dCL = −(Cm_α,cg/CL_α)/(Cm_δe − Cm_α,cg CL_δe/CL_α), dCL/dV = −2 CL/V, so dδe/dV = −2 CL/V · dδe/dCL.
  Tolerance 15 % (the trims add the thrust moment, the flight-path change at constant thrust and q-terms).
"""

import math

import pytest

from certkit.engine.conditions import speed_as
from certkit.units import KN, LB

from .helpers import own, run_rule

MAC_FT, XREF_FT = 27.456, 97.25


@pytest.fixture(scope="module")
def sm():
    return run_rule("25.171")


@pytest.fixture(scope="module")
def grad():
    return run_rule("25.173(a)")


def _at(result, loading, configuration, point, altitude=0.0):
    return next(
        f
        for f in own(result)
        if f.condition.loading == loading
        and f.condition.configuration == configuration
        and f.condition.get("speed_point") == point
        and f.condition.altitude == altitude
        and f.margin is not None
    )


def test_static_margin_hand_calculation(sm, ctx):
    f = _at(sm, "aft_mlw", "landing", "1.13 VSR")
    m = ctx.aero("landing").model
    mach = f.details["mach"]
    x_np = XREF_FT - MAC_FT * float(m.derivative("Cm_alpha", mach)) / float(m.derivative("CL_alpha", mach))
    assert f.value == pytest.approx((x_np - 101.92) / MAC_FT, abs=1e-4)
    assert f.margin == pytest.approx(f.value - 0.05, abs=1e-12)


def test_sign_aft_cg_reduces_static_margin_and_speed_stability(sm, grad, tmp_path):
    """Moving the most aft corner 1.5 ft aft lowers its static margin by 1.5/27.456 MAC and its dδe/dV."""
    edit = [("x: 101.92 ft}    # 42 % MAC", "x: 103.42 ft}    # 42 % MAC")]
    r = run_rule("25.171", tmp_path, edits=edit)
    before, after = _at(sm, "aft_mlw", "landing", "1.13 VSR"), _at(r, "aft_mlw", "landing", "1.13 VSR")
    assert after.value - before.value == pytest.approx(-1.5 / MAC_FT, abs=1e-6)
    g = run_rule("25.173(a)", tmp_path, edits=edit)
    assert _at(g, "aft_mlw", "landing", "1.3 VSR").value < _at(grad, "aft_mlw", "landing", "1.3 VSR").value


def test_a_horizontal_tail_moved_forward_fails(sm, tmp_path):
    """A deficient airplane by geometry: the horizontal tail moved 20 ft forward (root leading edge 168 → 148 ft; tail
    arm 87 → 67 ft). The tail's contribution to the stability about the CG falls with its arm, so the neutral point
    moves forward and the aftmost corner's stick-fixed static margin drops below the 5 % MAC minimum (aft_mlw, 3.2 %
    MAC; aft_mid is left at 5.3 %): §25.171 fails there, and every condition's margin is smaller than the
    baseline's."""
    r = run_rule(
        "25.171",
        tmp_path,
        edits=[
            (
                "root_leading_edge: {x: 168.0 ft, y: 0 ft, z: 2.0 ft}",
                "root_leading_edge: {x: 148.0 ft, y: 0 ft, z: 2.0 ft}",
            )
        ],
    )
    assert r.status == "fails"
    assert {f.condition.loading for f in own(r) if f.status == "fails"} == {"aft_mlw"}
    before = {
        (f.condition.loading, f.condition.configuration, f.condition.altitude, f.condition.get("speed_point")): f.value
        for f in own(sm)
        if f.value is not None
    }
    for f in own(r):
        if f.value is not None:
            key = (f.condition.loading, f.condition.configuration, f.condition.altitude, f.condition.get("speed_point"))
            assert f.value < before[key]


def test_speed_stability_hand_calculation(grad, ctx):
    f = _at(grad, "fwd_mlw", "landing", "1.3 VSR")
    c = f.condition
    m = ctx.aero("landing").model
    mach = speed_as(c, "MACH")
    d = lambda name: float(m.derivative(name, mach))  # noqa: E731
    v_fts = c.speed / 0.3048  # CAS = TAS at sea level
    cl = 460_000 / (0.5 * 0.0023769 * v_fts**2 * 4927.3)
    cm_a = d("Cm_alpha") + d("CL_alpha") * (92.04 - XREF_FT) / MAC_FT
    ddelta_dcl = -(cm_a / d("CL_alpha")) / (d("Cm_elevator") - cm_a * d("CL_elevator") / d("CL_alpha"))
    per_kt = math.degrees(-2 * cl / (c.speed / KN) * ddelta_dcl)
    assert c.mass / LB == pytest.approx(460_000, rel=1e-6)
    assert f.value == pytest.approx(per_kt, rel=0.15)
    assert f.value > 0 and f.status == "complies"


def test_speed_stability_at_a_fixed_throttle_where_the_flight_path_floats(grad, ctx):
    """aft_mrw (657,000 lb), clean, 35,000 ft, 1.3 VSR: the trim speed is held in level flight near full thrust
    (throttle above 0.9); the ±5 % speeds hold that throttle and the flight path floats (a slight climb and descent),
    so no probe asks for more than full thrust and the gradient is evaluated. Cross-check by the other trim
    formulation: trimmed at the flight-path angles found, solving for the throttle, each speed needs the held throttle
    again (1e-4), the stabiliser held at its trim-speed setting. At the forward CG the same point lies beyond the
    level-flight thrust ceiling: its trim point is the steady descent at full thrust, and it is evaluated too."""
    from certkit.units import FT

    beyond = _at(grad, "fwd_mrw", "clean", "1.3 VSR", altitude=35000 * FT)
    assert beyond.status == "complies" and beyond.details["trim_flight"].startswith("steady descent at full thrust")
    f = _at(grad, "aft_mrw", "clean", "1.3 VSR", altitude=35000 * FT)
    d = f.details
    assert f.status == "complies" and f.value > 0 and d["trim_flight"] == "level flight"
    assert 0.9 < d["throttle"] < 1.0
    from certkit.models.dynamics.trim import held_stabilizer

    c, k = f.condition, 0.05
    held = held_stabilizer(ctx.trim([c]).results)  # the stabiliser stays at its trim-speed setting
    for factor, gamma in ((1 - k, d["gamma_low_deg"]), (1 + k, d["gamma_high_deg"])):
        r = ctx.trim([c.with_(speed=c.speed * factor)], gamma=math.radians(gamma), stabilizer=held).results[0]
        thr = next(v for n, v in r.controls.items() if n.startswith("throttle"))
        assert r.converged and thr == pytest.approx(d["throttle"], abs=1e-4)
    assert d["gamma_low_deg"] * d["gamma_high_deg"] < 0  # the path changes sign across the trim speed


def test_every_speed_stability_point_is_evaluated(grad):
    """No §25.173(a) condition of the baseline is left not evaluated by a trim."""
    assert not [f for f in own(grad) if f.status == "not_evaluated" and f.condition.loading]


def test_not_evaluated(tmp_path):
    """(c) needs a control-force model, which the baseline does not declare; (a) and 25.171 need VMO."""
    r = run_rule("25.173(c)")
    assert r.status == "not_evaluated" and "control-force model" in own(r)[0].reason
    r = run_rule("25.171", tmp_path, edits=[("  VMO: 272 kn EAS              # = VC, see above\n", "")])
    assert r.status == "not_evaluated" and own(r)[0].reason == "needs speeds.VMO"


def test_top_of_the_stability_range_vfc(ctx, tmp_path, grad):
    """§25.173(a)/§25.177: the top of the range clean is VFC/MFC; without it the least §25.253(b) allows, midway
    between VMO and VD: (272 + 340)/2 = 306 kn EAS, = CAS at sea level (hand). A declared VFC (320 kn CAS) is used
    as given. Extended configurations end at VFE/VLE, so their "VFC" point is not applicable. The §25.173(a) top
    point is trimmed at VFC/1.05 so that its faster step reaches VFC (the speed in the condition, 291.4 kn)."""
    from certkit_rules.part25.support.stability_speeds import VFC_FLOOR, stability_limit_cas

    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context

    from .helpers import edited_baseline

    v, basis = stability_limit_cas(ctx, "clean", 0.0)
    assert v / KN == pytest.approx(306.0, abs=0.05) and basis == VFC_FLOOR
    assert stability_limit_cas(ctx, "landing", 0.0)[1].startswith("VFE/VLE")
    declared = Context(
        load_aircraft(edited_baseline(tmp_path, [("  VMO: 272 kn EAS", "  VFC: 320 kn CAS\n  VMO: 272 kn EAS")]))
    )
    v, basis = stability_limit_cas(declared, "clean", 0.0)
    assert v / KN == pytest.approx(320.0, abs=1e-6) and basis == "declared VFC/MFC"
    top = [f for f in own(grad) if f.condition.get("speed_point") == "VFC"]
    clean = [f for f in top if f.condition.configuration == "clean" and f.condition.altitude == 0.0]
    assert clean and all(speed_as(f.condition, "CAS") / KN == pytest.approx(306.0 / 1.05, abs=0.05) for f in clean)
    extended = [f for f in top if f.condition.configuration != "clean"]
    assert extended and all(f.status == "complies" and f.margin is None for f in extended)
    assert all("VFE/VLE" in f.reason for f in extended if f.condition.altitude == 0.0)  # above 20,000 ft: flap limit

"""§25.111 takeoff path with the critical engine failed at VEF (simulated), against hand numbers in the
paragraph's units.

Hand references (lb, ft, s; the baseline's GE90-94B class static thrust 97,300 lbf per engine, MTOW 656,000 lb):
* at brake release the runway acceleration with both engines is g · 2 T_static/W
  = 32.174 ft/s² × 2 × 97,300 lbf / 656,000 lb = 9.544 ft/s² (thrust line along the body axis, no aerodynamic
  force at rest, no rolling resistance yet: the tyre friction μ N tanh(v/0.3 m/s) builds up over the first
  0.3 m/s), and with one engine inoperative at rest half of it, 4.772 ft/s² (no windmilling drag at zero speed);
* VEF = V1 − Δv, Δv = a_OEI Δt + (a_AEO − a_OEI) τ (1 − e^(−Δt/τ)) with Δt = 1 s and the declared spool-down
  τ = 1.5 s: the speed a recognition interval after the failure must come back to V1 = 150 KCAS (within 1 kn: the
  accelerations are quasi-steady, the gear carrying the weight of rest; the 10-Hz run sees the failure up to a step
  late and holds each step's decaying thrust from its start);
* V2 = 161 KCAS is the (c)(2) limit; VR = 155 KCAS; the rudder's design limits are ±23.2° (aircraft file).
"""

import numpy as np
import pytest

from certkit.models.dynamics.procedures import runway_acceleration
from certkit.models.flight import flight_model, ground_model
from certkit.units import FT

from .helpers import finding_by as _by
from .helpers import own, run_rule

GEAR = (
    "    main: {x: 107.0 ft, y: 18.0 ft, z: -18.5 ft}   # main gear track 36 ft, wheelbase 84.9 ft [b777-apd]\n"
    "    nose: {x: 22.1 ft, y: 0 ft, z: -18.5 ft}\n"
    "    tail_strike_attitude: 12.1 deg   # 777-200, wheels on the runway, struts extended, flaps 5/15/20 [b777-fctm]\n"
)
LOADINGS = ("MTOW forward", "MTOW reference", "MTOW aft")


@pytest.fixture(scope="module")
def result():
    return run_rule("25.111")


def _static_rudder_deg(ctx, cas_kn):
    """Rudder (deg, negative: nose right) that balances, airborne at ``cas_kn`` with wings level and no sideslip, the
    yawing moment of the right engine's takeoff thrust and the failed left engine's windmilling drag at MTOW and the
    reference CG: the moment balance N_δr δr + N_thrust = 0 with the model's moments, linear in δr."""
    from certkit.atmosphere import convert_speed
    from certkit.models.mass.loading import reference_cg
    from certkit.units import KN

    ac = ctx.aircraft
    model = flight_model(
        ac,
        ctx.aero("takeoff").model,
        [ctx.loading(ac.mass.MTOW, reference_cg(ac), "r")],
        operative=np.array([[False, True]]),
    )
    u = np.zeros((1, len(model.control_names)))
    u[:, model.throttle_slice] = 1.0
    x = np.zeros((1, 12))
    x[0, 2], x[0, 3] = 10.0, float(convert_speed(cas_kn * KN, "CAS", "TAS", 0.0))
    r0 = model.derivatives_euler(x, u)[0, 8]
    u[0, model.control_index("rudder")] = np.radians(-10.0)
    r1 = model.derivatives_euler(x, u)[0, 8]
    return -10.0 * (-r0) / (r1 - r0)


def test_runs_are_representative_and_every_check_is_evaluated(result):
    """With the pilot of the aircraft file (AC 25-7D defaults: 1 s from the failure to the first pedal input, 30°/s)
    the engine-out runs are takeoffs (≤ 30 ft off the centreline on the ground, the tail-strike attitude not reached)
    and lift off within 15 kn of VR (777 FCTM: lift-off a few seconds after VR at 2–3°/s): every check of every
    loading earns a verdict."""
    for loading in LOADINGS:
        for f in (f for f in own(result) if f.condition.loading == loading):
            assert f.status in ("complies", "fails"), f.reason
            assert f.details["max_lateral_deviation_on_ground_ft"] <= 30.0
            assert f.details["vlof_kn"] - 155.0 <= 15.0
            assert f.details["max_pitch_on_ground_deg"] < 12.1


def test_the_rudder_peak_beyond_the_design_limit_is_the_airplane_not_the_pilot(result, ctx, tmp_path):
    """§25.111(a) fails on the rudder at every CG, and the cause is the declared data, not the procedure. (1) The rudder
    that merely balances the engine-out yawing moment at VEF (147 kn, full asymmetry, the moment balance with the
    model's moments, wings level, no sideslip) is already beyond the ±23.2° design limit (about 24°). (2) With the
    rudder's travel cut to that design limit, the VMCG §25.149(e) computes lies above VEF (about 150 kn at the heaviest
    forward corner; none below VR at the light aft one),
    so §25.107(a) VEF ≥ VMCG fails: no pilot who keeps the ground run within 30 ft of the centreline after a failure at
    VEF stays within 23.2°. The run's peak lies between the design limit and the 27.3° stop."""
    steady = _static_rudder_deg(ctx, 147.0)
    assert steady < -23.2
    for loading in LOADINGS:
        f = _by(result, loading, "(a) rudder")
        assert f.status == "fails" and f.limit == pytest.approx(-23.2)
        assert -27.3 - 1e-6 <= f.details["rudder_min_deg"] < -23.2
    cut = run_rule(
        "25.107", tmp_path, [("travel: {min: -27.3 deg, max: 27.3 deg}", "travel: {min: -23.2 deg, max: 23.2 deg}")]
    )
    vef = next(f for f in own(cut) if f.check.startswith("(a)"))
    assert vef.status == "fails" and "VMCG computed" in vef.details["basis"]


def test_the_ground_track_is_judged_on_the_baseline(result):
    """The engine-out runs keep within 30 ft of the centreline at every CG (§25.149(e)): the ground-track check complies
    with the run's own deviation as its value."""
    for loading in LOADINGS:
        f = _by(result, loading, "(a) ground track")
        assert f.status == "complies" and f.limit == 30.0
        assert f.value == f.details["max_lateral_deviation_on_ground_ft"] <= 30.0


FIN_25_PERCENT_SMALLER = ("    area: 527.84 ft^2          # [given]", "    area: 395.9 ft^2")


def test_a_fin_too_small_to_hold_the_centreline_fails_instead_of_going_unevaluated(tmp_path):
    """The baseline with a fin 25 % smaller (395.9 ft² for 527.84 ft², the rudder the same share of it): §25.149(e)
    finds no speed below VR at which the rudder alone holds the ground run within 30 ft, and the engine-out ground runs
    hold the rudder on its 27.3° stop at every CG and stray 32–34 ft from the centreline (the baseline's 15–16 ft).
    That is the airplane's directional control with the declared pilot: §25.111 judges every check of every loading
    (the ground track fails at every CG, the rudder its design limit everywhere) instead of setting the runs aside, and
    §25.113 reports the distances of the same runs (not evaluated only for want of a declared field length). (A fin
    10 % or 20 % smaller still holds the track, within 24 and 28 ft: the airplane lifts off 5 kn after VR.)"""
    res = run_rule("25.111", tmp_path, [FIN_25_PERCENT_SMALLER])
    assert all(f.status in ("complies", "fails") for f in own(res)), [f.reason for f in own(res)]
    base = run_rule("25.111")
    for loading in LOADINGS:
        track = _by(res, loading, "(a) ground track")
        assert track.status == "fails" and track.value > 30.0 > _by(base, loading, "(a) ground track").value
        assert _by(res, loading, "(a) rudder").details["rudder_min_deg"] == pytest.approx(-27.3, abs=1e-6)
    assert res.status == "fails"
    distance = run_rule("25.113", tmp_path, [FIN_25_PERCENT_SMALLER])
    assert all("no performance.takeoff_field_length declared" in f.reason for f in own(distance))


SPEEDS_15_KN_LOW = [
    ("  V1: 150 kn CAS", "  V1: 135 kn CAS"),
    ("  VR: 155 kn CAS", "  VR: 140 kn CAS"),
    ("  V2: 161 kn CAS", "  V2: 146 kn CAS"),
]


def test_rotated_15_kn_early_every_run_is_judged(tmp_path):
    """VR, V1 and V2 declared 15 kn low: the airplane rotated at 140 kn sits on its main wheels at the held 10.1°
    until it flies off at about 162–168 kn; the pilot holds that attitude until the wheels are clear of the runway, so
    no run comes near the tail-strike attitude with a wheel on it (10.4° at most; a pilot who rotated on toward the
    climb attitude as soon as the gear unloaded set the wheels back down at 12.1–12.2° at the forward and reference
    CG, and those runs earned no verdict); every check of every loading is judged and V2 is passed by 35 ft."""
    res = run_rule("25.111", tmp_path, SPEEDS_15_KN_LOW)
    assert all(f.status in ("complies", "fails") for f in own(res)), [f.reason for f in own(res)]
    for loading in LOADINGS:
        f = _by(res, loading, "(c)(2)")
        assert f.details["max_pitch_on_ground_deg"] <= 12.1 - 1.0
        assert f.status == "complies" and f.value > 146.0


def test_hand_calculation_accelerations_vef_and_v2_limit(result, ctx):
    """Initial acceleration 9.544 ft/s² (both engines) and 4.772 ft/s² (one engine out) within 0.5 %; V one second
    after the failure at VEF is V1 within 0.5 kn; the (c)(2) limit is V2 = 161 kn; lift-off after VR."""
    ac = ctx.aircraft
    c = _by(result, "MTOW reference", "(c)(2)").condition
    model = flight_model(
        ac, ctx.aero("takeoff").model, [ctx.loading(c.mass, c.x_cg, c.loading)], ground=ground_model(ac)
    )
    a_oei = runway_acceleration(model, 0.0, operative=np.array([[False, True]]))
    assert a_oei[0] / FT == pytest.approx(32.174 * 97300 / 656000, rel=5e-3)
    for loading in LOADINGS:
        f = _by(result, loading, "(c)(2)")
        assert f.details["initial_acceleration_m_s2"] / FT == pytest.approx(32.174 * 2 * 97300 / 656000, rel=5e-3)
        assert f.details["v_recognition_kn"] == pytest.approx(150.0, abs=1.0)
        assert f.details["vef_kn"] < 150.0
        assert f.limit == pytest.approx(161.0, abs=1e-6) and f.unit == "kn"
        assert f.details["vlof_kn"] > 155.0 and f.value > 161.0 - 5.0
        assert f.condition.get("inoperative") == "left"
    from certkit.report.figures import render_result

    render_result(result)
    assert result.evidence and result.evidence[0].svg and not any("evidence" in n for n in result.notes)


def test_a_smaller_rudder_design_limit_fails_the_engine_out_takeoff(result, tmp_path):
    """A deficient airplane: a rudder design limit of ±15° (the engine-out runs use about 26°; the pilot model moves
    the rudder over its travel, so the run is the same) fails (a)'s rudder check at every CG, by |δr| − 15°."""
    fwd = _by(result, "MTOW forward", "(a) rudder")
    assert fwd.limit == pytest.approx(-23.2) and fwd.value < -15.0
    edited = run_rule(
        "25.111",
        tmp_path,
        [("design_limits: {min: -23.2 deg, max: 23.2 deg}", "design_limits: {min: -15 deg, max: 15 deg}")],
    )
    for loading in LOADINGS:
        f = _by(edited, loading, "(a) rudder")
        assert f.status == "fails" and f.limit == pytest.approx(-15.0)
    assert _by(edited, "MTOW forward", "(a) rudder").value == pytest.approx(fwd.value, abs=1e-6)


def test_sign_cg_and_engine_failure(result, tmp_path):
    """Moving the CG aft shortens the tail's lever against the weight on the mains: with the elevator trimming (the
    baseline without its movable stabiliser) the elevator margin grows forward → reference → aft and the airplane
    lifts off earlier (lower V at 35 ft); with the stabiliser set to each CG's own V2 trim the CG is trimmed out and
    the margins need not order. Failing an engine makes the takeoff worse than with all engines: a lower speed at
    35 ft."""
    from .helpers import NO_STABILIZER

    plain = run_rule("25.111", tmp_path, [NO_STABILIZER])
    m = [_by(plain, c, "(a) elevator").margin for c in LOADINGS]
    assert m[0] < m[1] < m[2]
    v = [_by(plain, c, "(c)(2)").value for c in LOADINGS]
    assert v[0] > v[1] > v[2]
    for c in LOADINGS:
        d = _by(result, c, "(c)(2)").details
        assert d["v35_kn"] < d["all_engines_v35_kn"]
        # the left engine failed: the nose swings left (ψ < 0 first), the rudder pushes right (δr < 0, conventions);
        # its largest deflection is that push (after the lift-off the banked climb may swing it the other way less far)
        r = _by(result, c, "(a) rudder")
        assert r.details["rudder_min_deg"] < -10.0 and r.details["rudder_max_deg"] < -r.details["rudder_min_deg"]


def test_not_evaluated_without_landing_gear_or_v1(tmp_path):
    r = run_rule("25.111", tmp_path, [(GEAR, "")])
    assert r.status == "not_evaluated"
    assert all(f.status == "not_evaluated" and "landing_gear" in f.reason for f in own(r))
    r = run_rule("25.111", tmp_path, [("  V1: 150 kn CAS", "  #V1: 150 kn CAS")])
    assert r.status == "not_evaluated" and all("speeds.V1" in f.reason for f in own(r))


def test_pilot_rotation_below_tail_strike_and_distances(result):
    """The rotation a pilot flies (Boeing Flight Operations Review 1986: 2–3°/s, not more than 3°/s; lift-off attitude
    2–4° below the tail-strike attitude, 12.1° for the 777-200 per the FCTM): before lift-off the pitch rate stays
    within 3°/s + 0.3°/s (the commanded 2.5°/s and the overshoot of the attitude loop) and the attitude on the runway
    below 12.1°; the accelerate-go distance is the engine-out distance to 35 ft and the §25.113 takeoff distance the
    greater of it and 1.15 × the all-engines one (hand arithmetic on the reported distances, 1 ft rounding); the
    engine-out V35 lies 0–10 kn above V2."""
    for loading in LOADINGS:
        d = _by(result, loading, "(c)(2)").details
        assert 0.5 < d["max_pitch_rate_before_liftoff_deg_s"] <= 3.3
        assert d["max_pitch_on_ground_deg"] < 12.1
        assert d["accelerate_go_distance_ft"] == pytest.approx(d["distance_to_35ft_ft"], abs=1.0)
        assert d["all_engines_distance_x1.15_ft"] == pytest.approx(1.15 * d["all_engines_distance_to_35ft_ft"], abs=1.5)
        assert d["takeoff_distance_ft"] == pytest.approx(
            max(d["accelerate_go_distance_ft"], d["all_engines_distance_x1.15_ft"]), abs=1.5
        )
        assert "tail strike" in d["rotation_basis"] and "τ = 1.5 s" in d["spool_down_basis"]
        # the pitch flies V2 once airborne: the 35-ft speed within the band of a representative run, 0 to 10 kn above
        # V2 (§25.111(c)(2) "not less than V2 … as close as practical"; the 10 kn of the rule's criteria)
        assert 0.0 <= d["v35_kn"] - d["v2_kn"] <= 10.0


def test_too_little_elevator_is_judged_as_flown(tmp_path):
    """A deficient airplane: no nose-up elevator at all (travel and design limit cut to 0°; the baseline's rotation
    at forward CG uses about −12° with the stabiliser at its V2 trim). The rotation on the stabiliser alone lifts it
    off more than 20 kn after VR at every CG (the baseline 10–14 kn): a run that lifts off late is still a takeoff, so
    every check is evaluated (none 'not evaluated'), the late lift-off reported, the rudder failing as on the
    baseline; the distance it costs is §25.113's verdict (tests/rules/test_r25_113.py)."""
    cut = [
        ("travel: {min: -30 deg, max: 25 deg}", "travel: {min: 0 deg, max: 25 deg}"),
        ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: 0 deg, max: 16.8 deg}"),
    ]
    r = run_rule("25.111", tmp_path, cut)
    assert all(f.status in ("complies", "fails") for f in own(r))
    for loading in LOADINGS:
        d = _by(r, loading, "(c)(2)").details
        assert d["vlof_after_vr_kn"] > 20.0 and d["vlof_kn"] > 155.0 + 20.0
        assert _by(r, loading, "(a) rudder").status == "fails"

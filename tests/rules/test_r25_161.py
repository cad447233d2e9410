"""§25.161 longitudinal trim: the segments' speeds by hand, the margin arithmetic, limit and sign cases.

Climb speed 1.3 VSR1 with VSR1 = √(2W/(ρ0 S CLmax)) (Anderson, *Introduction to Flight*, eq. 6.47):
at fwd_mrw, 657,000 lb, CLmax 1.4, S 4927.3 ft², ρ0 0.0023769 slug/ft³: VSR1 = 167.73 kn, 1.3 VSR1 = 218.05 kn
(tolerance 0.01 kn). The margin is the design limit on the deflected side minus |δe| (deg): elevator design
limits −21.8°/+16.8° (aircraft file). The elevator cases run on the baseline without its movable stabiliser (the
elevator trims); the stabiliser's trim authority is tested on the baseline as declared.
"""

import math

import pytest

from certkit.units import KN

from .helpers import NO_STABILIZER, run_rule


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    return run_rule("25.161", tmp_path_factory.mktemp("plain"), [NO_STABILIZER])


def finding(result, loading, case, check="(c)(1) climb, clean elevator"):
    return next(
        f
        for f in result.findings
        if f.condition.loading == loading
        and f.condition.get("case") == case
        and f.margin is not None
        and f.check.startswith(check)
    )


def test_hand_calculation_climb_speed_and_margin(base):
    f = finding(base, "fwd_mrw", "climb")
    vsr1 = math.sqrt(2 * 657_000 / (0.0023769 * 4927.3 * 1.4)) / 1.6878099
    assert f.condition.speed / KN == pytest.approx(1.3 * vsr1, abs=0.01)
    limit = 16.8 if f.value >= 0 else -21.8
    assert f.margin == pytest.approx(abs(limit) - abs(f.value), abs=1e-9)
    assert f.details["elevator_deg"] == pytest.approx(f.value, abs=1e-3)


def test_a_smaller_elevator_design_limit_fails(tmp_path, base):
    """A deficient airplane: the elevator's trailing-edge-down design limit cut to 5° (the aft_light climb trims need
    about 9.7°): §25.161(c)(1) fails there, with the trim's message; the forward corners (nose-up elevator) still
    comply."""
    f = finding(base, "aft_light", "climb")
    assert f.value > 5.0
    r = run_rule(
        "25.161",
        tmp_path,
        [
            NO_STABILIZER,
            ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: -21.8 deg, max: 5 deg}"),
        ],
    )
    g = finding(r, "aft_light", "climb")
    assert g.status == "fails" and g.value > 5.0
    assert finding(r, "fwd_mrw", "climb").status == "complies"


def test_sign_larger_design_limit_more_margin_and_aft_cg_more_trailing_edge_down(tmp_path, base):
    r = run_rule(
        "25.161",
        tmp_path,
        [
            NO_STABILIZER,
            ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: -21.8 deg, max: 18.8 deg}"),
        ],
    )
    assert finding(r, "aft_light", "climb").margin == pytest.approx(
        finding(base, "aft_light", "climb").margin + 2, abs=1e-6
    )
    # aft CG needs less nose-up (more trailing-edge-down) elevator than forward CG at the same weight
    assert finding(base, "aft_mrw", "climb").value > finding(base, "fwd_mrw", "climb").value


def test_cases_of_the_paragraph(base):
    """Every case of (c)(1)–(c)(3) and (d) is flown at every corner: climb clean and takeoff flaps, power-off
    glide (idle: the flight path results, steeper than level), 3° approach gear down (the landing configuration;
    the baseline's approach configuration has its gear up), level flight
    at 1.3 VSR1 and VMO/MMO at both altitudes, and the engine-out climb with its three controls and bank."""
    checks = {f.check for f in base.findings}
    for c in (
        "(c)(1) climb, clean elevator",
        "(c)(1) climb, takeoff elevator",
        "(c)(2) power-off glide elevator",
        "(c)(2) 3° approach, landing elevator",
        "(c)(3) level flight elevator",
        "(d) engine-out climb elevator",
        "(d) engine-out climb rudder",
        "(d) engine-out climb aileron",
        "(d) engine-out climb bank within 5°",
    ):
        assert any(k.startswith(c) for k in checks), c
    glide = finding(base, "fwd_mrw", "glide", "(c)(2) power-off glide")
    assert glide.details["throttle:left"] == 0.0 and glide.details["flight_path_deg"] < -1.0
    level = [f for f in base.findings if f.condition.loading == "fwd_mrw" and f.check.startswith("(c)(3)")]
    # 272 KEAS at 35,000 ft is M 0.85 < MMO 0.87: VMO bounds the range at both altitudes
    assert {f.condition.speed_name for f in level} == {"1.3 VSR1", "VMO"}
    assert len({f.condition.altitude for f in level}) == 2
    banks = [f for f in base.findings if f.check.startswith("(d) engine-out climb bank")]
    assert len(banks) == 8 and all(f.limit == 5.0 and 0.0 < f.value <= 5.0 + 1e-9 for f in banks)
    # where the zero-sideslip trim needs more than 5°, the trim is flown at 5° (the sideslip results)
    steep = [f for f in banks if abs(f.details["zero_sideslip_bank_deg"]) > 5.0]
    assert all(f.value == pytest.approx(5.0, abs=1e-6) and abs(f.details["beta_deg"]) > 0.01 for f in steep)


def test_not_evaluated_without_takeoff_configuration(tmp_path):
    """No takeoff configuration: the (c)(1) flaps-in-takeoff-position climb is not evaluated, with the reason."""
    r = run_rule(
        "25.161",
        tmp_path,
        [
            ("  takeoff:\n    flap: 15 deg", "  takeoff_alt:\n    flap: 15 deg"),
            ("    takeoff: 215 kn CAS", "    takeoff_alt: 215 kn CAS"),
            ("        takeoff: {min: -10.25", "        takeoff_alt: {min: -10.25"),
        ],
    )
    f = [f for f in r.findings if f.check == "(c)(1) climb"]
    assert f and all(x.status == "not_evaluated" and x.reason == "needs configurations.takeoff" for x in f)


@pytest.fixture(scope="module")
def declared():
    """§25.161 on the baseline as declared (movable stabiliser, per-configuration trim limits)."""
    return run_rule("25.161")


def test_too_little_stabiliser_travel_fails_on_trim_authority(tmp_path, declared):
    """A deficient airplane: the stabiliser's trim range cut to −4°…+1° (the baseline's level-flight trims at the
    forward corners need more nose-up incidence at 1.3 VSR1): §25.161(c)(3) fails on the stabiliser at its nose-up stop,
    the elevator holding the rest — while with the declared range (−10.25°…+2.25°) the same trims comply. The
    stabiliser margin is the trim limit minus the incidence needed, so a failing one needs more than the stop."""
    check = "(c)(3) level flight stabiliser within its trim limits"

    def most_nose_up(result):
        return min(
            (f for f in result.findings if f.condition.loading == "fwd_light" and f.check == check),
            key=lambda f: f.value,
        )

    ok = most_nose_up(declared)
    assert ok.status == "complies" and -10.25 < ok.value < -4.0
    r = run_rule(
        "25.161",
        tmp_path,
        [("design_limits: {min: -10.25 deg, max: 2.25 deg}", "design_limits: {min: -4 deg, max: 1 deg}")],
    )
    f = most_nose_up(r)
    assert f.status == "fails" and f.limit == pytest.approx(-4.0) and f.value < -4.0
    assert "nose-up stop" in f.reason and f.details["stabilizer_deg"] == pytest.approx(-4.0, abs=1e-6)
    assert f.value == pytest.approx(ok.value, abs=1e-6)  # the incidence needed does not depend on the range


TAKEOFF_CLIMB = "(c)(1) climb, takeoff stabiliser within its trim limits"
CLEAN_CLIMB = "(c)(1) climb, clean stabiliser within its trim limits"


def test_stabiliser_margin_against_the_configurations_limits(declared):
    """The takeoff-flap climb is held to the flaps-extended nose-down limit, +3.75° (777 AMM 27-41-00), the clean climb
    to the flaps-up +2.25°; each finding names the limits that applied. The aft_mlw takeoff climb needs about +1.9°,
    inside both."""
    f = next(f for f in declared.findings if f.condition.loading == "aft_mlw" and f.check == TAKEOFF_CLIMB)
    assert f.limit == pytest.approx(3.75) and 0.0 < f.value < 3.75 and f.status == "complies"
    assert f.details["trim_limits"].startswith("stabilizer.design_limits_by_configuration.takeoff: -10.25° to 3.75°")
    c = next(f for f in declared.findings if f.condition.loading == "aft_mlw" and f.check == CLEAN_CLIMB)
    assert c.limit == pytest.approx(2.25) and c.details["trim_limits"].startswith("stabilizer.design_limits: ")


def test_narrow_flaps_extended_limits_fail_at_the_takeoff_flaps(tmp_path, declared):
    """A deficient airplane: the flaps-15 nose-down limit cut to +1° (the aft corners' takeoff-flap climbs need
    +1.4° to +3.9°): §25.161(c)(1) fails there on the stabiliser at its nose-down stop, against +1°, while the clean
    climbs (design_limits) are unchanged."""
    narrow = ("        takeoff: {min: -10.25 deg, max: 3.75 deg}", "        takeoff: {min: -10.25 deg, max: 1 deg}")
    r = run_rule("25.161", tmp_path, [narrow])
    fails = [f for f in r.findings if f.check == TAKEOFF_CLIMB and f.status == "fails"]
    assert {f.condition.loading for f in fails} >= {"aft_mid", "aft_mlw", "aft_light"}
    for f in fails:
        assert f.limit == pytest.approx(1.0) and f.value > 1.0 and "nose-down stop" in f.reason
        assert f.details["trim_limits"] == "stabilizer.design_limits_by_configuration.takeoff: -10.25° to 1.00°"
    before = {f.condition.loading: (f.status, f.value, f.limit) for f in declared.findings if f.check == CLEAN_CLIMB}
    after = {f.condition.loading: (f.status, f.value, f.limit) for f in r.findings if f.check == CLEAN_CLIMB}
    assert after == before


def test_a_horizontal_tail_a_quarter_smaller_fails(tmp_path):
    """A deficient airplane by geometry: the horizontal tail's area cut by 25 % (1119.2 → 839.4 ft², aspect ratio,
    taper, sweep and position kept: V_H 0.72 → 0.54). The tail's trimming moment per degree of stabiliser falls with
    its area while the moments to trim (flaps, thrust, CG) do not, so the declared stabiliser trim limits no longer
    suffice: (c)(1) fails in the climb at the aft corners (nose-down stop +2.25° reached) and (c)(2) in the 3°
    approach at the forward corners (nose-up stop −10.25°) — the baseline complies at the first and fails the second
    by less than 0.4° at two forward corners only."""
    r = run_rule("25.161", tmp_path, [("    area: 1119.2 ft^2          # [given]", "    area: 839.4 ft^2")])
    fails = [f for f in r.findings if f.status == "fails"]
    climb = {f.condition.loading for f in fails if f.condition.get("case") == "climb" and "stabiliser" in f.check}
    glide = [f for f in fails if f.condition.get("case") == "glide" and "stabiliser" in f.check]
    assert r.status == "fails"
    assert {"aft_mlw", "aft_light"} <= climb
    assert {f.condition.loading for f in glide} >= {"fwd_light", "fwd_mlw", "fwd_mid"}
    assert min(f.margin for f in glide) < -2.0  # deg of stabiliser beyond the nose-up stop


def test_beyond_the_level_flight_ceiling_the_steady_descent_at_full_thrust(declared):
    """(c)(3) at MRW, 35,000 ft and 1.3 VSR1 (218 kn CAS): level flight needs more than full thrust (the level trim
    alone does not converge), so the trim is judged in the steady descent at full thrust — the flight nearest to level
    the airplane can hold — named in the finding, its path a fraction of a degree down (the thrust deficit over the
    weight: at most the L/D ≈ 17 airplane's 1/17 rad = 3.4° if the engines gave nothing). Everywhere else level."""
    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context

    from .helpers import BASELINE

    level = [f for f in declared.findings if f.check.startswith("(c)(3) level flight") and f.margin is not None]
    assert level and not any(f.check.startswith("(c)(3)") and f.status == "not_evaluated" for f in declared.findings)
    held = [f for f in level if f.details["flight"] != "level flight"]
    assert {f.condition.loading for f in held} == {"fwd_mrw", "aft_mrw"}
    for f in held:
        assert f.condition.altitude == pytest.approx(35000 * 0.3048)
        assert f.details["flight"].startswith("steady descent at full thrust")
        assert -1.0 < f.details["flight_path_deg"] < 0.0
    cond = next(f.condition for f in held)
    alone = Context(load_aircraft(BASELINE)).trim([cond], kind="straight").results[0]
    assert not alone.converged and "more than full throttle" in "; ".join(e.message for e in alone.limits_exceeded)

"""§25.255 out-of-trim characteristics: the mistrim amount, the control margin, and the cases that cannot be evaluated.

Hand references: with a trim rate of 0.5 deg/s (a test value, twice the baseline's 0.25 deg/s from the 777 AMM's
direct mode, so that the nose-down stop is reached more often) three seconds of trim movement is 1.5°
(§25.255(a)(1)), limited by the trim system's stops (the baseline's +2.25° nose-down PFC limit); the margins are
the elevator design limits −21.8°/+16.8° minus the manoeuvre deflections.
"""

import pytest

from .helpers import NO_STABILIZER, control_forces_edit, own, run_rule

RATE = ("      rate: 0.25 deg/s ", "      rate: 0.5 deg/s ")
NO_RATE = ("      rate: 0.25 deg/s ", "      # rate: 0.25 deg/s ")


@pytest.fixture(scope="module")
def rated(tmp_path_factory):
    return run_rule("25.255", tmp_path_factory.mktemp("rate"), [RATE])


def test_without_a_rate_or_a_stabiliser_nothing_is_evaluated(tmp_path):
    (tmp_path / "unrated").mkdir()
    base = run_rule("25.255", tmp_path / "unrated", [NO_RATE])
    assert base.status == "not_evaluated"
    assert all(f.status == "not_evaluated" and "stabilizer.rate" in f.reason for f in own(base))
    (tmp_path / "plain").mkdir()
    plain = run_rule("25.255", tmp_path / "plain", [NO_STABILIZER])
    assert all(f.status == "not_evaluated" and "no movable stabiliser" in f.reason for f in own(plain))


def test_mistrim_is_three_seconds_of_rate_within_the_stops(rated):
    for f in own(rated):
        if f.margin is None:
            continue
        d = f.details
        moved = d["stabilizer_mistrim_deg"] - d["stabilizer_trim_deg"]
        if "nose-up" in f.condition.get("manoeuvre"):
            assert moved == pytest.approx(-1.5, abs=1e-3)
        else:  # nose down: 1.5° unless the +2.25° trim limit comes first
            assert moved == pytest.approx(min(1.5, 2.25 - d["stabilizer_trim_deg"]), abs=1e-3)
            assert d["stabilizer_mistrim_deg"] <= 2.25 + 1e-9


def test_control_margin_arithmetic_and_sense(rated):
    """Margin = design limit on the deflected side − |δe|; pulling takes trailing edge up, pushing trailing edge
    down, at every point; the nose-up mistrim needs more trailing-edge-down elevator than the nose-down one."""
    checks = [f for f in own(rated) if f.margin is not None]
    assert checks
    for f in checks:
        if "elevator within its design limit" in f.check:
            limit = 16.8 if f.value >= 0 else -21.8
            assert f.limit == pytest.approx(limit) and f.margin == pytest.approx(abs(limit) - abs(f.value), abs=1e-9)
        else:
            assert f.value > 0.0 and f.status == "complies"
    up = [
        f
        for f in checks
        if "push" in f.check and "design limit" in f.check and "nose-up" in f.condition.get("manoeuvre")
    ]
    down = {
        (f.condition.loading, f.condition.altitude, f.condition.speed_name): f
        for f in checks
        if "push" in f.check and "design limit" in f.check and "nose-down" in f.condition.get("manoeuvre")
    }
    for f in up:
        assert f.value > down[(f.condition.loading, f.condition.altitude, f.condition.speed_name)].value


def test_too_little_nose_down_elevator_fails_the_push(tmp_path, rated):
    """A deficient airplane: the elevator's trailing-edge-down design limit cut to 3°, less than the nose-up-mistrimmed
    push-overs to 0 g at VDF/MDF need (about 4°): those fail; the pulls still comply."""
    need = max(f.value for f in own(rated) if f.check.startswith("push") and "design limit" in f.check)
    assert need > 3.0
    r = run_rule(
        "25.255",
        tmp_path,
        [RATE, ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: -21.8 deg, max: 3 deg}")],
    )
    pushes = [f for f in own(r) if f.check.startswith("push") and "design limit" in f.check]
    assert any(f.status == "fails" and f.value > 3.0 for f in pushes)
    assert all(f.status == "complies" for f in own(r) if f.check.startswith("pull") and "design limit" in f.check)


def test_stick_forces_with_an_artificial_feel_elevator(tmp_path):
    """With an artificial-feel elevator (test values: 5 lbf preload, 30 lbf/in at q̄ 10 kPa, 2 deg/in; zero force at
    the original trim, elevator 0°) the forces are evaluated: pull F = −sign(δe)·5 − 30 (q̄/10 kPa) δe/2 lbf with
    q̄ = ½ ρ0 V_EAS² (hand, 0.05 lbf). The pull force rises with g at every point ((b)) — also where the nose-up
    mistrim leaves a push at 1 g and at 1.5 g — and the pull holding 1.5 g at VDF/MDF is within 125 lbf ((f))."""
    import math

    feel = control_forces_edit(
        "control_forces:\n  elevator:\n    type: artificial_feel\n    preload: 5 lbf\n"
        "    gradient: 30 lbf/in\n    gearing: 2 deg/in\n    q_feel_reference: 10 kPa\n"
    )
    r = run_rule("25.255", tmp_path, [RATE, feel])
    slopes = [f for f in own(r) if "stick force per g" in f.check]
    assert slopes and all(f.status == "complies" for f in slopes)
    for f in slopes:
        q = 0.5 * 1.225 * f.condition.speed**2
        for key, angle in (("pull_force_pull_lbf", "elevator_pull_deg"), ("pull_force_push_lbf", "elevator_push_deg")):
            d = f.details[angle]
            assert f.details[key] == pytest.approx(-math.copysign(5.0, d) - 30.0 * q / 10e3 * d / 2.0, abs=0.05)
    assert any(f.details["pull_force_pull_lbf"] < 0 for f in slopes)  # a push still at 1.5 g (nose-up mistrim)
    recovery = [f for f in own(r) if f.check.startswith("(f)")]
    assert recovery and all(
        f.condition.speed_name == "VDF/MDF" and f.limit == 125.0 and f.status == "complies" for f in recovery
    )


def test_baseline_mistrim_from_the_amm_rate():
    """The baseline declares the 777 AMM's direct-mode rate, 0.25°/s (27-41-00 p. 64): 3 s of it is 0.75° nose up and
    nose down, nose down no further than the +2.25° PFC trim limit (reached from the aft corners' trims at +1.56° to
    +1.76°); the elevator-fixed checks are computed and the stick-force checks name the missing column feel."""
    base = run_rule("25.255")
    rated = [f for f in own(base) if f.margin is not None]
    assert rated
    for f in rated:
        trim, mistrim = f.details["stabilizer_trim_deg"], f.details["stabilizer_mistrim_deg"]
        if "nose-up" in f.condition.get("manoeuvre"):
            assert mistrim - trim == pytest.approx(-0.75, abs=1e-3)
        else:
            assert mistrim - trim == pytest.approx(min(0.75, 2.25 - trim), abs=1e-3)
    force = [f for f in own(base) if f.check.endswith("stick force")]
    assert force and all(f.status == "not_evaluated" and "control_forces.elevator" in f.reason for f in force)


def test_beyond_the_level_flight_ceiling_the_mistrim_starts_from_the_descent_at_full_thrust(tmp_path):
    """With a fifth less thrust (77,840 lbf per engine) level flight at MMO and 35,000 ft needs more than full thrust at
    the heavier corners: the trim there is the steady descent at full thrust (0.1–0.5° down, in the finding's
    condition), from which the mistrim and the manoeuvres are judged like any other; no condition is left unevaluated
    for want of a level trim."""
    weak = run_rule("25.255", tmp_path, [("  static_thrust: 97300 lbf", "  static_thrust: 77840 lbf")])
    judged = [f for f in own(weak) if not f.check.endswith("stick force")]
    assert judged and all(f.status in ("complies", "fails") for f in judged), {f.reason for f in judged}
    paths = [f.condition.get("flight_path_deg") for f in judged if f.condition.get("flight_path_deg") is not None]
    assert paths and all(-1.0 < p < 0.0 for p in paths)
    assert all(f.condition.altitude > 10_000 for f in judged if f.condition.get("flight_path_deg") is not None)
    base = run_rule("25.255")
    assert not any(f.condition.get("flight_path_deg") for f in own(base))

"""§25.107(e)(1)(iv): VLOF at the maximum practicable rotation rate against the computed VMU.

The factors are the regulation's (docs/regulation-notes.md, (e)(1)(iv) (A)/(B)); the minimum unstick speed itself is
tested against the lift equation in tests/dynamics/test_unstick.py. Here: which branch applies, which way the
airplane's geometry and the rotation rate move the margins, and that a deficient airplane (a lower tail-strike
attitude: a longer aft body or shorter gear) fails.
"""

import pytest
from certkit_rules.part25.support.takeoff import takeoff_conditions
from certkit_rules.part25.support.unstick import unstick_speeds

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.evidence.performance import unstick_evidence
from certkit.units import KN

from ..conftest import BASELINE
from .helpers import run_rule

RULE = "25.107(e)(1)(iv)"
STRIKE = "tail_strike_attitude: 12.1 deg"


@pytest.fixture(scope="module")
def baseline_result():
    return run_rule(RULE)


def by(result, loading, engine_out):
    return next(
        f
        for f in result.findings
        if f.condition.loading == loading and (f.condition.get("inoperative") is not None) == engine_out
    )


LOADINGS = ("MTOW forward", "MTOW reference", "MTOW aft")


def test_the_baseline_is_geometry_limited_with_the_108_and_104_percent_factors(baseline_result):
    """VMU at the 12.1° tail-strike attitude at every loading, so (B)'s 1.08 (all engines) and 1.04 (engine out)."""
    assert len(baseline_result.findings) == 6
    for f in baseline_result.findings:
        assert f.status in ("complies", "fails"), f.reason
        assert f.details["vmu_limited_by"] == "attitude limit"
        assert f.details["vmu_attitude_deg"] == pytest.approx(12.1)
        assert f.limit == (1.04 if f.condition.get("inoperative") else 1.08)


def test_less_thrust_and_a_forward_cg_raise_vmu(baseline_result):
    """At the one-engine-inoperative thrust-to-weight ratio the thrust carries less of the weight (T sin θ), and a
    forward CG needs more nose-up elevator (tail download): VMU rises with both."""
    for loading in LOADINGS:
        assert by(baseline_result, loading, True).details["VMU"] > by(baseline_result, loading, False).details["VMU"]
    for engine_out in (False, True):
        vmu = [by(baseline_result, loading, engine_out).details["VMU"] for loading in LOADINGS]
        assert vmu[0] > vmu[1] > vmu[2]


def test_a_lower_tail_strike_attitude_fails(baseline_result, tmp_path):
    """An aft body that touches the runway at 10° (longer fuselage or shorter gear): VMU rises (less lift at the
    limiting attitude) while the all-engines lift-off speed stays (the airplane lifts off during the rotation, below
    10°), so the all-engines margins fall at every CG and fail at the forward CG (the most tail download). With an
    engine out the pilot holds 8° (2° below the tail-strike attitude): the forward and reference CG, which lift off
    above 8° on the baseline, lift off later."""
    low = run_rule(RULE, tmp_path, [(STRIKE, "tail_strike_attitude: 10 deg")])
    assert all(f.status in ("complies", "fails") for f in low.findings), [f.reason for f in low.findings]
    for loading in LOADINGS:
        f, b = by(low, loading, False), by(baseline_result, loading, False)
        assert f.margin < b.margin and f.details["VMU"] > b.details["VMU"]
    assert by(low, "MTOW forward", False).status == "fails" and low.status == "fails"
    for loading in LOADINGS[:2]:
        assert by(baseline_result, loading, True).details["max_pitch_to_liftoff_deg"] > 8.0
        assert by(low, loading, True).details["vlof_kn"] > by(baseline_result, loading, True).details["vlof_kn"]


def test_a_lift_maximum_below_the_tail_strike_uses_the_110_and_105_percent_factors(tmp_path):
    """With a tail that would touch only at 20° the takeoff configuration reaches its lift maximum first: VMU is
    lift-limited, below 20°, and (A)'s 1.10 and 1.05 apply."""
    high = run_rule(RULE, tmp_path, [(STRIKE, "tail_strike_attitude: 20 deg")])
    for f in high.findings:
        assert f.details["vmu_limited_by"] == "lift maximum"
        assert f.details["vmu_attitude_deg"] < 19.0
        assert f.limit == (1.05 if f.condition.get("inoperative") else 1.10)


def test_a_faster_rotation_lifts_off_earlier(baseline_result, tmp_path):
    """Rotated at 4°/s instead of 3°/s the airplane reaches its lift-off attitude sooner: the all-engines VLOF falls
    at every loading and so does the margin (VMU does not depend on the rotation)."""
    why = "sensitivity of the lift-off speed to the rotation rate"
    fast = run_rule(
        RULE,
        tmp_path,
        [
            (
                "\nsources:\n",
                f'\ncriteria:\n  "{RULE}":\n    values: {{max_practicable_rotation_rate_deg_s: 4.0}}\n'
                f'    justification: "{why}"\n\nsources:\n',
            )
        ],
    )
    for loading in LOADINGS:
        f, b = by(fast, loading, False), by(baseline_result, loading, False)
        assert f.details["VLOF"] < b.details["VLOF"] - 1.0 * KN
        assert f.details["VMU"] == pytest.approx(b.details["VMU"], rel=1e-9)
        assert f.margin < b.margin


def test_without_a_tail_strike_attitude_the_rule_is_not_evaluated(tmp_path):
    r = run_rule(RULE, tmp_path, [("    " + STRIKE, "")])
    assert r.status == "not_evaluated"
    assert any("tail_strike_attitude" in (f.reason or "") for f in r.findings)


def test_the_evidence_marks_the_lift_off_speed_of_the_least_margin(baseline_result):
    """The unstick-speed figure's horizontal line in each panel is the VLOF of the finding with the least margin there
    (the forward CG, all engines and engine out, on the baseline), as its caption says, whatever the order of the
    findings; one series per loading, named after it."""
    ctx = Context(load_aircraft(BASELINE))
    conditions = takeoff_conditions("").expand(ctx.aircraft)
    vmu = unstick_speeds(ctx, conditions)
    (ev,) = unstick_evidence(list(reversed(baseline_result.findings)), LOADINGS, vmu.all_engines, vmu.engine_out)
    for panel, engine_out in zip(ev.figure.panels, (False, True)):
        assert [s.label for s in panel.series] == list(LOADINGS)
        (vlof,) = [lim for lim in panel.limits if lim.label.startswith("VLOF")]
        forward = by(baseline_result, "MTOW forward", engine_out)
        assert forward.margin == min(
            f.margin for f in baseline_result.findings if (f.condition.get("inoperative") is not None) == engine_out
        )
        assert vlof.value == forward.details["VLOF"] and vlof.label == "VLOF MTOW forward"

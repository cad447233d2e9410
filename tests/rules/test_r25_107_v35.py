"""§25.107(c)(2) and (e)(1)(iii): the declared V2 against the speed the §25.111 engine-out takeoff reaches at 35 ft.

The regulation's text (docs/regulation-notes.md, § 25.107, verified): V2 may not be less than VR plus the speed
increment attained (§25.111(c)(2)) before 35 ft; VR may not be less than the speed that allows reaching V2 before
35 ft. Together they make V2 the 35-ft speed of the scheduled takeoff. Here: the baseline's engine-out takeoff, rotated
at the declared VR (V2 − 6 kt, the 777's schedule estimate), reaches 35 ft within 2 kn above the declared V2 (the
1.13 VSR minimum; docs/baseline-sources.md §14b), so (c)(2), which allows no excess, fails by under 2 kn; a flap of
shorter span lifts off later and fails it by more; a V2 declared 24 kn above the same VR is not reached by 35 ft.
"""

from .helpers import run_rule

RULE = "25.107(c)(2)"
LOADINGS = ("MTOW forward", "MTOW reference", "MTOW aft")
C2, E1III = "(c)(2)", "(e)(1)(iii)"


def _by(result, loading, check):
    return next(f for f in result.findings if f.condition.loading == loading and f.check.startswith(check))


def test_the_declared_v2_lies_below_the_35_ft_speed_of_the_baseline():
    """Every loading evaluated on the engine-out run; the 35-ft speed is above the declared 161 KCAS by less than
    2 kn (the airplane lifts off during the rotation, 4–7 kn after VR: the 777 FCTM's "lift-off a few seconds after
    VR" at 2–3°/s), so (c)(2) fails and (e)(1)(iii) complies at every CG, each with the run's own speeds as
    evidence."""
    res = run_rule(RULE)
    assert len(res.findings) == 6 and res.status == "fails"
    for loading in LOADINGS:
        c2, e = _by(res, loading, C2), _by(res, loading, E1III)
        assert c2.status == "fails" and e.status == "complies"
        assert abs(c2.value - 161.0) < 1e-6 and c2.unit == "kn"
        assert 0.0 < e.value - 161.0 < 2.0 and 4.0 < c2.details["vlof_kn"] - 155.0 < 7.0
        assert c2.condition.get("inoperative") is not None
        assert abs(c2.details["vr_kn"] - 155.0) < 1e-6 and c2.details["vlof_kn"] > 155.0


SHORTER_FLAP = ("flaps: {span_start: 0.10, span_end: 0.75", "flaps: {span_start: 0.10, span_end: 0.55")


def test_a_flap_of_shorter_span_lifts_off_later_and_fails_by_more(tmp_path):
    """A deficient airplane: the trailing-edge flap ending at 55 % of the semispan instead of 75 % (less takeoff lift
    at every attitude, Raymer eq. 12.22): the engine-out airplane lifts off later and reaches 35 ft faster at every
    CG, so (c)(2)'s margin falls everywhere; (e)(1)(iii) still complies."""
    base = run_rule(RULE)
    short = run_rule(RULE, tmp_path, [SHORTER_FLAP])
    for loading in LOADINGS:
        c2, b = _by(short, loading, C2), _by(base, loading, C2)
        assert c2.status == "fails" and c2.margin < b.margin
        assert c2.details["vlof_kn"] > b.details["vlof_kn"] and c2.details["v35_kn"] > b.details["v35_kn"]
        assert _by(short, loading, E1III).status == "complies"


def test_a_v2_the_takeoff_cannot_reach_by_35_ft_fails_e1iii(tmp_path):
    """V2 declared 185 KCAS with VR still 155: the engine-out airplane, flown toward V2, is still short of it at
    35 ft — VR is too low for that V2 ((e)(1)(iii) fails at every CG), and (c)(2) complies."""
    res = run_rule(RULE, tmp_path, [("  V2: 161 kn CAS", "  V2: 185 kn CAS")])
    for loading in LOADINGS:
        assert _by(res, loading, E1III).status == "fails" and _by(res, loading, E1III).value < 185.0
        assert _by(res, loading, C2).status == "complies"


def test_without_vr_nothing_is_judged(tmp_path):
    res = run_rule(RULE, tmp_path, [("  VR: 155 kn CAS               # V2 - 6 kt\n", "")])
    assert res.status == "not_evaluated"

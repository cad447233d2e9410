"""§25.107(c)(2) and (e)(1)(iii): the declared V2 against the speed the §25.111 engine-out takeoff reaches at 35 ft.

The regulation's text (docs/regulation-notes.md, § 25.107, verified): V2 may not be less than VR plus the speed
increment attained (§25.111(c)(2)) before 35 ft; VR may not be less than the speed that allows reaching V2 before
35 ft. Together they make V2 the 35-ft speed of the scheduled takeoff. Here: the baseline's declared V2 (the 1.13 VSR
minimum) lies below what its engine-out takeoff reaches; a schedule raised to V2 173 / VR 167 KCAS, keeping the
declared 6-kt V2 − VR, brings V2 and the 35-ft speed within 1.5 kn of each other (docs/baseline-sources.md §14b:
from V2 ≈ 169 KCAS the airplane lifts off during the rotation); a V2 declared 24 kn above the same VR is not reached
by 35 ft.
"""

from .helpers import run_rule

RULE = "25.107(c)(2)"
LOADINGS = ("MTOW forward", "MTOW reference", "MTOW aft")
C2, E1III = "(c)(2)", "(e)(1)(iii)"


def _by(result, loading, check):
    return next(f for f in result.findings if f.condition.loading == loading and f.check.startswith(check))


def test_the_declared_v2_lies_below_the_35_ft_speed_of_the_baseline():
    """Every loading evaluated on the engine-out run; the 35-ft speed is 5–10 kn above the declared 161 KCAS, so
    (c)(2) fails and (e)(1)(iii) complies at every CG, each with the run's own speeds as evidence."""
    res = run_rule(RULE)
    assert len(res.findings) == 6 and res.status == "fails"
    for loading in LOADINGS:
        c2, e = _by(res, loading, C2), _by(res, loading, E1III)
        assert c2.status == "fails" and e.status == "complies"
        assert abs(c2.value - 161.0) < 1e-6 and c2.unit == "kn"
        assert 5.0 < e.value - 161.0 < 10.0
        assert c2.condition.get("inoperative") is not None
        assert abs(c2.details["vr_kn"] - 155.0) < 1e-6 and c2.details["vlof_kn"] > 155.0


RAISED = [
    ("  V1: 150 kn CAS", "  V1: 162 kn CAS"),
    ("  VR: 155 kn CAS", "  VR: 167 kn CAS"),
    ("  V2: 161 kn CAS", "  V2: 173 kn CAS"),
]


def test_a_schedule_the_takeoff_lift_supports_nearly_meets_both(tmp_path):
    """With V2 173 / VR 167 / V1 162 KCAS the airplane lifts off during the rotation and reaches 35 ft within 1.5 kn of
    V2 at every CG: (c)(2)'s margin rises from −5…−9 kn to about −1 kn, (e)(1)(iii) still complies."""
    base = run_rule(RULE)
    raised = run_rule(RULE, tmp_path, RAISED)
    for loading in LOADINGS:
        c2 = _by(raised, loading, C2)
        assert -1.5 < c2.margin <= 0.0 and c2.margin > _by(base, loading, C2).margin
        assert _by(raised, loading, E1III).status == "complies"


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

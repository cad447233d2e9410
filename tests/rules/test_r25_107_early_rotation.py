"""§25.107(e)(3): the engine-out takeoff distance rotated 5 kt before VR against the distance rotated at VR.

The regulation's text (GPO 2007 print and a secondary copy, up to "5 knots less than VR"; the rest as the rule cites
it): the one-engine-inoperative takeoff distance, using a rotation speed 5 kt less than the established VR, may not
exceed the corresponding distance using the established VR, both determined under §25.113(a)(1). Both takeoffs are
the §25.111 pilot's (the same rotation rate to the same attitude held on the runway), the critical engine failed at
the same VEF; only the rotation speed moves.

* Baseline (V1 150 / VR 155 KCAS): rotating 5 kt early does not lengthen the distance at any CG.
* A deficient airplane: 18 % less thrust (80,000 lbf per engine) with V1 135 / VR 140 KCAS. The airplane lifts off at
  the speed the held attitude gives whatever the rotation speed, so rotating early only adds ground run at the
  rotated attitude's drag, which the weak engine-out acceleration pays for: the early-rotation distance is longer
  at every CG (by about 100–150 ft; halving the simulation step moved these margins by less than 5 ft, measured,
  hence the 30-ft bound).
* With V1 = VR the early rotation would come before V1 (§25.107(e)(1)(i) allows no such VR): both takeoffs then fail
  the engine at the VEF of V1 = VR − 5 kt, so the comparison is the baseline's, and the distance with the declared V1
  is reported beside it.
"""

import pytest

from .helpers import finding_by, own, run_rule

RULE = "25.107(e)(3)"
LOADINGS = ("MTOW forward", "MTOW reference", "MTOW aft")
CHECK = "(e)(3)"
WEAK = [
    ("static_thrust: 97300 lbf", "static_thrust: 80000 lbf"),
    ("  V1: 150 kn CAS", "  V1: 135 kn CAS"),
    ("  VR: 155 kn CAS", "  VR: 140 kn CAS"),
]


@pytest.fixture(scope="module")
def base():
    return run_rule(RULE)


def test_rotating_early_does_not_lengthen_the_baselines_distance(base):
    assert len(own(base)) == 3 and base.status == "complies"
    for loading in LOADINGS:
        f = finding_by(base, loading, CHECK)
        assert f.status == "complies" and f.unit == "ft" and f.margin >= 0.0
        d = f.details
        assert d["rotation_speed_kn"] == pytest.approx(150.0, abs=1e-6)
        assert "declared_v1_distance_ft" not in d  # V1 = VR − 5 kt: the established run is §25.111's
        for run in (d["established"], d["early_rotation"]):
            assert run["vlof_kn"] is not None and run["v35_kn"] is not None
        assert f.condition.get("inoperative") is not None


def test_thin_thrust_makes_the_early_rotation_longer(tmp_path):
    res = run_rule(RULE, tmp_path, WEAK)
    assert res.status == "fails"
    for loading in LOADINGS:
        f = finding_by(res, loading, CHECK)
        assert f.status == "fails" and f.margin < -30.0, (loading, f.margin)
        early, established = f.details["early_rotation"], f.details["established"]
        # the lift-off speed is the held attitude's, not the rotation speed's
        assert abs(early["vlof_kn"] - established["vlof_kn"]) < 0.5
        assert f.details["rotation_speed_kn"] == pytest.approx(135.0, abs=1e-6)


def test_v1_equal_to_vr_fails_the_engine_before_the_early_rotation_in_both_takeoffs(tmp_path, base):
    res = run_rule(RULE, tmp_path, [("  V1: 150 kn CAS", "  V1: 155 kn CAS")])
    for loading in LOADINGS:
        f, b = finding_by(res, loading, CHECK), finding_by(base, loading, CHECK)
        assert f.details["vef_kn"] == pytest.approx(b.details["vef_kn"], abs=1e-9)
        assert f.margin == pytest.approx(b.margin, abs=1e-9)
        # the engine failing later (the declared V1) shortens the established takeoff
        assert f.details["declared_v1_distance_ft"] < f.details["established_distance_ft"]
        assert "V1 taken at 150" in f.details["vef_basis"]


def test_without_vr_nothing_is_judged(tmp_path):
    res = run_rule(RULE, tmp_path, [("  VR: 155 kn CAS               # V2 - 6 kt\n", "")])
    assert res.status == "not_evaluated"

"""§25.113 takeoff distance from the simulated takeoffs, checked against a declared takeoff field length.

References: §25.113(a) (the greater of the engine-out distance to 35 ft and 115 % of the all-engines distance to
35 ft; hand arithmetic on the reported distances, 1-ft rounding); a deficient airplane (static thrust cut from
97,300 to 68,000 lbf per engine, 30 % less) must fail a field length the baseline meets (10,000 ft: the baseline needs
8,900–9,600 ft, the deficient airplane 14,500–16,700 ft). The rule's own representativeness bounds throughout: the
pilot steers the track back to the centreline, so the deficient airplane's engine-out run — 13 s rotated on lightly
loaded main wheels, sideslipping — stays within 30 ft of it (with a heading-only centreline loop it slid 47 ft off
and the run was not evaluated).
"""

import pytest

from .helpers import own, run_rule

FIELD = "performance:\n  takeoff_field_length: 10000 ft\n  source: test value\n"


def _edits(*extra, field=True):
    return [("\nsources:\n", "\n" + (FIELD if field else "") + "\nsources:\n"), *extra]


def test_distances_checked_against_a_declared_field_length(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    base = run_rule("25.113", tmp_path / "a", _edits())
    weak = run_rule("25.113", tmp_path / "b", _edits(("static_thrust: 97300 lbf", "static_thrust: 68000 lbf")))
    for f in own(base):
        d = f.details
        assert d["takeoff_distance_ft"] == pytest.approx(
            max(d["accelerate_go_distance_ft"], d["all_engines_distance_x1.15_ft"]), abs=1.5
        )
        assert d["all_engines_distance_x1.15_ft"] == pytest.approx(1.15 * d["all_engines_distance_to_35ft_ft"], abs=1.5)
        assert f.status == "complies" and f.limit == pytest.approx(10000.0) and f.unit == "ft"
    assert all(f.status == "fails" for f in own(weak))
    for fb, fw in zip(own(base), own(weak)):
        assert fb.value < 10000.0 < fw.value


def test_reported_but_not_checked_without_a_field_length(tmp_path):
    r = run_rule("25.113", tmp_path, _edits(field=False))
    for f in own(r):
        assert f.status == "not_evaluated" and "no performance.takeoff_field_length declared" in f.reason
        assert f"{f.details['takeoff_distance_ft']:,.0f} ft" in f.reason
    base = run_rule("25.113")  # the baseline declares no field length: reported, not checked
    assert all(f.status == "not_evaluated" and "no performance.takeoff_field_length" in f.reason for f in own(base))


def test_representativeness_bounds():
    """The bounds of a representative run (rules/part25/support/takeoff.py): VLOF ≤ VR + 15 kn (about a declared VLOF
    when
    there is one), V35 ≤ V2 + 10 kn with an engine out (§25.111(c)(2) 'as close as practical to V2'), ≤ 30 ft off the
    centreline on the ground (§25.149(e)), the attitude on the runway below the tail-strike attitude; each reason
    quotes the run's number and the bound. A run inside every bound has no reason."""
    from types import SimpleNamespace

    from certkit_rules.part25.support.takeoff import REPRESENTATIVE_CRITERIA, unrepresentative

    crit = SimpleNamespace(**{k: c.value for k, c in REPRESENTATIVE_CRITERIA.items()})
    good = {
        "vr_kn": 155.0,
        "v2_kn": 161.0,
        "vlof_kn": 163.0,
        "v35_kn": 165.0,
        "max_lateral_deviation_on_ground_ft": 12.0,
        "max_pitch_on_ground_deg": 10.5,
    }
    assert unrepresentative(good, crit, tail_strike_deg=12.1) == []
    assert unrepresentative({**good, "vlof_kn": 170.5}, crit) == ["VLOF 170.5 kn is 15.5 kn above VR (at most 15 kn)"]
    assert unrepresentative({**good, "vlof_kn": 170.5}, crit, vlof_declared_kn=160.0) == []
    assert unrepresentative({**good, "v35_kn": 171.5}, crit) == ["V35 171.5 kn is 10.5 kn above V2 (at most 10 kn)"]
    assert unrepresentative({**good, "v35_kn": 171.5}, crit, engine_out=False) == []
    assert unrepresentative({**good, "max_lateral_deviation_on_ground_ft": 31.0}, crit) == [
        "the ground run deviates 31 ft from the centreline (at most 30 ft)"
    ]
    assert "tail-strike" in unrepresentative({**good, "max_pitch_on_ground_deg": 12.2}, crit, tail_strike_deg=12.1)[0]
    assert unrepresentative({**good, "vlof_kn": None}, crit) == ["the airplane did not lift off"]

"""§25.113 takeoff distance from the simulated takeoffs, checked against a declared takeoff field length.

References: §25.113(a) (the greater of the engine-out distance to 35 ft and 115 % of the all-engines distance to
35 ft; hand arithmetic on the reported distances, 1-ft rounding); a deficient airplane (static thrust cut from
97,300 to 68,000 lbf per engine, 30 % less) must fail a field length the baseline meets (10,500 ft: the baseline needs
8,100–10,000 ft, the deficient airplane 14,500–16,700 ft). The rule's own representativeness bounds throughout: the
pilot steers the track back to the centreline, so the deficient airplane's engine-out run — 13 s rotated on lightly
loaded main wheels, sideslipping — stays within 30 ft of it (with a heading-only centreline loop it slid 47 ft off
and the run was not evaluated).
"""

import pytest

from .helpers import own, run_rule

FIELD = "performance:\n  takeoff_field_length: 10500 ft\n  source: test value\n"


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
        assert f.status == "complies" and f.limit == pytest.approx(10500.0) and f.unit == "ft"
    assert all(f.status == "fails" for f in own(weak))
    for fb, fw in zip(own(base), own(weak)):
        assert fb.value < 10500.0 < fw.value


def test_reported_but_not_checked_without_a_field_length(tmp_path):
    r = run_rule("25.113", tmp_path, _edits(field=False))
    for f in own(r):
        assert f.status == "not_evaluated" and "no performance.takeoff_field_length declared" in f.reason
        assert f"{f.details['takeoff_distance_ft']:,.0f} ft" in f.reason
    base = run_rule("25.113")  # the baseline declares no field length: reported, not checked
    assert all(f.status == "not_evaluated" and "no performance.takeoff_field_length" in f.reason for f in own(base))


def test_representativeness_bounds():
    """The bounds within which a run is a takeoff (rules/part25/support/takeoff.py): it lifts off and stays below the
    tail-strike attitude on the runway; each reason quotes the run's number and the bound. A late lift-off, a fast
    35-ft speed and a ground track off the centreline are not reasons: they are what the airplane does with the
    scheduled speeds, and the rules judge them (§25.111 the track)."""
    from certkit_rules.part25.support.takeoff import unrepresentative

    good = {
        "vr_kn": 155.0,
        "v2_kn": 161.0,
        "vlof_kn": 163.0,
        "v35_kn": 165.0,
        "max_lateral_deviation_on_ground_ft": 12.0,
        "max_pitch_on_ground_deg": 10.5,
        "max_pitch_to_liftoff_deg": 10.5,
    }
    assert unrepresentative(good, tail_strike_deg=12.1) == []
    assert unrepresentative({**good, "vlof_kn": 185.0, "v35_kn": 195.0}, tail_strike_deg=12.1) == []
    assert unrepresentative({**good, "max_lateral_deviation_on_ground_ft": 260.0}, tail_strike_deg=12.1) == []
    assert "tail-strike" in unrepresentative({**good, "max_pitch_on_ground_deg": 12.2}, tail_strike_deg=12.1)[0]
    assert unrepresentative({**good, "vlof_kn": None}) == ["the airplane did not lift off"]
    # a wheel set back down after the lift-off at 12.2°: the run is no takeoff for the path rules, while a check of
    # the lift-off itself (§25.107(e)(1)(iv)) reads the attitude up to the lift-off only
    after = {**good, "max_pitch_on_ground_deg": 12.2}
    assert unrepresentative(after, tail_strike_deg=12.1, to_liftoff=True) == []
    assert (
        "before the lift-off"
        in unrepresentative({**after, "max_pitch_to_liftoff_deg": 12.2}, tail_strike_deg=12.1, to_liftoff=True)[0]
    )


def test_an_airplane_that_rotates_late_needs_more_field(tmp_path):
    """A deficient airplane by its controls: no nose-up elevator (travel and design limit cut to 0°; the baseline
    rotates at the forward CG with about −12°). It rotates on the stabiliser's takeoff setting alone and lifts off
    more than 20 kn after VR at every CG (the baseline: 6–14 kn), so its takeoff distance exceeds the 10,500-ft
    field length the baseline meets. The late lift-off is judged, never a reason for 'not evaluated'."""
    cut = _edits(
        ("travel: {min: -30 deg, max: 25 deg}", "travel: {min: 0 deg, max: 25 deg}"),
        ("design_limits: {min: -21.8 deg, max: 16.8 deg}", "design_limits: {min: 0 deg, max: 16.8 deg}"),
    )
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    base = run_rule("25.113", tmp_path / "a", _edits())
    weak = run_rule("25.113", tmp_path / "b", cut)
    assert [f.status for f in own(base)] == ["complies"] * 3
    assert [f.status for f in own(weak)] == ["fails"] * 3
    for fb, fw in zip(own(base), own(weak)):
        assert fb.details["engine_out"]["vlof_after_vr_kn"] < 15.0 < 20.0 < fw.details["engine_out"]["vlof_after_vr_kn"]
        assert fw.details["all_engines"]["vlof_after_vr_kn"] > 20.0
        assert fb.value < 10500.0 < fw.value

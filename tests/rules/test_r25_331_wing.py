"""§25.331(c)(1) and (c)(2) report the wing loads of their runs: one wing finding per condition against the declared
wing capability, the wing considered up to the airplane's stall (linear strip loads), and a deficient wing fails."""

import pytest
from certkit_rules.part25.subpart_c.r25_331 import CheckedPitchManeuver, MaximumPitchControlDisplacement
from certkit_rules.part25.subpart_c.r25_331b import BalancedManeuver
from certkit_rules.part25.support.pitch_runs import WING_STALL_NOTE

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import evaluate_rule
from certkit.models.loads.capability import declared_capabilities

from .helpers import edited_baseline, hand_margin, in_mach_range

TWO_ALTITUDES = [("altitude_points: 5", "altitude_points: 2")]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("c_wing"), TWO_ALTITUDES)))
    return ctx, {
        r.id: evaluate_rule(r, ctx) for r in (MaximumPitchControlDisplacement, CheckedPitchManeuver, BalancedManeuver)
    }


def _wing(result):
    return [f for f in result.findings if _base(f).endswith(", wing")]


def _base(f) -> str:
    """The check's name without the capability comparison (``…, wing: ultimate bending at root (max)``)."""
    return f.check.split(":")[0]


def test_one_wing_finding_per_tail_finding(results):
    _, res = results
    for rid in ("25.331(c)(1)", "25.331(c)(2)"):
        r = res[rid]
        wing = _wing(r)
        tail = [f for f in r.findings if _base(f) + ", wing" in {_base(w) for w in wing}]
        assert wing and len(wing) == len(tail)
        assert {f.condition for f in wing} == {f.condition for f in tail}
        assert all("side of body bending max/min (kN·m)" in f.all_details() for f in wing)


def test_wing_margins_by_hand(results):
    """Every wing finding's margin from its reported loads and the declared wing allowables (docs/baseline-sources.md
    §10: side of body 38,494 / 46,624 kN·m positive limit / ultimate …), §25.303 factor 1.5, within the details' 0.1
    kN·m rounding."""
    ctx, res = results
    caps = declared_capabilities(ctx, "wing")
    for rid in ("25.331(c)(1)", "25.331(c)(2)"):
        for f in in_mach_range(_wing(res[rid])):
            norm, margin, check = hand_margin(f.all_details(), caps)
            assert f.normalized_margin == pytest.approx(norm, abs=5e-5), f.check
            if check in f.check:
                assert f.margin == pytest.approx(margin, abs=1.5 * 50 + 1)


def test_held_manoeuvres_past_the_stall_keep_the_wing_within_its_stalled_lift(results):
    """Held full-deflection manoeuvres drive α far past the stall (the airplane's lift stays at CLmax): the wing's
    loads are considered up to the stall only, so its root shear is bounded by the lift the whole airplane can make,
    n W with n at most the §25.337 limit 2.5 (+ the search tolerance) plus the tail's download (at most the tail's own
    root shear, both halves) — the half wing carries at most half of it."""
    ctx, res = results
    r = res["25.331(c)(2)"]
    tails = {f.condition: f for f in r.findings if _base(f).endswith(("nose up", "nose down"))}
    held = [f for f in _wing(r) if f.all_details().get("wing_window") == WING_STALL_NOTE]
    assert held  # the baseline's VA conditions at MRW stall
    for f in held:
        W = f.condition.mass * 9.80665
        tail = tails[f.condition].all_details()["root shear max/min (kN)"]
        bound = 0.5 * (2.52 * W + 2 * 1e3 * max(abs(tail[0]), abs(tail[1])))
        assert 1e3 * f.all_details()["root shear max/min (kN)"][0] <= bound


def test_checked_manoeuvre_wing_load_near_the_balanced_one(results):
    """A nose-up checked manoeuvre that reaches n₊ = 2.5 at VC loads the wing at most like the balanced 2.5 g pull-up
    at VC (§25.331(b)): at its peak load factor the pitching acceleration is nose down (the check), so the tail carries
    less download than the balancing load and the wing no more than n W plus it (5 % allowed for the load-factor
    tolerance and the rate terms); and not far less, the tail load being a small part of n W (≥ 80 %)."""
    _, res = results
    balanced = {
        (f.condition.loading, f.condition.altitude): f
        for f in res["25.331(b)"].findings
        if f.condition.get("point") == "VC at n+" and "wing:" in f.check
    }
    compared = 0
    for f in _wing(res["25.331(c)(2)"]):
        c = f.condition
        if (
            c.get("entry_speed") != "VC"
            or c.get("direction") != "nose up"
            or abs(f.all_details()["peak_n_z"] - 2.5) > 0.03
        ):
            continue
        b = balanced[(c.loading, c.altitude)]
        if b.all_details()["n"] != 2.5:
            continue
        ratio = (
            f.all_details()["side of body bending max/min (kN·m)"][0]
            / b.all_details()["side of body bending max/min (kN·m)"][0]
        )
        assert 0.8 <= ratio <= 1.05, c.label()
        compared += 1
    assert compared >= 4


def test_a_weak_wing_fails(tmp_path):
    """Deficient airplane: every positive wing bending allowable cut to 5,000 kN·m (the 1 g wing carries about
    13,000 kN·m at the side of body): every (c)(1) wing finding fails against exactly that, the tail's do not."""
    weak = TWO_ALTITUDES + [(f"positive: {v} kN*m}}", "positive: 5000 kN*m}") for v in (49896, 60434, 38494, 46624)]
    ctx = Context(load_aircraft(edited_baseline(tmp_path, weak)))
    r = evaluate_rule(MaximumPitchControlDisplacement, ctx)
    wing = [f for f in _wing(r) if f.status == "fails"]
    assert wing and len(wing) == len(_wing(r))
    assert all(f.limit == pytest.approx(5000e3) and "bending" in f.check for f in wing)
    assert not [f for f in r.findings if f.status == "fails" and not _base(f).endswith(", wing")]

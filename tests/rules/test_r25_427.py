"""§25.427(b) unsymmetrical tail loads: the 100/80 % split by hand from the symmetric §25.331(b) run, the fuselage
torsion from the removed air load's moment, and a deficient tailplane fails."""

from dataclasses import replace

import numpy as np
import pytest
from certkit_rules.part25.subpart_c.r25_331b import BalancedManeuver
from certkit_rules.part25.subpart_c.r25_427 import NO_FUSELAGE, UnsymmetricalTailLoads
from certkit_rules.part25.support.balanced_runs import balanced_maneuvers

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import criteria_for, evaluate_rule

from .helpers import edited_baseline, failures_with

FAST = [
    ("altitude_points: 5", "altitude_points: 2"),
    (
        "\nsources:\n",
        '\ncriteria:\n  "25.427(b)":\n    justification: "two gradients keep the test fast"\n'
        '    values: {gradients: "30 350"}\n  "25.341(a)":\n    justification: "the same gust runs"\n'
        '    values: {gradients: "30 350"}\nsources:\n',
    ),
]


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("t427"), FAST)))
    res = evaluate_rule(UnsymmetricalTailLoads, ctx)
    crit, _ = criteria_for(BalancedManeuver, ctx)
    sym = balanced_maneuvers(ctx, BalancedManeuver.conditions.expand(ctx.aircraft), crit)
    return ctx, res, sym


LB = 0.45359237


def test_split_by_hand_from_the_balancing_load(result):
    """The forward-CG balanced pull-up at VC (sea level) split by hand, independent of the rule's arrays: the half
    tail's air load S_A is half the §25.331(b) balancing load; its inertial load is the half tailplane's declared mass
    (5,800 lb / 2) at the finding's load factor, −m g n cos Γ normal to its dihedral plane; 100 % side S_A + S_I,
    80 % side 0.8 S_A + S_I (within 1 %: the body load factor n_z against the path's n). The fuselage takes the 20 %
    removed from one side: 0.2 × the half tail's air-load moment about the plane of symmetry, its root bending B_A
    (the §25.331(b) finding's root bending less the inertial part by hand, the mass spread with the trapezoid's area:
    −m g n ȳ, ȳ = (b/6)(1 + 2λ)/(1 + λ)) — statics of the two cantilevered halves (Megson §16.1), within 2 %.
    (A Schrenk span load cannot stand in for the balancing load: it is the small difference of the angle-of-attack,
    incidence and elevator loads, whose shapes differ.)"""
    from tests.loads.hand_span_load import planform

    ctx, res, sym = result
    key = next(
        c
        for c in sym.conditions
        if c.loading == "fwd_mrw" and c.get("point") == "VC at n+" and c.altitude == 0.0 and c.configuration == "clean"
    )
    bal = next(f for f in sym.findings if f.condition == key and "horizontal tail" in f.check)
    d = bal.all_details()
    s_a = 0.5e3 * d["tail_balancing_load_kN"]
    ht = ctx.aircraft.geometry.horizontal_tail
    s_i = -0.5 * 5800 * LB * 9.80665 * d["n_z_body"] * np.cos(ht.dihedral)
    split = {
        ("100%" if "100% side" in f.check else "80%"): f
        for f in res.findings
        if f.condition.get("source") == "25.331(b)"
        and f.condition.loading == "fwd_mrw"
        and f.condition.get("point") == "VC at n+"
        and f.condition.altitude == 0.0
        and f.condition.configuration == "clean"
    }
    assert split["100%"].all_details()["root shear max/min (kN)"][0] == pytest.approx((s_a + s_i) / 1e3, rel=0.01)
    assert split["80%"].all_details()["root shear max/min (kN)"][0] == pytest.approx((0.8 * s_a + s_i) / 1e3, rel=0.01)
    semispan, _, _ = planform(ht.area, ht.aspect_ratio, ht.taper)
    y_mass = semispan / 3 * (1 + 2 * ht.taper) / (1 + ht.taper)
    b_i = -0.5 * 5800 * LB * 9.80665 * d["n_z_body"] * y_mass
    b_a = 1e3 * d["root bending max/min (kN·m)"][0] - b_i
    torsion = split["80%"].all_details()["fuselage torsion at the tail max/min (kN·m)"][0]
    assert torsion == pytest.approx(0.2 * b_a / 1e3, rel=0.02)


def test_gust_conditions_split_and_the_rule_says_what_it_leaves_out(result):
    _, res, _ = result
    gust = [f for f in res.findings if f.condition.get("source") == "25.341(a)"]
    assert gust and all(f.status in ("complies", "fails") for f in gust)
    assert all("fuselage torsion at the tail max/min (kN·m)" in f.all_details() for f in gust)
    whole = {f.check: f for f in res.findings if f.condition.loading is None}
    assert "(b) symmetric loadings of §25.331(c)" not in whole  # (c)(1) and (c)(2) are both split
    scoped = [f for f in res.findings if f.details.get("not_evaluated_by_rule") == "25.427(b)(1)"]
    named = ("flaps-extended gusts", "continuous-turbulence")
    assert len(scoped) == 2 and set(named) == {w for w in named for f in scoped if w in f.reason}
    # the paragraph's other sub-paragraphs (14 CFR 25.427 (a), (c), (d)) are listed, not passed over
    others = {f.details.get("not_evaluated_by_rule") for f in res.findings if f.status == "not_evaluated"}
    assert {"25.427(a)", "25.427(c)", "25.427(d)"} <= others
    assert whole["(b) fuselage torsion at the tail"].reason == NO_FUSELAGE
    assert whole["(b) fuselage torsion at the tail"].all_details()["largest_torsion_kNm"] > 0


def test_flap_conditions_above_the_flap_altitude_do_not_apply(result):
    """A flap configuration above the flap altitude limit is not applicable in §25.331(b) (nothing to split), so its
    split is not applicable too — not "not evaluated" as if a trim had failed; the only conditions left not evaluated
    are the whole-airplane ones (what the rule leaves out, the undeclared fuselage capability)."""
    ctx, res, _ = result
    limit = 20000 * 0.3048
    high = [
        f for f in res.findings if f.condition.configuration not in (None, "clean") and f.condition.altitude > limit
    ]
    assert high and all(f.status == "complies" and f.reason.startswith("not applicable") for f in high)
    low = [
        f for f in res.findings if f.condition.configuration not in (None, "clean") and f.condition.altitude <= limit
    ]
    assert low and all(f.margin is not None for f in low)
    assert all(f.condition.loading is None for f in res.findings if f.status == "not_evaluated")


def test_full_side_of_a_gust_is_its_symmetric_loading(result):
    """The 100 % side of a gust condition carries the symmetric §25.341(a) tail loads: its extremes over every gradient
    and time equal the §25.341(a) finding's of the same condition (the runs are the same, shared in one process)."""
    ctx, res, _ = result
    from certkit_rules.part25.subpart_c.r25_341 import DiscreteGust

    sym = {
        f.condition: f
        for f in evaluate_rule(DiscreteGust, ctx).findings
        if "gust, up, horizontal tail" in f.check or "gust, down, horizontal tail" in f.check
    }
    compared = 0
    for f in res.findings:
        if f.condition.get("source") == "25.341(a)" and "100% side" in f.check:
            g = sym[replace(f.condition, extra=tuple((k, v) for k, v in f.condition.extra if k != "source"))]
            for key in ("root shear max/min (kN)", "root bending max/min (kN·m)", "root torsion max/min (kN·m)"):
                assert f.all_details()[key] == pytest.approx(g.all_details()[key], abs=0.11)
            compared += 1
    assert compared > 0


@pytest.mark.parametrize(
    "source, rule_name, check, least",
    [
        ("25.331(c)(1)", "MaximumPitchControlDisplacement", "(c)(1) maximum pitch control displacement", 10),
        ("25.331(c)(2)", "CheckedPitchManeuver", "(c)(2) checked manoeuvre", 40),
    ],
)
def test_full_side_of_a_pitch_manoeuvre_is_its_symmetric_loading(result, source, rule_name, check, least):
    """§25.427(b)(1) takes the §25.331 symmetric manoeuvres, the (c)(1) maximum pitch control displacement and the
    (c)(2) checked manoeuvre among them, in and out of trim: the 100 % side of each condition, rebuilt from the run's
    air and inertial parts over its window, has the extremes of the §25.331(c) finding's tail loads (its totals) for
    the same condition (to the 0.1 kN and kN·m the findings are rounded to)."""
    ctx, res, _ = result
    from certkit_rules.part25.subpart_c import r25_331

    sym = {
        f.condition: f
        for f in evaluate_rule(getattr(r25_331, rule_name), ctx).findings
        if (f.check.startswith(check) or f.check.startswith("(a)(2) out-of-trim"))
        and ", wing" not in f.check
        and "load factor" not in f.check
    }
    compared = 0
    for f in res.findings:
        if f.condition.get("source") == source and "100% side" in f.check:
            g = sym[replace(f.condition, extra=tuple((k, v) for k, v in f.condition.extra if k != "source"))]
            for key in (
                "root shear max/min (kN)",
                "root bending max/min (kN·m)",
                "side of body torsion max/min (kN·m)",
            ):
                assert f.all_details()[key] == pytest.approx(g.all_details()[key], abs=0.11)
            compared += 1
    assert compared >= least


def test_a_weak_tailplane_fails(tmp_path):
    """Deficient airplane: the tailplane root torsion allowable cut to 50 kN·m (its balancing and gust loads twist it
    by hundreds of kN·m): the 100 % side fails against exactly that allowable."""
    weak = FAST + [
        (
            "quantity: torsion, limit: 5204 kN*m, ultimate: 5204 kN*m",
            "quantity: torsion, limit: 50 kN*m, ultimate: 50 kN*m",
        )
    ]
    failing = failures_with(tmp_path, UnsymmetricalTailLoads, weak, "100% side")
    assert failing and all(f.limit == pytest.approx(50e3) and "torsion at root" in f.check for f in failing)


def _with_fuselage(limit_knm: float):
    """The baseline with a declared fuselage torsion capability at the tail (a test value)."""
    return FAST + [
        (
            "  vertical_tail:\n    - {station: root, quantity: shear",
            f"  fuselage:\n    - {{station: tail, quantity: torsion, limit: {limit_knm} kN*m, ultimate: "
            f'{limit_knm} kN*m, source: "test value"}}\n  vertical_tail:\n    - {{station: root, quantity: shear',
        )
    ]


def test_fuselage_torsion_against_a_declared_capability(tmp_path):
    """With structure.fuselage declared (tail, torsion; limit = ultimate = 2,000 kN·m, a test value), each split
    condition's fuselage torsion is compared by hand: margin = 2,000 kN·m − 1.5 |T| (the ultimate governs with equal
    allowables, §25.303), T the larger reported magnitude; and a 50 kN·m fuselage (deficient) fails everywhere the tail
    is loaded."""
    ctx = Context(load_aircraft(edited_baseline(tmp_path, _with_fuselage(2000))))
    res = evaluate_rule(UnsymmetricalTailLoads, ctx)
    fus = [f for f in res.findings if f.check.startswith("(b) fuselage torsion at the tail:")]
    assert fus and not any(f.reason == NO_FUSELAGE for f in res.findings)
    for f in fus:
        t = 1e3 * max(abs(v) for v in f.all_details()["fuselage torsion at the tail max/min (kN·m)"])
        assert f.margin == pytest.approx(2000e3 - 1.5 * t, abs=1.5 * 50 + 1)
    weak = failures_with(tmp_path, UnsymmetricalTailLoads, _with_fuselage(50), "fuselage torsion")
    assert weak and all(f.limit == pytest.approx(50e3) for f in weak)

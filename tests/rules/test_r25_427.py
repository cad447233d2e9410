"""§25.427(b) unsymmetrical tail loads: the 100/80 % split by hand from the symmetric §25.331(b) run, the fuselage
torsion from the removed air load's moment, and a deficient tailplane fails."""

from dataclasses import replace

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import criteria_for, evaluate_rule
from certkit_rules.part25.support.balanced_runs import balanced_maneuvers
from certkit_rules.part25.subpart_c.r25_331b import BalancedManeuver
from certkit_rules.part25.subpart_c.r25_427 import NO_FUSELAGE, NOT_SHARED, UnsymmetricalTailLoads

from .helpers import edited_baseline, failures_with

FAST = [("altitude_points: 5", "altitude_points: 2"),
        ("\nsources:\n", '\ncriteria:\n  "25.427(b)":\n    justification: "two gradients keep the test fast"\n'
                         '    values: {gradients: "30 350"}\n  "25.341(a)":\n    justification: "the same gust runs"\n'
                         '    values: {gradients: "30 350"}\nsources:\n')]


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("t427"), FAST)))
    res = evaluate_rule(UnsymmetricalTailLoads, ctx)
    crit, _ = criteria_for(BalancedManeuver, ctx)
    sym = balanced_maneuvers(ctx, BalancedManeuver.conditions.expand(ctx.aircraft), crit)
    return ctx, res, sym


def test_split_by_hand_from_the_symmetric_balanced_run(result):
    """For every §25.331(b) condition: the 100 % side carries the symmetric half-tail loads A + I, the 80 % side
    0.8 A + I (A the air load, I the inertial load of the half tail, from the symmetric run), and the fuselage takes
    the removed 20 % of the air load's moment about the plane of symmetry: 0.2 (B_A + S_A y_root) with B_A, S_A the
    air load's root bending and shear (statics of the two cantilevered halves)."""
    ctx, res, sym = result
    tail = sym.loads["horizontal_tail"]
    aero, inertia = sym.tail_parts
    by_label = {f.condition.label().replace(" · source 25.331(b)", ""): f for f in res.findings
                if f.condition.get("source") == "25.331(b)" and "80% side" in f.check}
    full = {f.condition.label().replace(" · source 25.331(b)", ""): f for f in res.findings
            if f.condition.get("source") == "25.331(b)" and "100% side" in f.check}
    assert len(by_label) == len(sym.conditions) > 0
    for i, c in enumerate(sym.conditions):
        f80, f100 = by_label[c.label()], full[c.label()]
        s_a, b_a, s_i = aero[i, 0, 0], aero[i, 1, 0], inertia[i, 0, 0]
        assert f100.all_details()["root shear max/min (kN)"][0] == pytest.approx((s_a + s_i) / 1e3, abs=0.06)
        assert f80.all_details()["root shear max/min (kN)"][0] == pytest.approx((0.8 * s_a + s_i) / 1e3, abs=0.06)
        torsion = 0.2 * (b_a + s_a * tail.station_y[0])
        assert f80.all_details()["fuselage torsion at the tail max/min (kN·m)"][0] == pytest.approx(torsion / 1e3, abs=0.06)


def test_gust_conditions_split_and_the_rule_says_what_it_leaves_out(result):
    _, res, _ = result
    gust = [f for f in res.findings if f.condition.get("source") == "25.341(a)"]
    assert gust and all(f.status in ("complies", "fails") for f in gust)
    assert all("fuselage torsion at the tail max/min (kN·m)" in f.all_details() for f in gust)
    whole = {f.check: f for f in res.findings if f.condition.loading is None}
    assert whole["(b) symmetric loadings of §25.331(c)"].reason == NOT_SHARED
    assert whole["(b) fuselage torsion at the tail"].reason == NO_FUSELAGE
    assert whole["(b) fuselage torsion at the tail"].all_details()["largest_torsion_kNm"] > 0


def test_full_side_of_a_gust_is_its_symmetric_loading(result):
    """The 100 % side of a gust condition carries the symmetric §25.341(a) tail loads: its extremes over every gradient
    and time equal the §25.341(a) finding's of the same condition (the runs are the same, shared in one process)."""
    ctx, res, _ = result
    from certkit_rules.part25.subpart_c.r25_341 import DiscreteGust

    sym = {f.condition: f for f in evaluate_rule(DiscreteGust, ctx).findings if "gust, up, horizontal tail" in f.check
           or "gust, down, horizontal tail" in f.check}
    compared = 0
    for f in res.findings:
        if f.condition.get("source") == "25.341(a)" and "100% side" in f.check:
            g = sym[replace(f.condition, extra=tuple((k, v) for k, v in f.condition.extra if k != "source"))]
            for key in ("root shear max/min (kN)", "root bending max/min (kN·m)", "root torsion max/min (kN·m)"):
                assert f.all_details()[key] == pytest.approx(g.all_details()[key], abs=0.11)
            compared += 1
    assert compared > 0


def test_a_weak_tailplane_fails(tmp_path):
    """Deficient airplane: the tailplane root torsion allowable cut to 50 kN·m (its balancing and gust loads twist it
    by hundreds of kN·m): the 100 % side fails against exactly that allowable."""
    weak = FAST + [("quantity: torsion, limit: 5204 kN*m, ultimate: 5204 kN*m",
                    "quantity: torsion, limit: 50 kN*m, ultimate: 50 kN*m")]
    failing = failures_with(tmp_path, UnsymmetricalTailLoads, weak, "100% side")
    assert failing and all(f.limit == pytest.approx(50e3) and "torsion at root" in f.check for f in failing)

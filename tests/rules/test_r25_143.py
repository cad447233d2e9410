"""§25.143(h) manoeuvring capability: coordinated turns checked by hand where the path is independent of certkit.

* Load factor and lift coefficient of a steady coordinated turn (Anderson, *Introduction to Flight*, eq. 6.81
  n = 1/cos φ, with the flight-path term n = cos γ / cos φ): landing case, VREF = 136 kn CAS at sea level,
  MLW 460,000 lb, S = 4927.3 ft², ρ0 = 0.0023769 slug/ft³, φ = 40°, γ = −3°: n = 1.30374,
  CL = n W / (½ ρ0 V² S) = 1.9434 (tolerance 1e-3).
* Thrust of the V2 + 10 kt all-engines case: two engines of the parametric turbofan (Mattingly lapse, see
  test_r25_121) at throttle 0.997 — the rule flies at the takeoff thrust kept 0.3 % inside the throttle range.
* Margin: the elevator design limit −21.8°/+16.8° (aircraft file) minus |δe| (deg).
"""

import math

import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.registry import discover, select
from certkit.engine.scheduler import criteria_for, evaluate_rule
from certkit.units import KN

from ..conftest import BASELINE
from .helpers import edited_baseline

LIMITS = "design_limits: {min: -21.8 deg, max: 16.8 deg}"


def rule_class(rule_id):
    (rule,) = [r for r in select(discover(), (rule_id,)) if r.id == rule_id]
    return rule


def evaluate_part(rule_id, ctx, keep=lambda c: True, **criteria):
    """The rule's findings on the conditions ``keep`` selects, with criteria overridden (fast partial runs)."""
    rule = rule_class(rule_id)
    crit, _ = criteria_for(rule, ctx)
    crit.update(criteria)
    return rule().evaluate(ctx, [c for c in rule.conditions.expand(ctx.aircraft) if keep(c)], crit)


def edited_context(tmp_path, edits):
    return Context(load_aircraft(edited_baseline(tmp_path, edits)))


@pytest.fixture(scope="module")
def shared():
    return Context(load_aircraft(BASELINE))


@pytest.fixture(scope="module")
def base(shared):
    return evaluate_rule(rule_class("25.143(h)"), shared)


def landing(c):
    return c.get("case") == "landing VREF"


def control(result, case, loading, name, turn=None):
    findings = result if isinstance(result, list) else result.findings
    return next(
        f
        for f in findings
        if f.condition.get("case") == case
        and f.condition.loading == loading
        and f.check.endswith(f"{name} within design limit")
        and (turn is None or f.condition.get("turn") == turn)
    )


def test_hand_calculation_load_factor_lift_and_margin(base):
    f = control(base, "landing VREF", "MLW reference", "elevator")
    n = math.cos(math.radians(-3)) / math.cos(math.radians(40))
    q = 0.5 * 0.0023769 * (136 * 1.6878099) ** 2
    assert f.details["load_factor"] == pytest.approx(n, abs=1e-4)
    assert f.details["CL"] == pytest.approx(n * 460_000 / (q * 4927.3), abs=1e-3)
    assert f.details["CL_over_CLmax"] == pytest.approx(n * 460_000 / (q * 4927.3) / 2.25, abs=1e-3)
    assert f.details["flight_path_deg"] == pytest.approx(-3.0) and f.details["bank_deg"] == pytest.approx(
        40.0, abs=1e-6
    )
    limit = 16.8 if f.value >= 0 else -21.8
    assert f.margin == pytest.approx(abs(limit) - abs(f.value), abs=1e-9)
    g = control(base, "takeoff V2+XX", "MTOW reference", "elevator")
    assert g.condition.speed / KN == pytest.approx(171.0, abs=1e-6)
    assert g.details["throttle:left"] == pytest.approx(0.997, abs=5e-4)  # at the takeoff thrust, climbing
    assert g.details["flight_path_deg"] > 0 and abs(g.details["thrust_residual"]) < 1e-4


def test_too_little_elevator_authority_fails(tmp_path, base):
    """A deficient airplane: the elevator's nose-up design limit cut to −7° (with the stabiliser trimmed wings level
    and held, the landing turn needs about −9° of elevator at the reference CG, −19° forward where the stabiliser is at
    its stop): the landing turn at MLW fails on the elevator at the forward and reference CG, with the trim's message;
    the aft CG (about −6°) still complies."""
    assert control(base, "landing VREF", "MLW reference", "elevator").value < -7.0
    ctx = edited_context(tmp_path, [(LIMITS, "design_limits: {min: -7 deg, max: 16.8 deg}")])
    r = evaluate_part("25.143(h)", ctx, landing)
    for loading in ("MLW forward", "MLW reference"):
        g = control(r, "landing VREF", loading, "elevator")
        assert g.status == "fails" and g.value < -7.0 and "limit -7.0°" in g.reason
    assert control(r, "landing VREF", "MLW aft", "elevator").status == "complies"


def warning(result, case, loading, turn=None):
    findings = result if isinstance(result, list) else result.findings
    return [
        f
        for f in findings
        if f.condition.get("case") == case
        and f.condition.loading == loading
        and f.check.endswith("free of stall warning")
        and (turn is None or f.condition.get("turn") == turn)
    ]


VSR_CLEAN_KN = 167.598  # 1-g stall, MTOW 656,000 lb, clean CLmax 1.4, S 4927.3 ft² (Anderson eq. 6.47)


def test_stall_warning_by_hand_and_the_vfto_turn_finding(base):
    """Without a declared warning onset the latest §25.207(c) allows is used: VSW = VSR + max(5 kn, 5 %) = 1.05 VSR,
    so the warning CL is CLmax/1.05² = 1.26984 clean. The 40° turn at VFTO = 198 kn (1.1814 VSR) needs
    CL/CLmax ≈ (1/cos 40°)/1.1814² = 0.935 (the flight path of the WAT-limited climb changes it by < 0.2 %): above
    0.907, so the en-route case fails (the reading: the VFTO turns fly inside any warning that meets
    §25.207(c) with the stall identified at VSR). The landing turn at VREF needs 0.864 CLmax: free of warning."""
    hand = (1 / math.cos(math.radians(40))) / (198 / VSR_CLEAN_KN) ** 2
    for f in warning(base, "en route VFTO", "MTOW forward"):
        assert f.limit == pytest.approx(1.4 / 1.05**2, rel=1e-6)
        assert f.value / 1.4 == pytest.approx(hand, rel=2e-3)
        assert f.status == "fails" and "§25.207(c)" in f.details["stall_warning_basis"]
    (land,) = warning(base, "landing VREF", "MLW reference")
    assert land.limit == pytest.approx(2.25 / 1.05**2, rel=1e-6) and land.status == "complies"


def test_a_declared_stall_warning_onset_is_used(tmp_path):
    """A declared clean warning onset at CL 1.33 (or VSW = 1.03 VSR, the least of §25.207(d): CL = 1.4/1.03² = 1.3196)
    puts the VFTO turns (CL ≈ 1.31) below it: free of warning, with the declared basis named."""
    clean = "    CLmax: 1.4                 # [given]\n"
    for line, limit in (
        ("    stall_warning: {CL: 1.33, source: test}\n", 1.33),
        ("    stall_warning: {speed_ratio: 1.03, source: test}\n", 1.4 / 1.03**2),
    ):
        ctx = edited_context(tmp_path, [(clean, clean + line)])
        r = evaluate_part("25.143(h)", ctx, lambda c: c.get("case") == "en route VFTO")
        found = warning(r, "en route VFTO", "MTOW reference")
        assert found and all(
            f.limit == pytest.approx(limit, rel=1e-6)
            and f.status == "complies"
            and "declared" in f.details["stall_warning_basis"]
            for f in found
        )


def test_bad_stall_warning_declarations_are_input_errors(tmp_path):
    """A warning CL at or above CLmax, or both a CL and a speed ratio: an input error naming the path."""
    from certkit.errors import UserError

    clean = "    CLmax: 1.4                 # [given]\n"
    for line, words in (
        ("    stall_warning: {CL: 1.45}\n", "below CLmax"),
        ("    stall_warning: {CL: 1.3, speed_ratio: 1.05}\n", "exactly one"),
    ):
        with pytest.raises(UserError) as err:
            load_aircraft(edited_baseline(tmp_path, [(clean, clean + line)]))
        assert words in str(err.value) and "configurations.clean" in str(err.value)


def test_sign_less_bank_more_margin_forward_cg_more_nose_up_and_rudder(shared, base):
    """A 30° instead of a 40° landing turn needs less nose-up elevator; forward CG needs more than aft; the
    V2 turn toward the operating engine needs rudder against the asymmetric thrust (left engine out: δr < 0)."""
    r = evaluate_part("25.143(h)", shared, landing, bank_deg=30.0)
    assert (
        control(r, "landing VREF", "MLW reference", "elevator").margin
        > control(base, "landing VREF", "MLW reference", "elevator").margin
    )
    assert (
        control(base, "landing VREF", "MLW forward", "elevator").value
        < control(base, "landing VREF", "MLW aft", "elevator").value
    )
    rud = control(base, "takeoff V2", "MTOW reference", "rudder", "toward the operating engine")
    assert rud.value < 0 and rud.condition.get("bank_deg") == 30.0


def test_not_evaluated_without_vref_and_a_turn_that_cannot_be_flown_fails(tmp_path, base, shared):
    """Without VREF the landing turn is not evaluated. The baseline's VFTO (1.18 VSR clean) turn at 40° needs about
    94 % of CLmax and is trimmed (the model reaches its declared CLmax); at 60° of bank it would need 1.44 × that: no
    steady turn exists, so its controls are not evaluated (the lift named) and the turn fails the stall-warning check
    on the least lift any steady turn at that speed and bank needs (a path as steep as 10°, cos 10° of the level
    turn's: still 1.4 × CLmax)."""
    ctx = edited_context(tmp_path, [("  VREF: 136 kn CAS ", "  # VREF: 136 kn CAS ")])
    r = evaluate_part("25.143(h)", ctx, landing)
    assert len(r) == 1 and r[0].status == "not_evaluated" and r[0].reason == "needs speeds.VREF"
    enroute = [f for f in base.findings if f.condition.get("case") == "en route VFTO"]
    assert enroute and all(f.margin is not None and 0.9 < f.details["CL_over_CLmax"] < 1.0 for f in enroute)
    steep = evaluate_part("25.143(h)", shared, lambda c: c.get("case") == "en route VFTO", bank_deg=60.0)
    trims = [f for f in steep if f.check.endswith("trim")]
    warnings = [f for f in steep if f.check.endswith("free of stall warning")]
    assert trims and all(f.status == "not_evaluated" and "CLmax" in f.reason for f in trims)
    assert len(warnings) == len(trims) and all(f.status == "fails" for f in warnings)
    assert all(f.value > 1.3 * 1.4 for f in warnings)  # the clean CLmax 1.4 (aircraft file)


def test_a_wing_too_small_for_the_turns_fails_them(tmp_path):
    """The baseline with a wing 15 % smaller (4,188 ft² for 4,927 ft², the same speeds): the 30° turn at V2 and the
    40° turn at VFTO at MTOW need 1.06 and 1.11 × CLmax, so the airplane cannot fly them; each fails the stall-warning
    check on the least lift it needs (none is left without a verdict for want of a trim)."""
    ctx = edited_context(
        tmp_path, [("  area: 4927.3 ft^2            # [given] wing reference area", "  area: 4188.2 ft^2")]
    )
    found = evaluate_part("25.143(h)", ctx, lambda c: c.get("case") in ("takeoff V2", "en route VFTO"))
    untrimmed = [f for f in found if f.check.endswith("trim")]
    assert untrimmed
    for f in untrimmed:
        twin = next(w for w in found if w.check.endswith("free of stall warning") and w.condition == f.condition)
        assert twin.status == "fails" and twin.value > twin.limit


def test_wat_limited_thrust_gives_the_minimum_gradient(shared):
    """'Asymmetric WAT-limited thrust' (§25.143(h) with EASA AMC 25.143(h)): the operating engine's thrust at which
    straight flight at V2, critical engine out, zero sideslip, climbs at exactly the §25.121(b) 2.4 % — checked by
    trimming at that thrust and reading the flight path back (Anderson eq. 5.12 path; tolerance 1e-4 in tan γ).
    At 80 % of MTOW it is below the takeoff thrust (at MTOW the baseline's gear-down takeoff configuration is close
    to the limit: capped at the takeoff thrust at some CGs)."""
    from certkit_rules.part25.support.maneuvering import wat_limited_thrust
    from certkit_rules.part25.support.thrust_trims import operating_thrust, trim_at_thrust

    conds = [
        c
        for c in evaluate_part("25.143(h)", shared, lambda c: c.get("case") == "takeoff V2")
        if c.condition.get("turn") == "toward the operating engine" and c.check.endswith("elevator within design limit")
    ]
    dead = "left"
    conds = [f.condition.with_(bank_deg=0.0, mass=0.8 * f.condition.mass) for f in conds]
    aim, capped = wat_limited_thrust(shared, conds, 0.024, 1.0, dead)
    assert not capped.any() and (aim < operating_thrust(shared, conds, 1.0, 1.0, dead)).all()
    _, gamma, _ = trim_at_thrust(shared, conds, aim, kind="sideslip", inoperative=dead)
    assert [math.tan(g) for g in gamma] == pytest.approx([0.024] * len(conds), abs=1e-4)

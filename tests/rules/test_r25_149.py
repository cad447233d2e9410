"""§25.149 minimum control speed.

Hand calculation of the grid crossing (linear interpolation where the control usage |δ|/δ_limit crosses 1),
the rule on the baseline: VMCA against 1.13 VSR, with VSR = √(2W/(ρ0 S CLmax)) in lb, ft, slug (656,000 lb,
4927.3 ft², takeoff CLmax of the model) to 0.1 %; and each bank's VMCA checked by trims on either side of it
against what limits it (a control at its design limit, or the lift maximum).
"""

import math

import numpy as np
import pytest
from certkit_rules.part25.support.control_speeds import control_usage, vmca_from_grid

from certkit.models.flight import control_limits
from certkit.units import KN

from .helpers import control_forces_edit, own, run_rule


@pytest.fixture(scope="module")
def result():
    return run_rule("25.149")


def test_grid_interpolation_hand_calculation():
    """Usage 1.4 at 100 kt and 0.8 at 110 kt: crossing at 100 + 0.4/0.6·10 = 106.67 kt."""
    assert vmca_from_grid([90, 100, 110, 120], [2.0, 1.4, 0.8, 0.5]) == pytest.approx(106.6667, abs=1e-3)
    assert vmca_from_grid([90, 100], [0.9, 0.5]) is None  # controllable everywhere: below the grid


def test_on_the_limit():
    """Usage exactly 1 at a grid speed: VMCA is that speed (margin 0 there)."""
    assert vmca_from_grid([90, 100, 110], [1.5, 1.0, 0.7]) == pytest.approx(100.0)


def test_sign_more_usage_raises_vmca():
    lo = vmca_from_grid([90, 100, 110], [1.5, 1.2, 0.7])
    hi = vmca_from_grid([90, 100, 110], [1.5, 1.2, 0.9])
    assert hi > lo


def test_baseline_vsr_and_vmc_not_declared(result, ctx):
    c = next(f for f in own(result) if f.check.startswith("(c)"))
    clmax = ctx.clmax("takeoff")
    vsr_kn = math.sqrt(2 * 656_000 / (0.0023769 * 4927.3 * clmax)) / 1.6878099
    assert c.details["VSR"] / 0.514444 == pytest.approx(vsr_kn, rel=1e-3)
    assert c.limit == pytest.approx(1.13 * c.details["VSR"], rel=1e-9)
    assert np.isfinite(c.value) and c.value < c.limit  # VMCA ≈ 139 kn against 1.13 VSR = 160.5 kn
    from certkit.report.figures import render_result

    render_result(result)
    assert result.evidence and result.evidence[0].svg and not any("evidence" in n for n in result.notes)
    # without a declared VMC the computed VMCA stands for it: the comparison is set apart (not the rule's own check),
    # so the computed (c), (d), (e) and (h)(1) checks decide the status
    assert not any(f.check.startswith("(b)") for f in own(result))
    b = next(f for f in result.findings if f.check.startswith("(b)"))
    assert b.status == "not_evaluated" and b.reason.startswith("no speeds.VMC declared")
    assert b.details["computed_VMCA_kn_cas"] == pytest.approx(c.value / 0.514444, abs=0.06)
    assert result.status == "complies_partial"


def test_a_small_rudder_raises_vmca_beyond_the_limit(result, tmp_path):
    """A deficient airplane: the rudder's design limit cut from ±23.2° to ±12°. The rudder's yawing moment is ∝ δr q,
    so the static VMCA grows about as √(23.2/12) = 1.39 (139 → ≈ 193 kn, the bank and aileron help aside), beyond
    1.13 VSR = 160.5 kn: (c) fails, at every engine failed."""
    base = next(f for f in own(result) if f.check.startswith("(c)"))
    r = run_rule(
        "25.149",
        tmp_path,
        edits=[("design_limits: {min: -23.2 deg, max: 23.2 deg}", "design_limits: {min: -12 deg, max: 12 deg}")],
    )
    small = [f for f in own(r) if f.check.startswith("(c)")]
    assert small and all(f.status == "fails" for f in small)
    assert all(1.2 < f.value / base.value < 1.5 for f in small)


def test_not_evaluated_without_takeoff_clmax(tmp_path):
    r = run_rule("25.149", tmp_path, edits=[("    CLmax: 1.95 ", "    #CLmax: 1.95 ")])
    assert r.status == "not_evaluated" and "configurations.takeoff.CLmax" in own(r)[0].reason


def test_vmca_brackets_where_the_limiting_control_runs_out(result, ctx):
    """Independent of the search: at each bank's VMCA the named limit holds. Rudder- or aileron-limited: that control
    is at its design limit (0.5 %), a trim 0.5 kn faster needs less than its limits and 0.5 kn slower more.
    Stall-limited: the trim 0.5 kn faster is within limits, 0.5 kn slower has no steady solution, and its lift-curve
    slope is below a quarter of CL_α (the lift maximum). No bank ends on a trim failure."""
    from certkit_rules.part25.support.control_speeds import at_lift_maximum

    limits = control_limits(ctx.aircraft)
    c = next(f for f in own(result) if f.check.startswith("(c)") and f.condition.get("inoperative") == "left")
    base = c.condition
    for bank, what in c.details["limited_by_bank"].items():
        assert what in ("rudder", "aileron", "stall")
        v = c.details["vmca_by_bank_kn"][bank] * KN
        phi = math.radians(float(bank.split()[0]))
        conds = [base.with_(speed=v + dv * KN, speed_kind="CAS") for dv in (0.5, -0.5)]
        fast, slow = ctx.trim(conds, kind="oei", bank=phi, inoperative="left", throttle=0.99).results
        assert control_usage(fast, limits) < 1.0
        if what == "stall":
            assert not slow.converged and at_lift_maximum(ctx, base.configuration, slow)
        else:
            assert control_usage(slow, limits) > 1.0
            at = ctx.trim(
                [base.with_(speed=v, speed_kind="CAS")], kind="oei", bank=phi, inoperative="left", throttle=0.99
            ).results[0]
            lo, hi = limits[what]
            d = at.controls[what]
            assert (d / hi if d >= 0 else d / lo) == pytest.approx(1.0, abs=0.005)


def test_vmca_is_the_least_over_the_banks_allowed(result):
    """§25.149(b): straight flight with not more than 5° of bank — VMCA is the least over the banks searched (0° to
    5° toward the operating engine, 1° steps); on the baseline an intermediate bank balances the rudder's and the
    aileron's needs and gives a lower VMCA than either end, and the finding says what limits it."""
    for c in (f for f in own(result) if f.check.startswith("(c)")):
        by_bank = c.details["vmca_by_bank_kn"]
        assert len(by_bank) == 6
        assert c.value / KN == pytest.approx(min(by_bank.values()), abs=0.01)
        assert min(by_bank.values()) < min(
            by_bank["5 deg" if "5 deg" in by_bank else "-5 deg"], by_bank["0 deg" if "0 deg" in by_bank else "-0 deg"]
        )
        assert 0 < abs(c.details["bank_at_vmca_deg"]) < 5
        assert c.details["vmca_limited_by"]


def test_vmca_mirror_symmetric_and_stable(result, ctx):
    """The baseline is a symmetric twin: with the right engine out the airplane is the mirror image of the left engine
    out (rudder, aileron, sideslip and bank change sign), so VMCA must be the same within the search's resolution
    (0.05 kn steps) — an independent physical requirement the search once broke (left 139.4 kn, right 139.8 kn: near
    the stall the retry of a non-converged trim depended on round-off). And a 1e-9 relative change of the mass, or a
    start speed 1e-6 relatively different, must not move VMCA by more than 0.05 kn."""
    from types import SimpleNamespace

    from certkit_rules.part25.support.control_speeds import vmca_search
    from certkit_rules.part25.support.minimum_control import VMCA_CONDITIONS, VMCA_CRITERIA, VMCA_RULE_ID, vmca_rows

    from certkit.engine.scheduler import criteria_for

    by_engine = {f.condition.get("inoperative"): f.value for f in own(result) if f.check.startswith("(c)")}
    assert set(by_engine) == {"left", "right"}
    assert by_engine["left"] / KN == pytest.approx(by_engine["right"] / KN, abs=0.05)
    crit, _ = criteria_for(SimpleNamespace(id=VMCA_RULE_ID, criteria=VMCA_CRITERIA), ctx)
    conds = [c.with_(mass=c.mass * (1 + 1e-9)) for c in VMCA_CONDITIONS.expand(ctx.aircraft)]
    rows = vmca_rows(ctx, conds, crit)
    nb = len(rows["vmca"]) // 2
    left, right = rows["vmca"][:nb], rows["vmca"][nb:]
    assert [rows["engines"][0], rows["engines"][nb]] == ["left", "right"]
    assert np.allclose(left / KN, right / KN, atol=0.05, rtol=0)  # every bank, not only the least
    assert min(left) / KN == pytest.approx(by_engine["left"] / KN, abs=0.05)
    moved, *_ = vmca_search(
        ctx,
        rows["conds"],
        rows["engines"],
        rows["banks"],
        rows["vsr"],
        crit.throttle,
        crit.grid_low,
        crit.grid_high,
        crit.speed_tolerance_kn * KN,
        start=1.2 * (1 + 1e-6),
    )
    assert np.allclose(moved / KN, rows["vmca"] / KN, atol=0.05, rtol=0)


def test_a_fin_forty_percent_smaller_fails(result, tmp_path):
    """A deficient airplane by geometry: the vertical tail's area cut by 40 % (527.84 → 316.70 ft², aspect ratio,
    taper and sweep kept, so its span shrinks too). The rudder's yawing moment falls with the fin while the
    engine-out moment does not: the rudder (or the aileron holding the sideslip the weaker fin needs) now runs out
    above 1.13 VSR at every bank — VMCA is control-limited, not stall-limited, and (c) fails for either engine."""
    r = run_rule("25.149", tmp_path, edits=[("    area: 527.84 ft^2          # [given]", "    area: 316.70 ft^2")])
    small = [f for f in own(r) if f.check.startswith("(c)")]
    assert len(small) == 2 and all(f.status == "fails" and f.value > f.limit for f in small)
    for f in small:
        assert set(f.details["limited_by_bank"].values()) <= {"rudder", "aileron"}
    base = min(f.value for f in own(result) if f.check.startswith("(c)"))
    assert min(f.value for f in small) > base + 20 * KN


def test_with_roll_control_to_spare_vmca_falls_with_bank(tmp_path):
    """The directional model against the classical static result behind §25.149(b)'s 5° of bank (FAA AC 25-7D's VMCA
    flight tests are flown with it): banking toward the operating engine lowers VMCA, the weight component then
    supplying the side force the rudder and the sideslip otherwise must. On the baseline the
    declared roll control (ailerons only, 17 % chord over 78–98 % span; the 777's roll spoilers are not declared)
    runs out first at 4° and 5° of bank, holding the sideslip of 6.6–8.5° the weak side force needs. With the roll
    power doubled (Cl_δa −0.14/rad, standing for the spoilers) the rudder-limited VMCA falls at every step of bank
    until straight flight reaches the lift maximum, and no bank is aileron-limited."""
    block = (
        "aerodynamics:\n  overrides_source: test, roll spoilers\n  overrides:\n    takeoff: {Cl_aileron: -0.14}\n"
        "sources:"
    )
    r = run_rule("25.149", tmp_path, edits=[("\nsources:", "\n" + block)])
    c = next(f for f in own(r) if f.check.startswith("(c)") and f.condition.get("inoperative") == "left")
    by_bank = [c.details["vmca_by_bank_kn"][f"{b} deg"] for b in range(6)]
    limits = [c.details["limited_by_bank"][f"{b} deg"] for b in range(6)]
    assert "aileron" not in limits
    rudder = [v for v, what in zip(by_bank, limits) if what == "rudder"]
    assert len(rudder) >= 3 and all(a > b for a, b in zip(rudder, rudder[1:]))
    assert all(what == "stall" for what in limits[len(rudder) :])
    assert c.details["vmca_limited_by"].startswith("the stall")


# --- (e) VMCG by simulation -------------------------------------------------------------------------------------------

FIN = ("area: 527.84 ft^2          # [given]", "area: 316.70 ft^2          # 40 % smaller fin")


def _vmcg(result):
    return [f for f in own(result) if f.check.startswith("(e) VMCG")]


def test_vmcg_over_the_weight_cg_corners(result):
    """Every corner of the weight–CG envelope gets a VMCG below VR = 155 KCAS, found inside the search (the deviation
    beyond 30 ft just below it and within 30 ft just above, in its own search table). The highest is a heavy corner
    (the yaw inertia grows with weight while the thrust asymmetry does not); without a declared VMCG the comparison with
    it is not evaluated and names the computed value."""
    found = _vmcg(result)
    assert len(found) == 8 and all(f.status == "complies" and f.limit == pytest.approx(155.0) for f in found)
    for f in found:
        below = [row for row in f.details["search"] if row["failure_speed_kn_cas"] < f.value - 0.5]
        above = [row for row in f.details["search"] if row["failure_speed_kn_cas"] > f.value + 0.5]
        assert all(r["max_lateral_deviation_ft"] is None or r["max_lateral_deviation_ft"] > 30.0 for r in below)
        assert all(r["max_lateral_deviation_ft"] <= 30.0 for r in above)
    worst = max(found, key=lambda f: f.value)
    assert worst.condition.mass > 600_000 * 0.4536
    declared = next(f for f in result.findings if f.check.startswith("(e) declared"))
    assert (
        declared not in own(result)
        and declared.status == "not_evaluated"
        and declared.details["computed_VMCG_kn_cas"] == pytest.approx(worst.value, abs=0.1)
    )


def test_declared_vmcg_checked_against_the_computed_one(result, tmp_path):
    """A declared VMCG 5 kn above the computed one complies by 5 kn; 5 kn below it fails by 5 kn (kn CAS)."""
    worst = max(f.value for f in _vmcg(result))
    for offset in (5.0, -5.0):
        (tmp_path / str(offset)).mkdir()
        r = run_rule(
            "25.149",
            tmp_path / str(offset),
            [("  V2: 161 kn CAS", f"  V2: 161 kn CAS\n  VMCG: {worst + offset:.2f} kn CAS")],
        )
        f = next(f for f in own(r) if f.check.startswith("(e) declared"))
        assert f.margin == pytest.approx(offset, abs=0.02) and f.status == ("complies" if offset > 0 else "fails")


def test_a_40_percent_smaller_fin_has_no_vmcg_on_the_runway(result, tmp_path):
    """A deficient airplane: the fin (and its rudder) 40 % smaller, aspect ratio kept. The rudder's yawing moment
    scales about with the fin's area times its arm, so the speed at which the rudder balances the engine-out moment
    grows about as 1/√0.6 = 1.29: from ≈ 136 kn to ≈ 175 kn, beyond VR = 155 kn. No failure speed on the runway keeps
    the deviation within 30 ft at the heavy corners: (e) fails there."""
    r = run_rule("25.149", tmp_path, [FIN])
    heavy = [f for f in _vmcg(r) if f.condition.mass > 600_000 * 0.4536]
    assert heavy and all(f.status == "fails" and "no VMCG on the runway" in f.reason for f in heavy)
    base = {f.condition.loading: f.value for f in _vmcg(result)}
    for f in _vmcg(r):
        assert f.status != "complies" or f.value > base[f.condition.loading]


def test_the_baseline_rudder_reaches_its_stop_below_150_lbf(result):
    """With the 777 AMM pedal feel (50 lbf at full pedal) the 150 lbf of (e) does not bind: the runs use the stops."""
    for f in _vmcg(result):
        assert f.details["rudder_limit"].startswith("the rudder's stops (pedal force there 50 lbf")


def test_a_heavy_pedal_feel_limits_the_rudder_and_raises_vmcg(result, tmp_path):
    """A deficient feel (springs, 20 lbf breakout + 40 lbf/in at 6 °/in: 150 lbf at (150 − 20)/40 × 6 = 19.5° of
    rudder, against the 27.3° stop). The rudder the pilot can hold at 150 lbf is 71 % of the stop's, so the static
    speed at which it balances the engine-out moment rises about as 1/√0.714 = 1.18 (the simulated VMCG more: the
    rudder saturates sooner in the swing): VMCG rises at every corner by more than 5 kn, and where it passes
    VR = 155 kn (the heavy corners, ≈ 136 kn × 1.18 ≈ 161 kn) (e) fails; at the light aft corner too, where the
    airplane lifts off unrotated before the rudder has arrested the swing."""
    feel = (
        "control_forces:\n  rudder:\n    type: artificial_feel\n    preload: 20 lbf\n    gradient: 40 lbf/in\n"
        "    gearing: 6 deg/in\n"
    )
    r = run_rule("25.149", tmp_path, [control_forces_edit(feel)])
    heavy = _vmcg(r)
    assert len(heavy) == 8
    base = {f.condition.loading: f.value for f in _vmcg(result)}
    for f in heavy:
        assert f.details["rudder_limit"] == "150 lbf pedal force: rudder -19.5° / 19.5°"
        assert f.value > base[f.condition.loading] + 5.0
    assert any(f.status == "fails" for f in heavy if f.condition.mass > 600_000 * 0.4536)
    # the light aft airplane lifts off at its attitude of rest (≈ 150 KCAS) before the weaker rudder has arrested the
    # swing from any cut that stays within 30 ft on the runway: no VMCG on the runway there either, and it says why
    light = next(f for f in heavy if f.condition.loading == "aft_light")
    assert light.status == "fails" and "still swinging away" in light.reason
    assert light.details["lifted_off_swinging_kn_cas"][0] > light.details["search"][-1]["failure_speed_kn_cas"]


def test_vmcl_where_the_rudder_runs_out_and_its_pedal_force(result, ctx):
    """(f) VMCL in the landing configuration (aft CG, MLW, go-around thrust, 5° bank toward the live engine):
    independent trims 0.5 kn either side of it — within the limits faster, beyond them slower — and the rudder at its
    23.2° design limit at VMCL (0.5 %). (h)(1) pedal force by hand from the AMM feel: 19.5 + 30.5 × 23.2/27.3 =
    45.4 lbf (the feel's breakout plus its spring over the pedal travel), against 150 lbf."""
    limits = control_limits(ctx.aircraft)
    f = next(
        f
        for f in own(result)
        if f.check.startswith("(h)(1)")
        and f.condition.configuration == "landing"
        and f.condition.get("inoperative") == "left"
    )
    d = f.details
    assert d["vmcl_limited_by"] == "rudder" and d["bank_at_vmcl_deg"] == 5.0
    v, phi = d["VMCL_kn_cas"] * KN, math.radians(5.0)
    base = f.condition
    fast, at, slow = ctx.trim(
        [base.with_(speed=v + dv * KN, speed_kind="CAS") for dv in (0.5, 0.0, -0.5)],
        kind="oei",
        bank=phi,
        inoperative="left",
        throttle=0.99,
    ).results
    assert control_usage(fast, limits) < 1.0 < control_usage(slow, limits)
    assert at.controls["rudder"] / limits["rudder"][0] == pytest.approx(1.0, abs=0.005)
    assert f.value == pytest.approx(19.5 + 30.5 * 23.2 / 27.3, abs=0.2) and f.status == "complies"
    assert {g.condition.configuration for g in own(result) if g.check.startswith("(h)(1)")} == {"approach", "landing"}


def test_vmcl_follows_the_rudder_power_and_decides_vref(tmp_path):
    """VMCL against the rudder's power, with §25.125's VREF ≥ VMCL. Deficient by geometry: the fin 40 % smaller — the
    rudder's yawing power falls with it, so the speed at which it balances the live engine rises (∝ 1/√0.6 = 1.29 ×
    for a rudder-limited VMCL) beyond the search's 1.4 VSR0, and VREF ≥ VMCL fails. The other way: the rudder's
    design limit at its full 27.3° travel (the baseline declares 23.2°) lowers VMCL (rudder force ∝ δ q), where the
    aileron may take over as the limit; VREF then clears it. Order: travel < baseline < small fin."""
    check = "(b)(2)(i)(B) VREF ≥ VMCL"
    (tmp_path / "fin").mkdir()
    (tmp_path / "travel").mkdir()
    runs = {
        "small fin": run_rule("25.125", tmp_path / "fin", [FIN]),
        "baseline": run_rule("25.125"),
        "full travel": run_rule(
            "25.125",
            tmp_path / "travel",
            [("design_limits: {min: -23.2 deg, max: 23.2 deg}", "design_limits: {min: -27.3 deg, max: 27.3 deg}")],
        ),
    }
    found = {k: [f for f in r.findings if f.check == check] for k, r in runs.items()}
    assert all(len(v) == 3 for v in found.values())
    vmcl = {k: v[0].details["VMCL"] / KN for k, v in found.items()}
    assert vmcl["full travel"] < vmcl["baseline"] < vmcl["small fin"]
    assert vmcl["small fin"] >= 1.4 * 110.0 and all(f.status == "fails" for f in found["small fin"])
    assert all(f.status == "complies" for f in found["full travel"])
    vref = 136.0
    for k, fs in found.items():  # the margin is VREF/VMCL − 1 at every CG (VMCL at the most unfavourable, aft)
        assert all(f.margin == pytest.approx(vref / vmcl[k] - 1.0, abs=1e-6) for f in fs)


#: a horizontal tail of the tail study's corner (20 % smaller than the baseline's, swept 42°, thin, its elevator a
#: third of the chord over 80 % of the span): the light airplane's cuts lift off before the heading recovers
SMALL_SWEPT_TAIL = (
    ("    area: 1119.2 ft^2          # [given]", "    area: 895.4 ft^2"),
    ("    aspect_ratio: 4.62         # [given]", "    aspect_ratio: 3.70"),
    ("    taper: 0.33                # [given]", "    taper: 0.26"),
    ("    sweep_quarter_chord: 34.82 deg   # [given]", "    sweep_quarter_chord: 41.78 deg"),
    ("    thickness_ratio: 0.088     # [given]", "    thickness_ratio: 0.071"),
    ("        span_start: 0.07       # [given]", "        span_start: 0.0"),
    ("        span_end: 0.94         # [given]", "        span_end: 0.80"),
    ("        chord_ratio: 0.29      # [given]", "        chord_ratio: 0.35"),
)


def test_a_light_airplane_lifting_off_before_the_recovery_still_has_a_vmcg(tmp_path):
    """At 310,000 lb the takeoff wing lifts the airplane off at its attitude of rest near 150 KCAS, 4.5 kn/s after an
    engine cut: with the tail above, every cut from 120 KCAS up leaves the runway before the heading is back parallel
    to the centreline. VMCG is "the calibrated airspeed during the takeoff run" at which the rudder alone keeps the
    path within 30 ft, and a simulator's VMCG test asks for the recovery with the main gear on the ground (14 CFR
    Part 60, Appendix A, test 1.b.2): such a run counts with its deviation on the runway, beyond 30 ft (it failed
    there) or within (the rudder held the path for the whole takeoff run). The light aft corner then has a VMCG inside
    its search, bracketed by two runs that lifted off, one beyond 30 ft on the runway and one within, as at the
    baseline's light aft corner (127.3 KCAS), not "no VMCG on the runway" (when those runs were set aside, the runs
    left on the runway, all below 121 KCAS, were all beyond the bound)."""
    r = run_rule("25.149", tmp_path, list(SMALL_SWEPT_TAIL))
    f = next(f for f in _vmcg(r) if f.condition.loading == "aft_light")
    assert f.status == "complies" and 120.0 < f.value < 135.0
    rows = f.details["search"]
    below = [row for row in rows if row["failure_speed_kn_cas"] < f.value]
    above = [row for row in rows if row["failure_speed_kn_cas"] > f.value]
    assert below[-1]["lifted_off_before_recovery"] and above[0]["lifted_off_before_recovery"]
    assert below[-1]["max_lateral_deviation_ft"] > 30.0 >= above[0]["max_lateral_deviation_ft"]
    # the deviation on the runway falls as the cut comes later (less of the run left, more rudder power)
    devs = [row["max_lateral_deviation_ft"] for row in rows if row["max_lateral_deviation_ft"] is not None]
    assert all(a >= b - 0.5 for a, b in zip(devs, devs[1:]))


def test_vmcg_not_evaluated_without_vr_and_the_rule_not_passed(tmp_path):
    """(e) needs the declared VR (the top of the search: VMCG is sought on the runway, below VR). Without it every
    weight–CG corner's VMCG finding says so and the rule as a whole is not evaluated — it does not comply on its
    other sub-paragraphs alone, which are still computed."""
    r = run_rule("25.149", tmp_path, edits=[("  VR: 155 kn CAS", "  #VR: 155 kn CAS")])
    vmcg = [f for f in own(r) if f.check.startswith("(e)")]
    assert len(vmcg) == 8  # the corners of the weight–CG envelope
    assert all(f.status == "not_evaluated" and f.reason == "needs speeds.VR" for f in vmcg)
    others = [f for f in own(r) if not f.check.startswith("(e)")]
    assert others and all(f.status != "not_evaluated" for f in others)
    assert r.status == "not_evaluated"

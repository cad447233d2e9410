"""§25.331(b) balanced manoeuvres on the baseline: loads by hand from the strip forces, the critical wing case against
the declared capability, and deficient airplanes that must fail."""

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.models.loads.capability import declared_capabilities
from certkit.engine.scheduler import evaluate_rule
from certkit.units import G0
from certkit_rules.part25.support.balanced_runs import NO_FLAP_STRIPS
from certkit_rules.part25.subpart_c.r25_331b import BalancedManeuver

from .helpers import NO_STRUCTURE, edited_baseline, failures_with, hand_margin

FAST = [("altitude_points: 5", "altitude_points: 2")]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("b331"), FAST)))
    rule = BalancedManeuver()
    from certkit.engine.scheduler import criteria_for

    crit, _ = criteria_for(BalancedManeuver, ctx)
    findings = rule.evaluate(ctx, BalancedManeuver.conditions.expand(ctx.aircraft), crit)
    return ctx, findings, rule.run


def _one(findings, loading, point, surface, altitude=0.0, configuration="clean"):
    return next(f for f in findings if f.condition.loading == loading and f.condition.get("point") == point
                and f.condition.altitude == altitude and f.condition.configuration == configuration
                and f.check.split(":")[0].endswith(surface))


def test_every_point_weight_and_configuration_is_scheduled(run):
    ctx, findings, _ = run
    corners = {v.name for v in ctx.aircraft.cg_envelope.vertices}
    clean = {(f.condition.loading, f.condition.get("point")) for f in findings if f.condition.configuration == "clean"}
    assert clean == {(c, p) for c in corners for p in ("A", "VC at n+", "D", "E", "F", "H")}
    flaps = {f.condition.configuration for f in findings if f.condition.get("point", "").startswith("VF")}
    assert flaps == set(ctx.aircraft.configurations) - {"clean"}


def test_load_factor_and_pull_up_rate_of_each_point(run):
    """n on the flight path as the point asks (n₊ = 2.5 at A, VC, D; 0 at E; n₋ = −1 at F, H; 2.0 flaps extended at
    VF, §25.345(a)(1)), and the pitch rate of a pull-up q = g (n − 1)/V (Etkin & Reid §6.7, level path)."""
    ctx, findings, _ = run
    expected = {"A": 2.5, "VC at n+": 2.5, "D": 2.5, "E": 0.0, "F": -1.0, "H": -1.0, "VF at n flaps": 2.0, "VF at 0": 0.0}
    for f in findings:
        if not f.all_details() or "n" not in f.all_details():
            continue
        point = f.condition.get("point")
        if "stall line" in f.all_details().get("speed_note", ""):
            # below the stall line's speed (VC Mach-limited at altitude): n on the ±C_N,max line, n = ±(V/VS1)²
            # with VS1 = √(2 m g / (ρ₀ S C_N,max)) (§25.333(b) stall lines, §25.335(c) VS1)
            cfg = ctx.aircraft.configurations["clean"]
            cn = BalancedManeuver.criteria["cn_over_cl"].value * (cfg.CLmax if expected[point] > 0 else -cfg.CLmin)
            vs1 = np.sqrt(2 * f.condition.mass * G0 / (1.225 * ctx.aircraft.reference.area * cn))
            n = np.sign(expected[point]) * (f.condition.speed / vs1) ** 2
            assert abs(n) < abs(expected[point]) and f.all_details()["n"] == pytest.approx(n, abs=2e-3)
        else:
            assert f.all_details()["n"] == expected[point]
        v_tas = f.condition.speed * np.sqrt(1.225 / _rho(f.condition.altitude))
        q = np.degrees(G0 * (f.all_details()["n"] - 1.0) / v_tas)
        assert f.all_details()["pitch_rate_deg_s"] == pytest.approx(q, rel=0.02, abs=0.002)


def _rho(h):
    from certkit.atmosphere import density

    return float(density(h))


def test_wing_root_bending_by_hand_from_the_strip_forces(run):
    """Root bending of one point summed by hand: Σ_j (q̄ N_j − m_j g n_z) × s_j over the half wing's strips (aerodynamic
    normal force of each strip at the balanced state, strip mass at the body load factor, arm s_j to the strip's
    middle along the span) — the beam statics of Megson §14.1 — against the rule's reported root bending."""
    ctx, findings, r = run
    f = _one(findings, "fwd_mrw", "VC at n+", "wing")
    i = r.conditions.index(f.condition)
    st = {k: v[i] for k, v in r.state.items()}
    wing = r.loads["wing"]
    strips = wing.strip_normal_force(st["qbar"], st["mach"], {k: st[k] for k in ("alpha", "q_hat", "elevator",
                                                                                  "aileron", "rudder")})
    hand = np.sum((strips - wing.strip_mass * G0 * st["n_z"]) * wing.strip_span)
    assert f.all_details()["root bending max/min (kN·m)"][0] == pytest.approx(hand / 1e3, rel=0.01)
    # and the wing carries about n W plus the tail download (both halves' air load)
    W = f.condition.mass * G0
    air = 2 * np.sum(strips)
    assert air == pytest.approx(2.5 * W - 1e3 * f.all_details()["tail_balancing_load_kN"], rel=0.03)


def test_margins_by_hand_and_the_critical_wing_case(run):
    """Each evaluated finding's margin recomputed from its reported loads and the declared capability; the baseline's
    critical wing case is the heaviest forward-CG airplane at the top of the envelope, side-of-body ultimate bending — the
    declared capability (openly derived, docs/baseline-sources.md §10) is below 1.5 × its balanced 2.5 g load."""
    ctx, findings, _ = run
    caps = {s: declared_capabilities(ctx, s) for s in ("wing", "horizontal_tail")}
    for f in findings:
        if f.status in ("complies", "fails"):
            surface = "wing" if f.check.split(":")[0].endswith("wing") else "horizontal_tail"
            norm, margin, _ = hand_margin(f.all_details(), caps[surface])
            assert f.margin == pytest.approx(margin, abs=0.2e3 + 1e-3 * abs(f.limit))
    wing = [f for f in findings if f.status in ("complies", "fails") and "wing:" in f.check]
    worst = min(wing, key=lambda f: f.margin / f.limit)
    assert worst.condition.loading == "fwd_mrw" and worst.condition.get("point") in ("A", "VC at n+", "D")
    assert worst.all_details()["n"] > 2.0  # on the n₊ line, or on the stall line just below it (Mach-limited VD at altitude)
    assert "ultimate bending at side of body" in worst.check
    assert worst.status == "fails"


def test_flaps_extended_tail_is_evaluated_wing_is_not(run):
    _, findings, _ = run
    flap = [f for f in findings if f.condition.configuration != "clean"]
    assert flap
    assert all(f.status == "not_evaluated" and f.reason == NO_FLAP_STRIPS for f in flap if "wing:" in f.check
               or f.check.endswith("wing"))
    tail = [f for f in flap if "horizontal tail" in f.check]
    assert tail and all(f.status in ("complies", "fails") for f in tail)


def test_envelope_is_kept_for_the_sizing_loop(run):
    _, _, r = run
    env = r.envelope
    assert set(env.peaks) == {"wing", "horizontal_tail"}
    assert np.isfinite(env.peaks["horizontal_tail"]).all()
    assert BalancedManeuver().run is None
    assert r.envelopes() == [env]


def test_not_evaluated_without_structural_capability(tmp_path):
    ctx = Context(load_aircraft(edited_baseline(tmp_path, FAST + [NO_STRUCTURE])))
    result = evaluate_rule(BalancedManeuver, ctx)
    clean = [f for f in result.findings if f.condition.configuration == "clean"]
    assert clean and all(f.status == "not_evaluated" and f.reason == "no structural capability declared" for f in clean)
    assert all("root bending max/min (kN·m)" in f.all_details() for f in clean)


def test_a_weak_tailplane_fails(tmp_path):
    """Deficient airplane: the tailplane root bending allowable cut to 100 kN·m (its balancing loads bend it by several
    hundred kN·m): the tail findings fail against exactly that allowable."""
    weak = FAST + [("quantity: bending, limit: 7366 kN*m, ultimate: 7366 kN*m",
                    "quantity: bending, limit: 100 kN*m, ultimate: 100 kN*m")]
    tail = failures_with(tmp_path, BalancedManeuver, weak, "horizontal tail")
    assert tail and all(f.limit == pytest.approx(100e3) and "bending at root" in f.check for f in tail)


def test_a_strong_wing_complies(tmp_path):
    """The converse: with the side-of-body and root positive bending allowables doubled the wing findings comply — the
    baseline's wing failures come from the declared allowables, not from the rule."""
    strong = FAST + [("positive: 49896 kN*m}", "positive: 99792 kN*m}"), ("positive: 60434 kN*m}", "positive: 120868 kN*m}"),
                     ("positive: 38494 kN*m}", "positive: 76988 kN*m}"), ("positive: 46624 kN*m}", "positive: 93248 kN*m}")]
    ctx = Context(load_aircraft(edited_baseline(tmp_path, strong)))
    result = evaluate_rule(BalancedManeuver, ctx)
    wing = [f for f in result.findings if "wing:" in f.check]
    assert wing and not [f for f in wing if f.status == "fails"]


def test_flap_load_factor_above_the_clean_one_is_an_input_error(tmp_path, cli):
    """Bad input: a flaps-extended limit load factor above the flaps-retracted one is reported with its path and line,
    and the CLI exits 2."""
    from certkit.errors import InputError

    bad = edited_baseline(tmp_path, [("    flaps_extended: 2.0", "    flaps_extended: 3.0")])
    with pytest.raises(InputError) as info:
        load_aircraft(bad)
    (p,) = [p for p in info.value.problems if p.path == "envelope.limit_load_factors.flaps_extended"]
    assert "must not exceed the clean positive limit load factor (2.5" in p.message and p.value == 3.0
    assert p.line == next(i for i, t in enumerate(bad.read_text().splitlines(), 1) if "flaps_extended: 3.0" in t)
    assert cli("check", bad, "--select", "25.331(b)", "--out", tmp_path / "out").exit_code == 2

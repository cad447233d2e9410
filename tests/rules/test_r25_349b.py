"""§25.349(b) unsymmetrical gusts on the baseline (sea level and ceiling, gradients 30 and 350 ft to stay fast):
the gust runs shared with §25.341(a) (simulated once in one process), the unbalanced rolling moment's arm against
lifting-line theory, the roll acceleration by hand from the loading's inertia, margins by hand against the
declared wing capability, the not-evaluated path, the increment reading, and a bad criterion as a user error."""

import numpy as np
import pytest
from certkit_rules.part25.subpart_c.r25_341 import DiscreteGust
from certkit_rules.part25.subpart_c.r25_349 import UnsymmetricalGust

from certkit.aircraft import load_aircraft
from certkit.engine.context import Context
from certkit.engine.scheduler import criteria_for, evaluate_rule
from certkit.errors import UserError
from certkit.models.loads.capability import declared_capabilities
from certkit.units import G0

from .helpers import NO_STRUCTURE, edited_baseline, hand_margin, own

FAST_CRITERIA = """criteria:
  "25.341(a)":
    justification: "two gradients keep the test fast"
    values: {gradients: "30 350"}
  "25.349(b)":
    justification: "the same gust runs as 25.341(a)"
    values: {gradients: "30 350"%s}
sources:
"""
FAST = [("altitude_points: 5", "altitude_points: 2"), ("\nsources:\n", "\n" + FAST_CRITERIA % "")]


@pytest.fixture(scope="module")
def shared(tmp_path_factory):
    """Both gust rules evaluated on one Context, as one process of the scheduler does (run_with)."""
    ctx = Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("unsym"), FAST)))
    sym = evaluate_rule(DiscreteGust, ctx)
    rule = UnsymmetricalGust()
    crit, _ = criteria_for(UnsymmetricalGust, ctx)
    findings = rule.evaluate(ctx, UnsymmetricalGust.conditions.expand(ctx.aircraft), crit)
    return ctx, sym, findings, rule.run, crit


def _evaluated(findings):
    return [f for f in findings if f.all_details()]


def test_gust_runs_are_shared_with_25_341a(shared):
    """One gust simulation for both rules (the memo holds one run set), and the symmetric root bending each
    §25.349(b) finding reports is the §25.341(a) finding's of the same condition."""
    ctx, sym, findings, _, _ = shared
    assert sum(1 for k in ctx._memo if isinstance(k, tuple) and k[0] == "discrete_gust_runs") == 1
    assert UnsymmetricalGust.run_with == DiscreteGust.run_with != ""
    by_cond = {f.condition: f for f in own(sym) if f.check.endswith(", wing") or ", wing:" in f.check}
    checked = 0
    for f in _evaluated(findings):
        # the maximum: §25.341(a) takes the wing in every §25.343 fuel state (the least fuel bends it most up), the
        # symmetric loading §25.349(b) splits is the wing without fuel, so only the up-bending extreme is shared
        a = by_cond[f.condition].all_details()["root bending max/min (kN·m)"]
        assert f.all_details()["symmetric_root_bending_max_min_kNm"][0] >= a[0] - 0.05
        checked += 1
    assert checked == len(_evaluated(findings)) > 0


def test_rolling_moment_arm_against_lifting_line(shared, baseline):
    """ΔL / (Δn m g) is the spanwise centre of the half wing's air load (ΔL = −0.2 M, Δn m g = −0.2 S). Reference:
    Schrenk's approximation (NACA TM 948, 1940) for the untwisted wing, the mean of the elliptic centre 4/(3π) =
    0.4244 (Prandtl's lifting line) and the trapezoidal planform's (1 + 2λ)/(3(1 + λ)) = 0.3842 at λ = 0.18:
    0.4043 of the semispan (measured in the plane of the dihedral wing, as the arm). ±10 %: the −4° washout moves
    the load inboard where the lift coefficient is low (0.371 at VD, sea level, light), the 31° sweep outboard.
    The full side rises (ΔL < 0 for an up load, body axes) and Δn < 0."""
    _, _, findings, run, _ = shared
    w = baseline.model.geometry.wing
    semispan = 0.5 * np.sqrt(w.aspect_ratio * w.area) / np.cos(w.dihedral)  # in the plane of the wing, as the arm
    masses = run.runs.batch.model.mass
    index = {c: i for i, c in enumerate(run.conditions)}
    for f in _evaluated(findings):
        d = f.all_details()
        i = index[f.condition]
        arm = d["peak_unbalanced_rolling_moment_MNm"] * 1e6 / (d["load_factor_change"] * masses[i] * G0)
        assert arm / semispan == pytest.approx(0.5 * (4 / (3 * np.pi) + 1.36 / 3.54), rel=0.10), f.condition.label()
        if d["peak_unbalanced_rolling_moment_MNm"] < 0:
            assert d["load_factor_change"] < 0 and d["roll_acceleration_deg_s2"] < 0


def test_roll_acceleration_from_the_loading_inertia(shared):
    """ṗ = ΔL / I_xx with the condition's roll inertia (mass properties of the loading, body axes); details rounded
    to 0.001 MN·m and 0.01 deg/s² (tolerance 0.2 %)."""
    _, _, findings, run, _ = shared
    J = run.runs.batch.model.inertia
    index = {c: i for i, c in enumerate(run.conditions)}
    for f in _evaluated(findings):
        d = f.all_details()
        expected = np.degrees(d["peak_unbalanced_rolling_moment_MNm"] * 1e6 / J[index[f.condition], 0, 0])
        assert d["roll_acceleration_deg_s2"] == pytest.approx(expected, rel=2e-3, abs=0.01)


def test_margins_by_hand_against_the_declared_wing_capability(shared, baseline):
    """Every evaluated finding's normalised margin recomputed from its reported loads and the baseline's declared
    wing capability (docs/baseline-sources.md §10; 0.1 kN rounding: 5e-5); both sides are reported for every
    simulated condition (every scheduled one flies on the baseline)."""
    ctx, _, findings, run, _ = shared
    caps = declared_capabilities(ctx, "wing")
    evaluated = _evaluated(findings)
    assert len(evaluated) == 2 * len(run.conditions)
    assert {f.check.rsplit(", ", 1)[1].split(":")[0] for f in evaluated} == {"100% side", "80% side"}
    for f in evaluated:
        normalized, _, _ = hand_margin(f.all_details(), caps)
        assert f.normalized_margin == pytest.approx(normalized, abs=5e-5), f.check
    assert len(evaluated) == len(findings)


def test_increment_basis_has_a_smaller_unbalance_for_up_gusts(shared):
    """'increment': only the gust increment over the 1 g trim is split, so an up gust's unbalanced rolling moment
    is smaller than with the whole air load split (the literal reading, default)."""
    ctx, _, findings, _, crit = shared
    crit = type(crit)({**crit, "airload_basis": "increment"})
    inc = UnsymmetricalGust().evaluate(ctx, UnsymmetricalGust.conditions.expand(ctx.aircraft), crit)
    total = {(f.condition, f.check.split(":")[0]): f for f in _evaluated(findings)}
    ups = [f for f in _evaluated(inc) if f.condition.get("gust") == "up"]
    assert ups
    for f in ups:
        t = total[(f.condition, f.check.split(":")[0])]
        assert abs(f.all_details()["peak_unbalanced_rolling_moment_MNm"]) < abs(
            t.all_details()["peak_unbalanced_rolling_moment_MNm"]
        )
        assert f.all_details()["airload_basis"] == "increment"


def test_bad_airload_basis_is_a_user_error(shared):
    ctx, _, _, _, crit = shared
    crit = type(crit)({**crit, "airload_basis": "half"})
    with pytest.raises(
        UserError, match=r"criteria\.25\.349\(b\)\.values\.airload_basis: 'half' is not one of total, increment"
    ):
        UnsymmetricalGust().evaluate(ctx, UnsymmetricalGust.conditions.expand(ctx.aircraft), crit)


def test_not_evaluated_without_structural_capability(tmp_path):
    ctx = Context(load_aircraft(edited_baseline(tmp_path, FAST + [NO_STRUCTURE])))
    result = evaluate_rule(UnsymmetricalGust, ctx)
    evaluated = _evaluated(own(result))
    assert evaluated and all(
        f.status == "not_evaluated" and f.reason == "no structural capability declared" for f in evaluated
    )
    assert all("root bending max/min (kN·m)" in f.all_details() for f in evaluated)  # the loads are still reported
    assert result.status == "not_evaluated"


def test_a_weak_wing_fails(tmp_path):
    """A deficient airplane: the side-of-body positive bending allowables cut to 15/20 MN·m (the baseline's gust
    bending there is about 33 MN·m ultimate): the up-gust conditions fail against exactly that allowable."""
    weak = FAST + [
        ("positive: 38494 kN*m}", "positive: 15000 kN*m}"),
        ("positive: 46624 kN*m}", "positive: 20000 kN*m}"),
    ]
    ctx = Context(load_aircraft(edited_baseline(tmp_path, weak)))
    result = evaluate_rule(UnsymmetricalGust, ctx)
    failing = [f for f in own(result) if f.status == "fails"]
    assert result.status == "fails" and failing
    crit = result.critical
    assert "side of body" in crit.check and crit.value > crit.limit
    assert crit.limit in (pytest.approx(15000e3), pytest.approx(20000e3))

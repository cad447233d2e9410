"""§25.351 yaw manoeuvre: the settled sideslip of the simulation against the lateral-directional static balance
solved by hand, the overswing and load signs over the baseline run, the not-evaluated path (VD missing) and the
comparison with a vertical-tail capability declared to sit exactly on the computed loads.
"""

import numpy as np
import pytest
from certkit_rules.part25.subpart_c.r25_351 import YawManeuver
from certkit_rules.part25.support.loads_conditions import trimmed_batch

from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.context import Context
from certkit.engine.scheduler import evaluate_rule
from certkit.models.loads.yaw import simulate_yaw
from certkit.units import KN

from .helpers import NO_STRUCTURE, hand_margin, own, run_rule

ROOT_SHEAR = "root shear max/min (kN)"


@pytest.fixture(scope="module")
def yaw(baseline):
    return evaluate_rule(YawManeuver, Context(baseline))


def test_steady_sideslip_by_hand(baseline):
    """Steady wings-level sideslip with a held rudder (Etkin & Reid, Dynamics of Flight, 3rd ed., §5.10):
    with φ = 0 and p ≈ 0 the side force turns the flight path, r = q̄ S C_Y / (m u), and the yaw and roll
    moments about the CG balance:
        C_Yβ β + (C_Yr b/2V − m u/(q̄ S)) r + C_Yδa Δδa = −C_Yδr Δδr
        C_nβ β + C_nr (b/2V) r + C_nδa Δδa = −C_nδr Δδr
        C_lβ β + C_lr (b/2V) r + C_lδa Δδa = −C_lδr Δδr
    the moment derivatives transferred from the aero reference point to the CG (C_n += C_Y x/b,
    C_l −= C_Y z/b, (x, z) the reference point in body axes from the CG). The classical one-equation
    estimate C_nβ β + C_nδr δr = 0 is also checked. VC = 272 KEAS at sea level, fwd_light, Δδr = −10°;
    the simulation is run to a 0.2 % settled band (up to 90 s). Tolerances: 1 % on β and Δδa, 5 % on r
    (3 × 3 balance); 4 % for the one-equation estimate (it neglects the side-force and roll coupling)."""
    ctx = Context(baseline)
    cond = ConditionSpace(loading=CgCorners(), configurations=("clean",), altitudes=None).expand(baseline.model)[0]
    batch = trimmed_batch(ctx, [cond.with_(speed=272 * KN, speed_kind="EAS")])
    model = batch.model
    jr, ja = model.control_index("rudder"), model.control_index("aileron")
    d_rudder = np.radians(-10.0)
    run = simulate_yaw(
        model, batch.x, batch.u, d_rudder, dt=0.04, t_max=90.0, window=6.0, tolerance=0.002, aileron_limits=(-1.5, 1.5)
    )
    assert run.settled[0]
    h = run.held
    mach, qbar, V, alpha = h["mach"][-1, 0], h["qbar"][-1, 0], h["V"][-1, 0], h["alpha"][-1, 0]
    aero = ctx.aero("clean").model
    S, b, m = model.aero.reference.area, model.b, float(model.mass[0])
    xb, _, zb = model.r_ref[0]

    def d(name):
        return float(aero.derivative(name, mach))

    def cy(k):
        return d("CY_" + k)

    def cn(k):
        return d("Cn_" + k) + cy(k) * xb / b

    def cl(k):
        return d("Cl_" + k) - cy(k) * zb / b

    A = np.array(
        [
            [cy("beta"), cy("r") * b / (2 * V) - m * V * np.cos(alpha) / (qbar * S), cy("aileron")],
            [cn("beta"), cn("r") * b / (2 * V), cn("aileron")],
            [cl("beta"), cl("r") * b / (2 * V), cl("aileron")],
        ]
    )
    beta, r, d_aileron = np.linalg.solve(A, -d_rudder * np.array([cy("rudder"), cn("rudder"), cl("rudder")]))
    assert h["beta"][-1, 0] == pytest.approx(beta, rel=0.01)
    assert h.controls[-1, 0, ja] - batch.u[0, ja] == pytest.approx(d_aileron, rel=0.01)
    assert h["r"][-1, 0] == pytest.approx(r, rel=0.05)
    assert h.controls[-1, 0, jr] - batch.u[0, jr] == pytest.approx(d_rudder, abs=1e-9)
    assert h["beta"][-1, 0] == pytest.approx(-cn("rudder") * d_rudder / cn("beta"), rel=0.04)


def test_overswing_exceeds_steady_and_load_signs(yaw):
    """Rudder to its negative stop (§25.351(a)(1) control system stops: the travel −27.3° of aircraft/lta.yaml, not
    the −23.2° design limit; nose-right yaw: C_nδr < 0; the 777 AMM pedal feel gives 50 lbf at the stop, below the
    300 lbf limit of (a)(2)): the sideslip is negative (β = −C_nδr δr / C_nβ has the sign of δr), the overswing
    |β| exceeds the settled |β| at every condition,
    and the fin root shear reverses between (a) (rudder force alone, C_Yδr δr < 0) and (b) (sideslip force
    C_Yβ β > 0 dominates)."""
    by = {}
    for f in own(yaw):
        by.setdefault(f.condition, {})[f.check[:3]] = f
    assert len(by) == 64  # 8 CG corners × 2 altitudes × 4 speeds
    for cond, ph in by.items():
        d = ph["(b)"].all_details()
        assert d["rudder_deg"] == pytest.approx(-27.3, abs=0.01) and "rudder at its stop" in d["pilot_effort"]
        assert d["overswing_beta_deg"] < 0 and d["steady_beta_deg"] < 0
        assert abs(d["overswing_beta_deg"]) > abs(d["steady_beta_deg"]), cond
        assert ph["(a)"].all_details()[ROOT_SHEAR][0] < 0 < ph["(b)"].all_details()[ROOT_SHEAR][0], cond
    assert all(f.status in ("complies", "fails") for f in own(yaw))


def test_baseline_margins_against_the_declared_capability(yaw, baseline):
    """The baseline's declared fin capability (docs/baseline-sources.md §10: root 5,022 kN, 14,276 kN·m,
    10,107 kN·m; 50 % height 1,899 kN, 2,742 kN·m, 1,927 kN·m; CFRP, limit = ultimate so 1.5 × the limit load
    governs): each phase finding's normalised margin recomputed by hand from its reported loads (0.1 kN
    rounding: 5e-5 of a ≥ 1.9 MN allowable)."""
    from certkit.models.loads.capability import declared_capabilities

    caps = declared_capabilities(Context(baseline), "vertical_tail")
    assert {c.station for c in caps} == {"root", "50% span"}
    for f in own(yaw):
        normalized, margin, check = hand_margin(f.all_details(), caps)
        assert f.normalized_margin == pytest.approx(normalized, abs=5e-5), f.check
        assert "ultimate" in f.check
        if check in f.check:
            assert f.margin == pytest.approx(margin, abs=1.5 * 50 + 1)


def test_not_evaluated_without_structure(tmp_path):
    """The baseline without its structure section: every phase of every condition is not evaluated with the
    reason, and still reports its fin loads (sea level and ceiling only, to stay fast)."""
    result = run_rule("25.351", tmp_path, edits=[NO_STRUCTURE, ("altitude_points: 5", "altitude_points: 2")])
    assert result.status == "not_evaluated"
    assert {f.reason for f in own(result)} == {"no structural capability declared"}
    assert all(ROOT_SHEAR in f.all_details() for f in own(result))


def test_not_evaluated_without_vd(tmp_path):
    """VD missing from the aircraft file: the rule is not evaluated before computing, naming speeds.VD."""
    result = run_rule("25.351", tmp_path, edits=[("  VD: 340 kn EAS", "  # VD removed")])
    assert result.status == "not_evaluated"
    assert all(f.status == "not_evaluated" for f in own(result))
    assert any("speeds.VD" in (f.reason or "") for f in own(result))


def test_capability_on_the_limit(yaw, tmp_path):
    """A fin root-shear capability declared equal to the largest |root shear| of the baseline run (limit) and
    1.5 × it (ultimate, §25.303): the critical margin is zero within rounding (the loads are reported in kN
    to 0.1, so the declared value is within 50 N); every other condition has a positive margin."""
    peak_kn = max(max(abs(v) for v in f.all_details()[ROOT_SHEAR]) for f in own(yaw))
    limit = peak_kn * 1e3
    structure = (
        "structure:\n  vertical_tail:\n"
        f'    - {{station: root, quantity: shear, limit: {limit}, ultimate: {1.5 * limit}, source: "test"}}\n'
        "sources:\n"
    )
    result = run_rule("25.351", tmp_path, edits=[NO_STRUCTURE, ("\nsources:\n", "\n" + structure)])
    margins = [f.margin for f in own(result) if f.margin is not None]
    assert len(margins) == len(own(yaw))
    assert min(margins) == pytest.approx(0.0, abs=0.05e3 * 1.5 + 1.0)
    assert all(m >= -0.05e3 * 1.5 - 1.0 for m in margins)
    worst = min(own(result), key=lambda f: f.margin)
    assert "root" in worst.check and "shear" in worst.check


def test_fin_root_torsion_arm_lies_within_the_root_chord(yaw, baseline):
    """Torsion about the 40 % chord line over shear is the lever arm of the fin load: it must lie within
    the fin's root chord (a regression guard: the strip force per circulation of a fin comes from a
    sideslip perturbation, not from α, which hardly loads a fin)."""
    from certkit.models.aero import planform

    fin = baseline.model.geometry.vertical_tail
    root_chord = float(planform.root_chord(2 * fin.area, 2 * fin.aspect_ratio, fin.taper))
    checked = 0
    for f in own(yaw):
        shear = f.all_details().get("root shear max/min (kN)")
        torsion = f.all_details().get("root torsion max/min (kN·m)")
        if shear and torsion and abs(shear[0]) > 50.0:
            assert abs(torsion[0] / shear[0]) < root_chord, (f.check, shear, torsion, root_chord)
            checked += 1
    assert checked > 0

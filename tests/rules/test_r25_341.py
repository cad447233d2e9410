"""§25.341(a) discrete gusts: F_g and U_ds by hand (ft, ft/s, the paragraph's units; formulas of FAA AC
25.341-1, unverified against the CFR: docs/regulation-notes.md §4), the two-phase gust simulation against
the closed-form quasi-steady heave solution, the sign of the wing load, the structural comparison with a
declared wing capability and the not-evaluated path. The rule runs on the baseline at sea level and the
ceiling with gradients 30 and 350 ft (criteria override) to stay fast.
"""

from types import SimpleNamespace

import numpy as np
import pytest
from certkit_rules.part25.subpart_c.r25_341 import DiscreteGust
from certkit_rules.part25.support.gust_runs import design_gust_velocity, flight_profile_alleviation

from certkit.atmosphere import density
from certkit.engine.registry import Criteria
from certkit.models.aero.derivative_model import StabilityDerivativeModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel
from certkit.models.loads.gust import gust_aero
from certkit.models.loads.gust_response import GustBatch, simulate_gust
from certkit.units import FT, G0

from ..loads.test_gust_response import MASS, A, S, V, closed_form
from .helpers import MACH_RANGE, NO_STRUCTURE, hand_margin, in_mach_range, own, run_rule

BEND_LIMIT = 25e6  # N·m, a wing root bending allowable near the baseline's gust loads
STRUCTURE = f"""structure:
  wing:
    - {{station: root, quantity: bending, limit: {BEND_LIMIT}, ultimate: {1.6 * BEND_LIMIT}, source: "test allowable"}}
criteria:
  "25.341(a)":
    justification: "two gradients keep the test fast"
    values: {{gradients: "30 350"}}
sources:
"""
FAST = [("altitude_points: 5", "altitude_points: 2"), NO_STRUCTURE, ("\nsources:\n", "\n" + STRUCTURE)]
#: the baseline with its declared capability (docs/baseline-sources.md §10), sea level and ceiling, 2 gradients
FAST_BASELINE = [
    ("altitude_points: 5", "altitude_points: 2"),
    ("\nsources:\n", "\ncriteria:\n" + STRUCTURE.split("criteria:\n", 1)[1]),
]


@pytest.fixture(scope="module")
def gust_run(tmp_path_factory):
    """(rule result, the rule's run record) on the baseline edited by FAST."""
    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context
    from certkit.engine.scheduler import criteria_for

    from ..conftest import BASELINE

    text = BASELINE.read_text()
    for old, new in FAST:
        text = text.replace(old, new)
    path = tmp_path_factory.mktemp("gust") / "gust.yaml"
    path.write_text(text)
    ctx = Context(load_aircraft(path))
    rule = DiscreteGust()  # as the scheduler does: evaluate, then the run is on the instance for evidence
    crit, _ = criteria_for(DiscreteGust, ctx)
    result = SimpleNamespace(findings=rule.evaluate(ctx, DiscreteGust.conditions.expand(ctx.aircraft), crit))
    return result, rule.run


@pytest.fixture(scope="module")
def gusts(gust_run):
    return gust_run[0]


def crit():
    return Criteria({k: c.value for k, c in DiscreteGust.criteria.items()})


def test_alleviation_factor_and_design_gust_by_hand(baseline):
    """R1 = 460,000/656,000 = 0.70122, R2 = 430,000/656,000 = 0.65549; F_gm = √(0.65549 tan(0.55074)) =
    √(0.65549 × 0.61412) = 0.63447; F_gz = 1 − 43,000/250,000 = 0.828; F_g(SL) = 0.73124; at 21,500 ft
    (half Z_mo) 0.86562; 1 at 43,000 ft. U_ds(SL, H = 100 ft) = 56 × 0.73124 × (100/350)^(1/6) =
    56 × 0.73124 × 0.81157 = 33.233 ft/s EAS. Tolerance 1e-4 (five-figure hand arithmetic)."""
    c = crit()
    assert flight_profile_alleviation(baseline.model, 0.0, c) == pytest.approx(0.73124, abs=1e-4)
    assert flight_profile_alleviation(baseline.model, 21_500 * FT, c) == pytest.approx(0.86562, abs=1e-4)
    assert flight_profile_alleviation(baseline.model, 43_000 * FT, c) == pytest.approx(1.0, abs=1e-12)
    uds = design_gust_velocity(56.0 * FT, 0.73124, 100 * FT, c) / FT
    assert uds == pytest.approx(33.233, abs=2e-3)
    assert design_gust_velocity(56.0 * FT, 1.0, 350 * FT, c) / FT == pytest.approx(56.0)


#: surfaces of negligible chord: Küssner's penetration lag vanishes (the quasi-steady limit of the gust lift)
QUASI_STEADY = (1e-9, 1e-9)


@pytest.mark.parametrize("H_ft", [30.0, 350.0])
def test_two_phase_heave_against_closed_form(H_ft):
    """The rule's gust simulation (gust phase at 2H/V / 200 steps, free phase after) on the heave-only model
    of tests/loads/test_gust_response.py, its surfaces of negligible chord (no penetration lag): Δn within 2 % of
    the peak of the closed-form quasi-steady solution
    while the gust acts; after it, the response decays (Δn → 0 within the settle time)."""
    ref = AeroReference(S, 60.0, 7.0, 30.0, 0.0)
    aero = gust_aero(
        StabilityDerivativeModel(ref, {"CL_alpha": A}),
        np.array([0.0, 1.0]),
        np.array([A, A]),
        np.zeros(2),
        np.zeros(2),
        np.zeros(2),
    )
    model = AircraftModel(aero, MASS, (30.0, 0.0, 0.0), np.diag([1e7, 1e7, 1e7]))
    qbar = 0.5 * density(0.0) * V**2
    alpha0 = MASS * G0 / (qbar * S * A)
    x0 = np.array([[0, 0, 0.0, V * np.cos(alpha0), 0, V * np.sin(alpha0), 0, 0, 0, 0, alpha0, 0]])
    H, Uds = H_ft * FT, 15.0
    run = simulate_gust(
        None,
        GustBatch(model, x0, np.zeros((1, 2)), np.array([V]), 0.0, QUASI_STEADY),
        H,
        Uds / V,
        200,
        2.0,
        surfaces=(),
    )
    tau = MASS * V / (qbar * S * A)
    t = run.sim.t
    during = t <= 2 * H / V
    dn = run.sim["n_z"][:, 0] - 1.0
    exact = closed_form(t, H, Uds, tau)
    peak = np.max(np.abs(exact[during]))
    assert np.max(np.abs(dn[during] - exact[during])) < 0.02 * peak
    assert abs(dn[-1]) < 0.05 * peak and t[-1] == pytest.approx(2 * H / V + 2.0, abs=run.dt + 1e-9)


def test_sign_up_gust_loads_the_wing_up(gust_run):
    """While the gust peaks at the wing (t = H/V) an up gust has raised the wing root shear and bending
    above their 1-g values and a down gust has lowered them (one condition, H = 30 and 350 ft, re-simulated
    through the rule's own run); peak n_z above 1 for up gusts, below for down gusts, in every finding.
    (After a long gust the rigid airplane overshoots the other way: the extremes of a condition need not
    come from the gust of the same sign.)"""
    result, run = gust_run
    conds = run.conditions
    i_up = next(i for i, c in enumerate(conds) if c.get("gust") == "up")
    i_down = next(
        i
        for i, c in enumerate(conds)
        if c.get("gust") == "down"
        and c.loading == conds[i_up].loading
        and c.altitude == conds[i_up].altitude
        and c.get("speed_point") == conds[i_up].get("speed_point")
    )
    for i, sign in ((i_up, 1.0), (i_down, -1.0)):
        for j, H in enumerate(run.gradients):
            ((_, _, r),) = run.replay([(i, j)])
            k = int(np.argmin(np.abs(r.sim.t - H / r.sim["V"][0, 0])))
            wing = r.loads["wing"][:, 0]
            assert sign * (wing[k, 0, 0] - wing[0, 0, 0]) > 0 and sign * (wing[k, 1, 0] - wing[0, 1, 0]) > 0
    wing = [f for f in own(result) if ", wing" in f.check and f.all_details()]
    assert all(f.all_details()["peak_n_z"] > 1.0 for f in wing if f.condition.get("gust") == "up")
    assert all(f.all_details()["peak_n_z"] < 1.0 for f in wing if f.condition.get("gust") == "down")


def test_capability_comparison_and_reasons(gusts):
    """Wing findings are compared with the declared root bending (limit 25 MN·m, ultimate 40 MN·m, so the
    normalised limit margin is the smaller and is reported): margin = 25 MN·m − the
    largest |root bending| of the condition (details rounded to 0.1 kN·m). The tailplane has no declared
    capability: not evaluated with the reason. Every condition flies: the heavy corners at VB at 43,000 ft, short of
    thrust level, on the full-thrust path (a shallow descent), marked with its flight-path angle."""
    assert all(f.all_details() for f in own(gusts))
    descending = {f.condition for f in own(gusts) if f.condition.get("flight_path_deg") is not None}
    assert descending and all(-3.0 < c.get("flight_path_deg") < 0.0 for c in descending)
    for f in in_mach_range(own(gusts)):
        if "horizontal tail" in f.check or "vertical tail" in f.check:  # the fin: lateral gusts
            assert f.status == "not_evaluated" and f.reason == "no structural capability declared"
        else:
            hi, lo = f.all_details()["root bending max/min (kN·m)"]
            expected = BEND_LIMIT - 1e3 * max(abs(hi), abs(lo))
            assert f.margin == pytest.approx(expected, abs=200.0)
            assert f.status == ("complies" if f.margin >= 0 else "fails")
            assert "limit bending at root" in f.check
            assert 0.0 <= f.all_details()["F_g"] <= 1.0
            assert f.all_details()["critical_H_root_bending_ft"] in (30.0, 350.0)


def test_not_evaluated_without_vc(tmp_path):
    r = run_rule("25.341(a)", tmp_path, [("  VC: 272 kn EAS", "  # VC removed")])
    assert r.status == "not_evaluated" and "speeds.VC" in own(r)[0].reason


def test_baseline_margins_against_the_declared_capability(tmp_path):
    """The baseline's declared wing and tailplane capability (docs/baseline-sources.md §10; wing root
    bending limit 49,896 kN·m up / 47,230 down, ultimate 60,434 / 47,230; tailplane CFRP, limit = ultimate):
    every evaluated finding's normalised margin recomputed by hand from its reported loads (0.1 kN rounding:
    5e-5). Gusts are the wing's design case here: its critical check is limit or ultimate bending."""
    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context
    from certkit.models.loads.capability import declared_capabilities

    from ..conftest import BASELINE

    result = run_rule("25.341(a)", tmp_path, FAST_BASELINE)
    ctx = Context(load_aircraft(BASELINE))
    caps = {
        "wing": declared_capabilities(ctx, "wing"),
        "horizontal tail": declared_capabilities(ctx, "horizontal_tail"),
        "vertical tail": declared_capabilities(ctx, "vertical_tail"),
    }
    evaluated = [f for f in own(result) if f.status != "not_evaluated" and f.margin is not None]
    assert evaluated and all(
        "no trim" in f.reason or MACH_RANGE in f.reason for f in own(result) if f.status == "not_evaluated"
    )
    for f in evaluated:
        surface = (
            "wing"
            if f.check.endswith(", wing") or ", wing:" in f.check
            else "vertical tail"
            if "vertical tail" in f.check
            else "horizontal tail"
        )
        normalized, margin, check = hand_margin(f.all_details(), caps[surface])
        assert f.normalized_margin == pytest.approx(normalized, abs=5e-5), f.check
        # information: the manoeuvring envelope's n at the speed (§25.337: n+ 2.5; n- -1.0 to VC, 0 at VD)
        d = f.all_details()
        if f.condition.get("gust") == "up":
            assert d["maneuver_envelope_n_z"] == 2.5 and d["beyond_maneuver_envelope"] == (d["peak_n_z"] > 2.5)
        elif f.condition.get("gust") == "down":
            assert -1.0 <= d["maneuver_envelope_n_z"] <= 0.0
            assert d["beyond_maneuver_envelope"] == (d["peak_n_z"] < d["maneuver_envelope_n_z"])
            if f.condition.get("speed_point") == "VD":
                assert d["maneuver_envelope_n_z"] == pytest.approx(0.0, abs=1e-4)
    wing = min((f for f in evaluated if ", wing:" in f.check), key=lambda f: f.normalized_margin)
    assert "bending" in wing.check and wing.status == "complies"


def test_wing_findings_name_the_critical_fuel_state(gusts):
    """The wing in the §25.343 fuel states (aircraft/lta.yaml: mains filled first, used last): at MRW the mains are
    full in every state (64,050 lb a side); at MLW (460,000 lb: 30,000–155,500 lb of fuel) the up-bending check (max)
    is critical with the least wing fuel, 15,000 lb a side (smallest inertia relief), a down-bending one (min) with the
    most (64,050 lb)."""
    lb = 0.45359237
    wing = [
        f
        for f in in_mach_range(own(gusts))
        if f.check.split(":")[0].endswith(", wing") and f.status in ("complies", "fails")
    ]
    assert wing and all("fuel_state" in f.all_details() for f in wing)
    assert any(f.condition.loading in ("fwd_mlw", "aft_mlw") for f in wing)
    for f in wing:
        main = f.all_details()["fuel_kg"]["right main"]
        if f.condition.loading == "fwd_mrw":
            assert main == pytest.approx(64050 * lb, abs=1)
        if f.condition.loading in ("fwd_mlw", "aft_mlw"):
            assert main == pytest.approx((15000 if "(max)" in f.check else 64050) * lb, abs=1), f.check

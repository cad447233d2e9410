"""Control-force model (:mod:`certkit.models.control_force`), its aircraft-file section and the rules it feeds.

Hand calculations are in pounds, feet, inches and degrees, independent of certkit's SI path:
ρ₀ = 0.0023769 slug/ft³, 1 lbf = 4.4482216 N, 1 ft = 0.3048 m, 1 in = 0.0254 m, 1 kPa = 20.885434 lb/ft².
The reversible case uses Nelson's stick-force relation (*Flight Stability and Automatic Control*, 2nd ed.,
ch. 2: F = G η q S_e c_e C_h, C_h = Ch_0 + Ch_α α_t + Ch_δ δ) with hand-picked numbers of a light-transport
elevator (not a worked example of the book, whose numbers were not available here).
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from certkit.aircraft import load_aircraft
from certkit.aircraft.model import ControlForces
from certkit.engine.context import Context
from certkit.engine.registry import discover, select
from certkit.engine.results import Condition
from certkit.engine.scheduler import criteria_for
from certkit.errors import InputError
from certkit.models.control_force import control_force_model, downwash_gradient, local_angle, stick_free_neutral_point
from certkit.units import LBF

from .helpers import NO_CONTROL_FORCES, control_forces_edit, edited_baseline, own, run_rule

RHO0_SLUG = 0.0023769
PSF_PER_KPA = 20.885434

#: a reversible elevator with friction (for §25.173) and a q-feel rudder (for §§25.147, 25.149, 25.351)
FORCES = """control_forces:
  source: test values (not the 777's)
  elevator:
    type: reversible
    hinge_moment: {Ch_0: 0.0, Ch_alpha: -0.10, Ch_delta: -0.25}
    chord: 4.5 ft
    area: 280 ft^2
    gearing: 1.0 deg/in
    hinge_moment_fraction: 0.02
    friction: 3 lbf
  rudder:
    type: artificial_feel
    preload: 10 lbf
    gradient: 40 lbf/in
    gearing: 6 deg/in
    q_feel_reference: 10 kPa
"""
#: an artificial-feel elevator (for §25.331(c))
ELEVATOR_FEEL = """control_forces:
  elevator:
    type: artificial_feel
    preload: 5 lbf
    gradient: 30 lbf/in
    gearing: 2 deg/in
    q_feel_reference: 10 kPa
"""


def _section(**controls):
    return SimpleNamespace(control_forces=ControlForces.model_validate(controls), geometry=None)


@pytest.fixture(scope="module")
def forces_ctx(tmp_path_factory):
    return Context(load_aircraft(edited_baseline(tmp_path_factory.mktemp("cf"), [control_forces_edit(FORCES)])))


@pytest.fixture(scope="module")
def feel_ctx(tmp_path_factory):
    return Context(
        load_aircraft(edited_baseline(tmp_path_factory.mktemp("feel"), [control_forces_edit(ELEVATOR_FEEL)]))
    )


def _rule(rule_id):
    (rule,) = [r for r in select(discover(), (rule_id,)) if r.id == rule_id]
    return rule


def _evaluate(rule_id, ctx, pick):
    """Evaluate one rule on the scheduled conditions that ``pick`` keeps (a fast subset)."""
    rule = _rule(rule_id)
    crit, _ = criteria_for(rule, ctx)
    conds = [c for c in rule.conditions.expand(ctx.aircraft) if pick(c)]
    return rule().evaluate(ctx, conds, crit), crit


# --------------------------------------------------------------------------- the model


def test_reversible_stick_force_hand_calculation():
    """F = −G f η q S_e c_e C_h at 200 ft/s sea level: S_e 35 ft², c_e 1.5 ft, G 0.6 rad/ft, f 1, η 0.9;
    Ch_α −0.1, Ch_δ −0.25 /rad, α_t 2°, δ −5°: C_h = 0.018326, q = 47.538 lb/ft², F = −24.70 lb (a pull of
    24.70 lb holds the trailing edge 5° up). Tolerance 1e-4 (unit constants)."""
    ac = _section(
        elevator={
            "type": "reversible",
            "hinge_moment": {"Ch_alpha": -0.1, "Ch_delta": -0.25},
            "chord": "1.5 ft",
            "area": "35 ft^2",
            "gearing": "0.6 rad/ft",
            "dynamic_pressure_ratio": 0.9,
        }
    )
    m = control_force_model(ac, "elevator")
    ch = -0.1 * math.radians(2) - 0.25 * math.radians(-5)
    q_psf = 0.5 * RHO0_SLUG * 200.0**2
    f_lb = -0.6 * 1.0 * 0.9 * q_psf * 35 * 1.5 * ch
    assert ch == pytest.approx(0.018326, abs=1e-6) and f_lb == pytest.approx(-24.70, abs=0.005)
    q_si = 0.5 * 1.225 * (200 * 0.3048) ** 2
    force = m.force(q_si, math.radians(2), math.radians(-5)) / LBF
    assert force == pytest.approx(f_lb, rel=1e-4)
    # the inverse gives the deflection back, and trimmed at that state the force is zero
    assert m.deflection_at_force(force * LBF, q_si, math.radians(2)) == pytest.approx(math.radians(-5), rel=1e-9)
    assert m.force(q_si, math.radians(2), math.radians(-5), trim=(math.radians(-5), math.radians(2))) == pytest.approx(
        0.0, abs=1e-9
    )
    # a 4:1 boost (pilot share 1/5) divides the force by 5; the span form (area = span × chord) is the same surface
    boosted = control_force_model(
        _section(
            elevator={
                "type": "reversible",
                "hinge_moment": {"Ch_alpha": -0.1, "Ch_delta": -0.25},
                "chord": "1.5 ft",
                "span": "23.333333 ft",
                "gearing": "0.6 rad/ft",
                "dynamic_pressure_ratio": 0.9,
                "hinge_moment_fraction": 0.2,
            }
        ),
        "elevator",
    )
    assert boosted.force(q_si, math.radians(2), math.radians(-5)) / LBF == pytest.approx(f_lb / 5, rel=1e-5)


def test_artificial_feel_and_wheel_hand_calculation():
    """Feel: F = 5 + 30 lbf/in × (15/10 q-feel) × 5 in = 230 lbf for 10° of elevator at 2°/in, q = 15 kPa.
    Aileron wheel (reversible pair): rim force = −(dδ/dθ)/(D/2) · q S c · 2 Ch_δ δ; D = 16 in, 0.5 rad/rad,
    S 20 ft², c 2 ft, Ch_δ −0.3, δ 10°, q = 100 lb/ft² → 2 × 0.3 × 0.17453 × 100 × 20 × 2 × 0.5/(8/12) = 62.83 lb."""
    ac = _section(
        elevator={
            "type": "artificial_feel",
            "preload": "5 lbf",
            "gradient": "30 lbf/in",
            "gearing": "2 deg/in",
            "q_feel_reference": "10 kPa",
        },
        aileron={
            "type": "reversible",
            "hinge_moment": {"Ch_0": 0.01, "Ch_alpha": -0.2, "Ch_delta": -0.3},
            "chord": "2 ft",
            "area": "20 ft^2",
            "wheel_gearing": 0.5,
            "wheel_diameter": "16 in",
        },
    )
    feel = control_force_model(ac, "elevator")
    assert feel.force(15e3, 0.3, math.radians(-10)) / LBF == pytest.approx(-(5 + 30 * 1.5 * 5), rel=1e-9)
    assert feel.force(15e3, 0.3, math.radians(2), trim=(math.radians(2), 0.0)) == 0.0
    d = feel.deflection_at_force(-230 * LBF, 15e3, 0.0, trim=(math.radians(1), 0.0))
    assert math.degrees(d) == pytest.approx(1 - 10, rel=1e-9)
    assert feel.deflection_at_force(3 * LBF, 15e3, 0.0) == 0.0  # inside the breakout band
    wheel = control_force_model(ac, "aileron")
    q_si = 100 / PSF_PER_KPA * 1e3
    rim = wheel.force(q_si, np.array([0.0, 0.2]), math.radians(10)) / LBF  # α cancels in the pair
    assert rim == pytest.approx(2 * 0.3 * math.radians(10) * 100 * 20 * 2 * 0.5 / (8 / 12), rel=1e-4)
    assert rim[0] == pytest.approx(rim[1], rel=1e-12)


def test_local_angles():
    """Tailplane α(1 − dε/dα) + i_t − ε₀ with the declared dε/dα; fin −β(1 − dσ/dβ)."""
    ac = _section(
        elevator={
            "type": "reversible",
            "hinge_moment": {"Ch_alpha": -0.1, "Ch_delta": -0.25},
            "chord": "1 m",
            "area": "2 m^2",
            "gearing": "1 rad/m",
            "downwash_gradient": 0.4,
            "downwash_at_zero_alpha": "1 deg",
        },
        rudder={
            "type": "reversible",
            "hinge_moment": {"Ch_alpha": -0.1, "Ch_delta": -0.25},
            "chord": "1 m",
            "area": "2 m^2",
            "gearing": "1 rad/m",
            "downwash_gradient": 0.2,
        },
    )
    ac.geometry = SimpleNamespace(horizontal_tail=SimpleNamespace(incidence=math.radians(-2)), wing=None)
    assert local_angle(ac, "elevator", 0.1, 0.0, 0.5) == pytest.approx(0.06 - math.radians(3), rel=1e-12)
    assert local_angle(ac, "rudder", 0.1, 0.05, 0.5) == pytest.approx(-0.04, rel=1e-12)


def test_stick_force_gradient_sign_and_zero_at_the_stick_free_neutral_point(forces_ctx):
    """Clean, sea level, 150 m/s CAS, 200 t: the average gradient (pull at 0.95 V − pull at 1.05 V)/0.1 V is
    positive (a pull below the trim speed) ahead of the stick-free neutral point, negative behind it, and
    crosses zero within 2.5 % MAC of x_np′ = x_ref − c̄ Cm_α′/CL_α′ (the textbook formula omits the thrust
    line and the Mach change over ±5 %)."""
    from certkit_rules.part25.subpart_b.r25_171 import stick_force_curves

    from certkit.engine.conditions import speed_as

    ctx = forces_ctx
    model = ctx.aero("clean").model
    chord = model.reference.chord
    base = Condition(
        loading="test", mass=200_000.0, x_cg=30.0, configuration="clean", altitude=0.0, speed=150.0, speed_kind="CAS"
    )
    mach = speed_as(base, "MACH")
    elevator = control_force_model(ctx.aircraft, "elevator")
    x_np = float(stick_free_neutral_point(model, elevator, mach, downwash_gradient(ctx.aircraft, mach)))
    x_fixed = model.reference.x_ref - chord * float(
        model.derivative("Cm_alpha", mach) / model.derivative("CL_alpha", mach)
    )
    assert x_np < x_fixed  # a floating elevator (Ch_α < 0) moves the neutral point forward
    xs = x_np + chord * np.array([-0.10, -0.02, 0.02])
    curves = stick_force_curves(ctx, [base.with_(x_cg=float(x)) for x in xs], 0.05)
    grad = np.array([r["gradient"] for _, r in curves])
    pull_low = np.array([r["pull_low"] for _, r in curves])
    assert grad[0] > 0 and pull_low[0] > 0  # stable: a pull holds the lower speed
    assert grad[2] < 0
    zero = xs[1] - grad[1] * (xs[2] - xs[1]) / (grad[2] - grad[1])
    assert abs(zero - x_np) / chord < 0.025
    # the gradient is proportional to the distance from the neutral point (linear in x_cg within 10 %)
    slope = (grad[1] - grad[2]) / (xs[2] - xs[1])
    assert grad[0] == pytest.approx(slope * (zero - xs[0]), rel=0.10)


# --------------------------------------------------------------------------- the aircraft-file section


@pytest.mark.parametrize(
    "block, path, message",
    [
        (
            "  elevator:\n    type: reversible\n    hinge_moment: {Ch_alpha: -0.1, Ch_delta: 0.25}\n    chord: 1 m\n"
            "    area: 2 m^2\n    gearing: 1 rad/m\n",
            "control_forces.elevator.hinge_moment.Ch_delta",
            "less than 0",
        ),
        (
            "  rudder:\n    type: artificial_feel\n    gradient: 30 lbf\n    gearing: 2 deg/in\n",
            "control_forces.rudder.gradient",
            "not a stiffness",
        ),
        (
            "  elevator:\n    type: artificial_feel\n    gradient: 30 lbf/in\n",
            "control_forces.elevator",
            "needs gearing",
        ),
        (
            "  elevator:\n    type: reversible\n    hinge_moment: {Ch_alpha: -0.1, Ch_delta: -0.25}\n    chord: 1 m\n"
            "    gearing: 1 rad/m\n    gradient: 30 lbf/in\n",
            "control_forces.elevator",
            "gradient belongs to type artificial_feel",
        ),
        (
            "  aileron:\n    type: springy\n    gearing: 1 rad/m\n",
            "control_forces.aileron.type",
            "'reversible' or 'artificial_feel'",
        ),
    ],
)
def test_schema_errors_name_the_path_and_line(tmp_path, block, path, message):
    edit = control_forces_edit("control_forces:\n" + block)
    with pytest.raises(InputError) as err:
        load_aircraft(edited_baseline(tmp_path, [edit]))
    (problem,) = [p for p in err.value.problems if p.path == path]
    assert message in problem.message
    lines = edited_baseline(tmp_path, [edit]).read_text().splitlines()
    # a field's error points at its line; a whole-control error at the control's mapping (its key or first entry)
    key = path.split(".")[-1]
    assert problem.line is not None and (key in lines[problem.line - 1] or key in lines[problem.line - 2])


def test_the_baseline_rudder_feel_is_the_777_amm_s(baseline):
    """The baseline's pedal feel reproduces the 777 AMM 27-21-00 feel and centering mechanism (D633W101-BEJ, p. 24):
    19.5 lb at breakout, 50 lb at full pedal (full rudder, 27.3°), at any speed (springs, not q-feel); to 0.01 lbf.
    The column and wheel feel of the 777 are not public: no elevator or aileron model is declared."""
    rudder = control_force_model(baseline.model, "rudder")
    assert rudder.kind == "artificial_feel" and rudder.q_reference is None
    stop = math.radians(27.3)
    just_moved = rudder.force(5e3, 0.0, 1e-9) / LBF
    full = rudder.force(np.array([5e3, 30e3]), 0.0, stop) / LBF
    assert just_moved == pytest.approx(19.5, abs=0.01)
    assert full == pytest.approx([50.0, 50.0], abs=0.01)
    assert rudder.force(5e3, 0.0, -stop) / LBF == pytest.approx(-50.0, abs=0.01)
    assert baseline.model.control_forces.elevator is None and baseline.model.control_forces.aileron is None


def test_the_baseline_pedal_forces_lie_inside_the_published_feel(ctx):
    """§25.147(a), §25.149(d) and §25.149(h)(1) (at VMCL, approach and landing flaps) on the baseline are computed from
    the AMM feel: each pedal force lies between the breakout (19.5 lbf) and the full-pedal force (50 lbf), so all
    comply with their 150 lbf limits."""
    findings, _ = _evaluate("25.147(a)", ctx, lambda c: True)
    findings += _evaluate("25.149", ctx, lambda c: c.get("inoperative") == "left")[0]
    pedal = [f for f in findings if "force" in f.check and "rudder" in f.check]
    assert len(pedal) >= 6 and sum("VMCL" in f.check for f in pedal) == 4  # VMCL: 2 configurations × 2 engines
    for f in pedal:
        assert f.status == "complies" and f.unit == "lbf" and f.limit == 150.0
        assert 19.5 < f.value < 50.0


# --------------------------------------------------------------------------- the rules


def test_stick_force_gradient_rule(forces_ctx):
    """§25.173(c): each finding's value is (pull at 0.95 V − pull at 1.05 V)/(0.1 V in kt) of its details, the
    limit 1 lbf / 6 kt; the clean 1.3 VSR trims at the forward CG are stable."""
    findings, crit = _evaluate("25.173(c)", forces_ctx, lambda c: c.altitude == 0.0 and c.configuration == "clean")
    done = [f for f in findings if f.margin is not None]
    assert done and all(f.unit == "lbf/kt" for f in done)
    for f in done:
        dv = 0.1 * f.condition.speed / (1852 / 3600)
        assert f.value == pytest.approx(
            (f.details["pull_force_low_speed_lbf"] - f.details["pull_force_high_speed_lbf"]) / dv, abs=2e-3
        )
        assert f.limit == pytest.approx(1 / 6)
    fwd = [f for f in done if f.condition.loading.startswith("fwd")]
    assert all(f.value > 0 for f in fwd)


def test_free_return_rule(forces_ctx):
    """§25.173(b): band = friction / (gradient × V_trim) with the 3 lbf friction; 7.5 % clean (cruise), 10 % flaps."""
    findings, _ = _evaluate("25.173(b)", forces_ctx, lambda c: c.altitude == 0.0 and c.loading.startswith("fwd"))
    done = [f for f in findings if f.margin is not None]
    assert done
    for f in done:
        v_kt = f.condition.speed / (1852 / 3600)
        assert f.value == pytest.approx(min(3.0 / (f.details["gradient_lbf_per_kt"] * v_kt), 1.0), rel=1e-3)
        assert f.limit == (0.075 if f.condition.configuration == "clean" else 0.10)


def test_configuration_change_force_rule(forces_ctx):
    """§25.145(b): one force finding per manoeuvre and corner (lbf, limit 50) beside each elevator-change finding."""
    findings, _ = _evaluate("25.145(b)", forces_ctx, lambda c: c.loading == "fwd_mlw")
    force = [f for f in findings if "control force" in f.check]
    change = [f for f in findings if "elevator change" in f.check]
    assert len(force) == len(change) > 0
    assert all(f.unit == "lbf" and f.limit == 50.0 for f in force)
    assert all(
        f.value == pytest.approx(abs(f.details["pull_force_lbf"]), abs=0.006) for f in force if f.margin is not None
    )
    # extending the flaps at idle (b)(1) needs a pull at the forward CG with this elevator (speed lower, nose-down
    # flaps)
    ext = [f for f in force if f.check.startswith("(b)(1)") and f.margin is not None]
    assert ext and all(f.details["pull_force_lbf"] > 0 for f in ext)


def _feel_pedal_lbf(rudder_deg, v_eas):
    """40 lbf/in × (q/10 kPa) × |δ|/(6°/in) + 10 lbf breakout."""
    q_kpa = 0.5 * 1.225 * v_eas**2 / 1e3
    return 10 + 40 * q_kpa / 10 * abs(rudder_deg) / 6


def test_oei_directional_pedal_force_rule(forces_ctx):
    """§25.147(a): the pedal force holding the wings-level OEI trim's rudder, hand-checked from the q-feel law at
    the trim speed (sea level, so CAS = EAS)."""
    findings, _ = _evaluate("25.147(a)", forces_ctx, lambda c: True)
    pedal = [f for f in findings if f.check.startswith("(a) rudder pedal force")]
    assert len(pedal) == 3 and all(f.margin is not None and f.unit == "lbf" and f.limit == 150.0 for f in pedal)
    for f in pedal:
        assert f.value == pytest.approx(_feel_pedal_lbf(f.details["rudder_deg"], f.condition.speed), rel=1e-3)


def test_vmca_rudder_force_rule(forces_ctx):
    """§25.149(d): the pedal force at the computed VMCA against 150 lbf, one per inoperative engine."""
    findings, _ = _evaluate("25.149", forces_ctx, lambda c: c.get("inoperative") == "left")
    (d,) = [f for f in findings if f.check.startswith("(d)")]
    assert d.unit == "lbf" and d.limit == 150.0 and d.margin is not None
    grid = [g for g in d.details["pedal_force_grid_lbf"] if g is not None]
    assert min(grid) - 0.2 <= d.value <= max(grid) + 0.2


def test_force_limited_deflections_of_the_loads_rules(forces_ctx, feel_ctx):
    """§25.351(a)(2) and §25.331(c) (pilot effort, §25.397): the deflection a force holds from the trim.
    Rudder at VD 340 KEAS (174.9 m/s), 200 lbf: x = (200 − 10)/(40 × 1.8736) in = 2.535 in → 15.21°.
    Elevator at 265 KEAS (136.3 m/s), 300 lbf pull: x = (300 − 5)/(30 × 1.1379) = 8.642 in → 17.28° up."""
    from certkit_rules.part25.support.structural_checks import force_limited_deflection

    c = Condition(speed=174.9, speed_kind="EAS", altitude=0.0)
    stop = math.radians(-23.2)
    defl, limited = force_limited_deflection(forces_ctx, "rudder", [c], [0.0], stop, 200.0)
    expected = (200 - 10) / (40 * 0.5 * 1.225 * 174.9**2 / 1e4) * 6
    assert math.degrees(defl[0]) == pytest.approx(-expected, rel=1e-6) and limited[0]
    assert expected == pytest.approx(15.21, abs=0.01)
    slow = Condition(speed=67.0, speed_kind="EAS", altitude=0.0)
    defl, limited = force_limited_deflection(forces_ctx, "rudder", [slow], [0.0], stop, 300.0)
    assert defl[0] == stop and not limited[0]  # the stop comes first at low speed
    up = Condition(speed=136.3, speed_kind="EAS", altitude=3000.0)
    defl, limited = force_limited_deflection(
        feel_ctx, "elevator", [up], [math.radians(1.0)], math.radians(-21.8), 300.0
    )
    step = (300 - 5) / (30 * 0.5 * 1.225 * 136.3**2 / 1e4) * 2
    assert math.degrees(defl[0]) == pytest.approx(1.0 - step, rel=1e-6) and limited[0]
    # without a model the stop is returned, flagged as not force-limited (None)
    defl, limited = force_limited_deflection(forces_ctx, "aileron", [c], [0.0], 0.3, 100.0)
    assert defl[0] == 0.3 and limited is None


def test_loads_rules_use_the_pilot_effort(feel_ctx):
    """§25.331(c)(1) at the forward light corner, sea level: the elevator step is the 300 lbf one at VA 269 KEAS (the
    schedule's sea-level value; 138.386 m/s, q = 11,730 Pa): x = (300 − 5)/(30 × 1.17296) = 8.383 in → 16.77° up, and
    the finding says so."""
    findings, _ = _evaluate("25.331(c)(1)", feel_ctx, lambda c: c.loading == "fwd_light" and c.altitude == 0.0)
    (f,) = [f for f in findings if ", wing" not in f.check]  # the tail's finding (the wing's has no elevator details)
    assert f.details["elevator_step_deg"] == pytest.approx(-16.77, abs=0.01)
    assert "pilot effort" in f.details["pilot_effort"]


@pytest.mark.parametrize(
    "rule_id, check, reason",
    [
        ("25.173(c)", "(c) stick-force gradient", "control_forces.elevator"),
        ("25.173(b)", "(b) free return", "control_forces.elevator"),
    ],
)
def test_not_evaluated_without_a_model(rule_id, check, reason):
    r = run_rule(rule_id)
    assert r.status == "not_evaluated"
    assert all(f.check.startswith(check) and reason in f.reason for f in own(r))


def test_force_parts_not_evaluated_without_a_model(tmp_path):
    """Without control_forces: §25.145(b), §25.147(a) and §25.149(d) keep their force parts not evaluated, naming
    the missing section; §25.173(b) needs the friction too."""
    ctx = Context(load_aircraft(edited_baseline(tmp_path, [NO_CONTROL_FORCES])))
    findings, _ = _evaluate("25.145(b)", ctx, lambda c: c.loading == "fwd_mlw")
    assert [f.reason for f in findings if "control force" in f.check] and all(
        f.status == "not_evaluated" and "control_forces.elevator" in f.reason
        for f in findings
        if "control force" in f.check
    )
    findings, _ = _evaluate("25.147(a)", ctx, lambda c: True)
    pedal = [f for f in findings if "pedal force" in f.check]
    assert len(pedal) == 3 and all(f.status == "not_evaluated" and "control_forces.rudder" in f.reason for f in pedal)
    findings, _ = _evaluate("25.149", ctx, lambda c: c.get("inoperative") == "left")
    (d,) = [f for f in findings if f.check.startswith("(d)")]
    assert d.status == "not_evaluated" and "control_forces.rudder" in d.reason


def test_free_return_needs_friction(tmp_path):
    r = run_rule("25.173(b)", tmp_path, edits=[control_forces_edit(FORCES.replace("    friction: 3 lbf\n", ""))])
    assert r.status == "not_evaluated" and "friction" in own(r)[0].reason


def test_a_force_model_needs_its_control_surface(tmp_path):
    """A force model of a control the geometry does not declare is an input error at the control's line."""
    edits = [
        control_forces_edit(ELEVATOR_FEEL),
        ("      elevator:\n        span_start: 0.07", "      elevatorx:\n        span_start: 0.07"),
    ]
    with pytest.raises(InputError) as err:
        load_aircraft(edited_baseline(tmp_path, edits))
    (problem,) = [p for p in err.value.problems if p.path == "control_forces.elevator"]
    assert "no control surface named 'elevator' on geometry.horizontal_tail" in problem.message and problem.line

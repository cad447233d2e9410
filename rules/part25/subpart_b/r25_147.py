"""§25.147 Directional and lateral control, one engine inoperative: (a) and (c) as two rules.

What a steady-trim model can show is that the controls hold the airplane in the steady condition the
paragraph starts from or manoeuvres to:

* (a) directional control — the approach configuration at MLW and 1.3 VSR1, the critical engine
  inoperative (windmilling), wings level, straight flight (``ctx.trim(kind="oei")``: bank given, sideslip,
  α, the three controls and the throttle solved for) at the power for level flight (γ = 0); where that
  power is more than maximum continuous, the trim is flown at maximum continuous thrust on the flight path
  it gives (:func:`certkit_rules.part25.support.thrust_trims.trim_at_thrust`, Anderson, *Aircraft Performance and
  Design*, 1999, eq. 5.12).
  The reasonably sudden 15° heading change is a dynamic manoeuvre: a not-evaluated finding. The 150 lbf rudder
  pedal force is read in the steady wings-level condition the heading change starts from: the pedal force that
  holds the trim's rudder with the rudder trim at neutral (:mod:`certkit.models.control_force`), which must leave
  room under 150 lbf; without ``control_forces.rudder`` it is not evaluated.
* (c) lateral control — 20° banked coordinated turns (zero sideslip, ``kind="turn"``) toward and away from
  the inoperative engine at 1.3 VSR1 and MTOW, the operating engine at maximum continuous thrust, in the most
  favourable climb configuration (flaps up), on the flight path that thrust gives
  (:func:`certkit_rules.part25.support.thrust_trims.trim_at_thrust`).

The margin of each finding is a control's design limit on the side it is deflected minus |deflection|
(deg, :func:`control_findings`). (b) and (e) apply to airplanes with four or more engines; (d) (roll
capability) is a handling quality with no steady-trim measure.
"""

from __future__ import annotations

import math

import numpy as np
from certkit_rules.part25.support.climb_checks import CGS
from certkit_rules.part25.support.control_checks import control_findings, pedal_force_finding, trim_details
from certkit_rules.part25.support.reference_speeds import reference_stall_speed
from certkit_rules.part25.support.thrust_trims import critical_engine, operating_thrust, trim_at_thrust
from certkit_rules.part25.support.turns import turn_details

from certkit.engine.conditions import Altitudes, ConditionSpace, DesignWeight
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model
from certkit.models.flight import control_limits

SOURCE = "14 CFR 25.147 (Amdt. 25-108; verified, docs/regulation-notes.md)"
AMDT = "25-108"
_MCT = Criterion(
    0.96,
    "",
    "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf at SL static",
    "maximum continuous over takeoff thrust of the engine model (as in 25.121(c))",
)


def _speed_criterion(paragraph: str) -> Criterion:
    return Criterion(1.3, "", f"{SOURCE} ({paragraph})", "speed, multiple of VSR1 of the configuration")


def _space(weight: str, configuration: str, note: str) -> ConditionSpace:
    """``weight`` at the forward, reference and aft CG, one configuration, sea level."""
    return ConditionSpace(
        loading=DesignWeight(weight, cgs=CGS),
        configurations=(configuration,),
        altitudes=Altitudes((0.0,)),
        note=f"{weight} at the forward, reference and aft CG; {note}",
    )


def _speed(ctx, conds):
    """1.3 VSR1 (m/s CAS at sea level) of each condition, its source, or (None, reason)."""
    try:
        vsr = [reference_stall_speed(ctx, c.configuration, c.mass) for c in conds]
    except ValueError as exc:
        return None, str(exc)
    return vsr, ""


def _engines(ctx):
    return len(ctx.aircraft.propulsion.engines)


def _refine(ctx, conds, crit, dead, thrust):
    vsr, why = _speed(ctx, conds)
    if vsr is None:
        return None, why
    return [
        c.with_(
            speed=crit.speed_over_vsr * v,
            speed_kind="CAS",
            speed_name=f"{crit.speed_over_vsr:g} VSR1",
            altitude=0.0,
            thrust=f"critical engine ({dead}) inoperative, {thrust}",
        )
        for c, (v, s) in zip(conds, vsr)
    ], ""


@rule
class DirectionalControlOEI(Rule):
    id = "25.147(a)"
    symbol = "directional-control-oei"
    title = "Directional control, one engine inoperative: yaw into the operating engine, wings level"
    amendment = AMDT
    requirement = """
        It must be possible, with the wings level, to yaw into the operative engine and to safely make a reasonably
        sudden change in heading of up to 15° in the direction of the critical inoperative engine, at 1.3 VSR1
        (except that the heading change at which the rudder pedal force is 150 lbf need not be exceeded), with the
        power for level flight at 1.3 VSR1 but not more than maximum continuous power, the gear retracted, flaps
        in the approach position and maximum landing weight. certkit checks that straight, wings-level flight with
        the critical engine inoperative trims with the rudder, aileron and elevator within their design limits.
        (b), for airplanes with four or more engines (two critical engines inoperative), is not applicable to a
        twin.
    """
    margin = """Each control's design limit on the side it is deflected − |deflection| (deg), at each CG; with
        control_forces.rudder, 150 lbf − |pedal force holding the wings-level trim, rudder trim neutral| (lbf)."""
    references = ("25.103", "25.121", "25.149")
    requires = ("mass.MLW", "configurations.approach")
    criteria = {
        "speed_over_vsr": _speed_criterion("a"),
        "pedal_force_lbf": Criterion(
            150.0, "lbf", SOURCE + " (a)", "rudder pedal force at which the heading change may stop"
        ),
        "mct_over_takeoff_thrust": _MCT,
    }
    conditions = _space(
        "MLW",
        "approach",
        "flaps approach, gear up; sea level; wings level; power for level flight, at most maximum continuous",
    )
    implementation = "partial"
    limitations = """
        Steady straight flight only: the 15° heading change (dynamic) is reported not evaluated; the 150 lbf is
        compared with the steady pedal force of the wings-level trim (rudder trim neutral), not the force during the
        heading change, and needs control_forces.rudder. The critical engine windmills (flight model drag); a movable
        stabiliser
        trims (elevator at its trim setting), else the stabiliser is fixed at its declared incidence. Evaluated at sea
        level, standard day.
    """

    unevaluated = (
        (
            "25.147(a)",
            "the reasonably sudden 15° heading change toward the inoperative engine (dynamic) is not "
            "simulated; only the steady wings-level engine-out trim is checked",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        dead = critical_engine(ctx)
        limits = control_limits(ctx.aircraft)
        rudder = control_force_model(ctx.aircraft, "rudder")
        out = []
        if _engines(ctx) >= 4:
            out += [
                Finding.not_evaluated(
                    c, "(b) two critical engines inoperative", "four-engine case of (b) is not implemented"
                )
                for c in conditions
            ]
        else:
            out += [
                Finding.not_applicable(
                    c,
                    "(b) two critical engines inoperative",
                    f"(b) applies to airplanes with four or more engines ({_engines(ctx)} here)",
                )
                for c in conditions
            ]
        conds, why = _refine(ctx, list(conditions), crit, dead, "power for level flight (at most maximum continuous)")
        if conds is None:
            return out + [Finding.not_evaluated(c, "(a) wings-level trim", why) for c in conditions]
        live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != dead]
        mct = operating_thrust(ctx, conds, 1.0, crit.mct_over_takeoff_thrust, dead)
        batch = ctx.trim(conds, kind="oei", bank=0.0, gamma=0.0, inoperative=dead)
        results = list(batch.results)
        gamma = np.zeros(len(conds))
        needed = np.array([sum(r.thrust[e] for e in live) if r.converged else np.inf for r in results])
        over = np.nonzero(needed > mct)[0]
        if len(over):  # level flight needs more than maximum continuous: fly at MCT on the path it gives
            sub = [conds[i] for i in over]
            res, g, _ = trim_at_thrust(ctx, sub, mct[over], kind="oei", bank=0.0, inoperative=dead)
            for j, i in enumerate(over):
                results[i], gamma[i] = res[j], g[j]
        for i, c in enumerate(conds):
            r = results[i]
            thrust = "maximum continuous thrust" if i in over else "level-flight thrust"
            here = c.with_(thrust=f"critical engine ({dead}) inoperative, {thrust} on the others")
            details = dict(
                trim_details(r),
                flight_path_deg=round(math.degrees(gamma[i]), 3),
                thrust_level_flight_N=float(needed[i]),
                thrust_mct_N=float(mct[i]),
            )
            if not r.converged:
                out.append(
                    Finding.not_evaluated(
                        here,
                        "(a) wings-level trim",
                        f"one-engine-inoperative trim did not "
                        f"converge (residual {r.residual_norm:.1e})"
                        + "".join(f"; {m.message}" for m in r.limits_exceeded),
                        **details,
                    )
                )
            else:
                for f in control_findings(here, "(a) wings level,", r, limits):
                    f.details.update(details)
                    out.append(f)
            out.append(pedal_force_finding(ctx, rudder, here, r, crit.pedal_force_lbf))
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.147(a) directional control, one engine inoperative",
            "One-engine-inoperative trims: controls against their design limits.",
            ("bank_deg", "beta_deg", "elevator_deg", "aileron_deg", "rudder_deg"),
        )


@rule
class LateralControlOEI(Rule):
    id = "25.147(c)"
    symbol = "lateral-control-oei"
    title = "Lateral control, one engine inoperative: 20° banked turns with and against the inoperative engine"
    amendment = AMDT
    requirement = """
        It must be possible to make 20° banked turns, with and against the inoperative engine, from steady flight at
        1.3 VSR1, with the remaining engines at maximum continuous power, the most unfavourable CG, the gear
        retracted and extended, the flaps in the most favourable climb position and maximum takeoff weight.
        certkit checks that the steady coordinated 20° turns, both directions, trim with the elevator, aileron and
        rudder within their design limits. (d) roll capability is not evaluated; (e) (four or more engines) is not
        applicable to a twin.
    """
    margin = "Each control's design limit on the side it is deflected − |deflection| (deg), each CG and turn direction."
    references = ("25.103", "25.121", "25.143", "25.149")
    requires = ("mass.MTOW", "configurations.clean")
    criteria = {
        "speed_over_vsr": _speed_criterion("c"),
        "bank_deg": Criterion(
            20.0, "deg", SOURCE + " (c)", "bank of the turns with and against the inoperative engine"
        ),
        "mct_over_takeoff_thrust": _MCT,
    }
    conditions = _space(
        "MTOW",
        "clean",
        "flaps up (most favourable climb position); sea level; turns toward and away from the inoperative engine",
    )
    implementation = "partial"
    limitations = """
        Steady coordinated turns (zero sideslip), not the roll into them. Flaps up is taken as the most favourable
        climb position; the gear-extended case is not flown separately (in the model the gear adds drag only, which
        changes the flight path, not the moments). (d) roll capability (text not in the notes; a handling quality)
        is reported not evaluated. Sea level, standard day.
    """

    unevaluated = (
        (
            "25.147(c)",
            "the roll into the 20° banked turns and the gear-extended case are not flown (steady "
            "coordinated turns, gear up)",
        ),
        (
            "25.147(d)",
            "roll capability with one engine inoperative (a roll-response handling quality) is not evaluated",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        dead = critical_engine(ctx)
        dead_y = next(e.position.y for e in ac.propulsion.engines if e.name == dead)
        toward_dead = -1.0 if dead_y < 0 else 1.0  # positive bank is right wing down
        limits = control_limits(ac)
        out = []
        for c in conditions:
            if _engines(ctx) < 4:
                out.append(
                    Finding.not_applicable(
                        c,
                        "(e) 20° turns, two engines inoperative",
                        f"(e) applies to airplanes with four or more engines ({_engines(ctx)} here)",
                    )
                )
        base, why = _refine(ctx, list(conditions), crit, dead, "maximum continuous thrust on the others")
        if base is None:
            return out + [Finding.not_evaluated(c, "(c) 20° turn trim", why) for c in conditions]
        conds, banks = [], []
        for c in base:
            for label, sign in (
                ("toward the inoperative engine", toward_dead),
                ("away from the inoperative engine", -toward_dead),
            ):
                conds.append(c.with_(bank_deg=crit.bank_deg, turn=label))
                banks.append(sign * math.radians(crit.bank_deg))
        banks = np.array(banks)
        aim = operating_thrust(ctx, conds, 1.0, crit.mct_over_takeoff_thrust, dead)
        results, gamma, residual = trim_at_thrust(ctx, conds, aim, kind="turn", bank=banks, inoperative=dead)
        for i, c in enumerate(conds):
            r = results[i]
            details = dict(
                turn_details(ctx, c, r, float(gamma[i]), float(banks[i])), thrust_residual=float(residual[i])
            )
            if not r.converged:
                out.append(
                    Finding.not_evaluated(
                        c,
                        "(c) 20° turn trim",
                        f"coordinated-turn trim did not converge "
                        f"(residual {r.residual_norm:.1e})" + "".join(f"; {m.message}" for m in r.limits_exceeded),
                        **details,
                    )
                )
                continue
            for f in control_findings(c, "(c) 20° turn", r, limits):
                f.details.update(details)
                out.append(f)
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.147(c) lateral control, one engine inoperative",
            "Turns toward and away from the inoperative engine: controls against their design limits.",
            ("bank_deg", "beta_deg", "elevator_deg", "aileron_deg", "rudder_deg"),
        )

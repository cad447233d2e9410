"""§§25.171–25.175 Static longitudinal stability: the stick-fixed static margin (§25.171), the speed-stability
gradient (§25.173(a)), the stick-force gradient (§25.173(c)) and the free return (§25.173(b)). The speed ranges it
shares with §§25.177 and 25.181 are in :mod:`certkit_rules.part25.support.stability_speeds`.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.stability_speeds import (
    FLAP_ALTITUDE,
    PHASES,
    by_configuration,
    flight_described,
    refine_speeds,
    steady_flight_trims,
)

from certkit.engine.conditions import Altitudes, CgCorners, ConditionSpace, speed_as
from certkit.engine.evidence.stability import margin_matrix_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.dynamics.trim import held_stabilizer
from certkit.units import FT, KN, LBF


def static_margin(ctx, configuration: str, x_cg, mach) -> np.ndarray:
    """Stick-fixed static margin (fraction of MAC): (x_np − x_cg)/c with the neutral point
    x_np = x_ref − c·Cm_α/CL_α of the configuration's model (airplane frame, X aft)."""
    m = ctx.aero(configuration).model
    ref = m.reference
    x_np = ref.x_ref - ref.chord * m.derivative("Cm_alpha", mach) / m.derivative("CL_alpha", mach)
    return (x_np - np.asarray(x_cg)) / ref.chord


VERIFIED_171_175 = "§§25.171–25.175 text verified (docs/regulation-notes.md §§ 25.171–25.175)"
_STABILITY_SPACE = dict(
    loading=CgCorners(), configurations=tuple(PHASES.values()), altitudes=Altitudes((0.0, 35000 * FT))
)


@rule
class StabilityGeneral(Rule):
    id = "25.171"
    symbol = "static-stability-general"
    title = "Stability: general (static margin)"
    amendment = "25-7"
    requirement = """
        The airplane must be longitudinally, directionally and laterally stable in accordance with §§25.173 through
        25.177. certkit reads longitudinal static stability first as the stick-fixed static margin: the neutral
        point (where Cm_α about the CG vanishes) must lie behind every CG of the envelope by at least the criterion.
    """
    margin = "(x_np − x_cg)/MAC − minimum static margin, fraction of MAC, at each corner, configuration and Mach."
    references = ("25.173", "25.175", "25.177")
    requires = ("configurations.clean.CLmax", "speeds.VMO")
    criteria = {
        "static_margin_min": Criterion(
            0.05,
            "MAC",
            "project choice: Raymer, Aircraft Design: A Conceptual Approach "
            "(6th ed.), §16.3 — transports typically 5 to 10 % MAC stick-fixed; the lower "
            "end is the minimum (Part 25 states no number)",
            "minimum stick-fixed static margin",
        ),
        "low_speed_factor": Criterion(1.13, "", "§25.177 / §25.181 speed range from 1.13 VSR", "low end of the speeds"),
        "flap_altitude_max": FLAP_ALTITUDE,
    }
    conditions = ConditionSpace(
        **_STABILITY_SPACE,
        extra=(("speed_point", ("1.13 VSR", "max allowable")),),
        note="Neutral point x_np = x_ref − c·Cm_α/CL_α of the configuration's model at the Mach number.",
    )
    limitations = "Stick-fixed only (no hinge-moment model for the stick-free neutral point); rigid airplane."

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "static margin")
        for cond in refined:
            mach = speed_as(cond, "MACH")
            sm = float(static_margin(ctx, cond.configuration, cond.x_cg, mach))
            out.append(
                Finding.compare(
                    cond,
                    "stick-fixed static margin ≥ minimum",
                    sm,
                    crit.static_margin_min,
                    at_least=True,
                    unit="MAC",
                    mach=round(float(mach), 4),
                )
            )
        return out

    def evidence(self, ctx, findings, crit):
        return margin_matrix_evidence(
            findings, "§25.171 static margin − minimum (normalised) over CG corners × configurations"
        )


def trims_at_throttle(ctx, conds, throttle, **trim_args):
    """Trims of ``conds`` with the throttle held at ``throttle`` (one value per condition): the flight-path angle is
    an unknown of the trim (it floats), so any throttle from idle to full is a steady climb or descent."""
    return ctx.trim(conds, throttle=np.asarray(throttle, dtype=float), **trim_args).results


def speed_step_trims(ctx, refined, k: float):
    """Per configuration: (conditions, trims at V₀, their throttles, trims at V₀(1 − k) then V₀(1 + k) with the
    throttle held, the flight path floating) — the trims §25.173(a) and the stick-force rules share (memoised in the
    Context). V₀ is trimmed in level flight, or beyond the weight's level-flight ceiling in the steady descent at full
    thrust (:func:`steady_flight_trims`)."""
    for idx in by_configuration(refined).values():
        conds = [refined[i] for i in idx]
        trim0, _ = steady_flight_trims(ctx, conds)
        t0 = [next(v for n, v in r.controls.items() if n.startswith("throttle")) for r in trim0]
        side = [c.with_(speed=c.speed * (1 - k)) for c in conds] + [c.with_(speed=c.speed * (1 + k)) for c in conds]
        held = held_stabilizer(trim0)  # a movable stabiliser stays at its V₀ trim; the elevator holds the speed change
        extra = {} if held is None else {"stabilizer": np.concatenate([held, held])}
        yield conds, trim0, t0, trims_at_throttle(ctx, side, t0 + t0, **extra)


@rule
class SpeedStability(Rule):
    id = "25.173(a)"
    cost = 2  # relative evaluation time (orders work over --jobs processes)
    symbol = "speed-stability-elevator-fixed"
    title = "Static longitudinal stability: elevator-fixed speed stability"
    amendment = "25-7"
    requirement = """
        Under the conditions of §25.175 (climb, cruise, approach and landing), a pull must be required to obtain and
        maintain speeds below the trim speed and a push above it. Without a control-force model certkit reads this
        as the elevator-fixed speed stability: at the trim thrust held constant, a lower speed must need more
        trailing-edge-up elevator, i.e. dδe/dV > 0 in certkit's signs (elevator trailing edge down positive).
    """
    margin = "dδe/dV (deg per kt CAS, central difference at ±5 % about the trim speed, thrust constant) − 0."
    references = ("25.175", "25.171", "25.173(c)")
    requires = ("configurations.clean.CLmax", "speeds.VMO")
    criteria = {
        "gradient_min": Criterion(
            0.0,
            "deg/kt",
            "§25.173(a) stable sense (" + VERIFIED_171_175 + ")",
            "smallest elevator-per-speed gradient (> 0 stable)",
        ),
        "speed_step": Criterion(
            0.05,
            "",
            "project choice: ±5 % about the trim speed, inside the §25.175 ranges",
            "relative speed step of the central difference",
        ),
        "low_speed_factor": Criterion(
            1.13,
            "",
            "project choice: the §25.177/§25.181 low end 1.13 VSR also for the "
            "§25.173 points (§25.175 itself trims at 1.3 VSR1 or more; the factor only sets "
            "the lowest speed point checked)",
            "low end of the speeds",
        ),
        "flap_altitude_max": FLAP_ALTITUDE,
    }
    conditions = ConditionSpace(
        **_STABILITY_SPACE,
        extra=(("speed_point", ("1.3 VSR", "max allowable", "VFC")),),
        note="Trim speeds 1.3 VSR (§25.175 climb, approach and landing trims), the "
        "configuration's maximum allowable speed (VMO clean, VFE/VLE extended) and, clean, "
        "VFC/(1 + step) so that the faster step reaches VFC/MFC, the top of the (a) range "
        "(declared, or the least §25.253(b) allows).",
    )
    limitations = """
        Elevator-fixed reading of a stick-force requirement (§25.173(c) needs a control-force model); trim in level
        flight at the power for level flight (beyond the level-flight ceiling of the weight, in the steady descent at
        full thrust), not the §25.175 climb power or idle-power landing; the speed steps hold that throttle and the
        flight path floats; the free-return (§25.173(b)) is not simulated.
    """

    implementation = "partial"
    unevaluated = (
        (
            "25.173(a)",
            "the stick-force reading of (a) (pull below the trim speed, push above) is read elevator-fixed; the force "
            "itself is §25.173(c)'s",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(
            ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "(a) speed stability"
        )
        k = crit.speed_step
        # the top point is trimmed below VFC so that its faster step reaches VFC and not beyond
        refined = [c.with_(speed=c.speed / (1 + k)) if c.get("speed_point") == "VFC" else c for c in refined]
        for conds, trim0, t0, res in speed_step_trims(ctx, refined, k):
            n = len(conds)
            for i, cond in enumerate(conds):
                lo, hi = res[i], res[n + i]
                check = "(a) elevator-fixed speed stability dδe/dV > 0"
                bad = [r for r in (trim0[i], lo, hi) if not r.converged]
                if bad:
                    out.append(
                        Finding.not_evaluated(
                            cond,
                            check,
                            "trim did not converge: " + "; ".join(e.message for r in bad for e in r.limits_exceeded),
                        )
                    )
                    continue
                dv = 2 * k * cond.speed / KN
                grad = np.degrees(hi.controls["elevator"] - lo.controls["elevator"]) / dv
                reason = "; ".join(
                    e.message for r in (trim0[i], lo, hi) for e in r.limits_exceeded if e.control == "elevator"
                )
                out.append(
                    Finding.compare(
                        cond,
                        check,
                        float(grad),
                        crit.gradient_min,
                        at_least=True,
                        unit="deg/kt",
                        reason=reason,
                        elevator_trim_deg=float(np.degrees(trim0[i].controls["elevator"])),
                        throttle=float(t0[i]),
                        trim_flight=flight_described(trim0[i], None if trim0[i].gamma == 0.0 else t0[i]),
                        gamma_low_deg=float(np.degrees(lo.gamma)),
                        gamma_high_deg=float(np.degrees(hi.gamma)),
                    )
                )
        return out

    def evidence(self, ctx, findings, crit):
        return margin_matrix_evidence(
            findings, "§25.173(a) speed-stability gradient (normalised) over CG corners × configurations"
        )


NO_FORCE_MODEL = (
    "needs a control-force model (control_forces.elevator: hinge moments and gearing, or an artificial-feel "
    "unit): the aircraft file declares none; the elevator-fixed gradient is checked by §25.173(a)"
)
_VERIFIED_173 = "14 CFR 25.173 (Amdt. 25-7; verified, docs/regulation-notes.md)"


def stick_force_curves(ctx, refined, k: float):
    """Elevator pull force (lbf) at the trim speed V₀ and at V₀(1 ∓ k), the throttle held at its trim value and
    the elevator trim device fixed at its V₀ setting (:mod:`certkit.models.control_force`), per condition:
    a list of (condition, dict) with ``pull_low``, ``pull_high``, ``gradient`` (lbf/kt, positive stable: the
    average slope (F_pull(V₀(1−k)) − F_pull(V₀(1+k))) / 2kV₀), or (condition, reason) where a trim failed."""
    elevator = control_force_model(ctx.aircraft, "elevator")
    out = []
    for conds, trim0, _, res in speed_step_trims(ctx, refined, k):
        n = len(conds)
        q0, a0, d0 = trim_state(ctx.aircraft, "elevator", trim0)
        q1, a1, d1 = trim_state(ctx.aircraft, "elevator", res)
        pull = -elevator.force(q1, a1, d1, trim=(np.concatenate([d0, d0]), np.concatenate([a0, a0]))) / LBF
        for i, cond in enumerate(conds):
            bad = [r for r in (trim0[i], res[i], res[n + i]) if not r.converged]
            if bad:
                out.append(
                    (cond, "trim did not converge: " + "; ".join(e.message for r in bad for e in r.limits_exceeded))
                )
                continue
            dv = 2 * k * cond.speed / KN
            out.append(
                (
                    cond,
                    dict(
                        pull_low=float(pull[i]),
                        pull_high=float(pull[n + i]),
                        gradient=float((pull[i] - pull[n + i]) / dv),
                        dv_kt=dv,
                        elevator_trim_deg=float(np.degrees(d0[i])),
                        model=elevator.kind,
                    ),
                )
            )
    return out


_FORCE_CRITERIA = {
    "speed_step": Criterion(
        0.05,
        "",
        "project choice: ±5 % about the trim speed, inside the §25.175 ranges "
        "(±15 % or ±50 kt, docs/regulation-notes.md)",
        "relative speed step of the average gradient",
    ),
    "low_speed_factor": Criterion(
        1.13,
        "",
        "project choice: the §25.177/§25.181 low end 1.13 VSR also for the "
        "§25.173 points (§25.175 itself trims at 1.3 VSR1 or more; the factor only sets the "
        "lowest speed point checked)",
        "low end of the speeds",
    ),
    "flap_altitude_max": FLAP_ALTITUDE,
}


@rule
class StickForceGradient(Rule):
    id = "25.173(c)"
    symbol = "stick-force-speed-gradient"
    title = "Static longitudinal stability: stick-force gradient"
    amendment = "25-7"
    requirement = """
        Under the conditions of §25.175, the average gradient of the stable slope of the stick force versus speed curve
        may not be less than 1 pound for each 6 knots. certkit computes the elevator pull force of the declared
        control-force model (control_forces.elevator) at ±5 % about each trim speed, the throttle and the elevator
        trim device held at their trim settings, and forms the average slope over that range.
    """
    margin = """average stick-force gradient (F_pull(0.95 V) − F_pull(1.05 V)) / 0.1 V (lbf per kt CAS; > 0 stable: a
        pull below the trim speed) − 1 lbf / 6 kt; not evaluated without control_forces.elevator."""
    references = ("25.173(a)", "25.173(b)", "25.175")
    requires = ("configurations.clean.CLmax", "speeds.VMO")
    criteria = {
        "force_gradient_min": Criterion(
            1.0 / 6.0,
            "lbf/kt",
            _VERIFIED_173 + " (c): 1 pound for each 6 knots",
            "smallest average stick-force gradient",
        ),
        **_FORCE_CRITERIA,
    }
    conditions = ConditionSpace(
        **_STABILITY_SPACE,
        extra=(("speed_point", ("1.3 VSR", "max allowable")),),
        note="The trims of §25.173(a): 1.3 VSR and the maximum allowable speed of each configuration, "
        "level flight, thrust held; needs control_forces.elevator.",
    )
    implementation = "partial"
    limitations = """
        Local average over ±5 % of the trim speed, not the whole §25.175 range (±15 % or ±50 kt plus the free-return
        range); level-flight trim thrust, not the §25.175 climb or idle power; friction is not added to the slope;
        the trim device is a hinge-moment bias fixed at its trim value (tab or feel-neutral shift); a movable stabiliser
        is held at its trim-speed setting (the elevator holds the speed change), else the stabiliser is fixed at its
        declared incidence.
    """

    unevaluated = (
        (
            "25.173(c)",
            "the average gradient is taken over ±5 % of the trim speed, not the whole §25.175 speed range,"
            " at level-flight thrust, not the §25.175 climb or idle power",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        check = f"(c) stick-force gradient ≥ {crit.force_gradient_min * 6:g} lbf per 6 kt"
        if ctx.aircraft.control_forces is None or ctx.aircraft.control_forces.elevator is None:
            return [Finding.not_evaluated(c, check, NO_FORCE_MODEL) for c in conditions]
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, check)
        for cond, r in stick_force_curves(ctx, refined, crit.speed_step):
            if isinstance(r, str):
                out.append(Finding.not_evaluated(cond, check, r))
                continue
            out.append(
                Finding.compare(
                    cond,
                    check,
                    r["gradient"],
                    crit.force_gradient_min,
                    at_least=True,
                    unit="lbf/kt",
                    pull_force_low_speed_lbf=round(r["pull_low"], 2),
                    pull_force_high_speed_lbf=round(r["pull_high"], 2),
                    elevator_trim_deg=round(r["elevator_trim_deg"], 3),
                    force_model=r["model"],
                )
            )
        return out


@rule
class FreeReturn(Rule):
    id = "25.173(b)"
    symbol = "stick-force-free-return"
    title = "Static longitudinal stability: free return to the trim speed"
    amendment = "25-7"
    requirement = """
        The airspeed must return to within 10 percent of the original trim speed for the climb, approach and landing
        conditions of §25.175(a), (c) and (d), and within 7.5 percent for the cruise condition of §25.175(b), when the
        control force is slowly released from any speed within the range of (a). With friction F_f in the elevator
        control, the released airplane settles where the stick force no longer exceeds the friction: ΔV = F_f / (dF/dV)
        with the stick-force gradient of §25.173(c).
    """
    margin = """(allowed fraction of the trim speed) − F_f / (gradient · V_trim) (fraction of the trim speed); an
        unstable or zero gradient does not return (band taken as the whole trim speed) and fails; not evaluated without
        control_forces.elevator.friction."""
    references = ("25.173(a)", "25.173(c)", "25.175")
    requires = ("configurations.clean.CLmax", "speeds.VMO")
    criteria = {
        "return_fraction": Criterion(
            0.10,
            "",
            _VERIFIED_173 + " (b): climb, approach and landing",
            "largest speed band left after release, fraction of the trim speed",
        ),
        "return_fraction_cruise": Criterion(
            0.075, "", _VERIFIED_173 + " (b): cruise", "the same, flaps retracted (cruise)"
        ),
        **_FORCE_CRITERIA,
    }
    conditions = StickForceGradient.conditions
    implementation = "partial"
    limitations = """
        Quasi-static release with the local stick-force gradient of §25.173(c) (no simulation of the slow release); the
        clean configuration is read as the cruise condition (7.5 %), the flap configurations as climb, approach and
        landing (10 %); friction as declared (control_forces.elevator.friction).
    """

    unevaluated = (
        (
            "25.173(b)",
            "the slow release of the control force is not simulated: the quasi-static return from the "
            "local force gradient stands for it",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        check = "(b) free return to the trim speed"
        decl = None if ctx.aircraft.control_forces is None else ctx.aircraft.control_forces.elevator
        if decl is None:
            return [Finding.not_evaluated(c, check, NO_FORCE_MODEL) for c in conditions]
        if decl.friction is None:
            return [
                Finding.not_evaluated(
                    c,
                    check,
                    "needs control_forces.elevator.friction (the friction of the elevator "
                    "control sets the free-return speed band)",
                )
                for c in conditions
            ]
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, check)
        friction = decl.friction / LBF
        for cond, r in stick_force_curves(ctx, refined, crit.speed_step):
            if isinstance(r, str):
                out.append(Finding.not_evaluated(cond, check, r))
                continue
            allowed = crit.return_fraction_cruise if cond.configuration == "clean" else crit.return_fraction
            v_kt = cond.speed / KN
            stable = r["gradient"] > 0
            # an unstable or neutral slope does not return: the band is taken as the whole trim speed
            band = min(friction / (r["gradient"] * v_kt), 1.0) if stable else 1.0
            out.append(
                Finding.compare(
                    cond,
                    check,
                    float(band),
                    allowed,
                    at_least=False,
                    unit="fraction of V_trim",
                    reason="" if stable else "unstable or neutral stick-force slope: the speed does not return",
                    friction_lbf=round(friction, 2),
                    gradient_lbf_per_kt=round(r["gradient"], 4),
                    return_band_kt=round(float(band * v_kt), 2),
                )
            )
        return out

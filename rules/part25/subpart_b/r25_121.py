"""§25.121 Climb: one-engine-inoperative, (a)–(d) as four rules.

The steady gradient with the critical engine inoperative (windmilling: the flight model gives the failed
engine's windmilling drag and the asymmetric thrust) is found by trimming at the gradient. Each condition
is trimmed in steady straight flight at zero sideslip (the minimum-drag OEI condition; the small bank
toward the live engine results), in one batch per configuration, at flight-path angle γ_k; the thrust the
trim needs, T_k, gives the next angle by the energy relation (Anderson, *Aircraft Performance and Design*,
1999, eq. 5.12: sin γ = (T − D)/W):

    γ_{k+1} = γ_k + (T_available − T_k) / W,        three trims from γ_0 = 0

so that the last trim is at (close to) the available thrust and its elevator, aileron and rudder are
the deflections needed to hold the climb; those are reported against their design limits. The gradient
is tan γ (height gained over horizontal distance).

Thrust available is the engine model's throttle 1: the takeoff rating of the declared deck, and for the
parametric turbofan (one rating) its sea-level static thrust with the Mattingly lapse, i.e. the takeoff
rating. Maximum continuous thrust for (c) is that thrust times ``mct_over_takeoff_thrust``.
"""

from __future__ import annotations

import math

import numpy as np

from certkit.atmosphere import RHO0, convert_speed, speed_of_sound
from certkit.conditions import ConditionSpace, DesignWeight, speed_as
from certkit.models.aero.drag import flap_drag_increment, landing_gear_drag_increment
from certkit.models.flight import control_limits, throttle_for_thrust, thrust_function
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.reference_speeds import declared_cas
from certkit.units import FT, G0
from certkit.reference_speeds import reference_stall_speed

AMDT = "25-140"  # the last amendment in the section's bracket [CFR 1-1-24 p. 217]
CONTROLS = ("elevator", "aileron", "rudder")
CGS = ("forward", "reference", "aft")


def critical_engine(ctx) -> str:
    """The critical engine: the outermost engine, left side first (for a symmetric turbofan layout the two
    outboard engines are equally critical; turbofans have no propeller asymmetry)."""
    engines = ctx.aircraft.propulsion.engines
    return min(engines, key=lambda e: (-abs(e.position.y), e.position.y)).name


def engine_count_criterion(ctx, crit, stem: str) -> tuple[float, int]:
    n = len(ctx.aircraft.propulsion.engines)
    key = {2: "two", 3: "three"}.get(n, "four")
    return crit[f"{stem}_{key}"], n


def gradient_criteria(paragraph: str, two: float, three: float, four: float) -> dict[str, Criterion]:
    src = f"14 CFR 25.121({paragraph})"
    return {f"gradient_{k}": Criterion(v, "", src, f"minimum steady climb gradient, {k}-engine airplanes")
            for k, v in (("two", two), ("three", three), ("four", four))}


def control_findings(cond, prefix: str, result, limits) -> list[Finding]:
    """Each trim control (elevator, aileron, rudder) against its design limit on the side it is deflected:
    margin = limit − |deflection| (deg); the trim's own message when it is beyond."""
    out = []
    for name in CONTROLS:
        if name not in result.controls or name not in limits:
            continue
        d = result.controls[name]
        lo, hi = limits[name]
        message = next((m.message for m in result.limits_exceeded if m.control == name), "")
        hint = next((m.hint for m in result.limits_exceeded if m.control == name), "")
        extra = {"hint": hint} if hint else {}
        if d >= 0:
            f = Finding.compare(cond, f"{prefix} {name} within design limit", math.degrees(d), math.degrees(hi),
                                at_least=False, unit="deg", reason=message, **extra)
        else:
            f = Finding.compare(cond, f"{prefix} {name} within design limit", math.degrees(d), math.degrees(lo),
                                at_least=True, unit="deg", reason=message, **extra)
        out.append(f)
    return out


def trim_details(result) -> dict:
    return {"alpha_deg": round(math.degrees(result.alpha), 3), "bank_deg": round(math.degrees(result.phi), 3),
            "beta_deg": round(math.degrees(result.beta), 3),
            **{f"{k}_deg": round(math.degrees(v), 3) for k, v in result.controls.items() if k in CONTROLS},
            **{k: round(v, 4) for k, v in result.controls.items() if k.startswith("throttle")},
            **({} if result.stabilizer is None else {"stabilizer_deg": round(math.degrees(result.stabilizer), 3)})}


def oei_climb(ctx, conds, thrust_fraction: float = 1.0, drag_credit=None, engine_out: bool = True):
    """Gradient (tan γ) with the critical engine inoperative at available thrust, for conditions of one
    configuration; returns (gradients, TrimBatch, info). The operating engines' throttle is held where they give
    ``thrust_fraction`` of their full thrust and the trim solves the flight-path angle (a steady climb at that
    thrust). ``drag_credit`` (ΔCD per condition) is drag that the configuration carries but the paragraph removes
    (the gear for §25.121(b)); ``engine_out=False`` gives the all-engines climb at the same thrust setting."""
    thrust, thrust_source = thrust_function(ctx.aircraft)
    dead = critical_engine(ctx) if engine_out else None
    live = [e.name for e in ctx.aircraft.propulsion.engines if e.name != dead]
    h = np.array([c.altitude or 0.0 for c in conds])
    tas = np.array([speed_as(c, "TAS") for c in conds])
    mach = tas / speed_of_sound(h)
    weight = np.array([c.mass for c in conds]) * G0
    full = np.asarray(thrust(np.ones_like(h), h, mach), dtype=float)
    available = len(live) * thrust_fraction * full
    throttle = throttle_for_thrust(thrust, thrust_fraction * full, h, mach)
    credit = np.zeros_like(h)
    if drag_credit is not None:
        qbar = 0.5 * RHO0 * np.array([float(convert_speed(v, "TAS", "EAS", hh)) for v, hh in zip(tas, h)]) ** 2
        credit = np.asarray(drag_credit, dtype=float) * qbar * ctx.aircraft.reference.area
    batch = ctx.trim(conds, kind="sideslip" if dead else "straight", beta=0.0, throttle=throttle, inoperative=dead)
    gamma = np.array([r.gamma if r.converged else np.nan for r in batch.results])
    needed = np.array([sum(r.thrust[n] for n in live) for r in batch.results])
    residual = (available - needed) / weight
    gamma = gamma + credit / weight  # drag the configuration carries but the segment does not (sin γ = (T − D)/W)
    info = {"inoperative": dead, "thrust_source": thrust_source, "available": available, "needed": needed,
            "credit": credit, "residual": residual, "weight": weight}
    return np.tan(gamma), batch, info


def climb_findings(ctx, conds, check: str, required: float, n_engines: int, *, thrust_fraction=1.0, drag_credit=None,
                   notes: str = "") -> list[Finding]:
    grads, batch, info = oei_climb(ctx, conds, thrust_fraction, drag_credit)
    limits = control_limits(ctx.aircraft)
    out = []
    for i, cond in enumerate(conds):
        r = batch.results[i]
        here = cond.with_(thrust=f"critical engine ({info['inoperative']}) inoperative, "
                                 f"{'maximum continuous' if thrust_fraction < 1 else 'takeoff'} thrust on the others")
        if not r.converged:
            out.append(Finding.not_evaluated(here, check, f"one-engine-inoperative trim did not converge "
                                                          f"(residual {r.residual_norm:.1e}); "
                                             + "; ".join(m.message for m in r.limits_exceeded)))
            continue
        details = dict(trim_details(r), thrust_available_N=float(info["available"][i]),
                       thrust_at_trim_N=float(info["needed"][i]), gear_drag_credit_N=float(info["credit"][i]),
                       gradient_residual=float(info["residual"][i]), engines=n_engines,
                       thrust_model=info["thrust_source"], method="trim at the thrust, flight-path angle solved")
        out.append(Finding.compare(here, check, float(grads[i]), required, at_least=True,
                                   unit="gradient", reason=notes, **details))
        out += control_findings(here, check.split(" ")[0], r, limits)
    return out


def refined(conds, speed: float, name: str, altitude: float = 0.0, configuration: str | None = None):
    return [c.with_(speed=speed, speed_kind="CAS", speed_name=name, altitude=altitude,
                    **({"configuration": configuration} if configuration else {})) for c in conds]


_COMMON_LIMITS = """
    Steady-state trim (no ground effect, no transient); the critical engine windmills with the flight model's
    windmilling drag (Torenbeek App. G form); weight not reduced by the fuel burned before the segment.
"""


@rule
class ClimbOEITakeoffGearDown(Rule):
    id = "25.121(a)"
    symbol = "oei-climb-takeoff-gear-down"
    title = "Climb OEI: takeoff, landing gear extended"
    amendment = AMDT
    requirement = """
        In the critical takeoff configuration along the flight path (gear extended), without ground effect, the
        steady climb gradient must be positive for two-engine airplanes (0.3 % three, 0.5 % four engines) at VLOF
        with the critical engine inoperative, the remaining engines at the thrust available when gear retraction
        begins, and the weight existing then.
    """
    margin = "Steady OEI gradient − minimum (0 for twins), at VLOF (VR when VLOF is not declared); ≥ 0 complies."
    references = ("25.107", "25.111", "25.121(b)")
    requires = ("speeds.VR", "configurations.takeoff")
    criteria = gradient_criteria("a", 0.0, 0.003, 0.005)
    conditions = ConditionSpace(loading=DesignWeight("MTOW", CGS), configurations=("takeoff",),
                                note="sea level, takeoff thrust; VLOF, or VR when VLOF is not declared")
    limitations = _COMMON_LIMITS + " VLOF ≈ VR when VLOF is not declared (a lower speed, so conservative)."

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        name = "VLOF" if ctx.aircraft.speeds.VLOF is not None else "VR"
        note = "" if name == "VLOF" else "VLOF not declared: evaluated at VR (VLOF ≥ VR)"
        conds = refined(conditions, declared_cas(ctx, name), name)
        out = climb_findings(ctx, conds, "(a) gradient at VLOF, gear down", required, n, notes=note)
        return [_positive(f, required) for f in out]

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import climb_gradient_evidence

        return climb_gradient_evidence(findings, "§25.121(a) OEI climb, takeoff, gear down")


def _positive(f: Finding, required: float) -> Finding:
    """(a) for twins asks a positive gradient: zero itself does not comply."""
    if f.unit == "gradient" and required == 0.0 and f.margin is not None and f.margin <= 0.0:
        f.status = "fails"
    return f


def gear_up_credit(ctx, configuration: str) -> tuple[float, str]:
    """ΔCD0 of the extended gear removed for a gear-up segment: the declared configuration increment less the
    flap estimate (Raymer eq. 12.61), capped at the class-I gear increment (Roskam Part I Table 3.6)."""
    cfg = ctx.aircraft.configurations[configuration]
    gear = landing_gear_drag_increment(cfg.gear)
    if gear == 0.0:
        return 0.0, "configuration has the gear up"
    if cfg.delta_CD0:
        flaps = float(flap_drag_increment(cfg.flap))
        credit = max(0.0, min(gear, cfg.delta_CD0 - flaps))
        return credit, (f"declared ΔCD0 {cfg.delta_CD0:.4f} less the flap estimate {flaps:.4f} (Raymer 12.61), "
                        f"capped at the gear increment {gear:.3f} (Roskam Part I Table 3.6)")
    return gear, f"gear increment {gear:.3f} (Roskam Part I Table 3.6)"


@rule
class ClimbOEITakeoffGearUp(Rule):
    id = "25.121(b)"
    symbol = "oei-climb-takeoff-gear-up"
    title = "Climb OEI: takeoff, landing gear retracted"
    amendment = AMDT
    requirement = """
        In the takeoff configuration with the landing gear retracted, without ground effect, the steady climb
        gradient at V2 may not be less than 2.4 % for two-engine airplanes (2.7 % three, 3.0 % four), with the
        critical engine inoperative and the remaining engines at takeoff thrust, at the weight when the gear is
        fully retracted; in non-icing and icing conditions.
    """
    margin = "Steady OEI gradient at V2 − 0.024 (twins); each trim control's design limit − |deflection| (deg)."
    references = ("25.107", "25.111", "25.121(a)")
    requires = ("speeds.V2", "configurations.takeoff")
    criteria = {**gradient_criteria("b)(1", 0.024, 0.027, 0.030),
                "configuration": Criterion("takeoff", "", "14 CFR 25.121(b): the takeoff configuration",
                                           "configuration flown; its extended gear drag is removed (gear retracted)")}
    conditions = ConditionSpace(loading=DesignWeight("MTOW", CGS), configurations=("takeoff",),
                                note="sea level, takeoff thrust, V2")
    limitations = _COMMON_LIMITS + """ The gear is retracted by removing its drag increment from the takeoff
        configuration's (see gear_up_credit); the gear's small pitching moment is kept. Icing (b)(2)(ii) is not
        evaluated."""

    implementation = "partial"
    unevaluated = (
        ("25.121(b)(2)(ii)", "icing conditions (takeoff ice accretion) not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        cfg = crit.configuration
        credit, how = gear_up_credit(ctx, cfg)
        conds = refined(conditions, declared_cas(ctx, "V2"), "V2", configuration=cfg)
        return climb_findings(ctx, conds, "(b) gradient at V2, gear up", required, n,
                              drag_credit=np.full(len(conds), credit), notes=f"gear retracted: ΔCD0 {credit:.4f} removed, {how}")

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import climb_gradient_evidence

        return climb_gradient_evidence(findings, "§25.121(b) OEI climb, takeoff, gear up")


@rule
class ClimbOEIFinalTakeoff(Rule):
    id = "25.121(c)"
    symbol = "oei-climb-final-takeoff"
    title = "Climb OEI: final takeoff"
    amendment = AMDT
    requirement = """
        In the en-route configuration at the end of the takeoff path (§25.111, at least 1500 ft), the steady
        climb gradient at VFTO may not be less than 1.2 % for two-engine airplanes (1.5 % three, 1.7 % four), with
        the critical engine inoperative and the remaining engines at maximum continuous thrust.
    """
    margin = "Steady OEI gradient at VFTO − 0.012 (twins); each trim control's design limit − |deflection| (deg)."
    references = ("25.111", "25.121(b)")
    requires = ("speeds.VFTO", "configurations.clean")
    criteria = {**gradient_criteria("c", 0.012, 0.015, 0.017),
                "mct_over_takeoff_thrust": Criterion(
                    0.96, "", "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf at SL static",
                    "maximum continuous over takeoff thrust, used when the engine model has one (takeoff) rating")}
    conditions = ConditionSpace(loading=DesignWeight("MTOW", CGS), configurations=("clean",),
                                note="1500 ft (end of the takeoff path), maximum continuous thrust, VFTO")

    limitations = _COMMON_LIMITS

    implementation = "partial"
    unevaluated = (
        ("25.121(c)(2)(ii)", "icing conditions (final takeoff ice accretion) not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        conds = refined(conditions, declared_cas(ctx, "VFTO"), "VFTO", altitude=1500 * FT)
        return climb_findings(ctx, conds, "(c) gradient at VFTO, en route", required, n,
                              thrust_fraction=crit.mct_over_takeoff_thrust)

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import climb_gradient_evidence

        return climb_gradient_evidence(findings, "§25.121(c) OEI final takeoff climb")


@rule
class ClimbOEIApproach(Rule):
    id = "25.121(d)"
    symbol = "oei-climb-approach"
    title = "Climb OEI: approach"
    amendment = AMDT
    requirement = """
        In the approach configuration (whose VSR does not exceed 110 % of the landing configuration's VSR), the
        steady climb gradient may not be less than 2.1 % for two-engine airplanes (2.4 % three, 2.7 % four) with
        the critical engine inoperative, the remaining engines at go-around thrust, maximum landing weight, and a
        climb speed of the normal landing procedure not exceeding 1.4 VSR (verified, [CFR 1-1-24] p. 217:
        docs/regulation-notes.md).
    """
    margin = """Steady OEI gradient at 1.4 VSR(approach) − 0.021 (twins); 1.10 − VSR(approach)/VSR(landing);
        each trim control's design limit − |deflection| (deg)."""
    references = ("25.103", "25.119", "25.125")
    requires = ("configurations.approach", "mass.MLW")
    criteria = {**gradient_criteria("d", 0.021, 0.024, 0.027),
                "speed_over_vsr": Criterion(1.4, "", "14 CFR 25.121(d)", "climb speed, at most this × VSR"),
                "vsr_ratio": Criterion(1.10, "", "14 CFR 25.121(d)",
                                       "VSR(approach) / VSR(landing), at most")}
    conditions = ConditionSpace(loading=DesignWeight("MLW", CGS), configurations=("approach",),
                                note="sea level, go-around thrust (throttle 1), gear up, 1.4 VSR of the approach configuration")
    limitations = _COMMON_LIMITS + " Evaluated at 1.4 VSR, the largest speed allowed (no procedure speed is declared)."

    implementation = "partial"
    unevaluated = (
        ("25.121(d)(2)(ii)", "icing conditions (approach ice accretion) not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        out = []
        conds = []
        for c in conditions:
            vsr, src = reference_stall_speed(ctx, "approach", c.mass)
            conds.append(c.with_(speed=crit.speed_over_vsr * vsr, speed_kind="CAS", speed_name="1.4 VSR", altitude=0.0))
            if "landing" in ctx.aircraft.configurations and ctx.clmax("landing") is not None:
                vsr_l, _ = reference_stall_speed(ctx, "landing", c.mass)
                out.append(Finding.compare(conds[-1], "(d) VSR approach ≤ 1.10 VSR landing", vsr / vsr_l, crit.vsr_ratio,
                                           at_least=False, unit="ratio", VSR_approach=vsr, VSR_landing=vsr_l, basis=src))
        return out + climb_findings(ctx, conds, "(d) gradient at ≤ 1.4 VSR, approach", required, n)

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import climb_gradient_evidence

        return climb_gradient_evidence(findings, "§25.121(d) OEI approach climb")

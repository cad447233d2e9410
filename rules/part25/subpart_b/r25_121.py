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
is tan γ (height gained over horizontal distance). A condition whose trim does not converge has no gradient to read;
where its speed lies below the configuration's stall speed (the least lift any steady flight there needs, on a path
up to 10°, beyond CLmax: rules/part25/support/turns.py) it fails "steady flight within CLmax".

Thrust available is the engine model's throttle 1: the takeoff rating of the declared deck, and for the
parametric turbofan (one rating) its sea-level static thrust with the Mattingly lapse, i.e. the takeoff
rating. Maximum continuous thrust for (c) is that thrust times ``mct_over_takeoff_thrust``.

Weight–altitude–temperature: with ``takeoff_landing_envelope`` declared, each paragraph is also evaluated at the
envelope's corners (:func:`certkit.models.performance.wat.envelope_corners`) at the design weight — the gradient
falls with weight, so it is the critical one — as standard-day trims at the pressure altitude and CAS with the day's
thrust (the reasoning is in :mod:`certkit.models.performance.wat`). A corner that meets the gradient there complies
as at sea level. One that does not is weight–altitude–temperature limited, not non-compliant: §25.1533(a)(1) and (2)
establish the maximum takeoff and landing weights as the weights at which §25.121(a)–(c) and (d) are met "for
altitudes and ambient temperatures" (and §25.25(a) the maximum weights for environmental conditions "such as
altitude and temperature"). Its weight at which the gradient is the minimum (the WAT limit, the flight manual's
limitation) is found by trims, the speeds kept at the same multiple of the stall speed (∝ √W) and the CG moved
inside the envelope at that weight; the corner's finding is that limitation, against the lowest weight the airplane
is declared to fly at (the CG envelope's lightest). It fails when even that weight cannot meet the gradient: the
declared envelope then holds a corner at which the airplane cannot operate (§25.1533(b): the extremes of altitude
and temperature are those at which compliance is shown). Flight-manual WAT limits the envelope declares
(``wat_limits``) are checked at their own altitude and temperature at the lower of that weight and the design weight:
there the gradient must be met.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from certkit_rules.part25.support.climb_checks import CGS
from certkit_rules.part25.support.control_checks import control_findings, trim_details
from certkit_rules.part25.support.reference_speeds import declared_cas, reference_stall_speed
from certkit_rules.part25.support.thrust_trims import at_mass, full_thrust, oei_climb, scaled_speed, wat_limit_search
from certkit_rules.part25.support.turns import STEEPEST_PATH, least_lift_coefficient

from certkit.engine.conditions import ConditionSpace, DesignWeight, speed_as
from certkit.engine.evidence.performance import climb_gradient_evidence
from certkit.engine.registry import ControlCase, ControlResponses, Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.aero.drag import flap_drag_increment, landing_gear_drag_increment
from certkit.models.flight import control_limits
from certkit.models.performance.wat import Ambient, envelope_corners
from certkit.units import FT, LB

AMDT = "25-140"  # the last amendment in the section's bracket [CFR 1-1-24 p. 217]
#: a WAT limit weight is reported when a trim there gives the minimum gradient within this (about 0.5 % in weight)
WAT_GRADIENT_TOLERANCE = 1e-4


def engine_count_criterion(ctx, crit, stem: str) -> tuple[float, int]:
    n = len(ctx.aircraft.propulsion.engines)
    key = {2: "two", 3: "three"}.get(n, "four")
    return crit[f"{stem}_{key}"], n


def gradient_criteria(paragraph: str, two: float, three: float, four: float) -> dict[str, Criterion]:
    src = f"14 CFR 25.121({paragraph})"
    return {
        f"gradient_{k}": Criterion(v, "", src, f"minimum steady climb gradient, {k}-engine airplanes")
        for k, v in (("two", two), ("three", three), ("four", four))
    }


def climb_findings(
    ctx, conds, check: str, required: float, n_engines: int, *, thrust_fraction=1.0, drag_credit=None, notes: str = ""
) -> list[Finding]:
    grads, batch, info = oei_climb(ctx, conds, thrust_fraction, drag_credit)
    limits = control_limits(ctx.aircraft)
    out = []
    for i, cond in enumerate(conds):
        r = batch.results[i]
        here = cond.with_(
            thrust=f"critical engine ({info['inoperative']}) inoperative, "
            f"{'maximum continuous' if thrust_fraction < 1 else 'takeoff'} thrust on the others"
        )
        if not r.converged:
            out.append(
                Finding.not_evaluated(
                    here,
                    check,
                    f"one-engine-inoperative trim did not converge "
                    f"(residual {r.residual_norm:.1e}); " + "; ".join(m.message for m in r.limits_exceeded),
                )
            )
            # below the stall speed no steady climb exists whatever a trim finds: the least lift any steady flight
            # at this speed and weight needs, against CLmax
            least, clmax = least_lift_coefficient(ctx, here), ctx.clmax(here.configuration, speed_as(here, "MACH"))
            if clmax and least > clmax:
                out.append(
                    Finding.compare(
                        here,
                        f"{check.split(' ')[0]} steady flight within CLmax",
                        least,
                        clmax,
                        at_least=False,
                        unit="C_L",
                        reason=f"no steady flight at this speed and weight: it needs at least CL {least:.3f} "
                        f"(on a path as steep as {math.degrees(STEEPEST_PATH):.0f}°), beyond CLmax {clmax:.3f}",
                    )
                )
            continue
        details = dict(
            trim_details(r),
            thrust_available_N=float(info["available"][i]),
            thrust_at_trim_N=float(info["needed"][i]),
            gear_drag_credit_N=float(info["credit"][i]),
            gradient_residual=float(info["residual"][i]),
            engines=n_engines,
            thrust_model=info["thrust_source"],
            method="trim at the thrust, flight-path angle solved",
        )
        out.append(
            Finding.compare(
                here, check, float(grads[i]), required, at_least=True, unit="gradient", reason=notes, **details
            )
        )
        out += control_findings(here, check.split(" ")[0], r, limits)
    return out


def wat_findings(
    ctx,
    conds,
    check: str,
    required: float,
    n_engines: int,
    speed_at,
    *,
    altitude_offset: float = 0.0,
    thrust_fraction=1.0,
    drag_credit: float = 0.0,
    notes: str = "",
    iterations: int = 5,
    declared: str = "takeoff_weight",
) -> list[Finding]:
    """The paragraph at every corner of the declared takeoff and landing envelope (none without one), at the
    conditions' weight and CGs; ``speed_at(condition, mass)`` gives the CAS flown at another weight, and the climb is
    ``altitude_offset`` above the airport (the ISA deviation kept). A corner whose lowest gradient is below the minimum
    is weight-limited (module docstring): its WAT limit weight is searched (at most ``iterations`` trims of all such
    corners at once) and the corner's finding becomes that limitation (:func:`_weight_limited`). Corners whose trim
    would be another's (a day colder than standard: flat-rated thrust, the same forces) share its trim."""
    env = ctx.aircraft.takeoff_landing_envelope
    if env is None:
        return []
    corners = [a for a in envelope_corners(env) if a.pressure_altitude != 0.0 or abs(a.delta_isa) > 1e-9]
    grid = [
        c.with_(altitude=a.pressure_altitude + altitude_offset, delta_isa_K=round(a.delta_isa, 3), airport=a.label())
        for a in corners
        for c in conds
    ]
    full = full_thrust(ctx, grid)[3]
    first: dict[tuple, int] = {}  # the corner nearest the standard day stands for those it equals
    for k in sorted(range(len(grid)), key=lambda k: abs(grid[k].get("delta_isa_K"))):
        c = grid[k]
        first.setdefault((c.mass, c.x_cg, c.configuration, c.altitude, c.speed, c.speed_kind, full[k]), k)
    same = [first[(c.mass, c.x_cg, c.configuration, c.altitude, c.speed, c.speed_kind, t)] for c, t in zip(grid, full)]
    trimmed = [grid[k] for k in sorted(set(same))]
    out = climb_findings(
        ctx,
        trimmed,
        f"{check}, WAT",
        required,
        n_engines,
        thrust_fraction=thrust_fraction,
        drag_credit=np.full(len(trimmed), drag_credit),
        notes=notes,
    )
    out = _weight_limited(ctx, out, check, required, speed_at, thrust_fraction, drag_credit, iterations)
    by_corner: dict[str, list[Finding]] = {}
    for f in out:
        by_corner.setdefault(f.condition.get("airport"), []).append(f)
    expanded = []
    for a in corners:
        label = a.label()
        twin = grid[same[next(k for k, c in enumerate(grid) if c.get("airport") == label)]]
        for f in by_corner.get(twin.get("airport"), []):
            if twin.get("airport") == label:
                expanded.append(f)
                continue
            copy = replace(
                f,
                condition=f.condition.with_(airport=label, delta_isa_K=round(a.delta_isa, 3)),
                details=dict(f.details),
            )
            copy.reason = "; ".join(
                x
                for x in (
                    f.reason,
                    f"the trim of {twin.get('airport')} (flat-rated thrust, "
                    "the same forces at this CAS and pressure altitude)",
                )
                if x
            )
            expanded.append(copy)
    return expanded + _declared_limits(
        ctx, conds, check, required, n_engines, speed_at, declared, altitude_offset, thrust_fraction, drag_credit, notes
    )


def _declared_limits(
    ctx, conds, check, required, n_engines, speed_at, declared, altitude_offset, thrust_fraction, drag_credit, notes
) -> list[Finding]:
    """The paragraph at each flight-manual WAT limit the envelope declares (``declared``: its ``takeoff_weight`` or
    ``landing_weight``), at its pressure altitude and temperature and the lower of that weight and the conditions'
    (the design weight), each CG moved inside the envelope: the declared limit complies only where the gradient is
    met there."""
    grid = []
    for w in ctx.aircraft.takeoff_landing_envelope.wat_limits:
        limit = getattr(w, declared)
        if limit is None:
            continue
        a = Ambient(w.pressure_altitude, w.temperature)
        for c in conds:
            at = at_mass(ctx, c, limit, lowest_operating_mass(ctx)[0], speed_at) if limit < c.mass else c
            grid.append(
                at.with_(
                    loading=f"declared WAT limit {limit / LB:,.0f} lb, {c.loading}",
                    altitude=a.pressure_altitude + altitude_offset,
                    delta_isa_K=round(a.delta_isa, 3),
                    airport=a.label(),
                )
            )
    if not grid:
        return []
    source = "; ".join(dict.fromkeys(w.source for w in ctx.aircraft.takeoff_landing_envelope.wat_limits if w.source))
    note = "; ".join(x for x in (notes, f"declared flight-manual WAT limit ({source or 'no source given'})") if x)
    return climb_findings(
        ctx,
        grid,
        f"{check}, declared WAT limit",
        required,
        n_engines,
        thrust_fraction=thrust_fraction,
        drag_credit=np.full(len(grid), drag_credit),
        notes=note,
    )


def lowest_operating_mass(ctx) -> tuple[float, str]:
    """The lowest weight the airplane is declared to fly at, and what it is: the CG envelope's lightest vertex (the
    loading envelope's minimum flight weight; §25.25(b))."""
    v = min(ctx.aircraft.cg_envelope.vertices, key=lambda v: v.mass)
    return v.mass, f"the CG envelope's lightest weight{f' ({v.name})' if v.name else ''}"


def _weight_limited(
    ctx, findings, check, required, speed_at, thrust_fraction, drag_credit, iterations
) -> list[Finding]:
    """Corners where a gradient at the design weight is below the minimum are weight–altitude–temperature limited
    (§25.1533(a)(1)/(2): the maximum takeoff and landing weights are those at which §25.121 is met, for altitudes and
    ambient temperatures). At such a corner the design-weight gradients become not applicable (the weight is above
    the corner's limit) and one finding states the limitation: value the WAT limit weight of the most unfavourable CG
    (kg), limit the lowest operating weight (:func:`lowest_operating_mass`), margin their difference; it fails when
    even that weight cannot meet the gradient. The trim at the limit weight adds its control findings."""
    worst: dict[str, Finding] = {}
    for f in findings:
        if f.unit == "gradient" and f.value is not None and f.value < required:
            key = f.condition.get("airport")
            if key not in worst or f.value < worst[key].value:
                worst[key] = f
    if not worst:
        return findings
    limited = _wat_limit_search(ctx, list(worst.values()), required, speed_at, thrust_fraction, drag_credit, iterations)
    lowest, what = lowest_operating_mass(ctx)
    limits = control_limits(ctx.aircraft)
    out = []
    for f in findings:
        key = f.condition.get("airport")
        if key in worst and f.unit == "gradient" and f.value is not None:
            f = Finding.not_applicable(
                f.condition,
                f.check,
                (
                    f"{f.condition.mass / LB:,.0f} lb is above this corner's WAT limit weight (set by the most "
                    "unfavourable "
                    f"CG, {worst[key].condition.loading}): gradient here {f.value:.2%} against {required:.1%}"
                ),
                gradient_at_design_weight=round(f.value, 6),
                **{k: v for k, v in f.details.items() if k != "hint"},
            )
        out.append(f)
    paragraph = check.split(" ")[0]
    for key, f in worst.items():
        cond, grad, trim, estimate = limited[key]
        here = cond.with_(loading=f"WAT limit, {f.condition.loading}")
        name = f"{check}, WAT limit weight"
        landing = paragraph == "(d)"
        where = f"{'landing' if landing else 'takeoff'} weight limited to {{:,.0f}} lb at {key} by §25.121{paragraph}"
        base = dict(
            lowest_operating_weight=what,
            design_weight_gradient=round(f.value, 6),
            most_unfavourable_cg=f.condition.loading,
        )
        if trim is not None and trim.converged and abs(grad - required) < WAT_GRADIENT_TOLERANCE:
            out.append(
                Finding.compare(
                    here,
                    name,
                    cond.mass,
                    lowest,
                    at_least=True,
                    unit="kg",
                    reason=(
                        where.format(cond.mass / LB)
                        + f": §25.1533(a)({2 if landing else 1}) — the AFM must carry this limit"
                    ),
                    wat_limit_mass_kg=round(cond.mass, 1),
                    wat_limit_speed_CAS_m_s=round(cond.speed, 3),
                    wat_limit_gradient=round(float(grad), 5),
                    **base,
                    **trim_details(trim),
                )
            )
            out += control_findings(here, paragraph, trim, limits)
        elif trim is not None and trim.converged and grad < required and cond.mass <= lowest * (1 + 1e-9):
            out.append(
                Finding.compare(
                    here,
                    name,
                    estimate,
                    lowest,
                    at_least=True,
                    unit="kg",
                    reason=(
                        f"no weight meets §25.121{paragraph} at {key}: at {what} ({lowest / LB:,.0f} lb) the gradient "
                        "is "
                        f"{grad:.2%} < {required:.1%}; the value is the weight extrapolated at constant CL from that "
                        "trim "
                        "(0 when none); the declared envelope includes a corner the airplane cannot operate at"
                    ),
                    gradient_at_lowest_weight=round(float(grad), 5),
                    **base,
                )
            )
        else:
            out.append(
                Finding.not_evaluated(
                    here,
                    name,
                    (
                        f"WAT limit weight not found at {key}: the trims between {what} and "
                        f"{f.condition.mass / LB:,.0f} lb "
                        f"did not converge to the minimum gradient (last {grad:.3%} at {cond.mass / LB:,.0f} lb)"
                    ),
                    **base,
                )
            )
    return out


def _wat_limit_search(ctx, failing, required, speed_at, thrust_fraction, drag_credit, iterations) -> dict:
    """corner → (condition at the last weight tried, its gradient, its trim, constant-CL weight estimate) for the
    findings ``failing`` (the lowest gradient of each corner):
    :func:`certkit_rules.part25.support.thrust_trims.wat_limit_search`."""
    found = wat_limit_search(
        ctx,
        [f.condition for f in failing],
        np.array([f.value for f in failing]),
        np.array([f.details["thrust_available_N"] for f in failing]),
        required,
        speed_at,
        lowest_operating_mass(ctx)[0],
        thrust_fraction=thrust_fraction,
        drag_credit=drag_credit,
        iterations=iterations,
        tolerance=WAT_GRADIENT_TOLERANCE,
    )
    return {f.condition.get("airport"): row for f, row in zip(failing, found)}


def refined(conds, speed: float, name: str, altitude: float = 0.0, configuration: str | None = None):
    return [
        c.with_(
            speed=speed,
            speed_kind="CAS",
            speed_name=name,
            altitude=altitude,
            **({"configuration": configuration} if configuration else {}),
        )
        for c in conds
    ]


WAT_MARGIN = (
    " At a weight-limited corner of the takeoff and landing envelope: its WAT limit weight − the CG envelope's "
    "lightest weight (kg)."
)

_COMMON_LIMITS = """
    Steady-state trim (no ground effect, no transient); the critical engine windmills with the flight model's
    windmilling drag (Torenbeek App. G form); weight not reduced by the fuel burned before the segment.
    Off-standard days: the standard-day trim at the pressure altitude and CAS with the day's thrust (Mattingly's
    lapse above the declared flat rating); the Reynolds-number change of drag with temperature is neglected. A
    corner whose gradient at the design weight is below the minimum is reported as its WAT limit weight (a
    flight-manual limitation, §25.1533(a)), found for the CG least favourable at the design weight; it fails only
    below the CG envelope's lightest weight. Declared flight-manual WAT limits (takeoff_landing_envelope.wat_limits)
    are checked at their own altitude and temperature, at the lower of the declared and the design weight.
"""


@rule
class ClimbOEITakeoffGearDown(Rule):
    id = "25.121(a)"
    offers = (ControlResponses((ControlCase("first segment gear down", "(a) "),)),)
    symbol = "oei-climb-takeoff-gear-down"
    title = "Climb OEI: takeoff, landing gear extended"
    amendment = AMDT
    requirement = """
        In the critical takeoff configuration along the flight path (gear extended), without ground effect, the
        steady climb gradient must be positive for two-engine airplanes (0.3 % three, 0.5 % four engines) at VLOF
        with the critical engine inoperative, the remaining engines at the thrust available when gear retraction
        begins, and the weight existing then.
    """
    margin = (
        "Steady OEI gradient − minimum (0 for twins), at VLOF (VR when VLOF is not declared); ≥ 0 complies."
        + WAT_MARGIN
    )
    references = ("25.107", "25.111", "25.121(b)")
    requires = ("speeds.VR", "configurations.takeoff")
    criteria = gradient_criteria("a", 0.0, 0.003, 0.005)
    conditions = ConditionSpace(
        loading=DesignWeight("MTOW", CGS),
        configurations=("takeoff",),
        note="sea level ISA, takeoff thrust; VLOF, or VR when VLOF is not declared; and the corners of the "
        "takeoff_landing_envelope when declared",
    )
    limitations = _COMMON_LIMITS + " VLOF ≈ VR when VLOF is not declared (a lower speed, so conservative)."

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        name = "VLOF" if ctx.aircraft.speeds.VLOF is not None else "VR"
        note = "" if name == "VLOF" else "VLOF not declared: evaluated at VR (VLOF ≥ VR)"
        conds = refined(conditions, declared_cas(ctx, name), name)
        out = climb_findings(ctx, conds, "(a) gradient at VLOF, gear down", required, n, notes=note)
        out += wat_findings(ctx, conds, "(a) gradient at VLOF, gear down", required, n, scaled_speed, notes=note)
        return [_positive(f, required) for f in out]

    def evidence(self, ctx, findings, crit):
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
        return credit, (
            f"declared ΔCD0 {cfg.delta_CD0:.4f} less the flap estimate {flaps:.4f} (Raymer 12.61), "
            f"capped at the gear increment {gear:.3f} (Roskam Part I Table 3.6)"
        )
    return gear, f"gear increment {gear:.3f} (Roskam Part I Table 3.6)"


@rule
class ClimbOEITakeoffGearUp(Rule):
    id = "25.121(b)"
    offers = (ControlResponses((ControlCase("second segment gear up", "(b) "),)),)
    symbol = "oei-climb-takeoff-gear-up"
    title = "Climb OEI: takeoff, landing gear retracted"
    amendment = AMDT
    requirement = """
        In the takeoff configuration with the landing gear retracted, without ground effect, the steady climb
        gradient at V2 may not be less than 2.4 % for two-engine airplanes (2.7 % three, 3.0 % four), with the
        critical engine inoperative and the remaining engines at takeoff thrust, at the weight when the gear is
        fully retracted; in non-icing and icing conditions.
    """
    margin = (
        "Steady OEI gradient at V2 − 0.024 (twins); each trim control's design limit − |deflection| (deg)." + WAT_MARGIN
    )
    references = ("25.107", "25.111", "25.121(a)")
    requires = ("speeds.V2", "configurations.takeoff")
    criteria = {
        **gradient_criteria("b)(1", 0.024, 0.027, 0.030),
        "configuration": Criterion(
            "takeoff",
            "",
            "14 CFR 25.121(b): the takeoff configuration",
            "configuration flown; its extended gear drag is removed (gear retracted)",
        ),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MTOW", CGS),
        configurations=("takeoff",),
        note="sea level ISA, takeoff thrust, V2; and the corners of the takeoff_landing_envelope when declared",
    )
    limitations = (
        _COMMON_LIMITS
        + """ The gear is retracted by removing its drag increment from the takeoff
        configuration's (see gear_up_credit); the gear's small pitching moment is kept. Icing (b)(2)(ii) is not
        evaluated."""
    )

    implementation = "partial"
    unevaluated = (("25.121(b)(2)(ii)", "icing conditions (takeoff ice accretion) not evaluated"),)

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        cfg = crit.configuration
        credit, how = gear_up_credit(ctx, cfg)
        conds = refined(conditions, declared_cas(ctx, "V2"), "V2", configuration=cfg)
        note = f"gear retracted: ΔCD0 {credit:.4f} removed, {how}"
        return climb_findings(
            ctx, conds, "(b) gradient at V2, gear up", required, n, drag_credit=np.full(len(conds), credit), notes=note
        ) + wat_findings(
            ctx, conds, "(b) gradient at V2, gear up", required, n, scaled_speed, drag_credit=credit, notes=note
        )

    def evidence(self, ctx, findings, crit):
        return climb_gradient_evidence(findings, "§25.121(b) OEI climb, takeoff, gear up")


@rule
class ClimbOEIFinalTakeoff(Rule):
    id = "25.121(c)"
    offers = (ControlResponses((ControlCase("final takeoff en route", "(c) "),)),)
    symbol = "oei-climb-final-takeoff"
    title = "Climb OEI: final takeoff"
    amendment = AMDT
    requirement = """
        In the en-route configuration at the end of the takeoff path (§25.111, at least 1500 ft), the steady
        climb gradient at VFTO may not be less than 1.2 % for two-engine airplanes (1.5 % three, 1.7 % four), with
        the critical engine inoperative and the remaining engines at maximum continuous thrust.
    """
    margin = (
        "Steady OEI gradient at VFTO − 0.012 (twins); each trim control's design limit − |deflection| (deg)."
        + WAT_MARGIN
    )
    references = ("25.111", "25.121(b)")
    requires = ("speeds.VFTO", "configurations.clean")
    criteria = {
        **gradient_criteria("c", 0.012, 0.015, 0.017),
        "mct_over_takeoff_thrust": Criterion(
            0.96,
            "",
            "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf at SL static",
            "maximum continuous over takeoff thrust, used when the engine model has one (takeoff) rating",
        ),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MTOW", CGS),
        configurations=("clean",),
        note="1500 ft (end of the takeoff path), ISA, maximum continuous thrust, VFTO; and "
        "1500 ft above each corner of the takeoff_landing_envelope when declared",
    )

    limitations = _COMMON_LIMITS

    implementation = "partial"
    unevaluated = (("25.121(c)(2)(ii)", "icing conditions (final takeoff ice accretion) not evaluated"),)

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        conds = refined(conditions, declared_cas(ctx, "VFTO"), "VFTO", altitude=1500 * FT)
        return climb_findings(
            ctx, conds, "(c) gradient at VFTO, en route", required, n, thrust_fraction=crit.mct_over_takeoff_thrust
        ) + wat_findings(
            ctx,
            conds,
            "(c) gradient at VFTO, en route",
            required,
            n,
            scaled_speed,
            altitude_offset=1500 * FT,
            thrust_fraction=crit.mct_over_takeoff_thrust,
        )

    def evidence(self, ctx, findings, crit):
        return climb_gradient_evidence(findings, "§25.121(c) OEI final takeoff climb")


@rule
class ClimbOEIApproach(Rule):
    id = "25.121(d)"
    offers = (ControlResponses((ControlCase("approach", "(d) "),)),)
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
    margin = (
        """Steady OEI gradient at 1.4 VSR(approach) − 0.021 (twins); 1.10 − VSR(approach)/VSR(landing);
        each trim control's design limit − |deflection| (deg)."""
        + WAT_MARGIN
    )
    references = ("25.103", "25.119", "25.125")
    requires = ("configurations.approach", "mass.MLW")
    criteria = {
        **gradient_criteria("d", 0.021, 0.024, 0.027),
        "speed_over_vsr": Criterion(1.4, "", "14 CFR 25.121(d)", "climb speed, at most this × VSR"),
        "vsr_ratio": Criterion(1.10, "", "14 CFR 25.121(d)", "VSR(approach) / VSR(landing), at most"),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MLW", CGS),
        configurations=("approach",),
        note="sea level ISA, go-around thrust (throttle 1), gear up, 1.4 VSR of the approach "
        "configuration; and the corners of the takeoff_landing_envelope when declared",
    )
    limitations = _COMMON_LIMITS + " Evaluated at 1.4 VSR, the largest speed allowed (no procedure speed is declared)."

    implementation = "partial"
    unevaluated = (("25.121(d)(2)(ii)", "icing conditions (approach ice accretion) not evaluated"),)

    def evaluate(self, ctx, conditions, crit):
        required, n = engine_count_criterion(ctx, crit, "gradient")
        out = []
        conds = []
        for c in conditions:
            vsr, src = reference_stall_speed(ctx, "approach", c.mass)
            conds.append(c.with_(speed=crit.speed_over_vsr * vsr, speed_kind="CAS", speed_name="1.4 VSR", altitude=0.0))
            if "landing" in ctx.aircraft.configurations and ctx.clmax("landing") is not None:
                vsr_l, _ = reference_stall_speed(ctx, "landing", c.mass)
                out.append(
                    Finding.compare(
                        conds[-1],
                        "(d) VSR approach ≤ 1.10 VSR landing",
                        vsr / vsr_l,
                        crit.vsr_ratio,
                        at_least=False,
                        unit="ratio",
                        VSR_approach=vsr,
                        VSR_landing=vsr_l,
                        basis=src,
                    )
                )
        at_mass = lambda c, m: crit.speed_over_vsr * reference_stall_speed(ctx, "approach", m)[0]  # noqa: E731
        return (
            out
            + climb_findings(ctx, conds, "(d) gradient at ≤ 1.4 VSR, approach", required, n)
            + wat_findings(
                ctx, conds, "(d) gradient at ≤ 1.4 VSR, approach", required, n, at_mass, declared="landing_weight"
            )
        )

    def evidence(self, ctx, findings, crit):
        return climb_gradient_evidence(findings, "§25.121(d) OEI approach climb")

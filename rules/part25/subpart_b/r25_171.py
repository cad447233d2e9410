"""§§25.171–25.175 Static longitudinal stability, and the speed ranges shared by the stability rules.

Shared helpers (used by §§25.147, 25.149, 25.177, 25.181 too): the reference stall speed VSR of a
configuration at a weight (1-g stall from the declared CLmax, §25.103(a)), the maximum allowable speed
of a configuration (VMO/MMO clean; VFE, and VLE with the gear down), and the refinement of a scheduled
condition's ``speed_point`` into a calibrated airspeed.
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from certkit.atmosphere import convert_speed
from certkit_rules.part25.subpart_b.r25_103 import reference_stall_speed

#: certkit configuration of each flight phase the stability paragraphs name
PHASES = {"takeoff": "takeoff", "cruise": "clean", "landing": "landing"}
SPEED_POINTS = ("1.13 VSR", "mid", "max allowable")


def vsr_cas(ctx, configuration: str, mass: float, h: float = 0.0) -> float:
    """Reference stall speed (m/s CAS) of ``configuration`` at ``mass`` at altitude ``h``: §25.103's VSR
    (declared, or the 1-g stall speed from the declared CLmax), as :mod:`r25_103` defines it for Subpart B."""
    eas, _ = reference_stall_speed(ctx, configuration, mass)
    return float(convert_speed(eas, "EAS", "CAS", h))


def max_allowable_cas(ctx, configuration: str, h: float = 0.0) -> float:
    """Maximum allowable speed of the configuration (m/s CAS): VMO/MMO clean; VFE of the flap setting, and
    VLE when the gear is down."""
    sp = ctx.aircraft.speeds
    cfg = ctx.aircraft.configurations[configuration]
    limits = []
    if configuration in sp.VFE:
        limits.append(float(convert_speed(sp.VFE[configuration].value, sp.VFE[configuration].kind, "CAS", h)))
    if getattr(cfg, "gear", None) == "down" and sp.VLE is not None:
        limits.append(float(convert_speed(sp.VLE.value, sp.VLE.kind, "CAS", h)))
    if not limits:
        vmo, _ = ctx.design_speed_eas("VMO", h)
        limits.append(float(convert_speed(float(vmo), "EAS", "CAS", h)))
    return min(limits)


def speed_at_point(ctx, cond, point: str, low_factor: float = 1.13) -> tuple[float, float, float]:
    """(speed, low, high) m/s CAS of ``point`` ("1.13 VSR" = the low end, "mid", "max allowable", or a
    multiple "1.3 VSR") for the condition."""
    h = cond.altitude or 0.0
    low = low_factor * vsr_cas(ctx, cond.configuration, cond.mass, h)
    high = max_allowable_cas(ctx, cond.configuration, h)
    named = {"1.13 VSR": low, "mid": 0.5 * (low + high), "max allowable": high}
    v = named[point] if point in named else float(point.split()[0]) * low / low_factor  # "1.3 VSR"
    return v, low, high


def by_configuration(conditions) -> dict[str, list[int]]:
    """Indices of the conditions grouped by configuration (one trim batch each)."""
    groups: dict[str, list[int]] = defaultdict(list)
    for i, c in enumerate(conditions):
        groups[c.configuration].append(i)
    return groups


def static_margin(ctx, configuration: str, x_cg, mach) -> np.ndarray:
    """Stick-fixed static margin (fraction of MAC): (x_np − x_cg)/c with the neutral point
    x_np = x_ref − c·Cm_α/CL_α of the configuration's model (airplane frame, X aft)."""
    m = ctx.aero(configuration).model
    ref = m.reference
    x_np = ref.x_ref - ref.chord * m.derivative("Cm_alpha", mach) / m.derivative("CL_alpha", mach)
    return (x_np - np.asarray(x_cg)) / ref.chord


FLAP_ALTITUDE_SOURCE = ("project choice: flaps and gear are not extended above 20,000 ft (Boeing 777 FCOM limitation, "
                        "the baseline's class); flap configurations are evaluated below it")


def refine_speeds(ctx, conditions, flap_altitude_max: float, low_factor: float = 1.13, check: str = "speed range"):
    """Each condition refined to the CAS of its ``speed_point`` (the ``extra`` axis), or a not-applicable
    finding for a flap/gear configuration above ``flap_altitude_max`` (m). Returns (refined, findings)."""
    from certkit.results import Finding

    refined, findings = [], []
    for cond in conditions:
        cfg = ctx.aircraft.configurations[cond.configuration]
        extended = cond.configuration != "clean" and (getattr(cfg, "flap", 0) or getattr(cfg, "gear", "up") == "down")
        if extended and (cond.altitude or 0.0) > flap_altitude_max + 1e-6:
            findings.append(Finding.not_applicable(cond, check, f"{cond.configuration} configuration above "
                                                   f"{flap_altitude_max / 0.3048:,.0f} ft (flap altitude limit)"))
            continue
        v, _, _ = speed_at_point(ctx, cond, cond.get("speed_point", "mid"), low_factor)
        refined.append(cond.with_(speed=v, speed_kind="CAS"))
    return refined, findings


# --- rules -----------------------------------------------------------------------------------

from certkit.conditions import Altitudes, CgCorners, ConditionSpace, speed_as  # noqa: E402
from certkit.registry import Criterion, Rule, rule  # noqa: E402
from certkit.results import Finding  # noqa: E402
from certkit.units import FT, KN  # noqa: E402

UNVERIFIED = "§§25.171–25.175 wording from memory (docs/regulation-notes.md marks them unverified)"
_STABILITY_SPACE = dict(loading=CgCorners(), configurations=tuple(PHASES.values()), altitudes=Altitudes((0.0, 35000 * FT)))
_FLAP_ALT = Criterion(6096.0, "m", FLAP_ALTITUDE_SOURCE, "highest altitude of flap configurations")


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
        "static_margin_min": Criterion(0.05, "MAC", "project choice: Raymer, Aircraft Design: A Conceptual Approach "
                                       "(6th ed.), §16.3 — transports typically 5 to 10 % MAC stick-fixed; the lower "
                                       "end is the minimum (Part 25 states no number)",
                                       "minimum stick-fixed static margin"),
        "low_speed_factor": Criterion(1.13, "", "§25.177 / §25.181 speed range from 1.13 VSR", "low end of the speeds"),
        "flap_altitude_max": _FLAP_ALT,
    }
    conditions = ConditionSpace(**_STABILITY_SPACE, extra=(("speed_point", ("1.13 VSR", "max allowable")),),
                                note="Neutral point x_np = x_ref − c·Cm_α/CL_α of the configuration's model at the Mach number.")
    limitations = "Stick-fixed only (no hinge-moment model for the stick-free neutral point); rigid airplane."

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "static margin")
        for cond in refined:
            mach = speed_as(cond, "MACH")
            sm = float(static_margin(ctx, cond.configuration, cond.x_cg, mach))
            out.append(Finding.compare(cond, "stick-fixed static margin ≥ minimum", sm, crit.static_margin_min,
                                       at_least=True, unit="MAC", mach=round(float(mach), 4)))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.report.evidence_stability import margin_matrix_evidence

        return margin_matrix_evidence(findings, "§25.171 static margin − minimum (normalised) over CG corners × configurations")


def trims_at_throttle(ctx, conds, throttle, gammas=(0.0, 0.02), **trim_args):
    """Trims of ``conds`` with the throttle held at ``throttle`` (one value per condition): the flight-path angle
    is found by a secant step between two probe trims at ``gammas`` (throttle is nearly linear in sin γ,
    T = D + W sin γ; the probes must need less than full throttle). Returns the final trim results."""
    t = np.asarray(throttle, dtype=float)
    th = lambda res: np.array([r.controls[next(k for k in r.controls if k.startswith("throttle"))] for r in res])  # noqa: E731
    g0, g1 = gammas
    t0 = th(ctx.trim(conds, gamma=g0, **trim_args).results)
    t1 = th(ctx.trim(conds, gamma=g1, **trim_args).results)
    slope = np.where(np.abs(t1 - t0) > 1e-9, (t1 - t0) / (g1 - g0), np.inf)
    gamma = np.clip(g0 + (t - t0) / slope, -0.3, 0.3)
    return ctx.trim(conds, gamma=gamma, **trim_args).results


@rule
class SpeedStability(Rule):
    id = "25.173(a)"
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
        "gradient_min": Criterion(0.0, "deg/kt", "§25.173(a) stable sense (" + UNVERIFIED + ")",
                                  "smallest elevator-per-speed gradient (> 0 stable)"),
        "speed_step": Criterion(0.05, "", "project choice: ±5 % about the trim speed, inside the §25.175 ranges",
                                "relative speed step of the central difference"),
        "low_speed_factor": Criterion(1.13, "", "§25.181 speed range from 1.13 VSR", "low end of the speeds"),
        "flap_altitude_max": _FLAP_ALT,
    }
    conditions = ConditionSpace(**_STABILITY_SPACE, extra=(("speed_point", ("1.3 VSR", "max allowable")),),
                                note="Trim speeds 1.3 VSR (§25.175 climb, approach and landing trims) and the "
                                     "configuration's maximum allowable speed (cruise up to VMO).")
    limitations = """
        Elevator-fixed reading of a stick-force requirement (§25.173(c) needs a control-force model); trim in level
        flight at the power for level flight, not the §25.175 climb power or idle-power landing; the free-return
        (§25.173(b)) is not simulated.
    """

    def evaluate(self, ctx, conditions, crit):
        refined, out = refine_speeds(ctx, conditions, crit.flap_altitude_max, crit.low_speed_factor, "(a) speed stability")
        k = crit.speed_step
        for config, idx in by_configuration(refined).items():
            conds = [refined[i] for i in idx]
            trim0 = ctx.trim(conds).results
            t0 = [next(v for n, v in r.controls.items() if n.startswith("throttle")) for r in trim0]
            side = [c.with_(speed=c.speed * (1 - k)) for c in conds] + [c.with_(speed=c.speed * (1 + k)) for c in conds]
            res = trims_at_throttle(ctx, side, t0 + t0)
            n = len(conds)
            for i, cond in enumerate(conds):
                lo, hi = res[i], res[n + i]
                check = "(a) elevator-fixed speed stability dδe/dV > 0"
                bad = [r for r in (trim0[i], lo, hi) if not r.converged]
                if bad:
                    out.append(Finding.not_evaluated(cond, check, "trim did not converge: "
                                                     + "; ".join(e.message for r in bad for e in r.limits_exceeded)))
                    continue
                dv = 2 * k * cond.speed / KN
                grad = np.degrees(hi.controls["elevator"] - lo.controls["elevator"]) / dv
                reason = "; ".join(e.message for r in (trim0[i], lo, hi) for e in r.limits_exceeded if e.control == "elevator")
                out.append(Finding.compare(cond, check, float(grad), crit.gradient_min, at_least=True, unit="deg/kt",
                                           reason=reason, elevator_trim_deg=float(np.degrees(trim0[i].controls["elevator"])),
                                           throttle=float(t0[i]), gamma_low_deg=float(np.degrees(lo.gamma)),
                                           gamma_high_deg=float(np.degrees(hi.gamma))))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.report.evidence_stability import margin_matrix_evidence

        return margin_matrix_evidence(findings, "§25.173(a) speed-stability gradient (normalised) over CG corners × configurations")


@rule
class StickForceGradient(Rule):
    id = "25.173(c)"
    symbol = "stick-force-speed-gradient"
    title = "Static longitudinal stability: stick-force gradient"
    amendment = "25-7"
    requirement = """
        The average gradient of the stable slope of the stick force versus speed curve may not be less than 1 pound
        for each 6 knots, under the conditions of §25.175.
    """
    margin = "average stick-force gradient − 1 lbf / 6 kt (lbf per kt), when a control-force model is declared."
    references = ("25.173(a)", "25.175")
    criteria = {"force_gradient_min": Criterion(1.0 / 6.0, "lbf/kt", "§25.173(c): 1 pound for each 6 knots (" + UNVERIFIED + ")",
                                                "smallest average stick-force gradient")}
    conditions = ConditionSpace(note="Needs a control-force model (hinge moments, gearing, feel system).")
    implementation = "partial"
    limitations = "The aircraft-file schema has no control-force model yet; the rule reports not_evaluated until it has."

    def evaluate(self, ctx, conditions, crit):
        return [Finding.not_evaluated(c, "(c) stick-force gradient ≥ 1 lbf per 6 kt",
                                      "needs a control-force model (elevator hinge moments, gearing, feel system): the "
                                      "aircraft file declares none; the elevator-fixed gradient is checked by §25.173(a)")
                for c in conditions]

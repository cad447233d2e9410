"""§25.161 Trim — longitudinal trim in climb, glide/approach and level flight; trim with an engine out.

Text (docs/regulation-notes.md): (a), (b), (c)(1), the start of (c)(2) and the end of (d) verified against
the GPO print [CFR 1-1-14 p. 389, 1-1-24 p. 225]; the rest of (c)(2) and (c)(3) from memory. certkit trims
every CG corner in each case (one batch per configuration) and checks that the trim is reached with the
controls within their design range. Without a movable stabiliser the stabiliser is fixed at its declared
setting and the elevator carries it all; with one (``geometry.horizontal_tail.stabilizer``) each trim solves for
the stabiliser with the elevator at its trim setting and the trim authority is reported as the stabiliser's margin to
its configuration's trim limit (a trim needing more has the stabiliser at its stop and the elevator holding the rest —
not trimmed):

    (c)(1) climb, maximum continuous thrust, 1.3 VSR1, gear up, flaps (i) retracted and (ii) takeoff;
    (c)(2) glide with power off (idle) at 1.3 VSR1, flaps retracted; and the approach alternative on a
           3° glidepath at 1.3 VSR in each declared approach/landing configuration with the gear down;
    (c)(3) level flight at 1.3 VSR1 and at VMO/MMO (sea level and the cruise altitude), gear and flaps up —
           where a weight cannot fly level there (more than full thrust), the steady descent at full thrust, named;
    (d)    climb at 1.3 VSR1 with the critical engine inoperative, the other at maximum continuous thrust,
           gear and flaps up, bank ≤ 5°: elevator, aileron and rudder within range and the bank within 5°.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
from certkit_rules.part25.support.control_checks import control_findings, trim_details
from certkit_rules.part25.support.reference_speeds import reference_stall_speed
from certkit_rules.part25.support.stability_speeds import flight_described, steady_flight_trims
from certkit_rules.part25.support.thrust_trims import oei_climb

from certkit.engine.conditions import CgCorners, ConditionSpace
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.flight import control_limits
from certkit.units import FT


def stabilizer_finding(cond, check, r, stabilizer) -> Finding:
    """Trim authority of a movable stabiliser: the incidence the trim needs (elevator at its trim setting) against
    the trim limit of the condition's configuration on the side of the nearer stop (deg); negative: beyond the stop,
    the elevator holding the rest. The details name the limits that applied."""
    lim, basis = stabilizer.trim_limits(cond.configuration)
    lo, hi = lim.min, lim.max
    need = r.stabilizer_required
    nose_up = need < 0.5 * (lo + hi)
    reason = (
        f"the stabiliser is at its {r.stabilizer_at_stop} stop ({math.degrees(r.stabilizer):.2f}°); it would need "
        f"{math.degrees(need):.2f}°, the elevator holds the rest at {math.degrees(r.controls['elevator']):.2f}°"
        if r.stabilizer_at_stop
        else ""
    )
    return Finding.compare(
        cond,
        f"{check} stabiliser within its trim limits",
        math.degrees(need),
        math.degrees(lo if nose_up else hi),
        at_least=nose_up,
        unit="deg",
        reason=reason,
        stabilizer_deg=round(math.degrees(r.stabilizer), 3),
        side="nose-up" if nose_up else "nose-down",
        trim_limits=f"stabilizer.{basis}: {math.degrees(lo):.2f}° to {math.degrees(hi):.2f}°",
    )


SEGMENTS = ("climb", "glide", "level", "engine-out climb")


@rule
class Trim(Rule):
    id = "25.161"
    symbol = "longitudinal-trim"
    title = "Trim"
    amendment = "25-108"
    requirement = """
        After being trimmed, and without further pressure on or movement of the primary or trim controls, the
        airplane must maintain longitudinal trim (c)(1) in a climb with maximum continuous power at a speed not
        more than 1.3 VSR1, gear retracted, flaps retracted and in the takeoff position; (c)(2) in a glide with
        power off at not more than 1.3 VSR1, or an approach on a 3° glidepath with the gear extended, whichever is
        the most severe; (c)(3) in level flight from 1.3 VSR1 to VMO/MMO; and (d) longitudinal, directional and
        lateral trim (bank not more than 5°) at 1.3 VSR1 in a climb with the critical engine inoperative, the
        others at maximum continuous power, gear and flaps retracted. Trim is shown with the controls within
        their design range at each CG corner.
    """
    margin = (
        "Control design limit − |trim deflection| on the side it is deflected (deg), at every CG corner and case; "
        "for (d) also 5° − |bank| (deg); with a movable stabiliser also the stabiliser incidence the trim needs "
        "to its configuration's trim limit on the nearer side (deg)."
    )
    references = ("25.103", "25.121", "25.335(a)")
    requires = ("configurations.clean",)
    criteria = {
        "climb_speed_over_vsr": Criterion(
            1.3, "", "14 CFR 25.161(c)(1), (d)", "climb speed, × VSR1 of the configuration"
        ),
        "glide_speed_over_vsr": Criterion(
            1.3, "", "14 CFR 25.161(c)(2)", "glide and approach speed, × VSR of the configuration"
        ),
        "glide_path_deg": Criterion(
            -3.0,
            "deg",
            "14 CFR 25.161(c)(2) (3° glidepath; wording unverified)",
            "flight-path angle of the approach alternative",
        ),
        "idle_throttle": Criterion(
            0.0,
            "",
            "14 CFR 25.161(c)(2) 'power off': flight idle of the engine model",
            "throttle of the power-off glide",
        ),
        "level_speed_low_over_vsr": Criterion(
            1.3, "", "14 CFR 25.161(b), (c)(3)", "low end of the level-flight trim range, × VSR1"
        ),
        "cruise_altitude_ft": Criterion(
            35000.0,
            "ft",
            "level-flight range flown at sea level and at a typical cruise altitude",
            "cruise altitude of the level-flight cases",
        ),
        "max_bank_deg": Criterion(5.0, "deg", "14 CFR 25.161(d)", "largest bank of the engine-out climb trim"),
        "mct_over_takeoff_thrust": Criterion(
            0.96,
            "",
            "FAA TCDS E00049EN, GE90-90B: maximum continuous 90,580 lbf / takeoff 94,000 lbf",
            "maximum continuous over takeoff thrust of the engine model",
        ),
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        extra=(("case", SEGMENTS),),
        note="climb: clean and takeoff flaps, MCT, 1.3 VSR1; glide: clean, idle, 1.3 VSR1, and each "
        "approach/landing configuration on −3° at 1.3 VSR; level: clean at 1.3 VSR1 and VMO/MMO, sea "
        "level and the cruise altitude; engine-out climb: clean, 1.3 VSR1, critical engine out, MCT",
    )
    implementation = "partial"
    limitations = """
        §25.161(b) lateral/directional trim with a lateral CG offset is not evaluated (the model's CG is on the plane
        of symmetry; a symmetric airplane trims with zero lateral controls), nor (c)(3)'s gear-down range to VLE (no
        gear-down clean configuration is declared) or (e) (four or more engines). Control forces (the 5 lbf of (d))
        need a control-force model. Without a movable stabiliser (geometry.horizontal_tail.stabilizer) the stabiliser
        is fixed at its declared incidence and the elevator carries the whole trim; with one, each trim is solved within
        its configuration's trim limits (stabilizer.design_limits_by_configuration where declared, else
        stabilizer.design_limits), named in each stabiliser finding's details (trim_limits).
    """

    unevaluated = (
        (
            "25.161(b)",
            "lateral and directional trim with a lateral CG offset is not evaluated (the CG is on the "
            "plane of symmetry)",
        ),
        (
            "25.161(c)(3)",
            "the gear-down level-flight range to VLE is not evaluated (no gear-down clean configuration declared)",
        ),
        ("25.161(d)", "the 5 lbf control force of (d) needs a control-force model: not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        cases = {k: [c for c in conditions if c.get("case") == k] for k in SEGMENTS}
        configs = ctx.aircraft.configurations
        vsr = lambda config, c: reference_stall_speed(ctx, config, c.mass)[0]  # noqa: E731
        for config in ("clean", "takeoff"):
            if not cases["climb"]:
                break
            if config not in configs:
                out += [
                    Finding.not_evaluated(
                        c.with_(configuration=config), "(c)(1) climb", f"needs configurations.{config}"
                    )
                    for c in cases["climb"]
                ]
                continue
            conds = [
                c.with_(
                    configuration=config,
                    altitude=0.0,
                    speed_kind="CAS",
                    speed_name="1.3 VSR1",
                    speed=crit.climb_speed_over_vsr * vsr(config, c),
                    thrust="maximum continuous",
                )
                for c in cases["climb"]
            ]
            grads, batch, _ = oei_climb(ctx, conds, crit.mct_over_takeoff_thrust, engine_out=False)
            out += self._controls(ctx, conds, batch, f"(c)(1) climb, {config}", ("elevator",), gradients=grads)
        if cases["glide"]:
            conds = [
                c.with_(
                    configuration="clean",
                    altitude=0.0,
                    speed_kind="CAS",
                    speed_name="1.3 VSR1",
                    speed=crit.glide_speed_over_vsr * vsr("clean", c),
                    thrust="power off (idle)",
                )
                for c in cases["glide"]
            ]
            batch = ctx.trim(conds, kind="straight", gamma=math.radians(-3.0), throttle=crit.idle_throttle)
            out += self._controls(ctx, conds, batch, "(c)(2) power-off glide", ("elevator",))
            approach = [k for k in ("approach", "landing") if k in configs and configs[k].gear == "down"]
            if not approach:
                out += [
                    Finding.not_evaluated(
                        c, "(c)(2) approach", "needs an approach or landing configuration with the gear down"
                    )
                    for c in cases["glide"]
                ]
            for config in approach:
                conds = [
                    c.with_(
                        configuration=config,
                        altitude=0.0,
                        speed_kind="CAS",
                        speed_name="1.3 VSR",
                        speed=crit.glide_speed_over_vsr * vsr(config, c),
                        thrust="for the 3° path",
                    )
                    for c in cases["glide"]
                ]
                batch = ctx.trim(conds, kind="straight", gamma=math.radians(crit.glide_path_deg))
                out += self._controls(ctx, conds, batch, f"(c)(2) 3° approach, {config}", ("elevator",))
        if cases["level"]:
            top = "VMO" if ctx.aircraft.speeds.VMO is not None or ctx.aircraft.speeds.MMO is not None else "VC"
            conds = []
            for h in (0.0, crit.cruise_altitude_ft * FT):
                v, mach_limited = ctx.design_speed_eas(top, h)
                top_name = {"VMO": "MMO", "VC": "MC"}[top] if bool(mach_limited) else top
                conds += [
                    c.with_(
                        configuration="clean",
                        altitude=h,
                        speed=float(v),
                        speed_kind="EAS",
                        speed_name=top_name,
                        thrust="for level flight",
                    )
                    for c in cases["level"]
                ]
                conds += [
                    c.with_(
                        configuration="clean",
                        altitude=h,
                        speed_kind="CAS",
                        speed_name="1.3 VSR1",
                        speed=crit.level_speed_low_over_vsr * vsr("clean", c),
                        thrust="for level flight",
                    )
                    for c in cases["level"]
                ]
            # beyond a weight's level-flight ceiling (MRW at the cruise altitude and 1.3 VSR1) the trim of the steady
            # descent at full thrust, the flight nearest to level the airplane can hold there, named in the finding
            results, stops = steady_flight_trims(ctx, conds)
            flights = [flight_described(r, stop) for r, stop in zip(results, stops)]
            out += self._controls(
                ctx, conds, SimpleNamespace(results=results), "(c)(3) level flight", ("elevator",), flights=flights
            )
        if cases["engine-out climb"]:
            conds = [
                c.with_(
                    configuration="clean",
                    altitude=0.0,
                    speed_kind="CAS",
                    speed_name="1.3 VSR1",
                    speed=crit.climb_speed_over_vsr * vsr("clean", c),
                )
                for c in cases["engine-out climb"]
            ]
            out += self._engine_out(ctx, conds, crit)
        return out

    def _engine_out(self, ctx, conds, crit):
        """(d): the zero-sideslip climb trim; where it needs more than 5° of bank, the trim at 5° bank toward the
        live engine (the sideslip results) at the same flight path — the paragraph lets the pilot choose."""
        grads, batch, info = oei_climb(ctx, conds, crit.mct_over_takeoff_thrust, engine_out=True)
        conds = [
            c.with_(thrust=f"critical engine ({info['inoperative']}) inoperative, maximum continuous on the other")
            for c in conds
        ]
        results = list(batch.results)
        zero_sideslip_bank = [math.degrees(r.phi) for r in results]
        bank_max = math.radians(crit.max_bank_deg)
        steep = [i for i, r in enumerate(results) if r.converged and abs(r.phi) > bank_max]
        if steep:
            sub = [conds[i] for i in steep]
            again = ctx.trim(
                sub,
                kind="oei",
                bank=[math.copysign(bank_max, results[i].phi) for i in steep],
                gamma=[results[i].gamma for i in steep],
                inoperative=info["inoperative"],
            )
            for k, i in enumerate(steep):
                results[i] = again.results[k]
        batch = type(batch)(model=batch.model, x=batch.x, u=batch.u, results=results)
        out = self._controls(
            ctx, conds, batch, "(d) engine-out climb", ("elevator", "aileron", "rudder"), gradients=grads
        )
        for i, cond in enumerate(conds):
            r = results[i]
            if r.converged:
                out.append(
                    Finding.compare(
                        cond,
                        "(d) engine-out climb bank within 5°",
                        abs(math.degrees(r.phi)),
                        crit.max_bank_deg,
                        at_least=False,
                        unit="deg",
                        zero_sideslip_bank_deg=round(zero_sideslip_bank[i], 3),
                        **trim_details(r),
                    )
                )
        return out

    @staticmethod
    def _controls(ctx, conds, batch, check, controls, gradients=None, flights=None):
        """The trim findings of one batch (one configuration), against that configuration's design limits;
        ``flights``: the steady flight each was trimmed in, where it is not the condition's own (a detail)."""
        out = []
        limits = control_limits(ctx.aircraft, configuration=conds[0].configuration) if conds else {}
        for i, cond in enumerate(conds):
            r = batch.results[i]
            if not r.converged:
                out.append(
                    Finding.not_evaluated(
                        cond,
                        f"{check} trim",
                        f"trim did not converge (residual {r.residual_norm:.1e}); "
                        + "; ".join(m.message for m in r.limits_exceeded),
                    )
                )
                continue
            found = control_findings(cond, check, r, limits)
            if r.stabilizer is not None:
                found.append(stabilizer_finding(cond, check, r, ctx.aircraft.geometry.horizontal_tail.stabilizer))
            for f in found:
                if any(name in f.check for name in controls + ("stabiliser",)):
                    f.details.update(trim_details(r))
                    f.details["flight_path_deg"] = round(math.degrees(r.gamma), 3)
                    if gradients is not None:
                        f.details["climb_gradient"] = float(np.asarray(gradients)[i])
                    if flights is not None:
                        f.details["flight"] = flights[i]
                    out.append(f)
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.161 trim",
            "Trims of each §25.161 condition: controls against their design limits (a movable "
            "stabiliser against its configuration's trim limits).",
            ("climb_gradient", "alpha_deg", "elevator_deg", "aileron_deg", "rudder_deg"),
        )

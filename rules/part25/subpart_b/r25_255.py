"""§25.255 Out-of-trim characteristics.

Text ([CFR 2003] §25.255, GPO; (a)–(c) read, (f) from memory): from the airplane trimmed at cruise speeds up to
VMO/MMO, satisfactory manoeuvring stability and controllability with the out-of-trim, nose up and nose down, of the
greater of (a)(1) a three-second movement of the longitudinal trim system at its normal rate (except as limited by
the trim system's stops) or (a)(2) the largest mistrim the autopilot can sustain in level high-speed cruise. In that
out-of-trim condition, with the normal acceleration varied from +1 g over −1 g to +2.5 g (or 0 g to 2.0 g and
extrapolated, (c)), (b)(1) the stick force vs g curve must have a positive slope up to VFC/MFC and (b)(2) between
VFC/MFC and VDF/MDF the longitudinal control force may not reverse; (f) from an overspeed at VDF/MDF at least
1.5 g must be produced for recovery with no more than 125 lbf.

certkit's reading, per CG corner and altitude: trim at VMO/MMO with the movable stabiliser (elevator at its trim
setting) in level flight, or where that needs more than full thrust in the steady descent at full thrust (the flight
path in the condition: the speed is reached as in the flight test, descending), move the stabiliser by the rate × 3 s
nose up and nose down (within its trim limits) and hold it; at VFC/MFC and VDF/MDF (thrust held at the trim), solve
the instantaneous symmetric pull-up to 1.5 g and push-over to 0 g for the elevator
(:func:`certkit.models.dynamics.pull_up.symmetric_pull_up`). Checks: the elevator within
its design limits (control margin), and the elevator-fixed sense of (b): more trailing-edge-up elevator to pull,
more trailing-edge-down to push (a positive elevator-per-g slope; no reversal). With control_forces.elevator the
stick force itself (zero at the original trim, pull positive) must rise with g from 0 g through 1 g to 1.5 g
((b)(1) positive slope, (b)(2) no reversal), and the pull holding 1.5 g at VDF/MDF may not exceed 125 lbf ((f));
without one the force checks are not evaluated.
"""

from __future__ import annotations

import math

import numpy as np
from certkit_rules.part25.support.stability_speeds import steady_flight_trims

from certkit.atmosphere import convert_speed, speed_of_sound
from certkit.engine.conditions import Altitudes, CgCorners, ConditionSpace
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model, dynamic_pressure, local_angle
from certkit.models.dynamics.pull_up import symmetric_pull_up
from certkit.models.flight import control_limits
from certkit.units import FT, KN, LBF

SOURCE = "14 CFR 25.255 ([CFR 2003] GPO text of (a)-(c); (f) from memory, docs/regulation-notes.md)"
_NO_FORCE = (
    "no control-force model (control_forces.elevator: hinge moments and gearing, or artificial feel): the "
    "stick force is not computed; the elevator-fixed sense and the control margin are checked instead"
)


def test_speeds(ctx, h: float) -> dict[str, float]:
    """VFC/MFC (declared, else midway between VMO/MMO and VD/MD as §25.253(b) allows at least) and VDF/MDF (taken as
    VD/MD, which it may not exceed), m/s EAS at altitude ``h``."""
    sp = ctx.aircraft.speeds
    vd, _ = ctx.design_speed_eas("VD", h)
    if sp.VFC is not None or sp.MFC is not None:
        vfc, _ = ctx.design_speed_eas("VFC", h)
    else:
        vmo, _ = ctx.design_speed_eas("VMO", h)
        vfc = 0.5 * (vmo + vd)
    return {"VFC/MFC": float(vfc), "VDF/MDF": float(vd)}


@rule
class OutOfTrim(Rule):
    id = "25.255"
    symbol = "out-of-trim-characteristics"
    title = "Out-of-trim characteristics"
    amendment = "25-42"
    requirement = """
        From the airplane trimmed at cruise speeds up to VMO/MMO and mistrimmed nose up and nose down by three
        seconds of trim-system movement at its normal rate (or the autopilot's largest sustainable mistrim), the
        stick force per g must be positive up to VFC/MFC and may not reverse between VFC/MFC and VDF/MDF over the
        load factors of (c), and 1.5 g must be reachable for recovery at VDF/MDF with at most 125 lbf (f).
    """
    margin = """Elevator design limit on the deflected side − |elevator| for the 1.5 g pull and the 0 g push (deg);
        the elevator change from 1 g in the right sense (deg, ≥ 0); with control_forces.elevator the pull-force change
        from 0 g to 1 g and from 1 g to 1.5 g (lbf, > 0) and 125 lbf − the pull holding 1.5 g at VDF/MDF."""
    references = ("25.253", "25.161", "25.655")
    requires = ("configurations.clean", "speeds.VMO", "speeds.VD")
    criteria = {
        "mistrim_seconds": Criterion(3.0, "s", SOURCE + " (a)(1)", "trim-system movement time at its normal rate"),
        "pull_load_factor": Criterion(
            1.5, "", SOURCE + " (c)(2) range 0 to 2.0 g; (f) 1.5 g recovery", "load factor of the pull-up"
        ),
        "push_load_factor": Criterion(0.0, "", SOURCE + " (c)(2) range 0 to 2.0 g", "load factor of the push-over"),
        "recovery_force_lbf": Criterion(
            125.0, "lbf", SOURCE + " (f)", "largest force for the 1.5 g recovery at VDF/MDF"
        ),
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=Altitudes((0.0, 35000 * FT)),
        note="clean, trimmed level at VMO/MMO at sea level and 35,000 ft, every CG corner",
    )
    implementation = "partial"
    limitations = """
        Steady manoeuvre points (instantaneous pull-up / push-over, the speed not held), not the flight-test dive;
        1.5 g and 0 g of the (c)(2) range, not the extrapolation to −1 g and 2.5 g; thrust held at the VMO/MMO trim
        (level, or the steady descent at full thrust where level flight at VMO/MMO needs more).
        The (a)(2) autopilot mistrim is not modelled (needs the autopilot's authority); without a declared trim rate
        the mistrim is not known and nothing is evaluated. Stick forces need control_forces.elevator.
    """
    unevaluated = (
        ("25.255(a)(2)", "the largest mistrim the autopilot can sustain is not modelled (no autopilot data)"),
        ("25.255(d)", "the extrapolation of (c)(2) to −1 g and +2.5 g is not evaluated"),
        ("25.255(e)", "the buffet-boundary and entry-speed limits of the flight test are not modelled"),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        st = ac.geometry.horizontal_tail.stabilizer if ac.geometry is not None else None
        why = (
            (
                "no movable stabiliser declared (geometry.horizontal_tail.stabilizer): the equivalent out-of-trim of "
                "an "
                "airplane without a power-operated trim system is not modelled"
            )
            if st is None
            else (
                "needs geometry.horizontal_tail.stabilizer.rate (the trim system's normal rate; (a)(1) three seconds "
                "of "
                "it)"
                if st.rate is None
                else ""
            )
        )
        if why:
            return [Finding.not_evaluated(c, "out-of-trim manoeuvre", why) for c in conditions]
        conds = []
        for c in conditions:
            vmo, _ = ctx.design_speed_eas("VMO", c.altitude or 0.0)
            conds.append(c.with_(speed=float(vmo), speed_kind="EAS", speed_name="VMO/MMO"))
        batch = ctx.trim(conds)
        trims, stops = steady_flight_trims(ctx, conds)  # beyond the level-flight ceiling: descending at full thrust
        limits = control_limits(ac, configuration=conds[0].configuration)  # the trims' configuration (one batch)
        lo, hi = limits["stabilizer"]
        e_lo, e_hi = limits["elevator"]
        delta = crit.mistrim_seconds * st.rate
        elevator = control_force_model(ac, "elevator")
        out = []
        model = batch.model
        held = [i for i, stop in enumerate(stops) if stop is not None]
        trim_u = batch.u.copy()
        for i in held:
            trim_u[i] = [trims[i].controls[name] for name in model.control_names]
        js, _je = model.control_index("stabilizer"), model.control_index("elevator")
        h = np.array([c.altitude or 0.0 for c in conds])
        for sense, sign in (("nose-up", -1.0), ("nose-down", 1.0)):
            u = trim_u.copy()
            u[:, js] = np.clip(u[:, js] + sign * delta, lo, hi)
            moved = np.abs(u[:, js] - trim_u[:, js])
            for speed_name in ("VFC/MFC", "VDF/MDF"):
                eas = np.array([test_speeds(ctx, hh)[speed_name] for hh in h])
                tas = np.array([float(convert_speed(v, "EAS", "TAS", hh)) for v, hh in zip(eas, h)])
                one = symmetric_pull_up(model, tas, h, 1.0, u)
                pull = symmetric_pull_up(model, tas, h, crit.pull_load_factor, u)
                push = symmetric_pull_up(model, tas, h, crit.push_load_factor, u)
                for i, c in enumerate(conds):
                    here = c.with_(
                        manoeuvre=f"mistrim {sense} {math.degrees(moved[i]):.2f}°"
                        + (" (at the trim limit)" if moved[i] < delta - 1e-9 else "")
                        + f", at {speed_name}",
                        speed=float(eas[i]),
                        speed_kind="EAS",
                        speed_name=speed_name,
                        **({} if stops[i] is None else {"flight_path_deg": round(math.degrees(trims[i].gamma), 2)}),
                    )
                    out += self._findings(
                        here,
                        i,
                        trims[i],
                        u[i, js],
                        one,
                        pull,
                        push,
                        (e_lo, e_hi),
                        crit,
                        elevator,
                        ac,
                        tas[i],
                        h[i],
                        speed_name,
                    )
        return out

    @staticmethod
    def _findings(here, i, trim, stab, one, pull, push, limits, crit, elevator, ac, tas, h, speed_name):
        if not trim.converged or not (one.converged[i] and pull.converged[i] and push.converged[i]):
            return [
                Finding.not_evaluated(
                    here,
                    "out-of-trim manoeuvre",
                    "the trim at VMO/MMO or a manoeuvre point did "
                    f"not converge (trim residual {trim.residual_norm:.1e})",
                )
            ]
        datum = trim.stabilizer - trim.controls["stabilizer"]
        details = dict(
            stabilizer_trim_deg=round(math.degrees(trim.stabilizer), 3),
            stabilizer_mistrim_deg=round(math.degrees(datum + stab), 3),
            elevator_1g_deg=round(math.degrees(one.elevator[i]), 3),
            elevator_pull_deg=round(math.degrees(pull.elevator[i]), 3),
            elevator_push_deg=round(math.degrees(push.elevator[i]), 3),
            tas_kn=round(tas / KN, 2),
        )
        e_lo, e_hi = limits
        out = []
        for label, d in (
            (f"pull to {crit.pull_load_factor:g} g", pull.elevator[i]),
            (f"push to {crit.push_load_factor:g} g", push.elevator[i]),
        ):
            limit, at_least = (e_lo, True) if d < 0 else (e_hi, False)
            out.append(
                Finding.compare(
                    here,
                    f"{label}: elevator within its design limit",
                    math.degrees(d),
                    math.degrees(limit),
                    at_least=at_least,
                    unit="deg",
                    **details,
                )
            )
        para = "(b)(1) positive slope" if speed_name == "VFC/MFC" else "(b)(2) no reversal"
        out.append(
            Finding.compare(
                here,
                f"{para}: more trailing-edge-up elevator to pull",
                math.degrees(one.elevator[i] - pull.elevator[i]),
                0.0,
                at_least=True,
                unit="deg",
                **details,
            )
        )
        out.append(
            Finding.compare(
                here,
                f"{para}: more trailing-edge-down elevator to push",
                math.degrees(push.elevator[i] - one.elevator[i]),
                0.0,
                at_least=True,
                unit="deg",
                **details,
            )
        )
        if elevator is None:
            out.append(Finding.not_evaluated(here, f"{para}: stick force", _NO_FORCE))
            return out
        mach = tas / float(speed_of_sound(h))
        q = float(dynamic_pressure(tas, h))
        trim_alpha = local_angle(ac, "elevator", trim.alpha, trim.beta, trim.V / float(speed_of_sound(trim.h)))
        trim_at = (trim.controls["elevator"], trim_alpha)
        force = lambda a, d: float(-elevator.force(q, local_angle(ac, "elevator", a, 0.0, mach), d, trim=trim_at) / LBF)  # noqa: E731
        f_one = force(one.alpha[i], one.elevator[i])
        f_pull, f_push = force(pull.alpha[i], pull.elevator[i]), force(push.alpha[i], push.elevator[i])
        forces = dict(
            pull_force_1g_lbf=round(f_one, 2),
            pull_force_pull_lbf=round(f_pull, 2),
            pull_force_push_lbf=round(f_push, 2),
            force_model=elevator.kind,
        )
        # (b): the pull force rises with g — from 1 g to the pull-up and from the push-over to 1 g (a pilot holding
        # a push at 1 g out of trim pulls by pushing less); positive: the stable sense
        out.append(
            Finding.compare(
                here,
                f"{para}: stick force per g, 1 g to {crit.pull_load_factor:g} g",
                f_pull - f_one,
                0.0,
                at_least=True,
                unit="lbf",
                **forces,
                **details,
            )
        )
        out.append(
            Finding.compare(
                here,
                f"{para}: stick force per g, {crit.push_load_factor:g} g to 1 g",
                f_one - f_push,
                0.0,
                at_least=True,
                unit="lbf",
                **forces,
                **details,
            )
        )
        if speed_name == "VDF/MDF":  # (f): the pull that holds 1.5 g (a push there needs no pull at all)
            out.append(
                Finding.compare(
                    here,
                    f"(f) {crit.pull_load_factor:g} g recovery pull force",
                    f_pull,
                    crit.recovery_force_lbf,
                    at_least=False,
                    unit="lbf",
                    **forces,
                    **details,
                )
            )
        return out

"""§25.111 Takeoff path — simulated takeoff from brake release to 35 ft.

What is simulated (docs/regulation-notes.md does not carry § 25.111's text; the paragraph is
quoted here from memory of the eCFR, *unverified*: "(a) The takeoff path extends from a standing
start to a point … (2) The airplane must be accelerated on the ground to VEF, at which point the
critical engine must be made inoperative … (b) During the acceleration to speed V2, the nose gear
may be raised off the ground at a speed not less than VR … (c)(2) The airplane must reach V2
before it is 35 feet above the takeoff surface …"):

* a batched six-degree-of-freedom takeoff run (certkit.models.dynamics.procedures.takeoff_run) of
  the takeoff configuration at MTOW and the forward, reference and aft CG, sea level ISA, from a
  standing start with both engines at takeoff thrust (throttle 1), brakes released at t = 0,
  elevator neutral on the ground roll, rotation at the declared VR at 3°/s by a pitch-attitude
  controller to the V2 attitude (the pitch attitude of the 1-g trim at V2 in the takeoff
  configuration), wings held level, up to the gear 35 ft above the runway;
* **all engines operating**. § 25.111(a)(2) asks for the critical engine failed at VEF. That run is
  not made: with the baseline's aerodynamic model the engine-out trim at V2 needs about −33° of
  rudder against a −23.2° design limit (ctx.trim kind "oei"), so a simulated continued takeoff
  departs laterally — a § 25.149 question that must be settled first. The rule is therefore
  ``partial``;
* the issue's "elevator found so that the takeoff field length matches the baseline's" cannot be
  done: the baseline declares no field length. The rotation is the pitch-attitude controller's.

Checks per condition:
    (b) the most nose-up elevator of the run against the elevator's design limit (margin in deg:
        δe − δe_min ≥ 0, the elevator never past its design limit while rotating and climbing out);
    (c)(2) the speed at 35 ft against V2 (margin kn CAS: V35 − V2 ≥ 0).
V_LOF, the distances to lift-off and to 35 ft and the initial acceleration are reported as details.
"""

from __future__ import annotations

import numpy as np

from certkit.atmosphere import convert_speed
from certkit.conditions import ConditionSpace, DesignWeight
from certkit.registry import Criterion, Rule, rule
from certkit.results import Evidence, Finding
from certkit.units import FT, KN

SOURCE = "14 CFR 25.111(c)(2) (text from memory, not in docs/regulation-notes.md: unverified)"


def _takeoff(ctx, conditions, crit):
    """Trim at V2 (target attitude) and the batched takeoff run of the conditions, memoised for the evidence."""
    from certkit.models.dynamics.procedures import takeoff_run
    from certkit.models.flight import control_limits, flight_model, ground_model

    def compute():
        ac = ctx.aircraft
        sp = ac.speeds
        vr = float(convert_speed(sp.VR.value, sp.VR.kind, "TAS", 0.0))
        at_v2 = [c.with_(altitude=0.0, speed=sp.V2.value, speed_kind=sp.V2.kind, speed_name="V2") for c in conditions]
        trims = ctx.trim(at_v2)
        theta = np.array([r.theta for r in trims.results])
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        model = flight_model(ac, ctx.aero("takeoff").model, loadings, ground=ground_model(ac))
        travel = control_limits(ac, design=False)
        # RK4 at 10 Hz: against 20 Hz the extreme elevator moves by < 0.1° and V35 by < 0.1 kn (measured on
        # the baseline), at 40 % of the cost
        run = takeoff_run(model, vr, theta, screen_height=crit.screen_height * FT,
                          elevator_limits=travel["elevator"], lateral_limits=travel, dt=0.1)
        return trims, run

    key = ("25.111 takeoff", tuple((c.mass, c.x_cg) for c in conditions), crit.screen_height)
    return ctx.memo(key, compute)


@rule
class TakeoffPath(Rule):
    id = "25.111"
    symbol = "takeoff-path"
    title = "Takeoff path (simulated rotation and climb to 35 ft)"
    amendment = "25-121"
    implementation = "partial"
    requirement = """
        From a standing start the airplane is accelerated to VR, rotated (the nose gear may leave the
        ground at no less than VR) and must reach V2 before it is 35 ft above the takeoff surface, with
        the critical engine failed at VEF. certkit simulates the run and checks that the elevator stays
        within its design limit while rotating and climbing out and that the speed at 35 ft is at least V2.
    """
    margin = """
        (b) most nose-up elevator of the run minus the elevator's design limit (deg; ≥ 0: never past it).
        (c)(2) speed at 35 ft minus V2 (kn CAS; ≥ 0 complies).
    """
    limitations = """
        All engines operating: the engine failure at VEF of (a)(2) is not simulated (the baseline's engine-out
        trim at V2 needs more rudder than its design limit, a § 25.149 matter to settle first); no ground
        effect; rotation by a pitch-attitude controller at 3°/s to the V2 attitude (no declared field length to
        match); (c)(1), (c)(3), (c)(4) and the path beyond 35 ft are not checked. The paragraph's text is
        from memory (not in docs/regulation-notes.md).
    """
    references = ("25.107", "25.121", "25.149")
    requires = ("speeds.VR", "speeds.V2", "geometry.landing_gear", "geometry.horizontal_tail.controls.elevator")
    criteria = {
        "screen_height": Criterion(35.0, "ft", SOURCE, "height above the takeoff surface by which V2 must be reached"),
    }
    conditions = ConditionSpace(loading=DesignWeight("MTOW", ("forward", "reference", "aft")),
                                configurations=("takeoff",),
                                note="Sea level ISA, takeoff thrust on both engines, from brake release.")

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        trims, run = _takeoff(ctx, conditions, crit)
        lo = np.degrees(ac.geometry.horizontal_tail.controls["elevator"].design_limits.min
                        if ac.geometry.horizontal_tail.controls["elevator"].design_limits is not None
                        else ac.geometry.horizontal_tail.controls["elevator"].travel.min)
        v2_kn = float(convert_speed(ac.speeds.V2.value, ac.speeds.V2.kind, "CAS", 0.0)) / KN
        vr_kn = float(convert_speed(ac.speeds.VR.value, ac.speeds.VR.kind, "CAS", 0.0)) / KN
        out = []
        for i, cond in enumerate(conditions):
            c0 = cond.with_(altitude=0.0, thrust="takeoff")
            tr = trims.results[i]
            if not tr.converged:
                out.append(Finding.not_evaluated(c0, "(c)(2) V2 by 35 ft", f"no 1-g trim at V2 for the target attitude: {tr.summary()}"))
                continue
            if not run.reached[i]:
                out.append(Finding.not_evaluated(
                    c0, "(c)(2) V2 by 35 ft",
                    f"the simulated takeoff did not reach {crit.screen_height:.0f} ft within the run "
                    f"(stop: {run.sim.stop_reason[i] or 'time limit'})"))
                continue
            cas = lambda v: float(convert_speed(v, "TAS", "CAS", 0.0)) / KN  # noqa: E731
            details = dict(vr_kn=vr_kn, vlof_kn=round(cas(run.v_lof[i]), 2), v35_kn=round(cas(run.v_screen[i]), 2),
                           liftoff_distance_ft=round(run.x_lof[i] / FT, 0), distance_to_35ft_ft=round(run.x_screen[i] / FT, 0),
                           time_to_35ft_s=round(float(run.t_screen[i]), 2),
                           initial_acceleration_m_s2=round(float(run.initial_acceleration[i]), 4),
                           target_pitch_deg=round(float(np.degrees(tr.theta)), 2))
            out.append(Finding.compare(
                c0.with_(speed=cas(run.v_screen[i]) * KN, speed_kind="CAS"),
                "(b) elevator during rotation and climb-out within its design limit",
                np.degrees(run.elevator_min[i]), lo, at_least=True, unit="deg",
                elevator_max_deg=round(float(np.degrees(run.elevator_max[i])), 2), **details))
            out.append(Finding.compare(
                c0.with_(speed=cas(run.v_screen[i]) * KN, speed_kind="CAS", speed_name="V35"),
                f"(c)(2) speed at {crit.screen_height:.0f} ft at least V2", cas(run.v_screen[i]), v2_kn,
                at_least=True, unit="kn", v2_kn=v2_kn, **details))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.report.evidence_time_histories import time_histories_svg

        conds = self.conditions.expand(ctx.aircraft)
        trims, run = _takeoff(ctx, conds, crit)
        elev = [f for f in findings if f.check.startswith("(b)") and f.margin is not None]
        if not elev:
            return []
        crit_f = min(elev, key=lambda f: f.margin)
        k = next(i for i, c in enumerate(conds) if c.x_cg == crit_f.condition.x_cg)
        sim = run.sim
        lo = crit_f.limit
        je = sim.control_names.index("elevator")
        svg = time_histories_svg(sim.t, [
            ("V (kn TAS)", sim["V"] / KN, {"VR": crit_f.details["vr_kn"], "V2": crit_f.details["v2_kn"]
                                            if "v2_kn" in crit_f.details else float(ctx.aircraft.speeds.V2.value / KN)}),
            ("gear height (ft)", run.wheel_height / FT, {"35 ft": crit.screen_height}),
            ("pitch θ (deg)", np.degrees(sim["theta"]), {}),
            ("elevator (deg)", np.degrees(sim.controls[:, :, je]), {"design limit": lo}),
        ], [c.loading for c in conds], critical=k, title="§25.111 takeoff (all engines) from brake release")
        return [Evidence("Takeoff time histories", svg,
                         f"Critical condition {conds[k].loading} (elevator margin {crit_f.margin:.2f}°) and its "
                         "neighbours; rotation at VR by pitch-attitude hold to the V2 attitude.")]

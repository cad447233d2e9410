"""§25.111 Takeoff path — simulated takeoff from brake release with the critical engine failed at VEF,
rotation at VR, lift-off, the screen height of 35 ft and a short climb-out.

What is simulated (docs/regulation-notes.md does not carry § 25.111's text; the paragraph is
quoted here from memory of the eCFR, *unverified*: "(a) The takeoff path extends from a standing
start to a point … (2) The airplane must be accelerated on the ground to VEF, at which point the
critical engine must be made inoperative and remain inoperative for the rest of the takeoff …
(3) After reaching VEF, the airplane must be accelerated to V2 … (b) During the acceleration to speed V2,
the nose gear may be raised off the ground at a speed not less than VR … (c)(1) The slope of the airborne
part of the takeoff path must be positive at each point; (c)(2) The airplane must reach V2 before it is
35 feet above the takeoff surface …"):

* the simulated takeoff of certkit_rules.part25.support.takeoff (one batched six-degree-of-freedom run,
  certkit.models.dynamics.procedures.takeoff_run) of the takeoff configuration at MTOW and the forward, reference and
  aft CG, sea level ISA, from a standing start at takeoff thrust, brakes released at t = 0; every loading is run with
  the critical engine failed at VEF (the findings) and with all engines operating (shown in the details, and the
  §25.113 distance);
* the pilot: rotation at VR at 2.5°/s (rate-limited attitude command, feed-forward elevator of the V2 trim, PI
  attitude feedback with rate damping) toward the V2 attitude, held below the declared tail-strike attitude less
  2° while a gear leg is on the runway, airborne the attitude flying V2; rudder on the runway heading and the
  centreline on the ground, wings level on the ground and 5° of bank toward the live engine in the air (§25.149(b));
* the critical engine (largest |y|; the left on a mirror-symmetric twin) fails at VEF (V1 less the
  engine-out speed gain over the 1-s recognition interval, §25.107(a)(2)), its thrust decaying to windmilling with
  the declared propulsion.failure_decay_time (at once without it); the speed actually reached a recognition
  interval after the failure is reported (``v_recognition_kn``) next to V1;
* the run continues ``climb_out_s`` (10 s) past 35 ft to give the gradient after the screen height.

Checks per condition (engine failed):
    (a)(2)-(3) elevator: the extreme elevator of the run within its design limits (margin deg: the smaller of
        δe_min − δe_lo and δe_hi − δe_max);
    (a)(2)-(3) rudder: the extreme rudder of the run within its design limits (margin deg, likewise) — the
        directional control the engine failure needs on the runway and in the air;
    (a)(2) ground track: the largest deviation from the runway centreline on the ground, from brake release to the
        lift-off, within the §25.149(e) 30 ft (margin ft: 30 − deviation) — the bound VEF ≥ VMCG (§25.107(a)(1))
        implies for the failure at VEF, here held to the lift-off (§25.149(e) measures it to the recovery of the
        heading: a rotation begun before that recovery is judged with it);
    (c)(1) slope of the airborne path from the screen height to the end of the climb-out positive (margin %:
        smallest gradient between records);
    (c)(2) the speed at 35 ft against V2 (margin kn CAS: V35 − V2 ≥ 0).
V_LOF, VEF, the speed a recognition interval after the failure, the distances (the accelerate-go distance and the
§25.113 takeoff distance), the largest heading deviation, the lateral deviation from the centreline at lift-off and
at 35 ft, the bank, the largest attitude on the runway and pitch rate before lift-off, and the mean gradient from
35 ft to the end of the climb-out are reported as details, with how far VLOF lies beyond VR and V35 beyond V2. A run
that is not a takeoff (certkit_rules.part25.support.takeoff.unrepresentative: no lift-off, the tail on the runway: the
pilot's rotation stays below it) earns no verdict: its checks are not evaluated, with the reason. A late lift-off and
a ground track off the centreline are not among them: an airplane that rotates slowly or that its rudder cannot hold
on the centreline with the scheduled speeds is judged as it flies.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.reference_speeds import declared_cas
from certkit_rules.part25.support.takeoff import (
    GROUND_TRACK_CRITERIA,
    PROCEDURE_CRITERIA,
    TAKEOFF_REQUIRES,
    distances,
    not_a_takeoff,
    run_summary,
    simulated_takeoffs,
    takeoff_conditions,
    unrepresentative,
)

from certkit.atmosphere import convert_speed
from certkit.engine.evidence.performance import takeoff_evidence
from certkit.engine.registry import ControlCase, ControlResponses, Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.models.flight import control_limits
from certkit.units import FT, KN

SOURCE = "14 CFR 25.111 (text from memory, not in docs/regulation-notes.md: unverified)"


def _design_margin(values_deg, lo_deg, hi_deg):
    """The binding side of a run's deflections against the design range: (extreme value, limit, at_least) for
    ``Finding.compare`` — the side with the smaller distance inside the range (< 0: beyond it)."""
    lo_m, hi_m = float(np.min(values_deg)) - lo_deg, hi_deg - float(np.max(values_deg))
    return (float(np.min(values_deg)), lo_deg, True) if lo_m <= hi_m else (float(np.max(values_deg)), hi_deg, False)


@rule
class TakeoffPath(Rule):
    id = "25.111"
    #: the extreme elevator and rudder of the engine-out takeoff (``control.25.111.takeoff_oei_vef.<control>``)
    offers = (
        ControlResponses(
            (
                ControlCase(
                    "takeoff OEI VEF", "(a) ", ("elevator", "rudder"), ("{control}_min_deg", "{control}_max_deg")
                ),
            )
        ),
    )
    cost = 4  # relative evaluation time (orders work over --jobs processes)
    run_with = "takeoff"  # §25.111, §25.113 and §25.107(e)(1)(iv) fly the same runs: one process simulates them
    symbol = "takeoff-path"
    title = "Takeoff path with the critical engine failed at VEF (simulated to 35 ft and a climb-out)"
    amendment = "25-121"
    implementation = "partial"
    requirement = """
        From a standing start the airplane is accelerated on the ground to VEF, where the critical engine is made
        inoperative for the rest of the takeoff; it is rotated (the nose gear may leave the ground at no less than
        VR), the slope of the airborne path must be positive and V2 must be reached before the airplane is 35 ft
        above the takeoff surface. certkit simulates the run with the engine failed at VEF and checks that the
        elevator and the rudder stay within their design limits, that the ground run stays within 30 ft of the
        centreline (the §25.149(e) bound VEF ≥ VMCG implies), that the airborne path climbs and that the speed
        at 35 ft is at least V2.
    """
    margin = """
        Elevator and rudder: the smaller distance of the run's extreme deflections inside the design limits (deg;
        ≥ 0: never past them). Ground track: 30 ft less the largest deviation from the centreline before the
        lift-off (ft; ≥ 0). (c)(1) smallest climb gradient from 35 ft to the end of the climb-out (%; ≥ 0).
        (c)(2) speed at 35 ft minus V2 (kn CAS; ≥ 0 complies).
    """
    limitations = """
        Ground effect on the wing's lift and induced drag (image-vortex factor,
        certkit/models/aero/ground_effect.py) and on the downwash at the tail (the wing's vortices and their image,
        span load solved with the image, certkit/models/aero/tail_ground_effect.py; within 0.02 of AVL's ground
        plane): on the runway the tail keeps about half of its free-air downwash per unit lift, a nose-down moment
        of about 2° of elevator at the ground attitude and 8–9° at the rotation attitude; not modelled: the wake's
        displacement near the ground, the flaps' own span load, the tail's own ground effect (the rotation's
        elevator is an estimate, not a bound); nose-wheel steering only as the aircraft file's takeoff_pilot
        declares it (pedal steering; without it the nose wheel is held straight); no spool-up (takeoff thrust at brake
        release); the failed engine's thrust decays as a first-order lag with
        the declared propulsion.failure_decay_time (windmilling at once without it); the pilot (rotation at
        2.5°/s to the V2 attitude below the declared tail-strike attitude less 2°, speed on pitch once airborne;
        the pedals on heading and centreline, held for takeoff_pilot.rudder_reaction_time after the failure and then
        moved at most at takeoff_pilot.rudder_rate, ≤ 5° bank toward the live engine in the air) stands for a pilot;
        VEF from V1 by a quasi-steady engine-out acceleration, never below the VMCG §25.149(e) computes; the path
        beyond the climb-out,
        (c)(3) 1.2 % from 400 ft and (c)(4) configuration changes are not computed. The runway has no edge: a
        ground run that strays beyond 30 ft fails the ground-track check and its other checks are judged as it
        flies on. A run that does not lift off or reaches the tail-strike attitude on the runway is not a takeoff
        a pilot flies: its checks are not evaluated, with the reason (a late lift-off is judged, and reported).
        The paragraph's text is from memory (not in docs/regulation-notes.md).
    """
    references = ("25.107", "25.121", "25.149")
    requires = TAKEOFF_REQUIRES
    criteria = {
        **PROCEDURE_CRITERIA,
        "gradient_min": Criterion(
            0.0, "%", SOURCE + " (c)(1) positive slope", "smallest climb gradient of the airborne path"
        ),
        **GROUND_TRACK_CRITERIA,
    }
    conditions = takeoff_conditions("Sea level ISA, takeoff thrust from brake release, critical engine failed at VEF.")

    unevaluated = (
        ("25.111(a)", "the takeoff path beyond 35 ft (to 1,500 ft or the en-route transition) is not simulated"),
        ("25.111(c)(3)", "the climb gradient from 400 ft (not less than 1.2 % for a twin) is not evaluated"),
        ("25.111(c)(4)", "no change of configuration before 400 ft other than gear retraction: not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        to = simulated_takeoffs(ctx, conditions, crit)
        trims, run, engine, vef = to.trims, to.run, to.engine, to.vef
        design = {k: np.degrees(v) for k, v in control_limits(ac).items() if k != "throttle"}
        cas = lambda v: float(convert_speed(v, "TAS", "CAS", 0.0)) / KN  # noqa: E731
        v1_kn, v2_kn, vr_kn = (declared_cas(ctx, name) / KN for name in ("V1", "V2", "VR"))
        sim = run.sim
        n = len(conditions)
        je, jr = sim.control_names.index("elevator"), sim.control_names.index("rudder")
        out = []
        for i, cond in enumerate(conditions):
            c0 = cond.with_(altitude=0.0, thrust="takeoff", inoperative=engine)
            tr = trims.results[i]
            checks = (
                "(a) elevator within its design limits, engine failed at VEF",
                "(a) rudder within its design limits, engine failed at VEF",
                "(c)(1) airborne path slope positive",
                f"(c)(2) speed at {crit.screen_height:.0f} ft at least V2",
                f"(a) ground track within {crit.lateral_deviation_max:g} ft of the centreline, engine failed at VEF",
            )
            if not tr.converged:
                out += [
                    Finding.not_evaluated(c0, ch, f"no 1-g trim at V2 for the target attitude: {tr.summary()}")
                    for ch in checks
                ]
                continue
            if not run.reached[i]:
                out += [
                    Finding.not_evaluated(
                        c0,
                        ch,
                        f"the simulated engine-out takeoff did not reach {crit.screen_height:.0f} ft "
                        f"within the run (stop: {sim.stop_reason[i] or 'time limit'})",
                    )
                    for ch in checks
                ]
                continue
            k_end = min(int(np.searchsorted(sim.t, sim.stop_time[i] - 1e-9)), sim.t.size - 1)
            k_scr = int(run.screen_index[i])
            ground = run.wheel_height[: k_end + 1, i] <= 0.0
            k_fail = int(np.argmax(sim["V"][:, i] >= vef[i]))
            t_rec = sim.t[k_fail] + crit.recognition_time
            v_rec = float(np.interp(t_rec, sim.t[: k_end + 1], sim["V"][: k_end + 1, i]))
            y = sim["y_E"][: k_end + 1, i] - sim["y_E"][0, i]
            k_lof = int(np.argmax(~ground)) if (~ground).any() else k_end
            a = n + i  # the all-engines twin
            details = dict(
                critical_engine=engine,
                vef_basis=to.vef_basis,
                vef_kn=round(cas(vef[i]), 2),
                v1_kn=v1_kn,
                v_recognition_kn=round(cas(v_rec), 2),
                **run_summary(to, i, vr_kn, v2_kn),
                liftoff_distance_ft=round(run.x_lof[i] / FT, 0),
                distance_to_35ft_ft=round(run.x_screen[i] / FT, 0),
                **distances(to, i, n),
                time_to_35ft_s=round(float(run.t_screen[i]), 2),
                initial_acceleration_m_s2=round(float(run.initial_acceleration[i]), 4),
                target_pitch_deg=round(float(np.degrees(to.theta_target[i])), 2),
                rotation_basis=to.basis["rotation"],
                tail_strike_basis=to.basis["tail_strike"],
                spool_down_basis=to.basis["spool_down"],
                pilot_basis=to.basis["pilot"],
                max_heading_deviation_deg=round(float(np.degrees(np.abs(sim["psi"][: k_end + 1, i]).max())), 2),
                lateral_deviation_at_liftoff_ft=round(float(y[k_lof] / FT), 1),
                lateral_deviation_at_35ft_ft=round(float(y[k_scr] / FT), 1),
                max_bank_deg=round(float(np.degrees(np.abs(sim["phi"][: k_end + 1, i]).max())), 2),
                mean_gradient_after_35ft_pct=round(float(run.climb_gradient[i]) * 100, 3),
                all_engines_vlof_kn=round(cas(run.v_lof[a]), 2),
                all_engines_v35_kn=round(cas(run.v_screen[a]), 2) if run.reached[a] else None,
                all_engines_elevator_min_deg=round(float(np.degrees(run.elevator_min[a])), 2),
            )
            c35 = c0.with_(speed=cas(run.v_screen[i]) * KN, speed_kind="CAS", speed_name="V35")
            why = unrepresentative(details, tail_strike_deg=to.basis["tail_strike_deg"])
            if why:
                out += [
                    Finding.not_evaluated(
                        c35,
                        ch,
                        not_a_takeoff(why),
                        **details,
                    )
                    for ch in checks
                ]
                continue
            for name, j, check in (("elevator", je, checks[0]), ("rudder", jr, checks[1])):
                defl = np.degrees(sim.controls[: k_end + 1, i, j])
                value, limit, at_least = _design_margin(defl, *design[name])
                air = ~ground & (np.arange(k_end + 1) >= k_lof)
                out.append(
                    Finding.compare(
                        c35,
                        check,
                        value,
                        limit,
                        at_least=at_least,
                        unit="deg",
                        **{
                            f"{name}_min_deg": round(float(defl.min()), 2),
                            f"{name}_max_deg": round(float(defl.max()), 2),
                            f"{name}_extreme_on_ground_deg": round(
                                float(defl[ground][np.argmax(np.abs(defl[ground]))]), 2
                            ),
                            f"{name}_extreme_airborne_deg": round(float(defl[air][np.argmax(np.abs(defl[air]))]), 2)
                            if air.any()
                            else None,
                            f"{name}_design_limits_deg": [round(float(d), 2) for d in design[name]],
                        },
                        **details,
                    )
                )
            grad = run.gradient[k_scr:k_end, i]
            grad = grad[np.isfinite(grad)]
            if grad.size == 0:
                out.append(
                    Finding.not_evaluated(
                        c35,
                        checks[2],
                        "no airborne record after the screen height (climb_out_s too short for the record interval)",
                        **details,
                    )
                )
            else:
                out.append(
                    Finding.compare(
                        c35, checks[2], float(grad.min()) * 100, crit.gradient_min, at_least=True, unit="%", **details
                    )
                )
            out.append(
                Finding.compare(c35, checks[3], cas(run.v_screen[i]), v2_kn, at_least=True, unit="kn", **details)
            )
            out.append(
                Finding.compare(
                    c35,
                    checks[4],
                    details["max_lateral_deviation_on_ground_ft"],
                    crit.lateral_deviation_max,
                    at_least=False,
                    unit="ft",
                    **details,
                )
            )
        return out

    def evidence(self, ctx, findings, crit):
        conds = self.conditions.expand(ctx.aircraft)
        to = simulated_takeoffs(ctx, conds, crit)
        return takeoff_evidence(ctx, conds, findings, to.run, to.engine, to.vef, crit)

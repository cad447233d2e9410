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

* one batched six-degree-of-freedom run (certkit.models.dynamics.procedures.takeoff_run) of the takeoff
  configuration at MTOW and the forward, reference and aft CG, sea level ISA, from a standing start at
  takeoff thrust (throttle 1), brakes released at t = 0; every loading is run twice in the same batch:
  **with the critical engine failed at VEF** (the findings) and with all engines operating (a reference
  shown in the details and the evidence);
* the critical engine is the one with the largest thrust moment arm |y| about the plane of symmetry; on a
  mirror-symmetric twin both are equally critical and the first declared (the left) is failed. It fails
  (windmilling, :class:`~certkit.models.dynamics.controllers.EngineFailure`) when the airspeed first
  reaches VEF;
* **VEF**: ``speeds.VEF`` when the aircraft model declares one; otherwise from the declared V1 less the
  speed gained with the engine failed over the recognition interval (§25.107(a)(2)):
  VEF = V1 − a_OEI(V1) · Δt_rec, with a_OEI the runway acceleration at V1 with the critical engine
  inoperative (procedures.runway_acceleration: quasi-steady, the gear carrying the weight of rest) and
  Δt_rec = ``recognition_time`` (1 s; 0 puts the failure at V1). The speed actually reached a recognition
  interval after the failure is reported (``v_recognition_kn``) next to V1;
* elevator neutral on the ground roll, rotation at the declared VR at 3°/s by a pitch-attitude controller to
  the V2 attitude (the pitch attitude of the 1-g level trim at V2 in the takeoff configuration, all
  engines), as the all-engines rule did;
* lateral–directional pilot (:class:`~certkit.models.dynamics.controllers.HeadingHold`): rudder holds the
  runway heading (PI on the heading error with yaw-rate damping), aileron wings level on the ground and
  ``bank_deg`` (5°) toward the operating engine once airborne (the §25.149(b) allowance); surfaces move
  over their full travel, and the extremes are compared with their design limits;
* the run continues ``climb_out_s`` (10 s) past 35 ft to give the gradient after the screen height.

Checks per condition (engine failed):
    (a)(2)-(3) elevator: the extreme elevator of the run within its design limits (margin deg: the smaller of
        δe_min − δe_lo and δe_hi − δe_max);
    (a)(2)-(3) rudder: the extreme rudder of the run within its design limits (margin deg, likewise) — the
        directional control the engine failure needs on the runway and in the air;
    (c)(1) slope of the airborne path from the screen height to the end of the climb-out positive (margin %:
        smallest gradient between records);
    (c)(2) the speed at 35 ft against V2 (margin kn CAS: V35 − V2 ≥ 0).
V_LOF, VEF, the speed a recognition interval after the failure, the distances, the largest heading
deviation, the lateral deviation from the centreline at lift-off and at 35 ft, the bank, and the mean
gradient from 35 ft to the end of the climb-out are reported as details.
"""

from __future__ import annotations

import numpy as np

from certkit.atmosphere import convert_speed
from certkit.conditions import ConditionSpace, DesignWeight
from certkit.models.dynamics.trim import held_stabilizer
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.units import FT, KN

SOURCE = "14 CFR 25.111 (text from memory, not in docs/regulation-notes.md: unverified)"


def critical_engine(aircraft) -> str:
    """Name of the engine whose failure gives the largest yawing moment (largest |y|; the first on a tie)."""
    engines = aircraft.propulsion.engines
    arms = [abs(e.position.y) for e in engines]
    return engines[int(np.argmax(arms))].name


def failure_speed(ctx, model, engine: str, crit) -> tuple[np.ndarray, str]:
    """VEF (m/s TAS, one per condition of ``model``) and how it was obtained (module docstring)."""
    from certkit.models.dynamics.procedures import runway_acceleration

    sp = ctx.aircraft.speeds
    declared = getattr(sp, "VEF", None)
    if declared is not None:
        return np.full(model.n, float(convert_speed(declared.value, declared.kind, "TAS", 0.0))), "declared VEF"
    v1 = float(convert_speed(sp.V1.value, sp.V1.kind, "TAS", 0.0))
    names = [e.name for e in model.engines]
    op = np.ones((model.n, len(names)), dtype=bool)
    op[:, names.index(engine)] = False
    a = runway_acceleration(model, v1, operative=op)
    return v1 - a * crit.recognition_time, f"V1 less {crit.recognition_time:g} s of the engine-out acceleration at V1"


def _takeoff(ctx, conditions, crit):
    """Trim at V2 (target attitude) and one batched run: rows 0..n-1 engine failed at VEF, n..2n-1 all engines."""
    from certkit.models.dynamics.procedures import takeoff_run
    from certkit.models.flight import control_limits, flight_model, ground_model

    def compute():
        ac = ctx.aircraft
        sp = ac.speeds
        n = len(conditions)
        vr = float(convert_speed(sp.VR.value, sp.VR.kind, "TAS", 0.0))
        at_v2 = [c.with_(altitude=0.0, speed=sp.V2.value, speed_kind=sp.V2.kind, speed_name="V2") for c in conditions]
        trims = ctx.trim(at_v2)
        theta = np.array([r.theta for r in trims.results])
        # a movable stabiliser is set to its trim at V2 (the takeoff trim) and held; None without one
        stab = held_stabilizer(trims.results)
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        rotation = {"basis": "the level-flight V2 attitude (no takeoff field length declared)"}
        tofl = ac.performance.takeoff_field_length if ac.performance is not None else None
        if tofl is not None:
            theta, rotation = rotation_for_field_length(ctx, loadings, theta, vr, float(tofl), crit, stab)
        model = flight_model(ac, ctx.aero("takeoff").model, loadings + loadings, ground=ground_model(ac))
        engine = critical_engine(ac)
        vef, vef_basis = failure_speed(ctx, model, engine, crit)
        vef[n:] = np.inf  # the all-engines rows
        y = {e.name: e.position.y for e in ac.propulsion.engines}
        toward_live = -np.sign(y[engine]) if y[engine] != 0 else 1.0  # bank right (+) when the left engine is dead
        bank = np.concatenate([np.full(n, toward_live * np.radians(crit.bank_deg)), np.zeros(n)])
        travel = control_limits(ac, design=False)
        # RK4 at 10 Hz: against 20 Hz the extreme elevator moves by < 0.1° and V35 by < 0.1 kn (measured on
        # the baseline, all engines), at 40 % of the cost
        run = takeoff_run(model, vr, np.concatenate([theta, theta]), screen_height=crit.screen_height * FT,
                          elevator_limits=travel["elevator"], lateral_limits=travel, dt=0.1,
                          failed_engine=engine, failure_speed=vef, lateral="heading", bank_airborne=bank,
                          climb_out=crit.climb_out_s, stabilizer0=None if stab is None else np.concatenate([stab, stab]))
        return trims, run, engine, vef, vef_basis, theta, rotation

    key = ("25.111 takeoff OEI", tuple((c.mass, c.x_cg) for c in conditions), crit.screen_height, crit.recognition_time,
           crit.bank_deg, crit.climb_out_s)
    return ctx.memo(key, compute)


#: rotation attitudes tried above the level-flight V2 attitude when a field length is matched (deg)
ROTATION_OFFSETS_DEG = (-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0, 8.0)


def rotation_for_field_length(ctx, loadings, theta_v2, vr, field_length: float, crit, stabilizer=None):
    """The rotation target attitude of each loading for which the all-engines takeoff matches the declared field
    length: 1.15 × the simulated distance to 35 ft (§25.113(a)(2)) = ``field_length``. One batch of all-engines runs
    at the V2 attitude plus :data:`ROTATION_OFFSETS_DEG`, then linear interpolation of the distance in the attitude
    (the distance falls as the target rises); held at the ends of the range (the basis says so)."""
    from certkit.models.dynamics.procedures import takeoff_run
    from certkit.models.flight import control_limits, flight_model, ground_model

    ac = ctx.aircraft
    n, offsets = len(loadings), np.radians(ROTATION_OFFSETS_DEG)
    model = flight_model(ac, ctx.aero("takeoff").model, list(loadings) * offsets.size, ground=ground_model(ac))
    targets = (theta_v2[None, :] + offsets[:, None]).ravel()
    run = takeoff_run(model, vr, targets, screen_height=crit.screen_height * FT,
                      elevator_limits=control_limits(ac, design=False)["elevator"], dt=0.1,
                      stabilizer0=None if stabilizer is None else np.tile(stabilizer, offsets.size))
    dist = np.where(run.reached, 1.15 * run.x_screen, np.nan).reshape(offsets.size, n)
    theta, notes = theta_v2.copy(), []
    for i in range(n):
        ok = np.isfinite(dist[:, i])
        d, th = dist[ok, i], targets.reshape(offsets.size, n)[ok, i]
        if d.size == 0:
            notes.append("no all-engines run reached 35 ft: V2 attitude kept")
            continue
        order = np.argsort(d)  # increasing distance ↔ decreasing attitude
        theta[i] = float(np.interp(field_length, d[order], th[order]))
        notes.append("matched" if d.min() <= field_length <= d.max() else
                     "held at the end of the attitudes tried (field length outside their distances "
                     f"{d.min() / FT:,.0f}–{d.max() / FT:,.0f} ft)")
    return theta, {"basis": f"rotation attitude solved so that 1.15 × the all-engines distance to "
                            f"{crit.screen_height:.0f} ft equals the declared takeoff field length "
                            f"{field_length / FT:,.0f} ft", "notes": notes,
                   "field_length_ft_by_attitude": [[round(float(x / FT), 0) for x in row] for row in dist.T]}


def _unrepresentative(details: dict, crit) -> list[str]:
    """Why a simulated engine-out takeoff does not stand for the takeoff a pilot flies (empty: it does): lift-off too
    long after VR, the screen height passed too far above V2, or the run wandering off the runway's centreline beyond
    the bounds of the criteria. Such a run earns no verdict."""
    out = []
    late = details["vlof_kn"] - details["vr_kn"]
    if late > crit.vlof_above_vr_max:
        out.append(f"VLOF {details['vlof_kn']:.1f} kn is {late:.1f} kn above VR (at most {crit.vlof_above_vr_max:g} kn)")
    fast = details["v35_kn"] - details["v2_kn"]
    if fast > crit.v35_above_v2_max:
        out.append(f"V35 {details['v35_kn']:.1f} kn is {fast:.1f} kn above V2 (at most {crit.v35_above_v2_max:g} kn)")
    wide = details["max_lateral_deviation_on_ground_ft"]
    if wide > crit.lateral_deviation_max:
        out.append(f"the ground run deviates {wide:.0f} ft from the centreline (at most {crit.lateral_deviation_max:g} ft)")
    return out


def _design_margin(values_deg, lo_deg, hi_deg):
    """The binding side of a run's deflections against the design range: (extreme value, limit, at_least) for
    ``Finding.compare`` — the side with the smaller distance inside the range (< 0: beyond it)."""
    lo_m, hi_m = float(np.min(values_deg)) - lo_deg, hi_deg - float(np.max(values_deg))
    return (float(np.min(values_deg)), lo_deg, True) if lo_m <= hi_m else (float(np.max(values_deg)), hi_deg, False)


@rule
class TakeoffPath(Rule):
    id = "25.111"
    cost = 4  # relative evaluation time (orders work over --jobs processes)
    symbol = "takeoff-path"
    title = "Takeoff path with the critical engine failed at VEF (simulated to 35 ft and a climb-out)"
    amendment = "25-121"
    implementation = "partial"
    requirement = """
        From a standing start the airplane is accelerated on the ground to VEF, where the critical engine is made
        inoperative for the rest of the takeoff; it is rotated (the nose gear may leave the ground at no less than
        VR), the slope of the airborne path must be positive and V2 must be reached before the airplane is 35 ft
        above the takeoff surface. certkit simulates the run with the engine failed at VEF and checks that the
        elevator and the rudder stay within their design limits, that the airborne path climbs and that the speed
        at 35 ft is at least V2.
    """
    margin = """
        Elevator and rudder: the smaller distance of the run's extreme deflections inside the design limits (deg;
        ≥ 0: never past them). (c)(1) smallest climb gradient from 35 ft to the end of the climb-out (%; ≥ 0).
        (c)(2) speed at 35 ft minus V2 (kn CAS; ≥ 0 complies).
    """
    limitations = """
        No ground effect; no nose-wheel steering (the tyres' side friction and the rudder hold the heading); no
        engine spool-down (the failed engine windmills at once) nor spool-up (takeoff thrust at brake release);
        rotation by a pitch-attitude controller at 3°/s to the attitude that matches a declared
        performance.takeoff_field_length (1.15 × the all-engines distance to 35 ft), else to the level-flight V2
        attitude; the pilot model (rudder PI on heading, ≤ 5° bank toward the live engine in the air) stands for
        a pilot; VEF from V1 by a quasi-steady engine-out acceleration when not declared; the path beyond the
        climb-out (c)(3) 1.2 % from 400 ft, (c)(4) configuration changes, and the takeoff distance (§25.113) are
        not computed. A run that lifts off more than 15 kn after VR, passes 35 ft more than 10 kn above V2 or
        deviates more than 30 ft from the centreline on the ground does not represent a takeoff a pilot flies: its
        checks are not evaluated, with the reason. The paragraph's text is from memory (not in docs/regulation-notes.md).
    """
    references = ("25.107", "25.121", "25.149")
    requires = ("speeds.V1", "speeds.VR", "speeds.V2", "geometry.landing_gear",
                "geometry.horizontal_tail.controls.elevator", "geometry.vertical_tail.controls.rudder")
    criteria = {
        "screen_height": Criterion(35.0, "ft", SOURCE + " (c)(2)", "height above the takeoff surface by which V2 must be reached"),
        "recognition_time": Criterion(1.0, "s", "project choice after §25.107(a)(2) (VEF to V1 is the speed gained over "
                                      "the recognition interval; 1 s is the usual demonstrated interval, AC 25-7 practice, "
                                      "unverified); 0 fails the engine at V1", "recognition interval from VEF to V1"),
        "bank_deg": Criterion(5.0, "deg", "project choice: the §25.149(b) allowance of not more than 5° of bank toward the "
                              "operating engine, flown once airborne", "bank toward the operating engine in the air"),
        "climb_out_s": Criterion(10.0, "s", "project choice: climb-out simulated past 35 ft for the gradient",
                                 "time simulated after the screen height"),
        "gradient_min": Criterion(0.0, "%", SOURCE + " (c)(1) positive slope", "smallest climb gradient of the airborne path"),
        "vlof_above_vr_max": Criterion(15.0, "kn", "project choice: a rotation a pilot flies lifts the airplane off a few "
                                       "seconds after VR; more means the simulated rotation does not represent the takeoff",
                                       "largest VLOF − VR of a representative run (CAS)"),
        "v35_above_v2_max": Criterion(10.0, "kn", "project choice after §25.111(c)(2) ('as close as practical to, but not "
                                      "less than, V2'; V2 is chosen to be reached at 35 ft, §25.107(c)(2))",
                                      "largest V35 − V2 of a representative run (CAS)"),
        "lateral_deviation_max": Criterion(30.0, "ft", "the §25.149(e) bound on the deviation from the runway centreline "
                                           "after an engine failure on the ground (a certificated airplane meets it at VMCG)",
                                           "largest lateral deviation on the ground of a representative run"),
    }
    conditions = ConditionSpace(loading=DesignWeight("MTOW", ("forward", "reference", "aft")),
                                configurations=("takeoff",),
                                note="Sea level ISA, takeoff thrust from brake release, critical engine failed at VEF.")

    unevaluated = (
        ("25.111(a)", "the takeoff path beyond 35 ft (to 1,500 ft or the en-route transition) is not simulated"),
        ("25.111(c)(3)", "the climb gradient from 400 ft (not less than 1.2 % for a twin) is not evaluated"),
        ("25.111(c)(4)", "no change of configuration before 400 ft other than gear retraction: not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        from certkit.models.flight import control_limits

        ac = ctx.aircraft
        trims, run, engine, vef, vef_basis, theta, rotation = _takeoff(ctx, conditions, crit)
        design = {k: np.degrees(v) for k, v in control_limits(ac).items() if k != "throttle"}
        cas = lambda v: float(convert_speed(v, "TAS", "CAS", 0.0)) / KN  # noqa: E731
        v1_kn = float(convert_speed(ac.speeds.V1.value, ac.speeds.V1.kind, "CAS", 0.0)) / KN
        v2_kn = float(convert_speed(ac.speeds.V2.value, ac.speeds.V2.kind, "CAS", 0.0)) / KN
        vr_kn = float(convert_speed(ac.speeds.VR.value, ac.speeds.VR.kind, "CAS", 0.0)) / KN
        sim = run.sim
        n = len(conditions)
        je, jr = sim.control_names.index("elevator"), sim.control_names.index("rudder")
        out = []
        for i, cond in enumerate(conditions):
            c0 = cond.with_(altitude=0.0, thrust="takeoff", inoperative=engine)
            tr = trims.results[i]
            checks = ("(a) elevator within its design limits, engine failed at VEF",
                      "(a) rudder within its design limits, engine failed at VEF",
                      "(c)(1) airborne path slope positive", f"(c)(2) speed at {crit.screen_height:.0f} ft at least V2")
            if not tr.converged:
                out += [Finding.not_evaluated(c0, ch, f"no 1-g trim at V2 for the target attitude: {tr.summary()}")
                        for ch in checks]
                continue
            if not run.reached[i]:
                out += [Finding.not_evaluated(c0, ch, f"the simulated engine-out takeoff did not reach {crit.screen_height:.0f} ft "
                                              f"within the run (stop: {sim.stop_reason[i] or 'time limit'})") for ch in checks]
                continue
            k_end = min(int(np.searchsorted(sim.t, sim.stop_time[i] - 1e-9)), sim.t.size - 1)
            k_scr = int(run.screen_index[i])
            ground = run.wheel_height[:k_end + 1, i] <= 0.0
            k_fail = int(np.argmax(sim["V"][:, i] >= vef[i]))
            t_rec = sim.t[k_fail] + crit.recognition_time
            v_rec = float(np.interp(t_rec, sim.t[:k_end + 1], sim["V"][:k_end + 1, i]))
            y = sim["y_E"][:k_end + 1, i] - sim["y_E"][0, i]
            k_lof = int(np.argmax(~ground)) if (~ground).any() else k_end
            a = n + i  # the all-engines twin
            details = dict(
                critical_engine=engine, vef_basis=vef_basis, vef_kn=round(cas(vef[i]), 2), v1_kn=v1_kn,
                v_recognition_kn=round(cas(v_rec), 2), vr_kn=vr_kn, v2_kn=v2_kn,
                vlof_kn=round(cas(run.v_lof[i]), 2), v35_kn=round(cas(run.v_screen[i]), 2),
                liftoff_distance_ft=round(run.x_lof[i] / FT, 0), distance_to_35ft_ft=round(run.x_screen[i] / FT, 0),
                time_to_35ft_s=round(float(run.t_screen[i]), 2),
                initial_acceleration_m_s2=round(float(run.initial_acceleration[i]), 4),
                target_pitch_deg=round(float(np.degrees(theta[i])), 2), rotation_basis=rotation["basis"],
                **({"rotation_match": rotation["notes"][i],
                    "field_length_ft_at_attitude_offsets": rotation["field_length_ft_by_attitude"][i]}
                   if "notes" in rotation else {}),
                max_heading_deviation_deg=round(float(np.degrees(np.abs(sim["psi"][:k_end + 1, i]).max())), 2),
                max_lateral_deviation_on_ground_ft=round(float(np.abs(y[ground]).max() / FT) if ground.any() else 0.0, 1),
                lateral_deviation_at_liftoff_ft=round(float(y[k_lof] / FT), 1),
                lateral_deviation_at_35ft_ft=round(float(y[k_scr] / FT), 1),
                max_bank_deg=round(float(np.degrees(np.abs(sim["phi"][:k_end + 1, i]).max())), 2),
                mean_gradient_after_35ft_pct=round(float(run.climb_gradient[i]) * 100, 3),
                all_engines_vlof_kn=round(cas(run.v_lof[a]), 2),
                all_engines_v35_kn=round(cas(run.v_screen[a]), 2) if run.reached[a] else None,
                all_engines_elevator_min_deg=round(float(np.degrees(run.elevator_min[a])), 2))
            c35 = c0.with_(speed=cas(run.v_screen[i]) * KN, speed_kind="CAS", speed_name="V35")
            unrepresentative = _unrepresentative(details, crit)
            if unrepresentative:
                out += [Finding.not_evaluated(c35, ch, "the simulated takeoff does not represent one a pilot flies: "
                                              + "; ".join(unrepresentative), **details) for ch in checks]
                continue
            for name, j, check in (("elevator", je, checks[0]), ("rudder", jr, checks[1])):
                defl = np.degrees(sim.controls[:k_end + 1, i, j])
                value, limit, at_least = _design_margin(defl, *design[name])
                air = ~ground & (np.arange(k_end + 1) >= k_lof)
                out.append(Finding.compare(
                    c35, check, value, limit, at_least=at_least, unit="deg",
                    **{f"{name}_min_deg": round(float(defl.min()), 2), f"{name}_max_deg": round(float(defl.max()), 2),
                       f"{name}_extreme_on_ground_deg": round(float(defl[ground][np.argmax(np.abs(defl[ground]))]), 2),
                       f"{name}_extreme_airborne_deg": round(float(defl[air][np.argmax(np.abs(defl[air]))]), 2)
                       if air.any() else None,
                       f"{name}_design_limits_deg": [round(float(d), 2) for d in design[name]]}, **details))
            grad = run.gradient[k_scr:k_end, i]
            grad = grad[np.isfinite(grad)]
            if grad.size == 0:
                out.append(Finding.not_evaluated(c35, checks[2], "no airborne record after the screen height "
                                                 "(climb_out_s too short for the record interval)", **details))
            else:
                out.append(Finding.compare(c35, checks[2], float(grad.min()) * 100, crit.gradient_min, at_least=True,
                                           unit="%", **details))
            out.append(Finding.compare(c35, checks[3], cas(run.v_screen[i]), v2_kn, at_least=True, unit="kn", **details))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import takeoff_evidence

        conds = self.conditions.expand(ctx.aircraft)
        trims, run, engine, vef, *_ = _takeoff(ctx, conds, crit)
        return takeoff_evidence(ctx, conds, findings, run, engine, vef, crit)

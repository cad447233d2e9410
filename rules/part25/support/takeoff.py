"""The simulated takeoff shared by §25.111 (takeoff path), §25.113 (takeoff distance) and the §25.107 rules that judge
the takeoff speeds on it (regulation content).

One batched six-degree-of-freedom run (:func:`certkit.models.dynamics.procedures.takeoff_run`) per set of loadings,
sea level ISA, takeoff thrust from brake release: rows 0..n−1 with the critical engine failed at VEF (§25.111(a)(2)),
rows n..2n−1 with all engines operating (the §25.113(a)(2) distance). The procedure a pilot flies (§25.101(f)):
  * aerodynamic controls other than the pilot's (a movable stabiliser) held at their V2-trim values throughout (the
    takeoff trim); elevator at its takeoff setting (neutral) to VR, then the rotation of
    :class:`~certkit.models.dynamics.takeoff_pilot.
    RotationPilot`: attitude command at ``rotation_rate_deg_s`` (2.5°/s: Boeing Flight Operations Review, 14 March
    1986, "typically 2–3 degrees per second … should not exceed 3"; the 777 FCTM the same) toward the attitude of
    the 1-g trim at V2, at most the declared tail-strike attitude (``geometry.landing_gear.tail_strike_attitude``)
    less ``tail_clearance_deg`` while a gear leg is on the runway (the same review: lift-off attitude about 2–4°
    below the tail-strike attitude), held there until the wheels are clear of the runway; then the rotation goes on
    toward the attitude that flies the speed: V2 with the engine failed,
    V2 + ``all_engines_speed_increment_kn`` with all engines; feed-forward elevator of the V2 trim, PI attitude
    feedback with rate damping;
  * the pedals on the runway heading and the centreline on the ground as the aircraft file's ``takeoff_pilot`` says
    (held for its reaction time after the failure, then at most its rudder rate; pedal nose-wheel steering when
    declared, the nose wheel held straight otherwise), wings level on the
    ground, ``bank_deg`` toward the live engine in the air (§25.149(b) allowance);
  * the critical engine (largest |y|) fails when the airspeed reaches VEF (V1 less the speed gained
    over the recognition interval after the failure, §25.107(a)(2); never below the computed VMCG, §25.107(a)(1)), its
    thrust decaying to windmilling drag with the
    declared ``propulsion.failure_decay_time`` (windmilling at once without it: the basis says so).
Representativeness (:func:`unrepresentative`): a run that does not lift off, or reaches the tail-strike attitude on the
runway (the pilot's rotation stays below it), does not stand for a takeoff a pilot flies and earns no verdict. How far
the ground run strays from the centreline after the engine failure is the airplane's directional control with the
declared pilot: not a reason, but a check of §25.111 (:data:`GROUND_TRACK_CRITERIA`), reported by every rule.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from certkit_rules.part25.support.ground_control import computed_vmcg
from certkit_rules.part25.support.thrust_trims import critical_engine, takeoff_trim

from certkit.atmosphere import convert_speed
from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.registry import Criterion
from certkit.models.dynamics.procedures import engine_failure_speed, takeoff_run
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN

#: criteria shared by the rules that use the simulated takeoff (same defaults: one memoised run serves them all)
PROCEDURE_CRITERIA = {
    "screen_height": Criterion(
        35.0,
        "ft",
        "14 CFR 25.111(c)(2), 25.113(a)",
        "height above the takeoff surface of the takeoff path's 35-ft point",
    ),
    "recognition_time": Criterion(
        1.0,
        "s",
        "project choice after §25.107(a)(2) (VEF to V1 is the speed gained over "
        "the recognition interval; 1 s is the usual demonstrated interval, AC 25-7 practice, "
        "unverified); 0 fails the engine at V1",
        "recognition interval from VEF to V1",
    ),
    "bank_deg": Criterion(
        5.0,
        "deg",
        "project choice: the §25.149(b) allowance of not more than 5° of bank toward the "
        "operating engine, flown once airborne",
        "bank toward the operating engine in the air",
    ),
    "climb_out_s": Criterion(
        10.0,
        "s",
        "project choice: climb-out simulated past 35 ft for the gradient",
        "time simulated after the screen height",
    ),
    "rotation_rate_deg_s": Criterion(
        2.5,
        "deg/s",
        "Boeing Flight Operations Review 'The importance of proper rotation "
        "technique' (14 Mar 1986): typically 2–3°/s, not more than 3°/s (secondary copy)",
        "commanded rotation rate",
    ),
    "tail_clearance_deg": Criterion(
        2.0,
        "deg",
        "Boeing Flight Operations Review (14 Mar 1986): lift-off attitude about "
        "2–4° below the tail-strike attitude (the least of the range; secondary copy)",
        "attitude kept below the tail-strike attitude with a gear leg on the runway",
    ),
    "all_engines_speed_increment_kn": Criterion(
        10.0,
        "kn",
        "project choice: all engines, the pitch flies V2 + 10 kn "
        "(the 777 FCTM's all-engines initial climb speed is V2 + 15 to "
        "V2 + 25, secondary copy; 10 kn keeps the run near the scheduled "
        "speeds)",
        "all-engines climb speed above V2 (CAS)",
    ),
}

#: what the simulated takeoffs need from the aircraft file (§25.111 and §25.113 fly the same runs)
TAKEOFF_REQUIRES = (
    "speeds.V1",
    "speeds.VR",
    "speeds.V2",
    "geometry.landing_gear",
    "geometry.horizontal_tail.controls.elevator",
    "geometry.vertical_tail.controls.rudder",
)


def takeoff_conditions(note: str) -> ConditionSpace:
    """The runs' conditions: MTOW at the forward, reference and aft CG, takeoff configuration."""
    return ConditionSpace(
        loading=DesignWeight("MTOW", ("forward", "reference", "aft")), configurations=("takeoff",), note=note
    )


#: §25.111's bound on the engine-out ground run's track (the run earns its verdicts whatever the track: a deviation is
#: the airplane's directional control with the declared pilot, judged, never a reason to set the run aside)
GROUND_TRACK_CRITERIA = {
    "lateral_deviation_max": Criterion(
        30.0,
        "ft",
        "the §25.149(e) bound on the deviation from the runway centreline after an engine failure on the ground, "
        "which VEF ≥ VMCG (§25.107(a)(1)) implies for the failure at VEF; applied up to the lift-off",
        "largest lateral deviation from the centreline on the ground, engine failed at VEF",
    ),
}


@dataclass
class Takeoffs:
    trims: object  # 1-g trims at V2 (one per loading)
    run: object  # TakeoffResult, 2n rows: engine failed, then all engines
    engine: str  # the failed (critical) engine
    vef: np.ndarray  # m/s TAS (inf on the all-engines rows)
    vef_basis: str
    theta_target: np.ndarray  # rad, ground rotation target per loading (after the tail-strike limit)
    basis: dict  # how the procedure was set up (rotation, tail strike, spool-down)


def simulated_takeoffs(
    ctx, conditions, crit, rotation_offset_kn: float = 0.0, failure_v1_kn: float | None = None, all_engines: bool = True
) -> Takeoffs:
    """The memoised engine-out and all-engines takeoffs of ``conditions`` (module docstring); ``crit`` holds the
    :data:`PROCEDURE_CRITERIA`. ``rotation_offset_kn`` (CAS) moves the rotation speed from the declared VR, the pilot's
    technique unchanged; ``failure_v1_kn`` (CAS) is the V1 VEF is derived from in place of the declared one. Without
    ``all_engines`` only the engine-out rows are flown (``run`` has n rows)."""

    def compute():
        ac = ctx.aircraft
        sp = ac.speeds
        n = len(conditions)
        copies = 2 if all_engines else 1
        tas = lambda s: float(convert_speed(s.value, s.kind, "TAS", 0.0))  # noqa: E731
        vr, v2, v1 = tas(sp.VR), tas(sp.V2), tas(sp.V1)
        if rotation_offset_kn:
            vr_cas = float(convert_speed(sp.VR.value, sp.VR.kind, "CAS", 0.0)) + rotation_offset_kn * KN
            vr = float(convert_speed(vr_cas, "CAS", "TAS", 0.0))
        if failure_v1_kn is not None:
            v1 = float(convert_speed(failure_v1_kn * KN, "CAS", "TAS", 0.0))
        trims, held = takeoff_trim(ctx, conditions)
        theta = np.array([r.theta for r in trims.results])
        de_ff = np.array([r.controls.get("elevator", 0.0) if r.converged else 0.0 for r in trims.results])
        settings = {k: np.tile(v, copies) for k, v in held.items()}
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        pilot = ac.takeoff_pilot
        steering = pilot.nose_wheel_steering or None
        model = flight_model(
            ac,
            ctx.aero("takeoff").model,
            loadings * copies,
            ground=ground_model(ac, nose_wheel="steered" if steering else "straight"),
        )
        engine = critical_engine(ctx)  # the same engine as the climb rules' (§25.121)
        vef, vef_basis = engine_failure_speed(
            model, v1, engine, crit.recognition_time, ac.propulsion.failure_decay_time
        )
        if failure_v1_kn is not None:
            vef_basis += f" (V1 taken at {failure_v1_kn:g} KCAS)"
        vmcg, _, _ = computed_vmcg(ctx)  # the failure is never scheduled below VMCG (§25.107(a)(1))
        if vmcg is not None and np.isfinite(vmcg):
            low = vef < float(convert_speed(vmcg, "CAS", "TAS", 0.0))
            if low.any():
                vef = np.where(low, float(convert_speed(vmcg, "CAS", "TAS", 0.0)), vef)
                vef_basis += f"; raised to VMCG {vmcg / KN:.1f} KCAS (§25.149(e)) where below it"
        vef[n:] = np.inf  # the all-engines rows
        y = {e.name: e.position.y for e in ac.propulsion.engines}
        toward_live = -np.sign(y[engine]) if y[engine] != 0 else 1.0  # bank right (+) when the left engine is dead
        bank = np.concatenate([np.full(n, toward_live * np.radians(crit.bank_deg)), np.zeros(n)])[: copies * n]
        v_aeo = float(
            convert_speed(
                float(convert_speed(v2, "TAS", "CAS", 0.0)) + crit.all_engines_speed_increment_kn * KN,
                "CAS",
                "TAS",
                0.0,
            )
        )
        climb = np.concatenate([np.full(n, v2), np.full(n, v_aeo)])[: copies * n]
        strike = ac.geometry.landing_gear.tail_strike_attitude
        margin = np.radians(crit.tail_clearance_deg)
        target = theta if strike is None else np.minimum(theta, strike - margin)
        decay = ac.propulsion.failure_decay_time
        travel = control_limits(ac, design=False)
        # RK4 at 10 Hz: against 20 Hz the extreme elevator moves by < 0.1° and V35 by < 0.1 kn (measured on
        # the baseline, all engines), at 40 % of the cost
        run = takeoff_run(
            model,
            vr,
            np.tile(target, copies),
            climb_speed=climb,
            settings=settings,
            elevator_ff=np.tile(de_ff, copies),
            tail_strike=None,
            rotation_rate=np.radians(crit.rotation_rate_deg_s),
            screen_height=crit.screen_height * FT,
            elevator_limits=travel["elevator"],
            lateral_limits=travel,
            dt=0.1,
            failed_engine=engine,
            failure_speed=vef,
            failure_decay_time=decay,
            lateral="pilot",
            bank_airborne=bank,
            climb_out=crit.climb_out_s,
            reaction_time=pilot.rudder_reaction_time,
            rudder_rate=pilot.rudder_rate,
            steering=steering,
        )
        basis = {
            "rotation": (
                f"rotation at {crit.rotation_rate_deg_s:g}°/s from "
                + (f"VR {rotation_offset_kn:+g} kt" if rotation_offset_kn else "VR")
                + " toward the 1-g V2 attitude"
                + (
                    ""
                    if strike is None
                    else f", at most {np.degrees(strike):.1f}° tail strike − {crit.tail_clearance_deg:g}° on the runway"
                )
                + f"; airborne to V2 (engine out) / V2 + {crit.all_engines_speed_increment_kn:g} kn (all engines)"
            ),
            "tail_strike": (
                "declared geometry.landing_gear.tail_strike_attitude"
                if strike is not None
                else "no tail-strike attitude declared (geometry.landing_gear.tail_strike_attitude): the "
                "rotation is limited by the V2 attitude only"
            ),
            "pilot": (
                f"rudder held {pilot.rudder_reaction_time:g} s after the failure, then at most "
                f"{np.degrees(pilot.rudder_rate):g}°/s (takeoff_pilot); "
                + (
                    f"pedal nose-wheel steering {np.degrees(steering):g}° at full pedal"
                    if steering
                    else "no nose-wheel steering declared (the nose wheel held straight)"
                )
            ),
            "spool_down": (
                f"first-order thrust decay, τ = {decay:g} s (propulsion.failure_decay_time)"
                if decay
                else "no propulsion.failure_decay_time declared: the failed engine windmills at once"
            ),
            "tail_strike_deg": None if strike is None else round(float(np.degrees(strike)), 2),
            "held_settings": (
                {k: [round(float(np.degrees(v)), 2) for v in vals[:n]] for k, vals in settings.items()} or None
            ),
        }
        return Takeoffs(trims, run, engine, vef, vef_basis, target, basis)

    key = (
        "simulated takeoffs",
        tuple((c.mass, c.x_cg) for c in conditions),
        tuple(float(getattr(crit, k)) for k in PROCEDURE_CRITERIA),
        float(rotation_offset_kn),
        failure_v1_kn,
        all_engines,
    )
    return ctx.memo(key, compute)


def failure_speed_at_v1(ctx, cond, recognition_time: float | None = None):
    """(VEF m/s CAS, how it was obtained) of the loading of ``cond`` at sea level: V1 less the speed gained over the
    recognition interval (:data:`PROCEDURE_CRITERIA`'s unless given) after the critical engine's failure, as the
    simulated takeoff fails it; (None, why) without V1 or the landing gear."""
    ac = ctx.aircraft
    if ac.speeds.V1 is None or ctx.missing(("geometry.landing_gear",)):
        return None, "needs speeds.V1 and geometry.landing_gear (VEF from V1)"
    dt = PROCEDURE_CRITERIA["recognition_time"].value if recognition_time is None else recognition_time

    def compute():
        v1 = float(convert_speed(ac.speeds.V1.value, ac.speeds.V1.kind, "TAS", 0.0))
        model = flight_model(
            ac,
            ctx.aero("takeoff").model,
            [ctx.loading(cond.mass, cond.x_cg, cond.loading or "")],
            ground=ground_model(ac),
        )
        vef, basis = engine_failure_speed(model, v1, critical_engine(ctx), dt, ac.propulsion.failure_decay_time)
        return float(convert_speed(float(vef[0]), "TAS", "CAS", 0.0)), basis

    return ctx.memo(("vef at v1", cond.mass, cond.x_cg, dt), compute)


def distances(to: Takeoffs, i: int, n: int) -> dict:
    """§25.113(a) distances of loading ``i`` (ft; None where the run did not reach 35 ft): the engine-out distance to
    35 ft (the accelerate-go distance, failure at VEF), the all-engines distance to 35 ft and 1.15 × it, and the
    takeoff distance, the greater of the engine-out and the factored all-engines distances; and the length of the
    engine-out run (a lower bound of its distance to 35 ft when it did not get there)."""
    run = to.run
    ft = lambda v: round(float(v) / FT, 0) if np.isfinite(v) else None  # noqa: E731
    oei, aeo = run.x_screen[i], run.x_screen[n + i]
    return {
        "accelerate_go_distance_ft": ft(oei),
        "all_engines_distance_to_35ft_ft": ft(aeo),
        "all_engines_distance_x1.15_ft": ft(1.15 * aeo),
        "takeoff_distance_ft": ft(max(oei, 1.15 * aeo)) if np.isfinite(oei) and np.isfinite(aeo) else None,
        "all_engines_liftoff_distance_ft": ft(run.x_lof[n + i]),
        "engine_out_run_length_ft": ft(run.sim["x_N"][-1, i] - run.x0[i, 0]),
    }


def run_summary(to: Takeoffs, i: int, vr_kn: float, v2_kn: float) -> dict:
    """What row ``i`` of the run did with the scheduled speeds (CAS kn, ft, deg): lift-off and 35-ft speeds and how far
    they lie beyond VR and V2, the largest deviation from the centreline and attitude on the runway."""
    run = to.run
    cas = lambda v: round(float(convert_speed(v, "TAS", "CAS", 0.0)) / KN, 2) if np.isfinite(v) else None  # noqa: E731
    vlof, v35 = cas(run.v_lof[i]), cas(run.v_screen[i])
    return {
        "vr_kn": vr_kn,
        "v2_kn": v2_kn,
        "vlof_kn": vlof,
        "v35_kn": v35,
        "vlof_after_vr_kn": None if vlof is None else round(vlof - vr_kn, 2),
        "v35_above_v2_kn": None if v35 is None else round(v35 - v2_kn, 2),
        "max_lateral_deviation_on_ground_ft": round(float(run.lateral_on_ground_max[i]) / FT, 1),
        "max_pitch_on_ground_deg": round(float(np.degrees(run.pitch_on_ground_max[i])), 2),
        "max_pitch_to_liftoff_deg": round(float(np.degrees(run.pitch_to_liftoff_max[i])), 2),
        "max_pitch_rate_before_liftoff_deg_s": (
            round(float(np.degrees(run.pitch_rate_max[i])), 2) if np.isfinite(run.pitch_rate_max[i]) else None
        ),
    }


def unrepresentative(summary: dict, tail_strike_deg: float | None = None, to_liftoff: bool = False) -> list[str]:
    """Why a simulated run is not a takeoff a pilot flies (empty: it is): no lift-off, the tail on the runway (with
    ``to_liftoff``, up to the lift-off only: what a check of the lift-off itself needs). Such a run earns no verdict.
    How late the airplane lifts off after VR, how fast it passes 35 ft and how far its ground run strays from the
    centreline are physics (its rotation capability and directional control with the scheduled speeds), not reasons:
    :func:`run_summary` reports them and §25.111 judges the track (:data:`GROUND_TRACK_CRITERIA`)."""
    if summary["vlof_kn"] is None:
        return ["the airplane did not lift off"]
    out = []
    pitch = summary["max_pitch_to_liftoff_deg" if to_liftoff else "max_pitch_on_ground_deg"]
    if tail_strike_deg is not None and pitch >= tail_strike_deg:
        out.append(
            f"the attitude on the runway reaches {pitch:.1f}°{' before the lift-off' if to_liftoff else ''}, at or "
            f"past the {tail_strike_deg:.1f}° tail-strike attitude"
        )
    return out


def not_a_takeoff(why: list[str], run: str = "the simulated takeoff") -> str:
    """The reason of the finding a run :func:`unrepresentative` sets aside: ``run`` and the ``why`` it gave."""
    return f"{run} does not represent one a pilot flies: " + "; ".join(why)

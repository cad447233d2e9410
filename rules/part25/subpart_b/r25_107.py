"""§25.107 Takeoff speeds (Amdt. 25-121 era text). Declared V1, VR, V2, VFTO against VSR, VMC, VMCG; and
§25.107(e)(1)(iv), VLOF at the maximum practicable rotation rate against the computed VMU.

Each sub-check of §25.107 is its own finding, so the rule reports what it can: the VSR parts are evaluated from
§25.103's reference stall speed of the takeoff configuration at MTOW; the VMC parts use the declared VMC, or
where none is declared the VMCA that §25.149 computes (the basis is named in the finding); the VMCG part the
declared VMCG or the one §25.149(e) computes by simulation, against VEF (V1 less the speed gained over the
recognition interval after the critical engine's failure).

§25.107(e)(1)(iv) is a rule of its own (its conditions are the takeoff runs' three CGs): VMU from
:func:`certkit.models.dynamics.unstick.minimum_unstick_speed` (all engines, and with the critical engine windmilling:
the one-engine-inoperative thrust-to-weight ratio), VLOF from the simulated takeoffs of §25.111 rotated at the
maximum practicable rate, the factors those of the geometry-limited branch where VMU is reached at the tail-strike
attitude. §25.107(c)(2) and (e)(1)(iii), V2 and VR against the speed the §25.111 engine-out takeoff reaches at 35 ft,
are rule 25.107(c)(2).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from certkit_rules.part25.support.ground_control import computed_vmcg
from certkit_rules.part25.support.maneuvering import EN_ROUTE_CRITERIA, case_spec, turn_findings
from certkit_rules.part25.support.minimum_control import computed_vmca
from certkit_rules.part25.support.reference_speeds import declared_cas, ratio_check, reference_stall_speed
from certkit_rules.part25.support.takeoff import (
    PROCEDURE_CRITERIA,
    TAKEOFF_REQUIRES,
    failure_speed_at_v1,
    not_a_takeoff,
    run_summary,
    simulated_takeoffs,
    takeoff_conditions,
    unrepresentative,
)
from certkit_rules.part25.support.unstick import unstick_speeds

from certkit.atmosphere import convert_speed
from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.evidence.performance import margins_evidence, unstick_evidence
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.units import FT, KN

AMDT = "25-121"
TAKEOFF = "takeoff"


@rule
class TakeoffSpeeds(Rule):
    id = "25.107"
    symbol = "takeoff-speeds"
    title = "Takeoff speeds"
    amendment = AMDT
    requirement = """
        VFTO may not be less than 1.18 VSR of the en-route configuration (g)(1).
        V2MIN may not be less than 1.13 VSR (two- and three-engine propeller airplanes, and turbojets without
        provisions for a significant reduction of the one-engine-inoperative power-on stall speed; 1.08 VSR for
        propeller airplanes with more than three engines and turbojets with such provisions) nor 1.10 VMC (b);
        V2 may not be less than V2MIN (c)(1). VEF may not be less than VMCG, V1 not less than VEF (a).
        VR may not be less than V1 nor 1.05 VMC (e)(1)(i)-(ii); the VLOF it gives against VMU ((e)(1)(iv)) is
        rule 25.107(e)(1)(iv), V2 and VR against the speed at 35 ft ((c)(2), (e)(1)(iii)) rule 25.107(c)(2), the
        VR − 5 kt engine-out distance ((e)(3)) rule 25.107(e)(3), VFTO's manoeuvring capability ((g)(2)) rule
        25.107(g)(2).
    """
    margin = """
        Ratios less their factors (≥ 0 complies): V2/VSR − 1.13, V2/VMC − 1.10, VR/V1 − 1, VR/VMC − 1.05,
        VEF/VMCG − 1, VFTO/VSR − 1.18; VSR of the takeoff configuration (of the clean one for VFTO) at
        MTOW (§25.103), speeds CAS.
    """
    references = ("25.103", "25.111", "25.121(b)", "25.143(h)", "25.149")
    requires = ("speeds.V2", "configurations.takeoff")
    criteria = {
        "v2_over_vsr": Criterion(
            1.13,
            "",
            "14 CFR 25.107(b)(1)(ii)",
            "V2MIN/VSR, turbojet without power-on stall-speed reduction provisions "
            "(1.08 under (b)(2)(ii): override with the justification)",
        ),
        "v2_over_vmc": Criterion(1.10, "", "14 CFR 25.107(b)(3)", "V2MIN/VMC"),
        "vr_over_v1": Criterion(1.0, "", "14 CFR 25.107(e)(1)(i)", "VR may not be less than V1"),
        "vr_over_vmc": Criterion(1.05, "", "14 CFR 25.107(e)(1)(ii)", "VR/VMC"),
        "v1_over_vmcg": Criterion(
            1.0,
            "",
            "14 CFR 25.107(a)(1)-(2)",
            "VEF/VMCG, VEF ≥ VMCG (VEF from V1 less the recognition interval's speed gain)",
        ),
        "vfto_over_vsr": Criterion(
            1.18, "", "14 CFR 25.107(g)(1)", "VFTO/VSR, VSR of the en-route (clean) configuration"
        ),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MTOW", ("reference",)),
        configurations=(TAKEOFF,),
        altitudes=None,
        note="VSR from the declared trimmed CLmax is not CG-sensitive here, so the reference CG.",
    )
    limitations = """
        V2 against VR plus the increment to 35 ft (c)(2) and VR giving V2 by 35 ft (e)(1)(iii) are rule 25.107(c)(2)
        (on the §25.111 takeoffs); the VR − 5 kt one-engine-inoperative distance (e)(3) is rule 25.107(e)(3); VFTO and
        the §25.143(h) manoeuvring capability (g)(2) is rule 25.107(g)(2).
    """

    implementation = "partial"
    unevaluated = (
        (
            "25.107(c)(3)",
            "V2 against the speed that provides the §25.143(h) manoeuvring capability is not judged here (§25.143(h) "
            "flies the V2 turn)",
        ),
        ("25.107(e)(4)", "over-rotation and out-of-trim variations from the established takeoff are not evaluated"),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            cond = cond.with_(altitude=0.0)
            vsr, source = reference_stall_speed(ctx, TAKEOFF, cond.mass)
            speeds = {n: declared_cas(ctx, n) for n in ("V1", "VR", "V2", "VMC", "VMCG", "VFTO")}
            speeds["VSR"] = vsr
            speeds["VSR clean"], clean_source = reference_stall_speed(ctx, "clean", cond.mass)
            vmc_basis = "declared VMC"
            if speeds["VMC"] is None:
                speeds["VMC"] = computed_vmca(ctx)
                vmc_basis = "VMCA computed by §25.149 (no VMC declared)"
            out += [
                ratio_check(cond, "(b)(1), (c)(1) V2 ≥ 1.13 VSR", speeds, "V2", "VSR", crit.v2_over_vsr, basis=source),
                ratio_check(
                    cond, "(b)(3), (c)(1) V2 ≥ 1.10 VMC", speeds, "V2", "VMC", crit.v2_over_vmc, basis=vmc_basis
                ),
                ratio_check(cond, "(e)(1)(i) VR ≥ V1", speeds, "VR", "V1", crit.vr_over_v1),
                ratio_check(cond, "(e)(1)(ii) VR ≥ 1.05 VMC", speeds, "VR", "VMC", crit.vr_over_vmc, basis=vmc_basis),
                self._vef_check(ctx, cond, speeds, crit),
                ratio_check(
                    cond.with_(configuration="clean"),
                    "(g)(1) VFTO ≥ 1.18 VSR (en route)",
                    speeds,
                    "VFTO",
                    "VSR clean",
                    crit.vfto_over_vsr,
                    basis=clean_source,
                ),
            ]
        return out

    @staticmethod
    def _vef_check(ctx, cond, speeds, crit):
        """(a) VEF ≥ VMCG: VEF the speed from which V1 is reached one recognition interval after the failure of the
        critical engine (the simulated takeoff's, at MTOW and the reference CG: V1 ≥ VEF by construction); VMCG the
        declared one, or where none is declared the highest §25.149(e) computes over the weight–CG corners."""
        check = "(a) VEF ≥ VMCG (V1 ≥ VEF)"
        basis = "declared VMCG"
        if speeds["VMCG"] is None:
            vmcg, corner, _ = computed_vmcg(ctx)
            if vmcg is None:
                return Finding.not_evaluated(cond, check, "needs speeds.VMCG (or what §25.149(e) needs to compute it)")
            speeds["VMCG"] = vmcg
            basis = f"VMCG computed by §25.149(e) (highest over the weight–CG corners: {corner}; no VMCG declared)"
        vef, vef_basis = failure_speed_at_v1(ctx, cond)
        if vef is None:
            return Finding.not_evaluated(cond, check, vef_basis)
        speeds["VEF"] = vef
        if not np.isfinite(speeds["VMCG"]):
            return Finding.compare(
                cond.with_(speed=vef, speed_kind="CAS", speed_name="VEF"),
                check,
                0.0,
                1.0,
                at_least=True,
                unit="ratio",
                VEF=vef,
                basis=basis,
                vef_basis=vef_basis,
                reason="§25.149(e) finds no VMCG on the runway (below VR)",
            )
        return ratio_check(cond, check, speeds, "VEF", "VMCG", crit.v1_over_vmcg, basis=f"{basis}; VEF: {vef_basis}")

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.107 takeoff speed ratios",
            "Declared takeoff speeds as ratios against their §25.107 factors.",
            ("V1", "VR", "V2", "VSR", "VMC", "VMCG"),
        )


@rule
class LiftOffSpeedMargin(Rule):
    id = "25.107(e)(1)(iv)"
    run_with = "takeoff"  # the §25.111 takeoff runs' trims and VMCG, memoised in one process
    symbol = "vlof-over-vmu"
    title = "VLOF against VMU at the maximum practicable rotation rate (simulated), all engines and engine out"
    amendment = AMDT
    requirement = """
        VR may not be less than a speed that, if the airplane is rotated at its maximum practicable rate, results
        in a VLOF of not less than 110 % of VMU with all engines operating and 105 % of VMU at the
        one-engine-inoperative thrust-to-weight ratio — 108 % and 104 % where VMU is limited by the airplane's
        geometry (tail contact with the runway). VMU (§25.107(d)) is the speed at and above which the airplane can
        safely lift off and continue the takeoff.
    """
    margin = """
        VLOF/VMU less the factor (ratio; ≥ 0 complies), per loading, all engines and engine out: VLOF of the
        simulated takeoff rotated at the maximum practicable rate (the critical engine failed at VEF for the engine-out
        VLOF), VMU the quasi-static minimum unstick speed (certkit.models.dynamics.unstick) at that loading, all
        engines and with the critical engine windmilling; speeds CAS, sea level.
    """
    references = ("25.107", "25.111")
    requires = (*TAKEOFF_REQUIRES, "geometry.landing_gear.tail_strike_attitude")
    criteria = {
        **PROCEDURE_CRITERIA,
        "max_practicable_rotation_rate_deg_s": Criterion(
            3.0,
            "deg/s",
            "project choice: the largest rate of the manufacturer's technique (Boeing Flight Operations Review, "
            "14 Mar 1986: typically 2–3°/s, 'should not exceed 3°/s'; secondary copy); a faster rotation lifts off "
            "earlier and is the §25.107(e)(4) over-rotation case",
            "rotation rate of the (e)(1)(iv) takeoffs",
        ),
        "vlof_over_vmu": Criterion(
            1.10, "", "14 CFR 25.107(e)(1)(iv)(A) (docs/regulation-notes.md, P)", "VLOF/VMU, all engines"
        ),
        "vlof_over_vmu_oei": Criterion(
            1.05, "", "14 CFR 25.107(e)(1)(iv)(A) (docs/regulation-notes.md, P)", "VLOF/VMU, one engine inoperative"
        ),
        "vlof_over_vmu_geometry": Criterion(
            1.08,
            "",
            "14 CFR 25.107(e)(1)(iv)(B); EASA AMC 25.107(e)(1)(iv) (docs/regulation-notes.md, P)",
            "VLOF/VMU, all engines, VMU limited by tail contact",
        ),
        "vlof_over_vmu_geometry_oei": Criterion(
            1.04,
            "",
            "14 CFR 25.107(e)(1)(iv)(B); EASA AMC 25.107(e)(1)(iv) (docs/regulation-notes.md, P)",
            "VLOF/VMU, one engine inoperative, VMU limited by tail contact",
        ),
    }
    conditions = takeoff_conditions("Sea level ISA, takeoff thrust; the §25.111 loadings.")
    limitations = """
        VMU is quasi-static (lift, thrust and weight in balance at the attitude, the pitch held by the elevator, the
        model's ground effect; no pitch rate, no strut extension): free-air data in the sense of §25.107(d), not
        verified by a ground test. The maximum practicable rotation rate is a criterion (3°/s), the rotation of the
        §25.111 pilot at that rate toward the V2 attitude and at most the tail-strike attitude less the clearance. A
        run that does not lift off or reaches the tail-strike attitude on the runway before it lifts off earns no
        verdict (after the lift-off the VLOF is what it is: the pilot model's rotation toward the climb attitude can set
        a wheel back down, which §25.111 judges; so is the engine-out ground track, whatever it is).
    """

    def evaluate(self, ctx, conditions, crit):
        n = len(conditions)
        fast = SimpleNamespace(**{k: getattr(crit, k) for k in PROCEDURE_CRITERIA})
        fast.rotation_rate_deg_s = crit.max_practicable_rotation_rate_deg_s
        to = simulated_takeoffs(ctx, conditions, fast)
        scheduled = simulated_takeoffs(ctx, conditions, crit)
        vmu = unstick_speeds(ctx, conditions)
        self.unstick = [c.loading or "" for c in conditions], vmu
        vr_kn, v2_kn = (declared_cas(ctx, name) / KN for name in ("VR", "V2"))
        strike = float(np.degrees(ctx.aircraft.geometry.landing_gear.tail_strike_attitude))
        cas = lambda v: float(convert_speed(v, "TAS", "CAS", 0.0))  # noqa: E731
        out = []
        for engine_out, label in ((False, "all engines"), (True, "one engine inoperative")):
            u = vmu.engine_out if engine_out else vmu.all_engines
            speeds = vmu.vmu_cas(engine_out)
            for i, cond in enumerate(conditions):
                row = i if engine_out else n + i
                name = ("vlof_over_vmu_geometry" if u.geometry_limited[i] else "vlof_over_vmu") + (
                    "_oei" if engine_out else ""
                )
                factor = getattr(crit, name)
                check = f"(e)(1)(iv) VLOF ≥ {factor:g} VMU, {label}"
                c = cond.with_(altitude=0.0, **({"inoperative": vmu.engine} if engine_out else {}))
                if not np.isfinite(speeds[i]):
                    out.append(
                        Finding.not_evaluated(
                            c,
                            check,
                            f"no attitude up to the {strike:.1f}° tail-strike attitude lifts the airplane off below "
                            "the search's upper speed with the elevator within its travel",
                        )
                    )
                    continue
                summary = run_summary(to, row, vr_kn, v2_kn)
                why = unrepresentative(summary, tail_strike_deg=strike, to_liftoff=True)
                details = {
                    "VMU": speeds[i],
                    "vmu_limited_by": u.limited_by[i],
                    "vmu_attitude_deg": round(float(np.degrees(u.attitude[i])), 2),
                    "vmu_elevator_deg": round(float(np.degrees(u.elevator[i])), 2),
                    "vmu_lift_coefficient": round(float(u.lift_coefficient[i]), 4),
                    "rotation_rate_deg_s": crit.max_practicable_rotation_rate_deg_s,
                    "vlof_scheduled_rotation_kn": run_summary(scheduled, row, vr_kn, v2_kn)["vlof_kn"],
                    **summary,
                }
                if why:
                    out.append(
                        Finding.not_evaluated(
                            c, check, "the takeoff at the maximum practicable rate " + "; ".join(why), **details
                        )
                    )
                    continue
                vlof = cas(to.run.v_lof[row])
                out.append(
                    Finding.compare(
                        c.with_(speed=vlof, speed_kind="CAS", speed_name="VLOF"),
                        check,
                        vlof / speeds[i],
                        factor,
                        at_least=True,
                        unit="ratio",
                        VLOF=vlof,
                        **details,
                    )
                )
        return out

    def evidence(self, ctx, findings, crit):
        kept = getattr(self, "unstick", None)
        curves = [] if kept is None else unstick_evidence(findings, kept[0], kept[1].all_engines, kept[1].engine_out)
        return curves + margins_evidence(
            findings,
            "§25.107(e)(1)(iv) VLOF against VMU",
            "Lift-off speed at the maximum practicable rotation rate against the minimum unstick speed.",
            ("VLOF", "VMU", "vmu_limited_by", "vlof_scheduled_rotation_kn"),
        )


@rule
class SpeedsAt35Feet(Rule):
    id = "25.107(c)(2)"
    run_with = "takeoff"  # the engine-out runs of §25.111, memoised in one process
    symbol = "v2-and-vr-at-35-ft"
    title = "V2 against VR plus the speed increment to 35 ft, and VR reaching V2 by 35 ft ((e)(1)(iii)) (simulated)"
    amendment = AMDT
    requirement = """
        V2 may not be less than VR plus the speed increment attained (in accordance with §25.111(c)(2)) before
        reaching a height of 35 feet above the takeoff surface (c)(2); VR may not be less than the speed (determined
        in accordance with §25.111(c)(2)) that allows reaching V2 before reaching a height of 35 feet above the
        takeoff surface (e)(1)(iii).
    """
    margin = """
        Knots CAS, per loading, on the §25.111 engine-out takeoff (critical engine failed at VEF, rotated at VR as
        scheduled, then flown as close as practical to V2): (c)(2) V2 − (VR + the increment from VR to the speed at
        35 ft), i.e. V2 − V35; (e)(1)(iii) V35 − V2. ≥ 0 complies; together they ask that V2 be the 35-ft speed of
        the scheduled takeoff.
    """
    references = ("25.107", "25.111")
    requires = TAKEOFF_REQUIRES
    criteria = dict(PROCEDURE_CRITERIA)
    conditions = takeoff_conditions("Sea level ISA, takeoff thrust; the §25.111 loadings.")
    limitations = """
        The increment is the simulated pilot's (rotation at the scheduled rate to the attitude held on the runway,
        then the climb attitude that flies V2): a run that is not a takeoff (no lift-off, the tail on the runway)
        earns no verdict. No tolerance is applied to the equality the two sub-paragraphs ask for: a V35 above V2 by
        any amount fails (c)(2), below it (e)(1)(iii).
    """

    checks = ("(c)(2) V2 ≥ VR + the speed increment to 35 ft", "(e)(1)(iii) VR allowing V2 by 35 ft")

    def evaluate(self, ctx, conditions, crit):
        to = simulated_takeoffs(ctx, conditions, crit)
        vr_kn, v2_kn = (declared_cas(ctx, name) / KN for name in ("VR", "V2"))
        out = []
        for i, cond in enumerate(conditions):  # the engine-out rows
            c = cond.with_(altitude=0.0, inoperative=to.engine)
            summary = run_summary(to, i, vr_kn, v2_kn)
            why = unrepresentative(summary, tail_strike_deg=to.basis["tail_strike_deg"])
            if not why and summary["v35_kn"] is None:
                why = ["the engine-out run does not reach 35 ft"]
            if why:
                reason = not_a_takeoff(why)
                out += [Finding.not_evaluated(c, check, reason, **summary) for check in self.checks]
                continue
            v35 = summary["v35_kn"]
            details = {**summary, "speed_increment_kn": round(v35 - vr_kn, 2), "vef_basis": to.vef_basis}
            out += [
                Finding.compare(c, self.checks[0], v2_kn, v35, at_least=True, unit="kn", V35=v35, **details),
                Finding.compare(c, self.checks[1], v35, v2_kn, at_least=True, unit="kn", **details),
            ]
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.107(c)(2) and (e)(1)(iii): V2 and the speed at 35 ft",
            "The declared V2 against the speed the engine-out takeoff reaches at 35 ft, rotated at the declared VR.",
            ("V35", "vr_kn", "v2_kn", "vlof_kn", "speed_increment_kn"),
        )


@rule
class EarlyRotationDistance(Rule):
    id = "25.107(e)(3)"
    run_with = "takeoff"  # the established-VR engine-out runs of §25.111, memoised in one process
    symbol = "early-rotation-distance"
    title = "One-engine-inoperative takeoff distance rotated at VR − 5 kt against that at VR (simulated)"
    amendment = AMDT
    requirement = """
        It must be shown that the one-engine-inoperative takeoff distance, using a rotation speed of 5 knots less
        than VR established in accordance with (e)(1) and (2), does not exceed the corresponding
        one-engine-inoperative takeoff distance using the established VR; the takeoff distances determined in
        accordance with §25.113(a)(1).
    """
    margin = """
        Feet, per loading: the engine-out distance to 35 ft (§25.113(a)(1)) of the §25.111 takeoff rotated at the
        established VR, less that of the same takeoff rotated 5 kt CAS earlier (≥ 0 complies): same loading, engine
        failure and pilot technique, only the rotation speed moved; each distance interpolated to where the lowest
        wheel crosses 35 ft.
    """
    references = ("25.111", "25.113")
    requires = TAKEOFF_REQUIRES
    criteria = {
        **PROCEDURE_CRITERIA,
        "early_rotation_kn": Criterion(
            5.0,
            "kn",
            "14 CFR 25.107(e)(3) (text up to 'less than VR' corroborated by the GPO 2007 print and a secondary copy; "
            "the rest not read in a primary rendering)",
            "how much earlier than VR (CAS) the abused takeoff rotates",
        ),
        "distance_increase_allowed": Criterion(
            0.0,
            "",
            "14 CFR 25.107(e)(3): 'does not exceed' (no allowance); the FAA flight-test hazard analysis citing "
            "AC 25-7A (Section 2 para 10b, secondary) accepts 'no more than 1% increase' in a test: 0.01 for that "
            "reading",
            "fraction by which the early-rotation distance may exceed the established one",
        ),
    }
    conditions = takeoff_conditions("Sea level ISA, takeoff thrust from brake release; the §25.111 loadings.")
    limitations = """
        The early rotation is the §25.111 pilot's (the same rate toward the same attitude on the runway, then V2 in the
        air) begun 5 kt CAS before VR; the critical engine fails at the same VEF in both takeoffs. Where the declared
        V1 lies above VR − 5 kt, both fail it at the VEF of V1 = VR − 5 kt (§25.107(e)(1)(i) allows no rotation below
        V1; the engine is cut before the rotation, as in the flight-test practice), so that only the rotation speed
        differs; the distance with the declared V1 is reported beside. The pilot holds the attitude
        below the tail-strike attitude on the runway; a run that still reaches it (the rotation overshooting), that
        does not lift off or does not reach 35 ft earns no verdict — except an early-rotation run still short of 35 ft
        after rolling past the established distance, which fails on that lower bound. Sea level, MTOW, dry runway.
    """

    def evaluate(self, ctx, conditions, crit):
        vr_kn, v2_kn, v1_kn = (declared_cas(ctx, name) / KN for name in ("VR", "V2", "V1"))
        early_kn = vr_kn - crit.early_rotation_kn
        failure_v1 = early_kn if v1_kn > early_kn + 1e-6 else None  # V1 at the early rotation speed where above it
        scheduled = simulated_takeoffs(ctx, conditions, crit)
        established = (
            scheduled
            if failure_v1 is None
            else simulated_takeoffs(ctx, conditions, crit, failure_v1_kn=failure_v1, all_engines=False)
        )
        early = simulated_takeoffs(
            ctx, conditions, crit, -crit.early_rotation_kn, failure_v1_kn=failure_v1, all_engines=False
        )
        strike = established.basis["tail_strike_deg"]
        allowed = 1.0 + crit.distance_increase_allowed
        check = f"(e)(3) engine-out takeoff distance rotated at VR − {crit.early_rotation_kn:g} kt ≤ at VR"
        ft = lambda v: round(float(v) / FT, 1) if np.isfinite(v) else None  # noqa: E731
        out = []
        for i, cond in enumerate(conditions):  # the engine-out rows of the runs
            c = cond.with_(altitude=0.0, thrust="takeoff", inoperative=established.engine)
            at_vr = run_summary(established, i, vr_kn, v2_kn)
            at_early = run_summary(early, i, early_kn, v2_kn)
            d_vr, d_early = established.run.x_screen_crossing[i], early.run.x_screen_crossing[i]
            details = {
                "established": at_vr,
                "early_rotation": at_early,
                "rotation_speed_kn": round(early_kn, 2),
                "vef_kn": round(float(convert_speed(established.vef[i], "TAS", "CAS", 0.0)) / KN, 2),
                "vef_basis": established.vef_basis,
                "rotation_basis": early.basis["rotation"],
            }
            if failure_v1 is not None:
                details["declared_v1_distance_ft"] = ft(scheduled.run.x_screen_crossing[i])
            why = unrepresentative(at_vr, tail_strike_deg=strike)
            if not why and not np.isfinite(d_vr):
                why = [f"it does not reach {crit.screen_height:g} ft"]
            if why:
                reason = not_a_takeoff(why, "the established-VR engine-out takeoff")
                out.append(Finding.not_evaluated(c, check, reason, **details))
                continue
            details["established_distance_ft"] = ft(d_vr)
            limit = ft(allowed * d_vr)
            if not np.isfinite(d_early):
                rolled = early.run.sim["x_N"][-1, i] - early.run.x0[i, 0]
                if rolled > allowed * d_vr:  # still short of 35 ft beyond the established distance
                    reason = (
                        f"rotated at {early_kn:.0f} KCAS the engine-out takeoff had not reached {crit.screen_height:g} "
                        f"ft after {ft(rolled):,.0f} ft (a lower bound of its distance)"
                    )
                    out.append(
                        Finding.compare(
                            c, check, ft(rolled), limit, at_least=False, unit="ft", reason=reason, **details
                        )
                    )
                    continue
                why = unrepresentative(at_early, tail_strike_deg=strike) or [
                    f"it does not reach {crit.screen_height:g} ft within the run"
                ]
                out.append(
                    Finding.not_evaluated(c, check, f"rotated at {early_kn:.0f} KCAS: " + "; ".join(why), **details)
                )
                continue
            details["early_distance_ft"] = ft(d_early)
            why = unrepresentative(at_early, tail_strike_deg=strike)
            if why:
                reason = (
                    f"rotated at {early_kn:.0f} KCAS the engine-out takeoff " + "; ".join(why) + " (the pilot holds "
                    f"{crit.tail_clearance_deg:g}° below it): the distance of a run with the tail on the runway is not "
                    "modelled"
                )
                out.append(Finding.not_evaluated(c, check, reason, **details))
                continue
            out.append(
                Finding.compare(
                    c.with_(speed=early_kn * KN, speed_kind="CAS", speed_name=f"VR − {crit.early_rotation_kn:g} kt"),
                    check,
                    ft(d_early),
                    limit,
                    at_least=False,
                    unit="ft",
                    distance_ratio=round(float(d_early / d_vr), 5),
                    **details,
                )
            )
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.107(e)(3) early rotation",
            "Engine-out distance to 35 ft rotated 5 kt before VR against the distance rotated at VR.",
            ("early_distance_ft", "established_distance_ft", "distance_ratio", "rotation_speed_kn"),
        )


@rule
class FinalTakeoffSpeedManeuvering(Rule):
    id = "25.107(g)(2)"
    run_with = "coordinated turns"  # the §25.143(h) en-route turns, memoised in one process
    symbol = "vfto-maneuvering"
    title = "VFTO against the §25.143(h) manoeuvring capability: the en-route 40° coordinated turn at VFTO"
    amendment = AMDT
    requirement = """
        VFTO may not be less than a speed that provides the maneuvering capability specified in §25.143(h): en route,
        at VFTO, a constant-speed coordinated turn at 40° of bank with asymmetric WAT-limited thrust, free of stall
        warning or other characteristics that might interfere with normal manoeuvring.
    """
    margin = """
        Per loading (MTOW at the forward, reference and aft CG), altitude (sea level and 1500 ft) and turn direction,
        at the declared VFTO: the stall-warning onset's 1-g lift coefficient − the turn's CL = n W/(q S) (≥ 0: free of
        warning, VFTO at or above the speed that gives the capability), and each trim control's design limit −
        |deflection| (deg). A speed at which the turn's lift coefficient reaches the warning onset is reported (the
        declared VFTO × √(CL/CL_warning), the load factor and path held).
    """
    references = ("25.143(h)", "25.121(c)", "25.207")
    requires = ("speeds.VFTO", "configurations.clean", "mass.MTOW")
    criteria = dict(EN_ROUTE_CRITERIA)
    conditions = ConditionSpace(
        extra=(("case", ("en route VFTO",)),),
        note="The §25.143(h) en-route case: MTOW at the forward, reference and aft CG, sea level and 1500 ft, turns "
        "toward and away from the inoperative (critical) engine.",
    )
    implementation = "partial"
    limitations = """
        The turns and thrust of §25.143(h) (its reading of "asymmetric WAT-limited": the thrust that climbs at the
        §25.121(c) minimum gradient in straight flight, at most maximum continuous thrust; the stall-warning onset
        declared or the latest §25.207(c) allows); a movable stabiliser trimmed wings level and held. Only the speed
        the declared VFTO is judged at; the speed that would just give the capability is an estimate beside it.
    """
    unevaluated = (
        (
            "25.107(g)(2)",
            "characteristics other than stall warning that might interfere with normal manoeuvring at VFTO (buffet "
            "onset) are not evaluated, as in §25.143(h)",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            for f in turn_findings(ctx, cond, case_spec("en route VFTO", crit), "(g)(2) VFTO, §25.143(h) 40° turn"):
                if f.check.endswith("free of stall warning") and f.status != "not_evaluated":
                    v = f.condition.speed
                    f.details["speed_at_warning_onset_kn"] = round(v * (f.value / f.limit) ** 0.5 / KN, 2)
                out.append(f)
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.107(g)(2) VFTO and the §25.143(h) turn",
            "The 40° coordinated turn at VFTO with asymmetric WAT-limited thrust: stall warning and controls.",
            ("load_factor", "CL", "stall_warning_CL", "speed_at_warning_onset_kn", "flight_path_deg"),
        )

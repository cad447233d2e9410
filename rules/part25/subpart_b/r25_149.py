"""§25.149 Minimum control speed: the computed VMCA against 1.13 VSR and against a declared VMC; VMCL (§25.149(f))
computed in each approach and landing configuration with its (h)(1) rudder force; VMCG by simulation.

VMCA is the speed at which, in straight one-engine-inoperative flight with the operating engine at full
throttle (maximum takeoff thrust; the flight-path angle takes up the excess thrust), takeoff flaps, the most
aft CG at MTOW, sea level, the rudder or the aileron reaches its design limit — the better of 5° of bank
toward the operating engine and wings level; below it straight flight cannot be held.
The search is :func:`certkit_rules.part25.support.control_speeds.vmca_search`.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.control_checks import pedal_force_finding
from certkit_rules.part25.support.control_speeds import BANK_FRACTIONS, throttle_of, vmca_from_grid
from certkit_rules.part25.support.ground_control import VMCG_CONDITIONS, VMCG_CRITERIA, VMCG_REQUIRES, vmcg_runs
from certkit_rules.part25.support.minimum_control import (
    VMCA_CONDITIONS,
    VMCA_CRITERIA,
    VMCA_REQUIRES,
    VMCA_RULE_ID,
    VMCL_CONDITIONS,
    condition_vmca,
    vmca_rows,
)

from certkit.atmosphere import convert_speed
from certkit.engine.evidence.performance import vmca_evidence
from certkit.engine.registry import Rule, rule
from certkit.engine.results import Finding
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.flight import control_limits
from certkit.units import KN, LBF


def _kn_cas(v_tas: float) -> float:
    """A sea-level true airspeed (m/s), as the VMCG search runs it, in knots CAS."""
    return float(convert_speed(v_tas, "TAS", "CAS", 0.0)) / KN


@rule
class MinimumControlSpeed(Rule):
    id = VMCA_RULE_ID
    cost = 2  # relative evaluation time (orders work over --jobs processes)
    symbol = "minimum-control-speed"
    title = "Minimum control speeds VMCA (in the air), VMCL (approach and landing) and VMCG (on the ground, simulated)"
    amendment = "25-108"
    requirement = """
        (b) VMC is the calibrated airspeed at which, when the critical engine is suddenly made inoperative, it is
        possible to maintain control with that engine still inoperative and straight flight with not more than 5° of
        bank. (c) VMC may not exceed 1.13 VSR with maximum available takeoff thrust, the most unfavourable CG, trimmed
        for takeoff, maximum sea-level takeoff weight, the most critical takeoff configuration with the gear
        retracted, airborne with negligible ground effect. (d) The rudder force may not exceed 150 lbf. (e) VMCG is the
        calibrated airspeed on the takeoff run at which, the critical engine suddenly made inoperative, control can be
        kept with the rudder alone (no nose-wheel steering), the wings level, and the path from the failure to the
        recovery to a direction parallel to the centreline deviates no more than 30 ft from the centreline. (f) VMCL
        is VMC during approach and landing with all engines operating, the critical engine failed at go-around
        thrust, trimmed for approach, the most unfavourable CG and weight (or as a function of weight); (h)(1) the
        rudder force in its demonstration may not exceed 150 lbf.
    """
    margin = """
        (c) 1.13 VSR − VMCA (m/s CAS), VMCA computed; (b) declared VMC − VMCA (m/s CAS), when VMC is declared;
        (d) 150 lbf − |rudder pedal force at VMCA| (lbf), with control_forces.rudder; (h)(1) the same at VMCL,
        per approach and landing configuration and inoperative engine (VMCL in the finding); (e) VR − VMCG (kn CAS)
        per corner of the weight–CG envelope, and declared VMCG − the highest computed VMCG (kn CAS) when VMCG is
        declared.
    """
    references = ("25.103", "25.107", "25.147")
    requires = VMCA_REQUIRES
    criteria = {**VMCA_CRITERIA, **VMCG_CRITERIA}
    conditions = VMCA_CONDITIONS
    implementation = "partial"
    limitations = """
        Static (steady) VMCA: the dynamic recovery of (d) (heading change ≤ 20°) is not simulated. VMCA is where the
        rudder or aileron reaches its design limit, or, where straight flight at a bank reaches the lift maximum with
        the controls within their limits, stall-limited (below that speed; reported as such); a trim failing above the
        stall is not evaluated; the 150 lbf of (d) is a separate finding at that VMCA (the pedal
        force of the steady trim, rudder trim neutral), evaluated only with control_forces.rudder; the speed at which
        the force reaches 150 lbf is reported with it. The
        baseline's takeoff configuration has the gear down (more drag, steeper flight path only; the moments are
        those of the gear-up airplane in the model). Thrust at throttle 1 is the maximum takeoff thrust. Banks from
        wings level to 5° toward the operating engine are searched in 1° steps; VMCA is the least (to within the 1°
        step, conservative). (e) VMCG by simulation (:mod:`certkit.models.dynamics.ground_control`): the critical engine
        cut with the declared spool-down, the nose wheel castering, the stabiliser at the V2 takeoff trim, the column
        holding the attitude of rest, the pilot's rudder held for the criteria's reaction time (1 s) after the cut and
        then moved at the declared takeoff_pilot.rudder_rate over its travel on heading and centreline, wings level;
        the deviation is the largest from the cut to the heading's return parallel to the centreline, or to the
        lift-off where a light airplane leaves the runway at the attitude of rest before its heading is back (the
        takeoff run is over: such a run counts when beyond the bound on the runway, or within it with the swing
        arrested there, the heading turning back; one still swinging away decides nothing; the search table marks
        the runs that lifted off); the search
        runs 9 failure speeds from 0.85 to 1.15 times the static rudder-moment balance speed (more toward 60 KCAS or
        VR only where the crossing lies outside), VMCG interpolated linearly (spacing about 5 kn, within 0.6 kn of a
        finer search on the baseline).
        The rudder is limited by the 150 lbf pedal force of (e) with control_forces.rudder (a q-feel or hinge-moment
        force taken at VR and zero sideslip), else by its stops only; sea level ISA, no wind;
        the takeoff configuration named 'takeoff' only.
    """

    unevaluated = (
        (
            "25.149(d)",
            "the dynamic recovery after the sudden engine failure (heading change ≤ 20°) is not simulated:"
            " VMCA is the static one",
        ),
        (
            "25.149(h)",
            "for VMCL, the roll through 20° away from the inoperative engine in 5 s ((h)(3)) and the dynamic "
            "engine failure ((h)(2)) are not simulated: VMCL is the static one",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = self._vmca(ctx, conditions, crit)
        return out + self._vmcl(ctx, crit) + self._vmcg(ctx, crit)

    def _vmcl(self, ctx, crit):
        """(f) VMCL in each declared approach and landing configuration (the VMCA search at go-around thrust, aft CG,
        MLW), judged by (h)(1): the rudder pedal force at VMCL ≤ 150 lbf (with control_forces.rudder). VMCL itself
        stands in each finding (speed, bank, what limits it) and §25.125 checks VREF against it."""
        conds = VMCL_CONDITIONS.expand(ctx.aircraft)
        check = f"(h)(1) rudder force at VMCL ≤ {crit.rudder_force_lbf:g} lbf"
        if not conds or ctx.missing(("mass.MLW",)):
            return [Finding.outside_scope("25.149(f)", "no approach or landing configuration (or no MLW) declared")]
        nb = len(BANK_FRACTIONS)
        out = []
        for cfg in dict.fromkeys(c.configuration for c in conds):  # one trim batch per configuration
            out += self._vmcl_of(ctx, [c for c in conds if c.configuration == cfg], crit, check, nb)
        return out

    def _vmcl_of(self, ctx, conds, crit, check, nb):
        rows = vmca_rows(ctx, conds, crit)  # the same search, at VMCL's conditions
        out = []
        for k, cond in enumerate(conds):
            pair = range(nb * k, nb * k + nb)
            vmcl, best, below = condition_vmca(rows, k, crit)
            vsr = rows["vsr"][best]
            found = cond.with_(speed=vmcl, speed_kind="CAS", speed_name="VMCL", thrust="go-around")
            details = dict(
                VMCL_kn_cas=round(vmcl / KN, 2),
                VMCL_over_VSR=round(vmcl / vsr, 4),
                bank_at_vmcl_deg=round(float(np.degrees(rows["banks"][best])), 1),
                vmcl_limited_by=rows["limited_by"][best],
                vmcl_by_bank_kn={
                    f"{np.degrees(rows['banks'][j]):.0f} deg": round(float(rows["vmca"][j]) / KN, 2) for j in pair
                },
            )
            if any(rows["limited_by"][j] == "trim failure" for j in pair):
                out.append(
                    Finding.not_evaluated(
                        found,
                        check,
                        "the straight one-engine-inoperative trim failed above the stall: VMCL is not determined",
                        **details,
                    )
                )
                continue
            if below:
                details["vmcl_note"] = f"controls within limits down to {crit.grid_low} VSR: VMCL is below it"
            ordered = sorted((h["speed"], h["trim"]) for h in rows["history"][best] if np.isfinite(h["usage"]))
            f = self._force_finding(
                ctx, found, vmcl, [v for v, _ in ordered], [t for _, t in ordered], crit, check=check, name="VMCL"
            )
            f.details.update(details)
            out.append(f)
        return out

    @staticmethod
    def _vmcg(ctx, crit):
        """(e) VMCG by simulation over the corners of the weight–CG envelope (:mod:`.ground_control`): per corner,
        VMCG no higher than VR (a speed on the runway at which the rudder alone holds the 30-ft band), and, with a
        declared speeds.VMCG, the declared value not below the highest computed one."""
        conds = VMCG_CONDITIONS.expand(ctx.aircraft)
        check = f"(e) VMCG (rudder only, ≤ {crit.vmcg_deviation_max_ft:g} ft off the centreline) found below VR"
        missing = ctx.missing(VMCG_REQUIRES)
        if missing:
            why = "needs " + ", ".join(missing)
            return [Finding.not_evaluated(c.with_(altitude=0.0), check, why) for c in conds]
        res = vmcg_runs(ctx, conds, crit)
        out = []
        worst, worst_cond = -np.inf, None
        for i, c in enumerate(conds):
            c0 = c.with_(altitude=0.0, thrust="takeoff", inoperative=res.engine)
            table = [
                {
                    "failure_speed_kn_cas": round(_kn_cas(v), 1),
                    "max_lateral_deviation_ft": (round(d / 0.3048, 1) if np.isfinite(d) else None),
                    "lifted_off_before_recovery": lifted,
                }
                for v, d, lifted in zip(res.search.speeds[i], res.search.deviations[i], res.search.lifted[i])
            ]
            details = dict(
                search=table,
                lifted_off_swinging_kn_cas=[round(_kn_cas(v), 1) for v in res.search.undecided[i]],
                **res.basis,
            )
            vmcg = res.speed_cas[i]
            if not np.isfinite(vmcg):
                out.append(
                    Finding.not_evaluated(
                        c0,
                        check,
                        "every engine-cut run lifted off at the attitude of rest within the bound with its heading "
                        "still swinging away: none says on which side of the bound the takeoff run's control lies",
                        **details,
                    )
                )
                continue
            found = c0.with_(speed=float(vmcg), speed_kind="CAS", speed_name="VMCG")
            reason = ""
            undecided, top = res.search.undecided[i], res.search.speeds[i][-1]
            if res.above[i]:
                vmcg = np.inf
                if undecided and undecided[0] > top:
                    reason = (
                        f"the deviation exceeds {crit.vmcg_deviation_max_ft:g} ft on the runway for a failure at "
                        f"every speed up to {_kn_cas(top):.1f} kn; from {_kn_cas(undecided[0]):.1f} kn the airplane "
                        "lifts off at the attitude of rest with its heading still swinging away (the rudder has not "
                        "arrested the swing within the takeoff run): no VMCG on the runway (value shown as VR + 1 kn)"
                    )
                else:
                    at_vr = res.search.deviations[i][-1] / 0.3048
                    reason = (
                        f"the deviation exceeds {crit.vmcg_deviation_max_ft:g} ft for a failure at every speed up to "
                        f"VR ({res.high_cas / KN:.1f} kn; at VR "
                        + (f"{at_vr:.0f} ft" if np.isfinite(at_vr) else "the heading does not recover")
                        + "): no VMCG on the runway (value shown as VR + 1 kn)"
                    )
            elif res.below[i]:
                reason = f"within the bound from the lowest speed searched ({crit.vmcg_low_kn:g} kn): VMCG no higher"
            value = float(vmcg) / KN if np.isfinite(vmcg) else float(res.high_cas) / KN + 1.0
            out.append(
                Finding.compare(
                    found,
                    check,
                    value,
                    round(res.high_cas / KN, 2),
                    at_least=False,
                    unit="kn",
                    reason=reason,
                    **details,
                )
            )
            if vmcg > worst:
                worst, worst_cond = vmcg, found
        declared = ctx.aircraft.speeds.VMCG
        if worst_cond is not None:
            dcheck = "(e) declared VMCG ≥ computed VMCG"
            shown = round(worst / KN, 1) if np.isfinite(worst) else None
            if declared is None:
                why = (
                    "no speeds.VMCG declared: the highest computed VMCG stands for it (§25.107(a)(1), VEF ≥ VMCG in "
                    "the takeoff runs); a declared VMCG is checked against it"
                )
                # set apart: the computed VMCG stands for the undeclared one, the computed checks decide the status
                out.append(
                    Finding.outside_scope(
                        "25.149(e)", why, condition=worst_cond, check=dcheck, computed_VMCG_kn_cas=shown
                    )
                )
            else:
                vmcg_decl = float(convert_speed(declared.value, declared.kind, "CAS", 0.0)) / KN
                limit = worst / KN if np.isfinite(worst) else res.high_cas / KN
                out.append(
                    Finding.compare(
                        worst_cond,
                        dcheck,
                        vmcg_decl,
                        round(limit, 2),
                        at_least=True,
                        unit="kn",
                        computed_VMCG_kn_cas=shown,
                        reason="" if np.isfinite(worst) else "no VMCG on the runway (limit: VR)",
                    )
                )
        return out

    def _vmca(self, ctx, conditions, crit):
        rudder = control_force_model(ctx.aircraft, "rudder")
        out = []
        rows = vmca_rows(ctx, conditions, crit)
        for k, cond in enumerate(conditions):
            nb = len(BANK_FRACTIONS)
            vsr, pair = rows["vsr"][nb * k], tuple(range(nb * k, nb * k + nb))
            vmca, best, below = condition_vmca(rows, k, crit)
            r = rows["last"][best]
            table = [
                {
                    "bank_deg": round(float(np.degrees(rows["banks"][j])), 1),
                    "speed_kn_cas": round(h["speed"] / KN, 2),
                    "control_usage": round(h["usage"], 4) if np.isfinite(h["usage"]) else None,
                    "rudder_deg": round(float(np.degrees(h["trim"].controls["rudder"])), 2),
                    "aileron_deg": round(float(np.degrees(h["trim"].controls["aileron"])), 2),
                    "throttle": round(throttle_of(h["trim"]), 4),
                    "gamma_deg": round(float(np.degrees(h["gamma"])), 2),
                    "sideslip_deg": round(float(np.degrees(h["trim"].beta)), 2),
                    "converged": h["trim"].converged,
                }
                for j in pair
                for h in rows["history"][j]
            ]
            limit = crit.vmc_over_vsr_max * vsr
            what = rows["limited_by"][best]
            limited_by = {
                "rudder": "the rudder at its design limit",
                "aileron": "the aileron at its design limit",
                "stall": (
                    "the stall: at this bank the rudder and aileron hold straight flight down to the "
                    "speed where the lift reaches its maximum (no steady flight below); the control-"
                    "limited VMCA lies below the stall"
                ),
            }.get(what, what)
            common = dict(
                VSR=vsr,
                search=table,
                bank_at_vmca_deg=round(float(np.degrees(rows["banks"][best])), 1),
                vmca_limited_by=limited_by,
                vmca_by_bank_kn={
                    f"{np.degrees(rows['banks'][j]):.0f} deg": round(float(rows["vmca"][j]) / KN, 2) for j in pair
                },
                limited_by_bank={f"{np.degrees(rows['banks'][j]):.0f} deg": rows["limited_by"][j] for j in pair},
                force_model=(
                    "rudder at its design limit; the 150 lbf of (d) is a separate finding"
                    if rudder
                    else "none declared: rudder at its design limit, not 150 lbf"
                ),
            )
            if "trim failure" in [rows["limited_by"][j] for j in pair]:
                bad = [f"{np.degrees(rows['banks'][j]):.0f}°" for j in pair if rows["limited_by"][j] == "trim failure"]
                why = (
                    f"the straight one-engine-inoperative trim failed above the stall at bank {', '.join(bad)} "
                    "(neither a control limit nor the lift maximum): VMCA is not determined"
                )
                out += [
                    Finding.not_evaluated(cond, check, why, **common)
                    for check in (
                        "(c) VMCA ≤ 1.13 VSR",
                        f"(d) rudder force at VMCA ≤ {crit.rudder_force_lbf:g} lbf",
                        "(b) declared VMC ≥ computed VMCA",
                    )
                ]
                continue
            if below:
                found = cond.with_(speed=vmca, speed_kind="CAS", speed_name="VMCA")
                out.append(
                    Finding.compare(
                        found,
                        "(c) VMCA ≤ 1.13 VSR",
                        vmca,
                        limit,
                        at_least=False,
                        unit="m/s",
                        reason=f"controls within limits down to {crit.grid_low} VSR: VMCA is below "
                        "the search range (stall-limited)",
                        **common,
                    )
                )
            else:
                found = cond.with_(speed=vmca, speed_kind="CAS", speed_name="VMCA")
                top = all(rows["pinned_high"][j] for j in pair)
                why = "; ".join(e.message for e in r.limits_exceeded) if r is not None else ""
                reason = (
                    (
                        f"controls beyond their design limits up to {crit.grid_high} VSR (VMCA above the search "
                        f"range): {why}"
                    )
                    if top
                    else ""
                )
                if what == "stall":
                    reason = (
                        f"stall-limited: VMCA is below {vmca / KN:.1f} kn CAS, where straight flight at "
                        f"{np.degrees(rows['banks'][best]):.0f}° bank reaches the lift maximum with the controls "
                        "within their limits"
                    )
                out.append(
                    Finding.compare(
                        found,
                        "(c) VMCA ≤ 1.13 VSR",
                        vmca,
                        limit,
                        at_least=False,
                        unit="m/s",
                        reason=reason,
                        VMCA_over_VSR=vmca / vsr,
                        **common,
                    )
                )
            ordered = sorted((h["speed"], h["trim"]) for h in rows["history"][best] if np.isfinite(h["usage"]))
            out.append(self._force_finding(ctx, found, vmca, [v for v, _ in ordered], [t for _, t in ordered], crit))
            declared = ctx.aircraft.speeds.VMC
            if declared is None:
                why = (
                    "no speeds.VMC declared: the computed VMCA stands for VMC (§25.149(c) here, §25.107(b)(3) and "
                    "(e)(1)(ii)); a declared VMC is checked against it"
                )
                out.append(  # set apart like the VMCG comparison above
                    Finding.outside_scope(
                        "25.149(b)",
                        why,
                        condition=found,
                        check="(b) declared VMC ≥ computed VMCA",
                        computed_VMCA_kn_cas=round(vmca / KN, 1),
                    )
                )
            else:
                vmc = float(convert_speed(declared.value, declared.kind, "CAS", cond.altitude or 0.0))
                out.append(
                    Finding.compare(found, "(b) declared VMC ≥ computed VMCA", vmc, vmca, at_least=True, unit="m/s")
                )
        return out

    def evidence(self, ctx, findings, crit):
        rows = vmca_rows(ctx, self.conditions.expand(ctx.aircraft), crit)
        return vmca_evidence(findings, rows, control_limits(ctx.aircraft))

    @staticmethod
    def _force_finding(ctx, found, vmca, speeds, results, crit, check=None, name="VMCA"):
        """(d) rudder pedal force (lbf, rudder trim neutral) at the computed VMCA (or (h)(1) at VMCL: ``check``,
        ``name``), interpolated between the trims the search visited (its last iterate is at the speed); with the
        highest of those speeds at which the force reaches the limit (the force-limited speed, when the visited speeds
        bracket it). ``pedal_force_grid_lbf`` lists the forces at the visited speeds (the name kept from the former
        grid)."""
        check = check or f"(d) rudder force at VMCA ≤ {crit.rudder_force_lbf:g} lbf"
        rudder = control_force_model(ctx.aircraft, "rudder")
        if rudder is None:
            return pedal_force_finding(ctx, None, found, None, crit.rudder_force_lbf, check)
        q, a, d = trim_state(ctx.aircraft, "rudder", results)
        force = np.abs(rudder.force(q, a, d)) / LBF
        ok = np.isfinite(force)  # a trim that did not converge has no force: (c) covers it
        usage = np.where(ok, force / crit.rudder_force_lbf, 0.0)
        if not ok.any():
            return Finding.not_evaluated(found, check, "no trim of the search converged")
        at_vmca = float(np.interp(vmca, np.asarray(speeds)[ok], force[ok]))
        limited = vmca_from_grid(speeds, usage)
        return Finding.compare(
            found,
            check,
            at_vmca,
            crit.rudder_force_lbf,
            at_least=False,
            unit="lbf",
            force_model=rudder.kind,
            **{f"force_limited_{name}_kn_cas": None if limited is None else round(limited / KN, 1)},
            pedal_force_grid_lbf=[None if not np.isfinite(f) else round(float(f), 1) for f in force],
        )

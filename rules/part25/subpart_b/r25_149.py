"""§25.149 Minimum control speed: the computed VMCA against 1.13 VSR and against a declared VMC.

VMCA is found on a grid of calibrated speeds (one batch of one-engine-inoperative trims): straight flight
with 5° of bank toward the operating engine, the operating engine at full throttle (maximum takeoff
thrust; the flight-path angle takes up the excess thrust), takeoff flaps, the most aft CG at MTOW, sea level.
VMCA is the highest speed at which the rudder or the aileron reaches its design limit (linear
interpolation between grid speeds); below it straight flight cannot be held.
"""

from __future__ import annotations

import numpy as np

from certkit.conditions import Altitudes, ConditionSpace, DesignWeight
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.flight import control_limits
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.units import KN, LBF
from certkit_rules.part25.subpart_b.r25_171 import trims_at_throttle, vsr_cas

SOURCE = "14 CFR 25.149 (Amdt. 25-108; (a)-(e) verified, docs/regulation-notes.md)"


def control_usage(res, limits) -> float:
    """Largest |deflection| / design limit of rudder and aileron (∞ when the trim did not converge)."""
    if not res.converged:
        return np.inf
    use = []
    for name in ("rudder", "aileron"):
        d = res.controls[name]
        lo, hi = limits[name]
        use.append(d / hi if d >= 0 else d / lo)
    return max(use)


def vmca_from_grid(speeds, usage) -> float | None:
    """Highest speed where the control usage crosses 1 going down in speed (linear interpolation);
    None when the controls stay within their limits at every grid speed."""
    speeds, usage = np.asarray(speeds), np.asarray(usage)
    over = usage > 1.0
    if not over.any():
        return None
    k = int(np.max(np.nonzero(over)[0]))
    if k == len(speeds) - 1:
        return float(speeds[-1])
    u0, u1 = usage[k], usage[k + 1]
    if not np.isfinite(u0):
        return float(speeds[k + 1])
    return float(speeds[k] + (u0 - 1.0) / (u0 - u1) * (speeds[k + 1] - speeds[k]))


@rule
class MinimumControlSpeed(Rule):
    id = "25.149"
    symbol = "minimum-control-speed"
    title = "Minimum control speed VMC (VMCA)"
    amendment = "25-108"
    requirement = """
        (b) VMC is the calibrated airspeed at which, when the critical engine is suddenly made inoperative, it is
        possible to maintain control with that engine still inoperative and straight flight with not more than 5° of
        bank. (c) VMC may not exceed 1.13 VSR with maximum available takeoff thrust, the most unfavourable CG, trimmed
        for takeoff, maximum sea-level takeoff weight, the most critical takeoff configuration with the gear
        retracted, airborne with negligible ground effect. (d) The rudder force may not exceed 150 lbf.
    """
    margin = """
        (c) 1.13 VSR − VMCA (m/s CAS), VMCA computed; (b) declared VMC − VMCA (m/s CAS), when VMC is declared;
        (d) 150 lbf − |rudder pedal force at VMCA| (lbf), with control_forces.rudder.
    """
    references = ("25.103", "25.107", "25.147")
    requires = ("configurations.takeoff.CLmax",)
    criteria = {
        "vmc_over_vsr_max": Criterion(1.13, "", SOURCE + " (c)", "largest VMC / VSR"),
        "bank_deg": Criterion(5.0, "deg", SOURCE + " (b)", "bank toward the operating engine"),
        "throttle": Criterion(0.99, "", "project choice: 99 % of the throttle range stands for maximum takeoff thrust "
                              "(the trim cannot converge on the throttle stop itself)", "throttle of the operating engine"),
        "grid_low": Criterion(0.6, "", "project choice: grid from 0.6 VSR", "lowest grid speed, multiple of VSR"),
        "grid_high": Criterion(1.4, "", "project choice: grid to 1.4 VSR", "highest grid speed, multiple of VSR"),
        "grid_points": Criterion(33, "", "project choice: 2.5 % VSR steps", "number of grid speeds"),
        "rudder_force_lbf": Criterion(150.0, "lbf", SOURCE + " (d)", "largest rudder force to maintain control at VMC"),
    }
    conditions = ConditionSpace(loading=DesignWeight("MTOW", cgs=("aft",)), configurations=("takeoff",),
                                altitudes=Altitudes((0.0,)), extra=(("inoperative", ("left", "right")),),
                                note="Operating engine at full throttle; bank toward it; sea level, standard day.")
    implementation = "partial"
    limitations = """
        Static (steady) VMCA: the dynamic recovery of (d) (heading change ≤ 20°) is not simulated. VMCA is where the
        rudder or aileron reaches its design limit; the 150 lbf of (d) is a separate finding at that VMCA (the pedal
        force of the steady trim, rudder trim neutral), evaluated only with control_forces.rudder; the speed at which
        the force reaches 150 lbf is reported with it. The
        baseline's takeoff configuration has the gear down (more drag, steeper flight path only; the moments are
        those of the gear-up airplane in the model). Thrust at throttle 1 is the maximum takeoff thrust.
    """

    def evaluate(self, ctx, conditions, crit):
        limits = control_limits(ctx.aircraft)
        rudder = control_force_model(ctx.aircraft, "rudder")
        out = []
        n = int(crit.grid_points)
        factors = np.linspace(crit.grid_low, crit.grid_high, n)
        for cond in conditions:
            engine = cond.get("inoperative")
            names = [e.name for e in ctx.aircraft.propulsion.engines]
            y = {e.name: e.position.y for e in ctx.aircraft.propulsion.engines}
            live = [nm for nm in names if nm != engine]
            # bank toward the operating engine: right wing down (+) when the live engine is on the right
            bank = np.radians(crit.bank_deg) * (1.0 if y[live[0]] > 0 else -1.0)
            vsr = vsr_cas(ctx, cond.configuration, cond.mass, cond.altitude or 0.0)
            grid = [cond.with_(speed=float(f * vsr), speed_kind="CAS") for f in factors]
            # "not more than 5° of bank": the better of wings level and the full bank at each speed
            runs = [trims_at_throttle(ctx, grid, np.full(n, crit.throttle), gammas=(-0.08, -0.04), kind="oei",
                                      bank=b, inoperative=engine) for b in (bank, 0.0)]
            usages = np.array([[control_usage(r, limits) for r in rs] for rs in runs])
            best = np.argmin(usages, axis=0)
            res = [runs[b][i] for i, b in enumerate(best)]
            usage = list(usages.min(axis=0))
            vmca = vmca_from_grid(factors * vsr, usage)
            table = [{"speed_kn_cas": round(float(f * vsr / KN), 1), "control_usage": None if not np.isfinite(u) else round(float(u), 4),
                      "rudder_deg": round(float(np.degrees(r.controls["rudder"])), 2),
                      "aileron_deg": round(float(np.degrees(r.controls["aileron"])), 2), "converged": r.converged,
                      "bank_deg": round(float(np.degrees(r.phi)), 1), "sideslip_deg": round(float(np.degrees(r.beta)), 2)}
                     for f, u, r in zip(factors, usage, res)]
            limit = crit.vmc_over_vsr_max * vsr
            if vmca is None:
                found = cond.with_(speed=float(factors[0] * vsr), speed_kind="CAS", speed_name="VMCA")
                out.append(Finding.compare(found, "(c) VMCA ≤ 1.13 VSR", float(factors[0] * vsr), limit, at_least=False,
                                           unit="m/s", reason=f"controls within limits down to {crit.grid_low} VSR: "
                                           "VMCA is below the grid (stall-limited)", VSR=vsr, grid=table))
                vmca = float(factors[0] * vsr)
            else:
                found = cond.with_(speed=vmca, speed_kind="CAS", speed_name="VMCA")
                top = usage[-1] > 1.0
                why = "; ".join(e.message for e in res[-1].limits_exceeded)
                out.append(Finding.compare(found, "(c) VMCA ≤ 1.13 VSR", vmca, limit, at_least=False, unit="m/s",
                                           reason=(f"controls beyond their design limits up to {crit.grid_high} VSR "
                                                   f"(VMCA above the grid): {why}") if top else "",
                                           VSR=vsr, VMCA_over_VSR=vmca / vsr, grid=table,
                                           force_model=("rudder at its design limit; the 150 lbf of (d) is a separate finding"
                                                        if rudder else "none declared: rudder at its design limit, not 150 lbf")))
            out.append(self._force_finding(ctx, found, vmca, factors * vsr, res, crit))
            declared = ctx.aircraft.speeds.VMC
            if declared is None:
                out.append(Finding.not_evaluated(found, "(b) declared VMC ≥ computed VMCA", "needs speeds.VMC",
                                                 computed_VMCA_kn_cas=round(vmca / KN, 1)))
            else:
                from certkit.atmosphere import convert_speed

                vmc = float(convert_speed(declared.value, declared.kind, "CAS", cond.altitude or 0.0))
                out.append(Finding.compare(found, "(b) declared VMC ≥ computed VMCA", vmc, vmca, at_least=True, unit="m/s"))
        return out


    @staticmethod
    def _force_finding(ctx, found, vmca, speeds, results, crit):
        """(d) rudder pedal force (lbf, rudder trim neutral) at the computed VMCA, interpolated on the grid; with
        the highest grid speed at which the force reaches the limit (the force-limited VMCA)."""
        from certkit_rules.part25.subpart_b.r25_147 import pedal_force_finding

        check = f"(d) rudder force at VMCA ≤ {crit.rudder_force_lbf:g} lbf"
        rudder = control_force_model(ctx.aircraft, "rudder")
        if rudder is None:
            return pedal_force_finding(ctx, None, found, None, crit.rudder_force_lbf, check)
        q, a, d = trim_state(ctx.aircraft, "rudder", results)
        force = np.abs(rudder.force(q, a, d)) / LBF
        ok = np.isfinite(force)  # a trim that did not converge has no force: (c) covers it
        usage = np.where(ok, force / crit.rudder_force_lbf, 0.0)
        if not ok.any():
            return Finding.not_evaluated(found, check, "no grid trim converged")
        at_vmca = float(np.interp(vmca, np.asarray(speeds)[ok], force[ok]))
        limited = vmca_from_grid(speeds, usage)
        return Finding.compare(found, check, at_vmca, crit.rudder_force_lbf, at_least=False, unit="lbf",
                               force_model=rudder.kind,
                               force_limited_VMCA_kn_cas=None if limited is None else round(limited / KN, 1),
                               pedal_force_grid_lbf=[None if not np.isfinite(f) else round(float(f), 1) for f in force])

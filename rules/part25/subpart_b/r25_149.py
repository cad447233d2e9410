"""§25.149 Minimum control speed: the computed VMCA against 1.13 VSR and against a declared VMC.

VMCA is the speed at which, in straight one-engine-inoperative flight with the operating engine at full
throttle (maximum takeoff thrust; the flight-path angle takes up the excess thrust), takeoff flaps, the most
aft CG at MTOW, sea level, the rudder or the aileron reaches its design limit — the better of 5° of bank
toward the operating engine and wings level; below it straight flight cannot be held.

Search (:func:`vmca_search`): every (inoperative engine, bank) row of the rule is solved in the same trim
batch at each step (a trim batch costs about the same for 4 rows as for 1). The control usage
u = max(|δr|/δr_lim, |δa|/δa_lim) of a straight OEI trim is nearly linear in 1/V² (the asymmetric thrust
moment over the dynamic pressure), so VMCA — the root of u − 1 — is found from 1.2 VSR by a first step
V·√u (at most ±15 %), then a secant in s = 1/V², kept inside the bracket of speeds known above and below
(bisection in 1/V² when the secant leaves it). Each iterate is one trim at a fixed flight-path angle: two
probe trims at γ = −0.04 and −0.02 at the start speed give dthrottle/dγ and du/dthrottle, the usage of each
iterate is brought to the full-throttle value by that first-order correction, and the next flight-path
angle is the corrected one, extrapolated linearly in speed; an iterate that needs more than full thrust at
its guessed angle is retried 0.02 rad lower (it says nothing about the controls). A row stops when its
speed step is below ``speed_tolerance_kn`` (0.05 kn: VMCA to 0.1 kn) with |u − 1| < 0.02, or pinned at
an end of the range. On the baseline: 7 trim batches, 0.3 s, against 12 batches of 33 speeds (3.3 s) for
the former grid; the grid's VMCA is 0.36 kn higher because its throttle matching ends at 0.978, not 0.99
(tests/rules/test_r25_149.py compares both, and a fine grid with the throttle on target within 0.1 kn).
"""

from __future__ import annotations

import numpy as np

from certkit.conditions import Altitudes, ConditionSpace, DesignWeight
from certkit.models.control_force import control_force_model, trim_state
from certkit.models.flight import control_limits
from certkit.registry import Criterion, Rule, rule
from certkit.results import Finding
from certkit.units import KN, LBF
from certkit_rules.part25.subpart_b.r25_171 import vsr_cas

SOURCE = "14 CFR 25.149 (Amdt. 25-108; (a)-(e) verified, docs/regulation-notes.md)"


#: banks searched, as fractions of the largest allowed (5°) toward the operating engine: wings level to 5° in 1° steps
BANK_FRACTIONS = np.linspace(1.0, 0.0, 6)

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


def throttle_of(res) -> float:
    return next(v for k, v in res.controls.items() if k.startswith("throttle"))


def vmca_search(ctx, conds, engines, banks, vsr, throttle, low, high, tol, start: float = 1.2, max_iter: int = 10):
    """VMCA (m/s CAS) of each row (``conds[i]`` with ``engines[i]`` inoperative at bank ``banks[i]``) by the
    safeguarded secant in 1/V² of the module docstring, all rows in one trim batch per step; ``vsr`` (m/s CAS)
    per row, ``low``/``high`` the search range and ``start`` the first speed in multiples of VSR, ``tol`` the
    speed step (m/s) at which a row stops. Returns (vmca, pinned_low, pinned_high, history, last trims):
    ``pinned_low``/``pinned_high`` flag rows whose root lies beyond the range (VMCA is then that bound),
    ``history`` per row a list of dicts (speed, usage at the target throttle, gamma, trim)."""
    limits = control_limits(ctx.aircraft)
    n = len(conds)
    vsr = np.asarray(vsr, dtype=float)
    v_lo, v_hi = low * vsr, high * vsr

    def trims(speeds, gammas):
        cs = [c.with_(speed=float(v), speed_kind="CAS") for c, v in zip(conds, speeds)]
        return ctx.trim(cs, kind="oei", gamma=gammas, bank=banks, inoperative=list(engines)).results

    # two probe trims at the start speed: usage and throttle slopes per row
    g0, g1 = -0.04, -0.02
    v = np.clip(start * vsr, v_lo, v_hi)
    probe = [trims(v, np.full(n, g)) for g in (g0, g1)]
    t = np.array([[throttle_of(r) for r in p] for p in probe])
    u = np.array([[control_usage(r, limits) for r in p] for p in probe])
    ok = np.isfinite(u).all(axis=0) & (np.abs(t[1] - t[0]) > 1e-9)
    with np.errstate(invalid="ignore", divide="ignore"):
        dthr_dg = np.where(ok, (t[1] - t[0]) / (g1 - g0), np.nan)
        du_dthr = np.where(ok, (u[1] - u[0]) / (t[1] - t[0]), 0.0)
        gam = np.where(ok, np.clip(g1 + (throttle - t[1]) / dthr_dg, -0.3, 0.3), g1)
    use = np.where(ok, u[1] + du_dthr * (throttle - t[1]), np.inf)
    hist = [[{"speed": float(v[i]), "usage": float(use[i]), "gamma": float(gam[i]), "trim": probe[1][i]}] for i in range(n)]
    below = np.where(use > 1.0, v, np.nan)    # highest speed known with usage > 1 (or no trim)
    above = np.where(use <= 1.0, v, np.nan)   # lowest speed known with usage ≤ 1
    prev = [None] * n
    cur = [(v[i], use[i], gam[i]) for i in range(n)]
    done = np.zeros(n, dtype=bool)
    last = list(probe[1])
    for _ in range(max_iter):
        new, g_new = v.copy(), gam.copy()
        for i in np.flatnonzero(~done):
            v1, u1, gg1 = cur[i]
            lo_b = below[i] if np.isfinite(below[i]) else v_lo[i]
            hi_b = above[i] if np.isfinite(above[i]) else v_hi[i]
            cand = np.nan
            if np.isfinite(u1) and prev[i] is None:
                cand = v1 * np.clip(np.sqrt(u1), 0.85, 1.15)   # u ∝ 1/V²: the first step, at most 15 %
            elif np.isfinite(u1) and np.isfinite(prev[i][1]) and abs(u1 - prev[i][1]) > 1e-12:
                s0, s1 = prev[i][0] ** -2, v1 ** -2
                s_new = s1 + (1.0 - u1) * (s1 - s0) / (u1 - prev[i][1])
                cand = s_new ** -0.5 if s_new > 0 else np.nan
            if not (np.isfinite(cand) and lo_b <= cand <= hi_b):
                cand = (0.5 * (lo_b ** -2 + hi_b ** -2)) ** -0.5   # bisection in 1/V² inside the bracket
            new[i] = cand
            g_new[i] = gg1
            if prev[i] is not None and abs(v1 - prev[i][0]) > 1e-9:  # γ linear in V through the last two
                g_new[i] = gg1 + (cand - v1) * (gg1 - prev[i][2]) / (v1 - prev[i][0])
            g_new[i] = float(np.clip(g_new[i], -0.3, 0.3))
        res = trims(new, g_new)
        for i in np.flatnonzero(~done):
            r = res[i]
            thr = throttle_of(r)
            # the trim keeps its throttle iterate just below 1: at the stop it is thrust-limited
            if not r.converged and (thr >= 1.0 - 1e-4 or any(e.control == "throttle" for e in r.limits_exceeded)):
                # thrust-limited at the guessed flight-path angle (not a control verdict): retry lower
                hist[i].append({"speed": float(new[i]), "usage": np.nan, "gamma": float(g_new[i]), "trim": r})
                gam[i] = cur[i][2] - 0.02 if abs(new[i] - cur[i][0]) < 1e-9 else g_new[i] - 0.02
                cur[i] = (cur[i][0], cur[i][1], gam[i])
                prev[i] = None if prev[i] is None else (prev[i][0], prev[i][1], prev[i][2] - 0.02)
                v[i] = cur[i][0]
                continue
            uu = control_usage(r, limits) + du_dthr[i] * (throttle - thr)
            gg = float(np.clip(g_new[i] + (throttle - thr) / dthr_dg[i], -0.3, 0.3)) if ok[i] and r.converged else g_new[i]
            hist[i].append({"speed": float(new[i]), "usage": float(uu), "gamma": gg, "trim": r})
            step = abs(new[i] - cur[i][0])
            prev[i], cur[i], last[i] = cur[i], (new[i], uu, gg), r
            v[i], gam[i] = new[i], gg
            if not np.isfinite(uu) or uu > 1.0:
                below[i] = np.nanmax([below[i], new[i]])
            else:
                above[i] = np.nanmin([above[i], new[i]])
            at_bound = new[i] <= v_lo[i] * (1 + 1e-9) or new[i] >= v_hi[i] * (1 - 1e-9)
            bracketed = np.isfinite(below[i]) and np.isfinite(above[i]) and above[i] - below[i] < 2 * tol
            if step < tol and (abs(uu - 1.0) < 0.02 or at_bound or bracketed):
                done[i] = True
        if done.all():
            break
    pinned_low = ~np.isfinite(below) & (v <= v_lo * (1 + 1e-9))
    pinned_high = ~np.isfinite(above) & (v >= v_hi * (1 - 1e-9))
    return v, pinned_low, pinned_high, hist, last


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


def _vmca_rows(ctx, conditions, crit):
    """The search over rows (condition, bank) — :data:`BANK_FRACTIONS` of the largest bank toward the operating
    engine per condition, wings level included (VMCA is the least over the banks the paragraph allows: an
    intermediate bank can balance the rudder's and the aileron's needs) — memoised for the evidence."""
    def compute():
        y = {e.name: e.position.y for e in ctx.aircraft.propulsion.engines}
        conds, engines, banks, vsr = [], [], [], []
        for cond in conditions:
            engine = cond.get("inoperative")
            live = [nm for nm in y if nm != engine]
            # bank toward the operating engine: right wing down (+) when the live engine is on the right
            bank = np.radians(crit.bank_deg) * (1.0 if y[live[0]] > 0 else -1.0)
            v = vsr_cas(ctx, cond.configuration, cond.mass, cond.altitude or 0.0)
            for b in BANK_FRACTIONS * bank:
                conds.append(cond)
                engines.append(engine)
                banks.append(b)
                vsr.append(v)
        banks = np.array(banks)
        vmca, lo, hi, hist, last = vmca_search(ctx, conds, engines, banks, vsr, crit.throttle, crit.grid_low,
                                               crit.grid_high, crit.speed_tolerance_kn * KN)
        return {"vmca": vmca, "pinned_low": lo, "pinned_high": hi, "history": hist, "last": last, "banks": banks,
                "vsr": vsr, "engines": engines, "conds": conds}

    key = ("25.149 vmca", tuple((c.mass, c.x_cg, c.get("inoperative")) for c in conditions), crit.bank_deg, crit.throttle,
           crit.grid_low, crit.grid_high, crit.speed_tolerance_kn)
    return ctx.memo(key, compute)


def condition_vmca(rows, k: int, crit) -> tuple[float, int, bool]:
    """VMCA (m/s CAS) of scheduled condition ``k``: the least over its banks; the search's lower end when the
    controls stay within their limits down to it. Returns (VMCA, the row of the best bank, below the range)."""
    nb = len(BANK_FRACTIONS)
    pair = range(nb * k, nb * k + nb)
    best = min(pair, key=lambda j: rows["vmca"][j])
    if all(rows["pinned_low"][j] for j in pair) or rows["pinned_low"][best]:
        return float(crit.grid_low * rows["vsr"][best]), best, True
    return float(rows["vmca"][best]), best, False


def computed_vmca(ctx):
    """The airplane's VMCA (m/s CAS) as §25.149 computes it with its criteria (and the aircraft file's overrides):
    the highest over its conditions (each engine inoperative, most unfavourable CG); None when the rule's inputs
    are missing. For the rules that need VMC when the aircraft file declares none (§25.107)."""
    from certkit.scheduler import criteria_for

    if ctx.missing(MinimumControlSpeed.requires):
        return None
    crit, _ = criteria_for(MinimumControlSpeed, ctx)
    conds = MinimumControlSpeed.conditions.expand(ctx.aircraft)
    rows = _vmca_rows(ctx, conds, crit)
    return max(condition_vmca(rows, k, crit)[0] for k in range(len(conds)))


@rule
class MinimumControlSpeed(Rule):
    id = "25.149"
    cost = 2  # relative evaluation time (orders work over --jobs processes)
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
        "grid_low": Criterion(0.6, "", "project choice: search from 0.6 VSR", "lowest speed searched, multiple of VSR"),
        "grid_high": Criterion(1.4, "", "project choice: search to 1.4 VSR", "highest speed searched, multiple of VSR"),
        "speed_tolerance_kn": Criterion(0.05, "kn", "project choice: secant step at which the search stops (VMCA to "
                                        "0.1 kn)", "speed step of the VMCA search"),
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
        those of the gear-up airplane in the model). Thrust at throttle 1 is the maximum takeoff thrust. Banks from
        wings level to 5° toward the operating engine are searched in 1° steps; VMCA is the least (to within the 1°
        step, conservative).
    """

    unevaluated = (
        ("25.149(d)", "the dynamic recovery after the sudden engine failure (heading change ≤ 20°) is not simulated:"
                      " VMCA is the static one"),
        ("25.149(e)", "VMCG (ground) is not determined"),
        ("25.149(f)", "VMCL (landing, all engines) is not determined"),
    )

    def evaluate(self, ctx, conditions, crit):
        rudder = control_force_model(ctx.aircraft, "rudder")
        out = []
        rows = _vmca_rows(ctx, conditions, crit)
        for k, cond in enumerate(conditions):
            nb = len(BANK_FRACTIONS)
            vsr, pair = rows["vsr"][nb * k], tuple(range(nb * k, nb * k + nb))
            vmca, best, below = condition_vmca(rows, k, crit)
            r = rows["last"][best]
            table = [{"bank_deg": round(float(np.degrees(rows["banks"][j])), 1), "speed_kn_cas": round(h["speed"] / KN, 2),
                      "control_usage": round(h["usage"], 4) if np.isfinite(h["usage"]) else None,
                      "rudder_deg": round(float(np.degrees(h["trim"].controls["rudder"])), 2),
                      "aileron_deg": round(float(np.degrees(h["trim"].controls["aileron"])), 2),
                      "throttle": round(throttle_of(h["trim"]), 4), "gamma_deg": round(float(np.degrees(h["gamma"])), 2),
                      "sideslip_deg": round(float(np.degrees(h["trim"].beta)), 2), "converged": h["trim"].converged}
                     for j in pair for h in rows["history"][j]]
            limit = crit.vmc_over_vsr_max * vsr
            limited_by = ("a control at its design limit" if r is not None and r.converged else
                          "the steady trim ceasing to exist (near the stall: stall-limited)")
            common = dict(VSR=vsr, search=table, bank_at_vmca_deg=round(float(np.degrees(rows["banks"][best])), 1),
                          vmca_limited_by=limited_by,
                          vmca_by_bank_kn={f"{np.degrees(rows['banks'][j]):.0f} deg": round(float(rows["vmca"][j]) / KN, 2)
                                           for j in pair},
                          force_model=("rudder at its design limit; the 150 lbf of (d) is a separate finding"
                                       if rudder else "none declared: rudder at its design limit, not 150 lbf"))
            if below:
                found = cond.with_(speed=vmca, speed_kind="CAS", speed_name="VMCA")
                out.append(Finding.compare(found, "(c) VMCA ≤ 1.13 VSR", vmca, limit, at_least=False, unit="m/s",
                                           reason=f"controls within limits down to {crit.grid_low} VSR: VMCA is below "
                                           "the search range (stall-limited)", **common))
            else:
                found = cond.with_(speed=vmca, speed_kind="CAS", speed_name="VMCA")
                top = all(rows["pinned_high"][j] for j in pair)
                why = "; ".join(e.message for e in r.limits_exceeded) if r is not None else ""
                out.append(Finding.compare(found, "(c) VMCA ≤ 1.13 VSR", vmca, limit, at_least=False, unit="m/s",
                                           reason=(f"controls beyond their design limits up to {crit.grid_high} VSR "
                                                   f"(VMCA above the search range): {why}") if top else "",
                                           VMCA_over_VSR=vmca / vsr, **common))
            ordered = sorted((h["speed"], h["trim"]) for h in rows["history"][best] if np.isfinite(h["usage"]))
            out.append(self._force_finding(ctx, found, vmca, [v for v, _ in ordered], [t for _, t in ordered], crit))
            declared = ctx.aircraft.speeds.VMC
            if declared is None:
                out.append(Finding.not_evaluated(found, "(b) declared VMC ≥ computed VMCA", "needs speeds.VMC",
                                                 computed_VMCA_kn_cas=round(vmca / KN, 1)))
            else:
                from certkit.atmosphere import convert_speed

                vmc = float(convert_speed(declared.value, declared.kind, "CAS", cond.altitude or 0.0))
                out.append(Finding.compare(found, "(b) declared VMC ≥ computed VMCA", vmc, vmca, at_least=True, unit="m/s"))
        return out

    def evidence(self, ctx, findings, crit):
        from certkit.evidence.performance import vmca_evidence

        rows = _vmca_rows(ctx, self.conditions.expand(ctx.aircraft), crit)
        return vmca_evidence(findings, rows, control_limits(ctx.aircraft))

    @staticmethod
    def _force_finding(ctx, found, vmca, speeds, results, crit):
        """(d) rudder pedal force (lbf, rudder trim neutral) at the computed VMCA, interpolated between the trims the
        search visited (its last iterate is at VMCA); with the highest of those speeds at which the force reaches the
        limit (the force-limited VMCA, when the visited speeds bracket it). ``pedal_force_grid_lbf`` lists the forces
        at the visited speeds (the name kept from the former grid)."""
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
            return Finding.not_evaluated(found, check, "no trim of the search converged")
        at_vmca = float(np.interp(vmca, np.asarray(speeds)[ok], force[ok]))
        limited = vmca_from_grid(speeds, usage)
        return Finding.compare(found, check, at_vmca, crit.rudder_force_lbf, at_least=False, unit="lbf",
                               force_model=rudder.kind,
                               force_limited_VMCA_kn_cas=None if limited is None else round(limited / KN, 1),
                               pedal_force_grid_lbf=[None if not np.isfinite(f) else round(float(f), 1) for f in force])

"""§25.349(a) Rolling conditions, manoeuvring: sudden aileron from a steady symmetric manoeuvre at load factors 0
and 2/3 of the design positive limit, at VA (to the stop), VC (the deflection that gives at least the VA roll rate)
and VD (at least one third of it), as one batched rigid-airplane simulation; wing (both halves), horizontal-tail
(both halves) and fin loads from the strip loads model at every time step, compared with the declared structural
capability (§25.303, §25.305).

Text: docs/regulation-notes.md §25.349 (P: a secondary copy of the CFR text, consistent word for word in (a) with
EASA CS 25.349; amendment bracket not seen). Approximations: no control-force model, so the pilot-effort limit
cannot reduce the deflection (the aileron's stop, its travel, bounds it); rigid wing (the torsional flexibility that
(a) asks to consider when finding the deflections is not modelled — no aileron effectiveness loss); spoilers not
modelled; one roll direction (right wing down: the airplane is symmetric and both wing halves are computed, the
left one as the right half of the mirror image); the pilot holds the pull (elevator) and the rudder at their
manoeuvre values; the roll rate compared between speeds, and the end of the time history whose loads are
considered, is where |p| first stops growing (the steady rolling velocity of (a)(1); the maximum roll acceleration
comes at the end of the aileron ramp, inside it).

§25.349(b) Unsymmetrical gusts: the §25.341(a) gust responses (shared with that rule through ``run_with``, simulated
once) with 100 % of the wing air load on one side and 80 % on the other at every instant; the unbalanced vertical
force and rolling and pitching moments are reacted by the rigid airplane's inertia (the "rational manner" of the
lead-in), :mod:`certkit.models.loads.unsymmetrical`. "The wing air load" is read as the whole air load (1 g trim +
gust), the literal text; the criterion ``airload_basis: increment`` applies the fractions to the gust increment only.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import partial

import numpy as np
from certkit_rules.part25.support.fuel_states import fuel_detail, fuel_tank_names, fuelled_wing, state_envelope
from certkit_rules.part25.support.gust_runs import GUST_CONDITIONS, GUST_REQUIRES, GUST_RUN_CRITERIA, gust_runs
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    beyond_mach_range,
    capability_finding,
    condition_mach,
    control_stops,
    critical_state_finding,
    entry_speeds,
    set_aside_finding,
)

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.evidence.loads import allowables, unsymmetrical_gust_evidence
from certkit.engine.evidence.roll import roll_evidence
from certkit.engine.registry import Criterion, Loads, SimulationRule, rule
from certkit.engine.results import Finding, LoadsRun, SimulationRun
from certkit.errors import UserError
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import QUANTITIES, airplane_loads
from certkit.models.loads.response import LoadEnvelope, response_loads, times_at
from certkit.models.loads.roll import (
    aileron_for_roll_rate,
    mirror,
    peak_roll_rate,
    rolling_window,
    simulate_roll,
    stall_line_load_factor,
    symmetric_manoeuvre_state,
)
from certkit.models.loads.unsymmetrical import unsymmetrical_wing
from certkit.units import FT, KN

REG = "14 CFR 25.349(a) (secondary copy of the CFR text, docs/regulation-notes.md §25.349)"
SPEEDS = ("VA", "VC", "VD")
LOAD_FACTORS = ("zero", "two-thirds")
SURFACES = ("wing", "horizontal_tail", "vertical_tail")
MIRRORED = ("wing", "horizontal_tail")
PARAGRAPH = {
    "VA": "(a)(2) VA, sudden aileron to the stop",
    "VC": "(a)(3) VC, roll rate ≥ that at VA",
    "VD": "(a)(4) VD, roll rate ≥ 1/3 of that at VA",
}
EFFORT_NOTE = (
    "no control-force model is declared: pilot effort (§25.349(a), §25.397) cannot reduce the deflection; "
    "the aileron stop (travel) bounds it"
)
FLEX_NOTE = (
    "rigid wing: the torsional flexibility that §25.349(a) asks to consider in finding the aileron deflections "
    "(aileron effectiveness loss) is not modelled"
)
NO_VA_NOTE = (
    "the VA roll rate of (a)(2) is not available for this loading, altitude and load factor (the VA condition "
    "could not be set up): full aileron, conservative"
)
PROXY_NOTE = (
    "the VA pull-up at this load factor is beyond the lift available: the VA roll rate of (a)(2) is taken at "
    "the {} load factor of the same loading and altitude"
)


@rule
class RollingConditions(SimulationRule):
    id = "25.349(a)"
    produces = (Loads("wing"), Loads("horizontal_tail"), Loads("vertical_tail"))
    cost = 5  # relative evaluation time (orders work over --jobs processes)
    symbol = "rolling-conditions"
    title = "Rolling conditions: sudden aileron at VA, VC and VD at load factors 0 and 2/3 n"
    amendment = "25-94"
    requirement = """
        Unsymmetrical (rolling) manoeuvre loads, with unbalanced aerodynamic moments about the CG reacted
        rationally by the inertia forces, in combination with an airplane load factor of zero and of two-thirds
        of the positive manoeuvring factor used in design: (a)(1) steady rolling velocities and maximum roll
        acceleration; (a)(2) at VA a sudden deflection of the aileron to the stop; (a)(3) at VC the aileron
        deflection that gives a roll rate not less than that of (a)(2); (a)(4) at VD the deflection that gives
        not less than one third of it (deflections as limited by pilot effort). The structure carries the
        loads (limit) and 1.5 × them (ultimate), §25.303/§25.305.
    """
    margin = """
        Per condition and surface (wing, horizontal tail, fin): the smallest of (allowable limit load − |limit
        load|) and (allowable ultimate load − 1.5 × |limit load|) over the declared stations and quantities, the
        limit load the extreme over the time history from the aileron input to the steady rolling velocity (where
        the roll rate first stops growing) and, for the wing and horizontal tail, over both halves;
        without a declared structural capability the condition is not evaluated and reports its loads.
    """
    references = ("25.333", "25.337", "25.341", "25.397", "25.427", "25.303", "25.305")
    requires = ("speeds.VA", "speeds.VC", "speeds.VD", "envelope.limit_load_factors", "geometry.wing")
    criteria = {
        "load_factor_fraction": Criterion(2 / 3, "", REG, "load factor = fraction × positive limit manoeuvring factor"),
        "load_factor_low": Criterion(0.0, "", REG, "the other airplane load factor (zero)"),
        "vc_roll_rate_ratio": Criterion(1.0, "", "14 CFR 25.349(a)(3)", "roll rate at VC ≥ ratio × roll rate at VA"),
        "vd_roll_rate_ratio": Criterion(1 / 3, "", "14 CFR 25.349(a)(4)", "roll rate at VD ≥ ratio × roll rate at VA"),
        "stall_band": Criterion(
            0.02,
            "",
            "certkit numerical choice: the airplane model rounds its lift onto C_Lmax (width 0.08 in C_L)",
            "a pull-up within this fraction below the stall line's load factor that the airplane model's lift "
            "maximum does not reach is set up at that maximum",
        ),
        "ramp_time": Criterion(
            0.1,
            "s",
            "certkit assumption: 'sudden' with no declared actuator rate",
            "time to reach the aileron deflection",
        ),
        "duration": Criterion(
            4.0,
            "s",
            "certkit numerical choice: past the steady rolling velocity (first roll-rate "
            "peak, ≤ 3.3 s) at every baseline condition",
            "time simulated from the aileron input",
        ),
        "time_step": Criterion(
            0.02, "s", "certkit numerical choice (0.04 s changes the peak roll rate by < 0.5 %)", "simulation step"
        ),
        "roll_rate_tolerance": Criterion(
            0.03, "", "certkit numerical choice", "VC/VD roll rate accepted within [target, (1 + tolerance) × target]"
        ),
        "search_steps": Criterion(
            4, "", "certkit numerical choice", "proportional corrections of the VC/VD deflection"
        ),
        **SAFETY,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=EnvelopeAltitudes(2),
        extra=(("speed_point", SPEEDS), ("load_factor", LOAD_FACTORS)),
        note="VA (≤ VC), VC and VD in EAS, Mach-limited at altitude; from a steady wings-level "
        "pull-up (2/3 n) or push-over (n = 0) set up on the trimmed flight path; aileron to "
        "the larger stop (travel) rolling right (the left wing is the mirror image).",
    )
    limitations = (
        EFFORT_NOTE + "; " + FLEX_NOTE + "; spoilers not modelled; elevator and rudder held at their "
        "manoeuvre values (no coordination); rigid airplane, quasi-steady strip aerodynamics; (b), the unsymmetrical "
        "gust, is rule 25.349(b)."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.349(a)",
            "the wing torsional flexibility that (a) says must be considered in finding the aileron "
            "deflections is not modelled (rigid wing); spoilers are not modelled",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return rolling_maneuvers(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        if self.run is None or not self.run.simulated:
            return []
        return roll_evidence(self.run, allowables(ctx, crit.ultimate_factor))


AT_MAXIMUM = (
    "n = {:.2f} lies just inside the stall line of the V–n envelope, above the airplane model's lift maximum with the "
    "pull-up's control deflections: set up at that maximum"
)


def _at_lift_maximum(model, batch, rows, st, n_target, n_stall, band):
    """The pull-ups whose load factor lies within ``band`` below the stall line (C_Lmax q̄ S / W) but beyond the
    lift maximum the airplane model reaches with the pull-up's deflections (its lift is rounded onto C_Lmax): set up
    again at the load factor reached, less 0.002 (a steady state below the maximum); returns the states, the load
    factors they are set up at and which rows were moved."""
    moved = np.zeros(len(n_target), dtype=bool)
    n_target = np.array(n_target, dtype=float, copy=True)
    if n_stall is None:
        return st, n_target, moved
    short = (~st.converged | (np.abs(st.n_z - n_target) > 1e-3)) & (n_target <= n_stall)
    short &= (n_target >= (1.0 - band) * n_stall) & np.isfinite(st.n_z) & (st.n_z > 1.0)
    idx = np.flatnonzero(short)
    if not idx.size:
        return st, n_target, moved
    again = symmetric_manoeuvre_state(
        model.subset(idx), batch.x[rows][idx], batch.u[rows][idx], st.n_z[idx] - 0.002, batch.gamma[rows][idx]
    )
    ok = again.converged
    fields = {}
    for name in ("x", "u", "n_z", "pitch_rate", "alpha", "converged"):
        value = np.array(getattr(st, name), copy=True)
        value[idx[ok]] = getattr(again, name)[ok]
        fields[name] = value
    n_target[idx[ok]] = again.n_z[ok]
    moved[idx[ok]] = True
    return replace(st, **fields), n_target, moved


def target_load_factor(ctx, cond, crit) -> float:
    """The airplane load factor of the condition: 0, or the fraction (2/3) of the positive limit manoeuvring factor."""
    if cond.get("load_factor") == "zero":
        return float(crit.load_factor_low)
    return float(crit.load_factor_fraction * ctx.aircraft.envelope.limit_load_factors.positive)


def full_aileron(ctx) -> float:
    """The aileron deflection (rad) to the stop rolling right: minus the larger magnitude of the control-system stops
    (travel; the airplane is symmetric, so rolling left to the positive stop is the mirror image)."""
    lo, hi = control_stops(ctx, "aileron")
    return -max(abs(lo), abs(hi))


def _deg(x, nd=2):
    return round(float(np.degrees(x)), nd)


@dataclass
class RollingRun(SimulationRun):
    """The rolling manoeuvres: the records (rolling right), the loads of each surface along them on the right and
    (mirror image) left halves (``right``, ``left``: surface → (n_t, n, 3, S)), the wing and tailplane halves'
    envelope (``env_sides``: right conditions then left), the fin's (``env_fin``), the aileron's index among the
    controls, the fraction of the aileron stop applied and the end of the considered window (s) of each condition."""

    right: dict = field(default_factory=dict)
    left: dict = field(default_factory=dict)
    env_sides: object = None
    env_fin: object = None
    aileron_index: int = -1
    fraction: object = None
    t_end: object = None

    def envelopes(self) -> list:
        return [e for e in (self.env_sides, self.env_fin) if e is not None]


def rolling_maneuvers(ctx, conditions, crit) -> RollingRun:
    """Batch simulation of every rolling condition; findings, load envelopes and histories for the evidence."""
    entries, key_of = [], {}
    for c in conditions:
        key = (c.loading, c.altitude, c.get("speed_point"))
        if key not in key_of:
            key_of[key] = len(entries)
            v = entry_speeds(ctx, c.altitude, [c.get("speed_point")])[c.get("speed_point")]
            entries.append(c.with_(speed=v, speed_kind="EAS", speed_name=None, load_factor=None))
    batch = trimmed_batch(ctx, entries)
    rows, sim_conds, refused = batch.distribute(
        conditions, lambda c: key_of[(c.loading, c.altitude, c.get("speed_point"))], [e.speed for e in entries]
    )
    findings = refusal_findings(
        refused, lambda c: [f"{PARAGRAPH[c.get('speed_point')]}: {s.replace('_', ' ')}" for s in SURFACES]
    )
    if not rows.size:
        return RollingRun(findings, reason="no condition could be trimmed (see the findings)")
    model = batch.model.subset(rows)
    n_target = np.array([target_load_factor(ctx, c, crit) for c in sim_conds])
    st = symmetric_manoeuvre_state(model, batch.x[rows], batch.u[rows], n_target, batch.gamma[rows])
    je, ja = model.control_index("elevator"), model.control_index("aileron")
    e_lo, e_hi = control_stops(ctx, "elevator")
    ok = np.ones(len(rows), dtype=bool)
    n_stall = stall_line_load_factor(model, batch.x[rows])
    n_asked = n_target
    st, n_target, at_maximum = _at_lift_maximum(model, batch, rows, st, n_asked, n_stall, float(crit.stall_band))
    for i, c in enumerate(sim_conds):
        reason = None
        if not st.converged[i] or abs(st.n_z[i] - n_target[i]) > 1e-3:
            if n_stall is not None and n_target[i] > n_stall[i]:
                # computed: CLmax q S / W at the speed and Mach is below the load factor — the point lies beyond the
                # stall line of the V–n envelope (§25.333), not a flight condition
                ok[i] = False
                findings += [
                    Finding.not_applicable(
                        c,
                        f"{PARAGRAPH[c.get('speed_point')]}: {s.replace('_', ' ')}",
                        f"n = {n_target[i]:.2f} at this speed lies beyond the stall line of the V–n envelope: CLmax q "
                        "S / W = "
                        f"{n_stall[i]:.2f} (the pull-up reached n {st.n_z[i]:.2f} at α {np.degrees(st.alpha[i]):.1f}°)",
                    )
                    for s in SURFACES
                ]
                continue
            reason = (
                f"the n = {n_target[i]:.2f} symmetric manoeuvre cannot be set up at this speed (the lift is short of "
                f"it: n reached {st.n_z[i]:.2f} at α {np.degrees(st.alpha[i]):.1f}°)"
            )
        elif not e_lo - 1e-9 <= st.u[i, je] <= e_hi + 1e-9:
            lim = e_lo if st.u[i, je] < e_lo else e_hi
            reason = (
                f"the n = {n_target[i]:.2f} symmetric manoeuvre needs {np.degrees(st.u[i, je]):.1f}° elevator, "
                f"stop {np.degrees(lim):.1f}°"
            )
        if reason:
            ok[i] = False
            findings += [
                Finding.not_evaluated(c, f"{PARAGRAPH[c.get('speed_point')]}: {s.replace('_', ' ')}", reason)
                for s in SURFACES
            ]
    idx = np.flatnonzero(ok)
    if not idx.size:
        return RollingRun(findings, reason="no symmetric manoeuvre could be set up (see the findings)")
    conds = [sim_conds[i] for i in idx]
    model = model.subset(idx)
    x0, u0 = st.x[idx], st.u[idx]
    amplitude = full_aileron(ctx) - u0[:, ja]
    # the VA reference of each (loading, altitude, load factor) group, and the targets of (a)(3)/(a)(4)
    group = [(c.loading, c.altitude, c.get("load_factor")) for c in conds]
    at_va = {g: i for i, (g, c) in enumerate(zip(group, conds)) if c.get("speed_point") == "VA"}
    ratio = {"VA": np.nan, "VC": float(crit.vc_roll_rate_ratio), "VD": float(crit.vd_roll_rate_ratio)}
    # a VA pull-up beyond the lift available (VA capped at VC at altitude): the VA roll rate at the other load factor
    # of the same loading and altitude stands in (the roll rate hardly depends on the load factor)
    other = {(g[0], g[1]): i for g, i in at_va.items()}
    ref = np.array([at_va.get(g, other.get((g[0], g[1]), -1)) for g in group])
    proxy = np.array([g not in at_va and r >= 0 for g, r in zip(group, ref)])
    speed_point = [c.get("speed_point") for c in conds]
    scaled = np.array([sp != "VA" and r >= 0 for sp, r in zip(speed_point, ref)])
    # VA rows are simulated at full deflection in the first run: their peak roll rates are the references
    timing = dict(duration=float(crit.duration), dt=float(crit.time_step), ramp=float(crit.ramp_time))
    sim_full = simulate_roll(model, x0, u0, amplitude, **timing)
    p_full = peak_roll_rate(sim_full)[0]
    p_va = np.where(ref >= 0, p_full[np.maximum(ref, 0)], np.nan)
    target = np.where(scaled, p_va * np.array([ratio[s] for s in speed_point]), 0.0)
    search = dict(tolerance=float(crit.roll_rate_tolerance), steps=int(crit.search_steps), **timing)
    sim, p_peak, frac = aileron_for_roll_rate(model, x0, u0, amplitude, target, scaled, sim_full, **search)
    t_end, valid, k_peak = rolling_window(sim)
    loads = airplane_loads(ctx)
    right = response_loads(loads, sim, model, SURFACES, valid=valid)
    left = response_loads(loads, mirror(sim), model, MIRRORED, valid=valid)
    labels = [c.label() for c in conds]
    env_sides = LoadEnvelope.merge(
        [
            LoadEnvelope.from_histories(
                loads,
                {s: right[s] for s in MIRRORED},
                sim.t,
                [f"{lab} — right (down-going wing)" for lab in labels],
                keys=conds,
            ),
            LoadEnvelope.from_histories(
                loads, left, sim.t, [f"{lab} — left (up-going wing)" for lab in labels], keys=conds
            ),
        ]
    )
    env_fin = LoadEnvelope.from_histories(loads, {"vertical_tail": right["vertical_tail"]}, sim.t, labels)
    n = len(conds)
    # the wing in each fuel state of §25.343, each side with its own roll acceleration (the fuel's roll inertia relief)
    fuel_r, names, fuel = fuelled_wing(ctx, loads, sim, model, right["wing"], conds)
    fuel_l, _, _ = fuelled_wing(ctx, loads, mirror(sim), model, left["wing"], conds)
    wing_states = np.stack(
        [np.fmin(fuel_r[:, :, 0], fuel_l[:, :, 0]), np.fmax(fuel_r[:, :, 1], fuel_l[:, :, 1])], axis=2
    )  # (M, n, 2, 3, S)
    env_sides = replace(
        env_sides, peaks={**env_sides.peaks, "wing": np.concatenate([state_envelope(fuel_r), state_envelope(fuel_l)])}
    )
    caps = {s: declared_capabilities(ctx, s) for s in SURFACES}
    pdot = np.gradient(sim["p"], sim.t, axis=0)
    for i, c in enumerate(conds):
        sp = speed_point[i]
        common = dict(
            V_kn_EAS=round(float(c.speed / KN), 1),
            load_factor=round(float(st.n_z[idx[i]]), 4),
            **({"load_factor_note": AT_MAXIMUM.format(n_asked[idx[i]])} if at_maximum[idx[i]] else {}),
            pitch_rate_deg_s=_deg(st.pitch_rate[idx[i]], 3),
            elevator_deg=_deg(u0[i, je]),
            aileron_deg=_deg(u0[i, ja] + frac[i] * amplitude[i]),
            aileron_fraction_of_stop=round(float(frac[i]), 4),
            peak_roll_rate_deg_s=_deg(p_peak[i]),
            loads_considered_until_s=round(float(t_end[i]), 2),
            peak_roll_acceleration_deg_s2=_deg(np.nanmax(np.abs(pdot[valid[:, i], i])), 1),
            bank_at_end_deg=_deg(sim["phi"][k_peak[i], i], 1),
            peak_sideslip_deg=_deg(np.nanmax(np.abs(sim["beta"][valid[:, i], i]))),
            pilot_effort=EFFORT_NOTE,
            wing_flexibility=FLEX_NOTE,
        )
        if sp != "VA":
            if scaled[i]:
                common.update(roll_rate_VA_deg_s=_deg(p_va[i]), target_roll_rate_deg_s=_deg(target[i]))
                if proxy[i]:
                    common["roll_rate_reference"] = PROXY_NOTE.format(conds[ref[i]].get("load_factor"))
                if frac[i] >= 1.0 and p_peak[i] < target[i]:
                    common["roll_rate_shortfall"] = "the target roll rate is not reached with the aileron at its stop"
            else:
                common["roll_rate_reference"] = NO_VA_NOTE
        beyond_mach = beyond_mach_range(loads, condition_mach(c))
        for s in SURFACES:
            if s in MIRRORED:
                R, L = env_sides.peaks[s][i], env_sides.peaks[s][n + i]
                peaks = np.stack([np.fmin(R[0], L[0]), np.fmax(R[1], L[1])])
                extra = {}
                for q in ("bending", "torsion"):
                    jq = QUANTITIES.index(q)
                    extra[f"root {q} down-going/up-going side max/min (kN·m)"] = [
                        [round(float(P[1, jq, 0]) / 1e3, 1), round(float(P[0, jq, 0]) / 1e3, 1)] for P in (R, L)
                    ]
                stations = env_sides.stations[s]
            else:
                peaks, extra, stations = env_fin.peaks[s][i], {}, env_fin.stations[s]
            if beyond_mach:
                check = f"{PARAGRAPH[sp]}: {s.replace('_', ' ')}"
                state = wing_states[:, i] if s == "wing" else peaks
                findings.append(set_aside_finding(c, check, beyond_mach, state, stations, **common, **extra))
                continue
            if s == "wing":
                findings.append(
                    critical_state_finding(
                        c,
                        f"{PARAGRAPH[sp]}: wing",
                        s,
                        wing_states[:, i],
                        stations,
                        caps[s],
                        crit.ultimate_factor,
                        partial(fuel_detail, names[i], fuel[i], fuel_tank_names(ctx)),
                        **common,
                        **extra,
                    )
                )
                continue
            findings.append(
                capability_finding(
                    c,
                    f"{PARAGRAPH[sp]}: {s.replace('_', ' ')}",
                    s,
                    peaks,
                    stations,
                    caps[s],
                    crit.ultimate_factor,
                    **common,
                    **extra,
                )
            )
    failed = [
        (f.condition.label(), f.reason)
        for f in findings
        if f.status == "not_evaluated" and f.reason and "structural capability" not in f.reason
    ][:: len(SURFACES)]
    return RollingRun(
        findings,
        conds,
        sim,
        failed=failed,
        right=right,
        left=left,
        env_sides=env_sides,
        env_fin=env_fin,
        aileron_index=ja,
        fraction=frac,
        t_end=t_end,
    )


# --------------------------------------------------------------------------- (b) unsymmetrical gusts

REG_B = (
    "14 CFR 25.349(b) (secondary copy of the CFR text, end of (b) completed from EASA CS 25.349(b); "
    "docs/regulation-notes.md)"
)
AIRLOAD_BASES = ("total", "increment")


@rule
class UnsymmetricalGust(SimulationRule):
    id = "25.349(b)"
    produces = (Loads("wing"),)
    cost = 2  # relative evaluation time beyond the §25.341(a) gust runs it shares (run_with)
    run_with = "discrete-gust"
    symbol = "unsymmetrical-gust"
    title = "Unsymmetrical vertical gusts: 100 % of the §25.341(a) wing air load on one side, 80 % on the other"
    amendment = "25-94"
    requirement = """
        The airplane meets unsymmetrical vertical gusts in level flight. The limit loads are found from the wing
        maximum air load of §25.341(a) (directly, or from its vertical load factor), with 100 % of the wing air
        load acting on one side of the airplane and 80 % on the other; the unbalanced aerodynamic moments about
        the CG are reacted in a rational or conservative manner by the principal masses' inertia forces (lead-in
        of §25.349). The structure carries the loads (limit) and 1.5 × them (ultimate), §25.303/§25.305.
    """
    margin = """
        Per §25.341(a) condition and wing side (100 % and 80 %): the smallest of (allowable limit load − |limit
        load|) and (allowable ultimate load − 1.5 × |limit load|) over the declared wing stations and quantities,
        the limit load the extreme over every gust gradient and time of the §25.341(a) response with the air load
        modified at each instant and the unbalanced vertical force, rolling and pitching moments reacted by the
        rigid airplane's inertia; without a declared structural capability the condition is not evaluated and
        reports its loads.
    """
    references = ("25.341", "25.303", "25.305", "25.427")
    requires = GUST_REQUIRES
    criteria = {
        **GUST_RUN_CRITERIA,
        "full_side_fraction": Criterion(1.0, "", REG_B, "fraction of the wing air load on the more loaded side"),
        "reduced_side_fraction": Criterion(0.8, "", REG_B, "fraction of the wing air load on the other side"),
        "airload_basis": Criterion(
            "total",
            "",
            "certkit reading of 'the wing air load' of 14 CFR 25.349(b) (docs/regulation-notes.md §25.349)",
            "'total': the fractions apply to the whole wing "
            "air load (1 g trim + gust); 'increment': to the gust increment over the 1 g trim",
        ),
        **SAFETY,
    }
    conditions = GUST_CONDITIONS
    limitations = (
        "The §25.341(a) response it modifies is that of the rigid airplane with the gust's lift lagged by "
        "Küssner's function and the motion's quasi-steady (see §25.341(a)); the modified air load is reacted by "
        "rigid-body vertical, roll and pitch "
        "accelerations at the instant (products of inertia and the damping of the starting roll neglected); "
        "wing loads only (the horizontal tail's unsymmetrical loads are §25.427(b))."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.349(b)",
            "the §25.341(a) response it modifies is the rigid airplane's (no structural modes), and the horizontal "
            "tail's unsymmetrical loads (§25.427(b)) are not in it",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return unsymmetrical_gusts(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        if self.run is None or not self.run.simulated:
            return []
        return unsymmetrical_gust_evidence(self.run, allowables(ctx, crit.ultimate_factor))


def _airload_basis(crit) -> str:
    basis = str(crit.airload_basis).strip().lower()
    if basis not in AIRLOAD_BASES:
        raise UserError(
            f"criteria.25.349(b).values.airload_basis: {crit.airload_basis!r} is not one of "
            f"{', '.join(AIRLOAD_BASES)} (the whole wing air load, or its gust increment over the 1 g trim)"
        )
    for name in ("full_side_fraction", "reduced_side_fraction"):
        if not 0.0 <= float(crit[name]) <= 1.0:
            raise UserError(f"criteria.25.349(b).values.{name}: {crit[name]!r} must lie between 0 and 1")
    return basis


@dataclass
class UnsymmetricalGustRun(LoadsRun):
    """The unsymmetrical gusts: per side the gradient that set each extreme (``which``), the gust runs they split
    (``runs``: :class:`certkit_rules.part25.subpart_c.gust_runs.GustRuns`), the peak unbalanced rolling moment per
    gradient and condition (``roll``, N·m), the sides' fractions, the air-load basis and the symmetric envelope."""

    which: dict | None = None
    gradients: object = None
    runs: object = None
    roll: object = None
    fractions: tuple = (1.0, 1.0)
    basis: str = ""
    symmetric: object = None

    def envelopes(self) -> list:
        return [e for e in (self.envelope, self.symmetric) if e is not None]


def unsymmetrical_gusts(ctx, conditions, crit) -> UnsymmetricalGustRun:
    """§25.349(b) from the memoised §25.341(a) gust runs: per gust gradient the wing's air load split 100/80 % at
    every instant (:func:`certkit.models.loads.unsymmetrical.unsymmetrical_wing`), envelopes per side."""
    basis = _airload_basis(crit)
    full, reduced = float(crit.full_side_fraction), float(crit.reduced_side_fraction)
    full_side, reduced_side = f"wing, {full:.0%} side", f"wing, {reduced:.0%} side"
    if full_side == reduced_side:
        full_side, reduced_side = full_side + " (right)", reduced_side + " (left)"

    def check(c, side):
        return f"(b) unsymmetrical gust, {c.get('gust')}, {side}"

    runs = gust_runs(ctx, conditions, crit)
    findings = refusal_findings(runs.refused, lambda c: [check(c, s) for s in (full_side, reduced_side)])
    if not runs.conditions:
        return UnsymmetricalGustRun(findings, reason="no condition could be trimmed (see the findings)")
    wing, model, n = runs.loads["wing"], runs.batch.model, len(runs.conditions)
    labels = [c.label() for c in runs.conditions]
    per_side: dict[str, list] = {full_side: [], reduced_side: []}
    roll = np.zeros((len(runs.wing), n))
    pdot, dnz, t_roll = np.zeros_like(roll), np.zeros_like(roll), np.zeros_like(roll)
    for j, (t, aero, inertia) in enumerate(runs.wing):
        u = unsymmetrical_wing(
            wing,
            aero,
            inertia,
            model.mass,
            model.cg,
            model.inertia,
            full,
            reduced,
            trim_aero=aero[0] if basis == "increment" else None,
        )
        per_side[full_side].append(LoadEnvelope.from_histories(runs.loads, {"wing": u.full}, t, labels))
        per_side[reduced_side].append(LoadEnvelope.from_histories(runs.loads, {"wing": u.reduced}, t, labels))
        k = np.argmax(np.abs(u.rolling_moment), axis=0)
        cols = np.arange(n)
        roll[j], pdot[j], dnz[j], t_roll[j] = (
            u.rolling_moment[k, cols],
            u.pdot[k, cols],
            u.delta_n_z[k, cols],
            times_at(t, k),
        )
    stations, peaks, times, which = {}, {}, {}, {}
    for side, parts in per_side.items():
        env, w = LoadEnvelope.worst_of(parts)
        stations[side], peaks[side], times[side], which[side] = (
            env.stations["wing"],
            env.peaks["wing"],
            env.times["wing"],
            w["wing"],
        )
    envelope = LoadEnvelope(stations, peaks, times, labels)
    j_roll = np.argmax(np.abs(roll), axis=0)
    caps = declared_capabilities(ctx, "wing")
    sym, _ = runs.symmetric
    b = QUANTITIES.index("bending")
    for i, c in enumerate(runs.conditions):
        jr = int(j_roll[i])
        common = dict(
            airload_basis=basis,
            critical_H_rolling_moment_ft=round(float(runs.gradients[jr] / FT), 0),
            peak_unbalanced_rolling_moment_MNm=round(float(roll[jr, i]) / 1e6, 3),
            roll_acceleration_deg_s2=round(float(np.degrees(pdot[jr, i])), 2),
            load_factor_change=round(float(dnz[jr, i]), 4),
            at_time_s=round(float(t_roll[jr, i]), 3),
            symmetric_root_bending_max_min_kNm=[
                round(float(sym.peaks["wing"][i, 1, b, 0]) / 1e3, 1),
                round(float(sym.peaks["wing"][i, 0, b, 0]) / 1e3, 1),
            ],
        )
        beyond_mach = beyond_mach_range(runs.loads, condition_mach(c))
        for side in (full_side, reduced_side):
            jb = int(which[side][i, 1 if runs.up[i] else 0, b, 0])
            if beyond_mach:
                findings.append(
                    set_aside_finding(c, check(c, side), beyond_mach, peaks[side][i], stations[side], **common)
                )
                continue
            findings.append(
                capability_finding(
                    c,
                    check(c, side),
                    "wing",
                    peaks[side][i],
                    stations[side],
                    caps,
                    crit.ultimate_factor,
                    critical_H_root_bending_ft=round(float(runs.gradients[jb] / FT), 0),
                    **common,
                )
            )
    return UnsymmetricalGustRun(
        findings,
        runs.conditions,
        envelope=envelope,
        which=which,
        gradients=runs.gradients,
        runs=runs,
        roll=roll,
        fractions=(full, reduced),
        basis=basis,
        symmetric=sym,
    )

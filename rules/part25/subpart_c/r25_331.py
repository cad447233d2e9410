"""§25.331(c) Pitch maneuver conditions: (c)(1) maximum pitch control displacement at VA and (c)(2)
the checked manoeuvre between VA and VD, as rigid-airplane batch simulations with the strip loads
model of the horizontal tail (:mod:`certkit.models.loads`).

The regulation text of (c)(2) is only partly verified (docs/regulation-notes.md): t₂ = t₁ + Δt,
t_max = t₂ + π/ω and Δt ≤ 5 s are verified; the sinusoid δ₁ sin ωt, t_max = 3π/(2ω) without hold and
ω ≥ πV/(2VA) are from memory — they are criteria here, overridable in the aircraft file.

Each condition's horizontal-tail limit loads are compared with the capabilities declared in the aircraft
file's ``structure.horizontal_tail`` (limit, and 1.5 × limit against ultimate, §25.303/§25.305); without
one the condition reports its loads and is not evaluated with the reason "no structural capability declared". The
structural checks it shares with §§25.341, 25.349 and 25.351 are in :mod:`certkit_rules.part25.support.structural_checks`.

(c)(2) reports the load factor each manoeuvre reaches and the §25.337 limit at its speed (n₊ nose up; nose
down n₋ = −1.0 up to VC, linearly to 0 at VD) in the details: the input is scaled to reach that limit, so being
on it is the manoeuvre's construction, not a verdict. Only a peak beyond the limit (+ the search tolerance) is a
finding: "fails" after a converged search, not evaluated when the search did not converge (its loads are
conservative). In (c)(1) the load factor may exceed the limit (loads after that need not be considered).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import partial

import numpy as np
from certkit_rules.part25.support.fuel_states import fuel_detail, fuel_tank_names, fuelled_wing, fuelled_wing_envelope
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    beyond_mach_range,
    capability_finding,
    condition_mach,
    control_stops,
    critical_state_finding,
    entry_speeds,
    force_limited_deflection,
    maneuver_limit_load_factor,
    set_aside_finding,
)

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.registry import HINGE_MOMENT, Criterion, Loads, SimulationRule, rule
from certkit.engine.results import Finding, LoadsRun
from certkit.models.dynamics.linearize import linearize
from certkit.models.dynamics.modes import identify_modes
from certkit.models.dynamics.simulate import Bound, Step, simulate
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.checked_maneuver import checked_maneuver_inputs
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope, below_stall, response_loads
from certkit.units import KN

REG_NOTES = "docs/regulation-notes.md §25.331(c)"
PILOT_EFFORT_NOTE = (
    "no control-force model is declared (control_forces.elevator): the pilot-effort limit of §25.397 "
    "(300 lbf elevator wheel) cannot reduce the deflection; the control-system stop (travel) bounds it"
)
PILOT_EFFORT = {
    "pilot_effort_lbf": Criterion(
        300.0,
        "lbf",
        "14 CFR 25.397(c) table, elevator wheel (symmetrical), maximum (verified, docs/regulation-notes.md); "
        "§25.331(c) lead-in allows the deflection to be limited by it; two-thirds may be used with reliable hinge-moment "
        "data (§25.397(b))",
        "limit pilot force on the pitch control (used with control_forces.elevator)",
    )
}


def _effort_note(limited, i) -> str:
    if limited is None:
        return PILOT_EFFORT_NOTE
    return (
        "deflection limited by the pilot effort (control_forces.elevator)"
        if limited[i]
        else "control-system stop (travel) reached below the pilot-effort force"
    )


# --------------------------------------------------------------------------- wing loads

#: the surfaces whose loads the §25.331(c) manoeuvres compute (the tail's window of time also bounds the wing's)
LOADED = ("horizontal_tail", "wing")
#: … their station loads, and the elevator's hinge moments along the manoeuvre (the elevator actuators' design case)
PRODUCED = tuple(Loads(s) for s in LOADED) + (Loads("elevator", HINGE_MOMENT),)


@dataclass
class PitchManeuverRun(LoadsRun):
    """A pitch manoeuvre's run: the batch's records with the station loads of :data:`LOADED` along them (``loads``:
    surface → (n_t, n, 3, S), NaN outside the considered window), the input kind of each condition (``kind``:
    0 scaled sinusoid, 1 held input, 2 maximal held input; None for a single kind) and the tail's station names."""

    loads: dict = field(default_factory=dict)
    kind: object = None
    stations: tuple = ()


NOTHING_TRIMMED = "no condition could be trimmed (see the findings)"


WING_STALL_NOTE = (
    "wing loads considered while the airplane's linear lift is below CLmax: the strip loads are linear "
    "in α, past the stall they overstate the wing's lift (which the airplane model rounds onto CLmax)"
)


def wing_before_stall(hist, model, sim) -> np.ndarray | None:
    """Blank the wing's loads of ``hist`` where the airplane is past its stall (:func:`below_stall`); returns the
    (nt, n) mask of the times kept (None without a stall model)."""
    keep = below_stall(model, sim)
    if keep is not None:
        hist["wing"] = np.where(keep[:, :, None, None], hist["wing"], np.nan)
    return keep


def wing_finding(ctx, cond, check: str, env, i: int, crit, fuelled, stalled: bool = False, **details) -> Finding:
    """The wing's finding of condition ``i`` of a manoeuvre's envelope (its loads in the same time window as the
    tail's, up to the stall) against the declared wing capability, in the critical fuel state (``fuelled``:
    :func:`fuelled_wing`'s peaks, names and fuel)."""
    if stalled:
        details["wing_window"] = WING_STALL_NOTE
    peaks, names, fuel = fuelled
    return critical_state_finding(
        cond,
        f"{check}, wing",
        "wing",
        peaks[:, i],
        env.stations["wing"],
        declared_capabilities(ctx, "wing"),
        crit.ultimate_factor,
        partial(fuel_detail, names[i], fuel[i], fuel_tank_names(ctx)),
        **details,
    )


def _modes_frequency(batch) -> np.ndarray:
    lin = linearize(batch.model, batch.x, batch.u)
    out = np.full(batch.n, np.nan)
    for i in range(batch.n):
        sp = identify_modes(lin, i).get("short_period")
        if sp is not None and np.isfinite(sp.natural_frequency):
            out[i] = sp.natural_frequency
    return out


def _label(cond) -> str:
    return cond.label()


# --------------------------------------------------------------------------- (c)(2) checked manoeuvre


@rule
class CheckedPitchManeuver(SimulationRule):
    id = "25.331(c)(2)"
    produces = PRODUCED
    cost = 5  # relative evaluation time (orders work over --jobs processes)
    symbol = "checked-pitch-maneuver"
    title = "Checked pitch manoeuvre between VA and VD"
    amendment = "25-141"
    requirement = """
        From unaccelerated flight at speeds from VA to VD the cockpit pitch control is moved as
        δ(t) = δ₁ sin ωt for 0 ≤ t ≤ t_max = 3π/(2ω), ω the undamped short-period frequency but not less
        than πV/(2VA); δ₁ such that the positive limit load factor (nose up) or 0 g (nose down) is reached
        but not exceeded. Where the sinusoid at the available deflection does not reach it, the peak is
        held for Δt (the minimum time to reach it, at most 5 s) before returning (t_max = t₂ + π/ω).
        Loads after n_z < 0 (nose up) or n_z > the limit (nose down), or after t_max, need not be
        considered. The horizontal tail must carry the resulting loads (§25.303, §25.305), and the load
        factor reached stays within the §25.337 limits (positive factor nose up; nose down the negative
        factor, −1.0 up to VC and zero at VD, §25.337(c)).
    """
    margin = """
        Per condition: the smallest of (allowable limit load − |limit load|) and (allowable ultimate load −
        1.5 × |limit load|) over the declared horizontal-tail stations and quantities; without a declared
        structural capability the condition is not evaluated and its loads are reported. The load factor
        reached is a detail; a peak beyond the §25.337 limit + the search tolerance is a further finding:
        (n₊ + tolerance) − highest n_z nose up, lowest n_z − (n₋(V) − tolerance) nose down, in g.
    """
    references = ("25.331(c)(1)", "25.333", "25.337", "25.397", "25.303", "25.305")
    requires = ("speeds.VA", "speeds.VD", "speeds.VC", "envelope.limit_load_factors", "geometry.horizontal_tail")
    criteria = {
        "omega_floor_factor": Criterion(
            0.5, "", "14 CFR 25.331(c)(2) (UNVERIFIED, " + REG_NOTES + ")", "ω ≥ factor × π V/VA (rad/s), i.e. πV/(2VA)"
        ),
        "t_max_periods": Criterion(
            1.5,
            "",
            "14 CFR 25.331(c)(2) (UNVERIFIED, " + REG_NOTES + ")",
            "t_max = factor × π/ω without hold (3π/(2ω))",
        ),
        "max_hold": Criterion(5.0, "s", "14 CFR 25.331(c)(2)(iii) (verified fragment)", "longest hold Δt at the peak"),
        "n_nose_down": Criterion(0.0, "", "14 CFR 25.331(c)(2)", "load factor the nose-down manoeuvre reaches"),
        "time_step": Criterion(0.04, "s", "certkit numerical choice (RK4; ω·dt ≤ 0.15)", "simulation step"),
        "search_steps": Criterion(10, "", "certkit numerical choice", "batched regula-falsi steps on δ₁ or Δt"),
        "load_factor_tolerance": Criterion(
            0.02,
            "",
            "certkit numerical choice",
            "|n_peak − n_target| accepted (also the allowance on the §25.337 limit of the load-factor check)",
        ),
        "search_resolution": Criterion(
            0.002,
            "",
            "certkit numerical choice",
            "the input search ends within this of the load factor: near the stall line the peak load factor is "
            "nearly flat in the amplitude, and a search stopped anywhere within the tolerance would pick inputs "
            "(and tail loads) that jump from one design to the next",
        ),
        **SAFETY,
        **PILOT_EFFORT,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=EnvelopeAltitudes(),
        extra=(("entry_speed", ("VA", "VC", "VD")), ("direction", ("nose up", "nose down"))),
        note="Entry speeds VA, VC and VD in EAS, each Mach-limited at altitude (VA ≤ VC).",
    )
    limitations = (
        "Rigid airplane, quasi-steady strip aerodynamics; the pilot effort limits the deflection only with "
        "control_forces.elevator (force at the trim's angle of attack, at the instant of the input), else the "
        "elevator goes to its stop (travel); the structural comparison needs capabilities declared in the aircraft file's `structure` section."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.331(c)(2)",
            "fuselage and vertical-tail loads of the checked manoeuvre are not reported (wing and horizontal-"
            "tail loads only)",
        ),
        (
            "25.331(a)(2)",
            "out-of-trim loads are not computed: the manoeuvres start from the 1 g trim, not from the "
            "§25.255 mistrim (stabiliser trimmed for the adjacent speed); no rule evaluates them",
        ),
        (
            "25.331(c)",
            "C_N,max does not vary with Mach: the wing loads' window is bounded by the low-speed CLmax, so at high "
            "Mach the manoeuvre reaches lift coefficients beyond buffet onset and maximum lift there",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return checked_maneuver(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return pitch_evidence(self.run, ctx, crit, "checked manoeuvre")


def pitch_evidence(run: PitchManeuverRun | None, ctx, crit, what: str) -> list:
    """Evidence of a pitch manoeuvre run: the tail's critical time histories, envelope and table, the wing's table,
    each against the declared allowables."""
    from certkit.engine.evidence.loads import allowables, envelope_evidence, maneuver_evidence

    if run is None or not run.simulated:
        return []
    allow = allowables(ctx, crit.ultimate_factor)
    return maneuver_evidence(run, "horizontal_tail", "elevator", allow=allow) + envelope_evidence(
        run.envelope, ("wing",), what, plot=False, allow=allow
    )


def checked_maneuver(ctx, conditions, crit) -> PitchManeuverRun:
    """Batch simulation of every checked-manoeuvre condition; returns findings, the envelope and the
    histories of the final inputs (for evidence)."""
    n_lim = ctx.aircraft.envelope.limit_load_factors.positive
    va_decl = float(ctx.design_speed_eas("VA", 0.0)[0])
    entries, key_of = [], {}
    for c in conditions:
        key = (c.loading, c.altitude, c.get("entry_speed"))
        if key not in key_of:
            v = entry_speeds(ctx, c.altitude, [c.get("entry_speed")])[c.get("entry_speed")]
            key_of[key] = len(entries)
            entries.append(c.with_(speed=v, speed_kind="EAS", speed_name=None, direction=None))
    batch = trimmed_batch(ctx, [e.with_() for e in entries])
    rows, sim_conds, refused = batch.distribute(
        conditions, lambda c: key_of[(c.loading, c.altitude, c.get("entry_speed"))], [e.speed for e in entries]
    )
    findings = refusal_findings(refused, lambda c: ["(c)(2) checked manoeuvre"])
    if not rows.size:
        return PitchManeuverRun(findings, reason=NOTHING_TRIMMED)
    omega_sp = _modes_frequency(batch)[rows]
    model = batch.model.subset(rows)
    x0, u0 = batch.x[rows], batch.u[rows]
    nose_up = np.array([c.get("direction") == "nose up" for c in sim_conds])
    v_eas = np.array([c.speed for c in sim_conds])
    omega_floor = crit.omega_floor_factor * np.pi * v_eas / va_decl
    omega = np.fmax(np.nan_to_num(omega_sp, nan=0.0), omega_floor)
    lim = control_stops(ctx, "elevator")
    de_trim = u0[:, model.control_names.index("elevator")]
    stop = np.where(nose_up, lim[0], lim[1])
    reach_to, effort_limited = force_limited_deflection(
        ctx, "elevator", sim_conds, de_trim, stop, crit.pilot_effort_lbf
    )
    available = np.abs(reach_to - de_trim)
    sign = np.where(nose_up, -1.0, 1.0)
    target = np.where(nose_up, n_lim - 1.0, 1.0 - crit.n_nose_down)
    trims = (model, x0, u0)
    found = checked_maneuver_inputs(
        *trims,
        nose_up,
        omega,
        available,
        target,
        n_limit=n_lim,
        max_hold=float(crit.max_hold),
        dt=float(crit.time_step),
        periods=float(crit.t_max_periods),
        steps=int(crit.search_steps),
        tolerance=float(crit.load_factor_tolerance),
        resolution=float(crit.search_resolution),
    )
    amp, hold, reach, held_short = found.amplitude, found.hold, found.reach, found.held_short
    resp, sim, valid, t_max = found.response, found.sim, found.valid, found.t_max
    loads = airplane_loads(ctx)
    hist = response_loads(loads, sim, model, LOADED, valid=valid)
    unstalled = wing_before_stall(hist, model, sim)
    stalled = np.zeros(len(rows), dtype=bool) if unstalled is None else (valid & ~unstalled).any(axis=0)
    fuelled = fuelled_wing(ctx, loads, sim, model, hist["wing"], sim_conds)
    env = fuelled_wing_envelope(
        LoadEnvelope.from_histories(loads, hist, sim.t, [_label(c) for c in sim_conds], keys=sim_conds), fuelled[0]
    )
    stations = loads["horizontal_tail"].station_names
    caps = declared_capabilities(ctx, "horizontal_tail")
    for i, c in enumerate(sim_conds):
        converged = abs(resp[i] - target[i]) <= float(crit.load_factor_tolerance)
        kind = (
            (
                "sinusoid, amplitude scaled to the load factor"
                if converged
                else f"sinusoid, the largest amplitude found below the load factor (search not converged in "
                f"{int(crit.search_steps)} steps)"
                if resp[i] < target[i]
                else f"sinusoid, amplitude search not converged in {int(crit.search_steps)} steps"
            )
            if reach[i]
            else "held at full deflection for the longest hold (load factor not reached)"
            if held_short[i]
            else "held at full deflection, minimum hold to the load factor"
        )
        peak_nz = float(
            np.nanmax(np.where(valid[:, i], sim["n_z"][:, i], np.nan))
            if nose_up[i]
            else np.nanmin(np.where(valid[:, i], sim["n_z"][:, i], np.nan))
        )
        reached, beyond = load_factor_reached(ctx, c, bool(nose_up[i]), peak_nz, converged, kind, crit)
        beyond_mach = beyond_mach_range(loads, condition_mach(c))
        if beyond_mach:
            findings += [
                set_aside_finding(
                    c,
                    f"(c)(2) checked manoeuvre, {c.get('direction')}",
                    beyond_mach,
                    env.peaks["horizontal_tail"][i],
                    stations,
                    peak_n_z=round(peak_nz, 4),
                    input=kind,
                ),
                set_aside_finding(
                    c,
                    f"(c)(2) checked manoeuvre, {c.get('direction')}, wing",
                    beyond_mach,
                    fuelled[0][:, i],
                    env.stations["wing"],
                    peak_n_z=round(peak_nz, 4),
                ),
            ]
            continue
        findings.append(
            capability_finding(
                c,
                f"(c)(2) checked manoeuvre, {c.get('direction')}",
                "horizontal_tail",
                env.peaks["horizontal_tail"][i],
                stations,
                caps,
                crit.ultimate_factor,
                delta1_deg=round(float(np.degrees(sign[i] * amp[i])), 3),
                omega_rad_s=round(float(omega[i]), 4),
                omega_short_period=round(float(np.nan_to_num(omega_sp[i])), 4),
                hold_s=round(float(hold[i]), 3),
                t_max_s=round(float(t_max[i]), 3),
                stop=sim.stop_reason[i] or "end",
                pilot_effort=_effort_note(effort_limited, i),
                **reached,
            )
        )
        findings.append(
            wing_finding(
                ctx,
                c,
                f"(c)(2) checked manoeuvre, {c.get('direction')}",
                env,
                i,
                crit,
                fuelled,
                bool(stalled[i]),
                input=kind,
                peak_n_z=round(peak_nz, 4),
            )
        )
        if beyond is not None:
            findings.append(beyond)
    return PitchManeuverRun(
        findings,
        sim_conds,
        sim,
        valid,
        envelope=env,
        loads=hist,
        kind=np.where(reach, 0, np.where(held_short, 2, 1)),
        stations=stations,
    )


def load_factor_reached(ctx, cond, nose_up: bool, peak_nz: float, settled: bool, kind: str, crit):
    """The load factor the checked manoeuvre reached (highest nose up, lowest nose down, within the loads' window)
    against the §25.337 limit at its speed, as details of the condition's findings (the input is scaled to reach that
    limit: being on it is how the manoeuvre is built, not a verdict). A finding only when the peak goes beyond the
    limit + the search tolerance: "fails" after a converged search, not evaluated when the search did not converge
    (its loads are conservative, the manoeuvre is not the paragraph's). Returns (details, finding or None)."""
    n_lim = maneuver_limit_load_factor(ctx, cond.speed, cond.altitude, nose_up)
    tol = float(crit.load_factor_tolerance)
    details = dict(peak_n_z=round(peak_nz, 4), limit_load_factor=round(n_lim, 4), search_tolerance=tol, input=kind)
    if nose_up and peak_nz < n_lim - tol:
        details["load_factor_note"] = (
            "the positive limit load factor is not reached with the available elevator and "
            "the longest hold (§25.331(c)(2)(iii) maximal input)"
        )
    limit = n_lim + tol if nose_up else n_lim - tol
    if not (peak_nz > limit if nose_up else peak_nz < limit):
        return details, None
    check = f"(c)(2) load factor beyond the §25.337 limit, {cond.get('direction')}"
    if not settled:
        return details, Finding.not_evaluated(
            cond,
            check,
            f"amplitude search not converged: peak n_z {peak_nz:.3f} is "
            f"beyond the §25.337 limit {n_lim:.3f} (loads of this condition are "
            "conservative)",
            **details,
        )
    return details, Finding.compare(cond, check, peak_nz, limit, at_least=not nose_up, unit="g", **details)


# --------------------------------------------------------------------------- (c)(1) maximum displacement at VA


@rule
class MaximumPitchControlDisplacement(SimulationRule):
    id = "25.331(c)(1)"
    produces = PRODUCED
    cost = 4  # relative evaluation time (orders work over --jobs processes)
    symbol = "maximum-pitch-control-displacement"
    title = "Maximum pitch control displacement at VA"
    amendment = "25-141"
    requirement = """
        In steady level flight at VA (point A1 of §25.333(b)) the cockpit pitch control is suddenly moved
        to obtain extreme nose-up pitching acceleration; the tail load is determined with the airplane's
        response. Loads after the normal acceleration at the CG exceeds the positive limit manoeuvring
        load factor, or after the tail load reaches its maximum, whichever is first, need not be considered.
    """
    margin = """
        Per condition: the smallest of (allowable limit load − |limit load|) and (allowable ultimate load −
        1.5 × |limit load|) over the declared horizontal-tail stations and quantities; without a declared
        structural capability the condition is not evaluated and its loads are reported.
    """
    references = ("25.331(c)(2)", "25.333", "25.337", "25.397", "25.303", "25.305")
    requires = ("speeds.VA", "speeds.VC", "envelope.limit_load_factors", "geometry.horizontal_tail")
    criteria = {
        "ramp_time": Criterion(
            0.1,
            "s",
            "certkit assumption: 'suddenly' with no declared actuator rate",
            "time to reach the full deflection",
        ),
        "duration": Criterion(4.0, "s", "certkit numerical choice", "longest simulated time"),
        "time_step": Criterion(0.02, "s", "certkit numerical choice", "simulation step"),
        **SAFETY,
        **PILOT_EFFORT,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=EnvelopeAltitudes(),
        note="At VA (EAS), capped at the Mach-limited VC at altitude.",
    )
    limitations = (
        "Rigid airplane, quasi-steady strip aerodynamics; the pilot effort limits the deflection only with "
        "control_forces.elevator (force at the trim's angle of attack, at the instant of the input), else the "
        "elevator goes to its stop (travel); the structural comparison needs capabilities declared in the aircraft file's `structure` section."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.331(c)(1)",
            "fuselage and vertical-tail loads of the manoeuvre are not reported (wing and horizontal-tail loads only)",
        ),
        (
            "25.391",
            "the elevator's hinge-line loads of this manoeuvre (§25.391, §25.395 control system, §25.397 pilot "
            "effort, §25.415 ground gusts) are not computed; no rule evaluates control-surface and control-system "
            "loads",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        n_lim = ctx.aircraft.envelope.limit_load_factors.positive
        entries = [
            c.with_(speed=entry_speeds(ctx, c.altitude, ["VA"])["VA"], speed_kind="EAS", speed_name="VA")
            for c in conditions
        ]
        batch = trimmed_batch(ctx, entries)
        findings = refusal_findings(batch.refusals(entries), lambda c: ["(c)(1) maximum pitch control displacement"])
        if not batch.n:
            return PitchManeuverRun(findings, reason=NOTHING_TRIMMED)
        lim = control_stops(ctx, "elevator")
        # to the nose-up (trailing edge up) stop, or as far as the pilot effort moves it
        target, effort_limited = force_limited_deflection(
            ctx, "elevator", batch.conditions, batch.control("elevator"), lim[0], crit.pilot_effort_lbf
        )
        step = target - batch.control("elevator")
        dt, ramp = float(crit.time_step), float(crit.ramp_time)
        sched = Step(0.0, step) if ramp <= 0 else _ramp(ramp, step)
        sim = simulate(
            batch.model,
            batch.x,
            batch.u,
            float(crit.duration),
            dt,
            inputs={"elevator": sched},
            stop=[Bound("n_z > limit", "n_z", upper=n_lim)],
        )
        loads = airplane_loads(ctx)
        hist = response_loads(loads, sim, batch.model, LOADED)
        # loads up to the first of: n_z above the limit (stop) or the tail load's maximum (root shear magnitude)
        root = np.abs(hist["horizontal_tail"][:, :, 0, 0])
        t_peak = sim.t[np.nanargmax(root, axis=0)]
        valid = sim.t[:, None] <= np.minimum(sim.stop_time, t_peak)[None, :] + 1e-9
        hist = {s: np.where(valid[:, :, None, None], h, np.nan) for s, h in hist.items()}
        unstalled = wing_before_stall(hist, batch.model, sim)
        stalled = np.zeros(batch.n, dtype=bool) if unstalled is None else (valid & ~unstalled).any(axis=0)
        fuelled = fuelled_wing(ctx, loads, sim, batch.model, hist["wing"], batch.conditions)
        env = fuelled_wing_envelope(
            LoadEnvelope.from_histories(
                loads, hist, sim.t, [_label(c) for c in batch.conditions], keys=batch.conditions
            ),
            fuelled[0],
        )
        stations = loads["horizontal_tail"].station_names
        caps = declared_capabilities(ctx, "horizontal_tail")
        for i, c in enumerate(batch.conditions):
            beyond_mach = beyond_mach_range(loads, condition_mach(c))
            if beyond_mach:
                findings += [
                    set_aside_finding(
                        c,
                        "(c)(1) maximum pitch control displacement",
                        beyond_mach,
                        env.peaks["horizontal_tail"][i],
                        stations,
                    ),
                    set_aside_finding(
                        c,
                        "(c)(1) maximum pitch control displacement, wing",
                        beyond_mach,
                        fuelled[0][:, i],
                        env.stations["wing"],
                    ),
                ]
                continue
            findings.append(
                capability_finding(
                    c,
                    "(c)(1) maximum pitch control displacement",
                    "horizontal_tail",
                    env.peaks["horizontal_tail"][i],
                    stations,
                    caps,
                    crit.ultimate_factor,
                    elevator_step_deg=round(float(np.degrees(step[i])), 3),
                    considered_until_s=round(float(min(sim.stop_time[i], t_peak[i])), 3),
                    stop=sim.stop_reason[i] or "end",
                    VA_kn_EAS=round(float(c.speed / KN), 1),
                    pilot_effort=_effort_note(effort_limited, i),
                    elevator_stop_deg=round(float(np.degrees(lim[0])), 2),
                    elevator_trim_deg=round(float(np.degrees(batch.control("elevator")[i])), 3),
                    **(
                        {
                            "stabilizer_trim_deg": round(
                                float(
                                    np.degrees(
                                        batch.control("stabilizer")[i] + ctx.aircraft.geometry.horizontal_tail.incidence
                                    )
                                ),
                                3,
                            )
                        }
                        if "stabilizer" in batch.model.control_names
                        else {}
                    ),
                )
            )
            findings.append(
                wing_finding(
                    ctx,
                    c,
                    "(c)(1) maximum pitch control displacement",
                    env,
                    i,
                    crit,
                    fuelled,
                    bool(stalled[i]),
                    considered_until_s=round(float(min(sim.stop_time[i], t_peak[i])), 3),
                )
            )
        return PitchManeuverRun(findings, batch.conditions, sim, valid, envelope=env, loads=hist, stations=stations)

    def evidence(self, ctx, findings, crit):
        return pitch_evidence(self.run, ctx, crit, "maximum pitch control displacement")


def _ramp(ramp: float, amplitude):
    from certkit.models.dynamics.simulate import Ramp

    return Ramp(0.0, ramp, amplitude)

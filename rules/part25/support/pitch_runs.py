"""The §25.331(c) pitch manoeuvres' shared procedures and batched runs, (c)(1) and (c)(2) (regulation content, no
rule here): the runs are memoised in the context so that §25.331(c) and §25.427(b), which splits their tail loads,
evaluated in one process (``run_with = "discrete-gust"``), simulate once. Paragraph text and
verification status: :mod:`certkit_rules.part25.subpart_c.r25_331`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import partial

import numpy as np
from certkit_rules.part25.support.envelope_criteria import CN_OVER_CL
from certkit_rules.part25.support.fuel_states import fuel_detail, fuel_tank_names, fuelled_wing, fuelled_wing_envelope
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit_rules.part25.support.out_of_trim import (
    MISTRIM_SECONDS,
    MISTRIMS,
    mistrim,
    mistrim_note,
    mistrim_rate,
    out_of_trim_speed,
)
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
from certkit.engine.registry import HINGE_MOMENT, Criterion, Loads
from certkit.engine.results import Finding, LoadsRun
from certkit.models.dynamics.linearize import linearize
from certkit.models.dynamics.modes import identify_rows
from certkit.models.dynamics.simulate import Bound, Ramp, Step, simulate
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.checked_maneuver import checked_maneuver_inputs
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope, below_stall, response_load_parts, summed_loads
from certkit.models.loads.vn_envelope import envelope as vn_envelope
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
        "§25.331(c) lead-in allows the deflection to be limited by it; two-thirds may be used with reliable "
        "hinge-moment "
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
    #: the tail's (aerodynamic, inertial) station loads along the runs, as the manoeuvre computed them
    tail_split: tuple = ()

    def tail_parts(self) -> tuple[np.ndarray, np.ndarray]:
        """The right half tailplane's (aerodynamic, inertial) station loads along the runs, each (n_t, n, 3, S),
        NaN outside the window the paragraph considers (what §25.427(b) splits)."""
        aero, inertia = self.tail_split
        keep = np.asarray(self.valid, dtype=bool)[:, :, None, None]
        return np.where(keep, aero, np.nan), np.where(keep, inertia, np.nan)


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
        ctx.memo(("declared_capabilities", "wing"), lambda: declared_capabilities(ctx, "wing")),
        crit.ultimate_factor,
        partial(fuel_detail, names[i], fuel[i], fuel_tank_names(ctx)),
        **details,
    )


def _modes_frequency(batch) -> np.ndarray:
    lin = linearize(batch.model, batch.x, batch.u)
    out = np.full(batch.n, np.nan)
    for i, modes in enumerate(identify_rows(lin)):
        sp = modes.get("short_period")
        if sp is not None and np.isfinite(sp.natural_frequency):
            out[i] = sp.natural_frequency
    return out


def _label(cond) -> str:
    return cond.label()


CHECKED_CRITERIA = {
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
    "mistrim_seconds": MISTRIM_SECONDS,
    "n_nose_down": Criterion(0.0, "", "14 CFR 25.331(c)(2)", "load factor the nose-down manoeuvre reaches"),
    "time_step": Criterion(0.04, "s", "certkit numerical choice (RK4; ω·dt ≤ 0.15)", "simulation step"),
    "search_steps": Criterion(
        10,
        "",
        "certkit numerical choice",
        "batched steps on δ₁ (the first probing the linear response) or Δt, regula falsi",
    ),
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
    "hold_resolution": Criterion(
        0.005,
        "s",
        "certkit numerical choice",
        "the hold search ends when the minimum hold is bracketed within this: the load factor flattens in the "
        "hold (a few hundredths of g per second), so a search stopped on the load factor alone would leave the "
        "hold, and the tail loads it sets, undetermined by a tenth of a second",
    ),
    **CN_OVER_CL,
    **SAFETY,
    **PILOT_EFFORT,
}


#: the entry speeds of the §25.331(a)(2) out-of-trim checked manoeuvres (the §25.255 speeds: trimmed at cruise speeds
#: up to VMO/MMO; VA lies below them)
OUT_OF_TRIM_ENTRIES = ("VC", "VD")


@dataclass(frozen=True)
class CheckedPoints(ConditionSpace):
    """The checked manoeuvres' conditions and, with a declared stabiliser trim rate, the out-of-trim ones at VC and VD:
    each direction from the mistrim in its own sense (nose-up pulls from the nose-up mistrim, nose-down pushes from the
    nose-down one) — the mistrim that leaves the elevator more travel toward the manoeuvre's stop; the opposite one
    leaves less, and the stabiliser's share of the tail load is already out of trim in the balanced manoeuvres."""

    def expand(self, aircraft):
        out = ConditionSpace.expand(self, aircraft)
        if mistrim_rate(aircraft) is not None:
            for sense in MISTRIMS:
                extra = (("entry_speed", OUT_OF_TRIM_ENTRIES), ("direction", (sense,)), ("trim", (sense,)))
                out += ConditionSpace.expand(replace(self, extra=extra), aircraft)
        return out

    def describe(self):
        return (
            ConditionSpace.describe(self)
            + "; out of trim (§25.331(a)(2), with a declared stabiliser trim rate): from VC and VD, each direction "
            "from the §25.255 mistrim in its own sense"
        )


CHECKED_CONDITIONS = CheckedPoints(
    loading=CgCorners(),
    configurations=("clean",),
    altitudes=EnvelopeAltitudes(),
    extra=(("entry_speed", ("VA", "VC", "VD")), ("direction", ("nose up", "nose down"))),
    note="Entry speeds VA, VC and VD in EAS, each Mach-limited at altitude (VA ≤ VC).",
)


def checked_maneuver(ctx, conditions, crit) -> PitchManeuverRun:
    """Batch simulation of every checked-manoeuvre condition; returns findings, the envelope and the
    histories of the final inputs (for evidence)."""
    n_lim = ctx.aircraft.envelope.limit_load_factors.positive
    va_decl = ctx.design_speed_eas_at("VA", 0.0)
    entries, key_of, reference = [], {}, {}
    for c in conditions:
        key = (c.loading, c.altitude, c.get("entry_speed"), c.get("trim"))
        if key not in key_of:
            v = entry_speeds(ctx, c.altitude, [c.get("entry_speed")])[c.get("entry_speed")]
            key_of[key] = len(entries)
            plain = c.with_(speed=v, speed_kind="EAS", speed_name=None, direction=None)
            entries.append(plain if c.get("trim") is None else plain.with_(trim=None))
            if c.get("trim") is not None:  # trimmed at the speed up to VMO/MMO (§25.255(a)), then mistrimmed
                ref = (c.loading, c.altitude, "reference", round(min(v, out_of_trim_speed(ctx, c.altitude or 0.0)), 6))
                if ref not in key_of:
                    key_of[ref] = len(entries)
                    entries.append(plain.with_(trim=None, speed=ref[3]))
                reference[key_of[key]] = (key_of[ref], c.get("trim"))
    batch = trimmed_batch(ctx, [e.with_() for e in entries])
    mistrimmed = hold_mistrims(ctx, batch, entries, reference, crit)
    rows, sim_conds, refused = batch.distribute(
        conditions,
        lambda c: key_of[(c.loading, c.altitude, c.get("entry_speed"), c.get("trim"))],
        [e.speed for e in entries],
    )
    findings = refusal_findings(refused, lambda c: [_check(c)])
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
    stall_n = _stall_line_load_factors(ctx, sim_conds, v_eas, crit)
    target = np.where(nose_up, np.minimum(n_lim, stall_n) - 1.0, 1.0 - crit.n_nose_down)
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
        hold_resolution=float(crit.hold_resolution),
    )
    amp, hold, reach, held_short = found.amplitude, found.hold, found.reach, found.held_short
    resp, sim, valid, t_max = found.response, found.sim, found.valid, found.t_max
    loads = airplane_loads(ctx)
    parts = response_load_parts(loads, sim, model, LOADED)
    hist = summed_loads(parts, valid)
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
        peak_nz = float(1.0 + resp[i] if nose_up[i] else 1.0 - resp[i])  # as the search read it, between samples
        reached, beyond = load_factor_reached(ctx, c, bool(nose_up[i]), peak_nz, converged, kind, crit)
        if nose_up[i] and stall_n[i] < n_lim:
            reached["stall_line_load_factor"] = round(float(stall_n[i]), 4)
            reached["load_factor_note"] = (
                f"the entry speed lies below the +C_N,max line's speed at n = {n_lim:g} (C_N,max at the entry "
                f"Mach number): the manoeuvre is flown to the stall line, n = {stall_n[i]:.3f}"
            )
        beyond_mach = beyond_mach_range(loads, condition_mach(c))
        if beyond_mach:
            findings += [
                set_aside_finding(
                    c,
                    _check(c),
                    beyond_mach,
                    env.peaks["horizontal_tail"][i],
                    stations,
                    peak_n_z=round(peak_nz, 4),
                    input=kind,
                ),
                set_aside_finding(
                    c,
                    _check(c) + ", wing",
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
                _check(c),
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
                **(mistrimmed.get(_mistrim_key(c), {}) if c.get("trim") is not None else {}),
                **reached,
            )
        )
        findings.append(
            wing_finding(
                ctx,
                c,
                _check(c),
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
        tail_split=parts["horizontal_tail"],
    )


def _stall_line_load_factors(ctx, conditions, v_eas, crit) -> np.ndarray:
    """The load factor of the positive stall line (½ρ₀V²S C_N,max(M)/W, the manoeuvring envelope's boundary below point
    A) at each condition's entry speed: where it lies below n₊ the checked manoeuvre's pull is bounded by it, as the
    balanced points are (§25.333(b): the envelope ends at the stall line)."""
    return np.array(
        [
            float(vn_envelope(ctx, c.mass, c.altitude or 0.0, crit.cn_over_cl).n_stall_pos(v))
            for c, v in zip(conditions, v_eas)
        ]
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


#: the criteria that define the checked manoeuvre's runs (shared by §25.427(b), which splits their tail loads)
CHECKED_RUN_CRITERIA = tuple(k for k in CHECKED_CRITERIA if k != "ultimate_factor")


def _check(c) -> str:
    if c.get("trim") is not None:
        return f"(a)(2) out-of-trim checked manoeuvre, {c.get('direction')}"
    return f"(c)(2) checked manoeuvre, {c.get('direction')}"


def hold_mistrims(ctx, batch, entries, reference, crit) -> dict:
    """Trim each out-of-trim entry of ``batch`` (``reference``: entry → (its reference entry, the mistrim's sense)) in
    1 g flight with the stabiliser held at its reference trim's setting moved by 3 s (``mistrim_seconds``) of the
    declared rate within the trim limits, the elevator solving (§25.255(a)(1)), in place of its own trim; an entry whose
    held trim does not converge, or whose reference did not trim, is refused (added to ``batch.failed``). Returns the
    finding details of each mistrim keyed by :func:`_mistrim_key`."""
    if not reference:
        return {}
    js = list(batch.model.control_names).index("stabilizer")
    pos, failed = {int(e): k for k, e in enumerate(batch.index)}, dict(batch.failed)
    todo, held, details = [], [], {}
    for e, (r, sense) in reference.items():
        if e not in pos:
            continue
        if r not in pos:
            failed[e] = f"no 1 g trim at the out-of-trim reference speed (VMO/MMO): {failed.get(r, '')}"
            continue
        stab = float(batch.u[pos[r], js])
        value, limited = mistrim(ctx, stab, sense, "clean", crit)
        todo.append(e)
        held.append(value)
        details[_mistrim_key(entries[e], sense)] = {
            "pitch_trim": mistrim_note(
                sense, entries[r].speed, value - stab, limited, "the elevator holds 1 g and makes the input"
            ),
            "stabilizer_deg": round(float(np.degrees(value)), 3),
        }
    throttle = batch.u[:, batch.model.throttle_slice].mean(axis=1)
    # level where the entry trimmed level; beyond the level-flight ceiling at the entry's own (full) throttle, the
    # flight path solved (the steady flight nearest to level, as the entry's trim)
    for level in (True, False):
        group = [k for k, e in enumerate(todo) if (batch.gamma[pos[e]] == 0.0) == level]
        if not group:
            continue
        conds = [batch.conditions[pos[todo[k]]] for k in group]
        stab = np.array([held[k] for k in group])
        if level:
            again = ctx.trim(conds, stabilizer=stab)
        else:
            again = ctx.trim(conds, stabilizer=stab, throttle=np.array([throttle[pos[todo[k]]] for k in group]))
        results, xs, us = list(again.results), again.x.copy(), again.u.copy()
        # a level entry whose mistrim (the elevator's trim drag) needs more than full thrust: the steady descent at
        # full thrust, the flight path solved and recorded in the condition
        short = [j for j, r in enumerate(results) if level and not r.converged and _needs_more_thrust(r)]
        if short:
            down = ctx.trim([conds[j] for j in short], stabilizer=stab[short], throttle=1.0)
            for jj, j in enumerate(short):
                if down.results[jj].converged and down.results[jj].gamma <= 0.0:
                    results[j], xs[j], us[j] = down.results[jj], down.x[jj], down.u[jj]
                    batch.gamma[pos[todo[group[j]]]] = down.results[jj].gamma
        for j, k in enumerate(group):
            e, r = todo[k], results[j]
            if r.converged and not r.limits_exceeded:
                batch.x[pos[e]], batch.u[pos[e]] = xs[j], us[j]
            else:
                msg = "; ".join(m.message for m in r.limits_exceeded) or "trim did not converge"
                failed[e] = f"no 1 g trim with the stabiliser mistrimmed (the elevator holding it): {msg}"
    batch.failed = sorted(failed.items())
    return details


def _needs_more_thrust(result) -> bool:
    """The trim ran out of thrust (a throttle exceedance at the full-throttle stop, not at idle)."""
    return any(m.control == "throttle" and m.limit > 0.0 for m in result.limits_exceeded)


def _mistrim_key(c, sense=None) -> tuple:
    """The key of an out-of-trim entry's details: its loading, altitude, entry speed and the mistrim's sense (the
    scheduled condition's own ``trim`` when ``sense`` is not given)."""
    return (c.loading, c.altitude, round(float(c.speed), 6), sense if sense is not None else c.get("trim"))


def checked_runs(ctx, conditions, crit) -> PitchManeuverRun:
    """:func:`checked_maneuver` memoised on the conditions and the criteria that define it (§25.331(c)(2) and
    §25.427(b), evaluated in one process, simulate once)."""
    key = ("checked_maneuver", tuple(conditions), tuple((k, str(crit[k])) for k in CHECKED_RUN_CRITERIA))
    return ctx.memo(key, lambda: checked_maneuver(ctx, conditions, crit))


# --------------------------------------------------------------------------- (c)(1) maximum displacement at VA

DISPLACEMENT_CRITERIA = {
    "displacement_ramp_time": Criterion(
        0.1,
        "s",
        "certkit assumption: 'suddenly' with no declared actuator rate",
        "(c)(1): time to reach the full deflection",
    ),
    "displacement_duration": Criterion(4.0, "s", "certkit numerical choice", "(c)(1): longest simulated time"),
    "displacement_time_step": Criterion(0.02, "s", "certkit numerical choice", "(c)(1): simulation step"),
    **SAFETY,
    **PILOT_EFFORT,
}
DISPLACEMENT_CONDITIONS = ConditionSpace(
    loading=CgCorners(),
    configurations=("clean",),
    altitudes=EnvelopeAltitudes(),
    note="At VA (EAS), capped at the Mach-limited VC at altitude.",
)


def maximum_displacement(ctx, conditions, crit) -> PitchManeuverRun:
    """Batch simulation of the (c)(1) sudden maximum nose-up pitch control at VA from level flight: the loads up to
    the first of the positive limit load factor and the tail load's maximum; findings, the envelope and the runs."""
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
    dt, ramp = float(crit.displacement_time_step), float(crit.displacement_ramp_time)
    sched = Step(0.0, step) if ramp <= 0 else Ramp(0.0, ramp, step)
    sim = simulate(
        batch.model,
        batch.x,
        batch.u,
        float(crit.displacement_duration),
        dt,
        inputs={"elevator": sched},
        stop=[Bound("n_z > limit", "n_z", upper=n_lim)],
    )
    loads = airplane_loads(ctx)
    parts = response_load_parts(loads, sim, batch.model, LOADED)
    hist = summed_loads(parts)
    # loads up to the first of: n_z above the limit (stop) or the tail load's maximum (root shear magnitude)
    root = np.abs(hist["horizontal_tail"][:, :, 0, 0])
    t_peak = sim.t[np.nanargmax(root, axis=0)]
    valid = sim.t[:, None] <= np.minimum(sim.stop_time, t_peak)[None, :] + 1e-9
    hist = {s: np.where(valid[:, :, None, None], h, np.nan) for s, h in hist.items()}
    unstalled = wing_before_stall(hist, batch.model, sim)
    stalled = np.zeros(batch.n, dtype=bool) if unstalled is None else (valid & ~unstalled).any(axis=0)
    fuelled = fuelled_wing(ctx, loads, sim, batch.model, hist["wing"], batch.conditions)
    env = fuelled_wing_envelope(
        LoadEnvelope.from_histories(loads, hist, sim.t, [_label(c) for c in batch.conditions], keys=batch.conditions),
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
    return PitchManeuverRun(
        findings,
        batch.conditions,
        sim,
        valid,
        envelope=env,
        loads=hist,
        stations=stations,
        tail_split=parts["horizontal_tail"],
    )


#: the criteria that define the (c)(1) runs (shared by §25.427(b), which splits their tail loads)
DISPLACEMENT_RUN_CRITERIA = tuple(k for k in DISPLACEMENT_CRITERIA if k != "ultimate_factor")


def displacement_runs(ctx, conditions, crit) -> PitchManeuverRun:
    """:func:`maximum_displacement` memoised on the conditions and the criteria that define it (§25.331(c)(1) and
    §25.427(b), evaluated in one process, simulate once)."""
    key = ("maximum_displacement", tuple(conditions), tuple((k, str(crit[k])) for k in DISPLACEMENT_RUN_CRITERIA))
    return ctx.memo(key, lambda: maximum_displacement(ctx, conditions, crit))

"""§25.351 Yaw maneuver conditions: sudden full rudder from unaccelerated flight, held to the overswing and the
steady sideslip, then returned to neutral; vertical-tail loads from the strip loads model at each phase's
critical instant, compared with the declared structural capability (§25.303, §25.305).

Text verified (docs/regulation-notes.md, Amdt. 25-91). Approximations: with ``control_forces.rudder`` declared the
rudder goes to the smaller of its stop ((a)(1), control system stops: the travel) and the deflection the 300/200 lbf
pedal force of (a)(2) holds from the trim at zero yaw (:func:`r25_331.force_limited_deflection`); without it the
rudder goes to its stop (travel); VMC is not declared in the baseline, so the lowest speed is 1.13 VSR
clean at the condition's weight (criterion); the roll is held wings level by the ailerons as an idealised
restraint (the deflection it needs is reported, it may exceed the aileron's design limit — spoilers are not
modelled); the airplane is symmetric, so one rudder direction is simulated; rigid airplane.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from certkit_rules.part25.support.loads_conditions import refusal_findings, trimmed_batch
from certkit_rules.part25.support.structural_checks import (
    SAFETY,
    beyond_mach_range,
    capability_finding,
    condition_mach,
    control_stops,
    entry_speeds,
    force_limited_deflection,
    set_aside_finding,
)

from certkit.engine.conditions import CgCorners, ConditionSpace, EnvelopeAltitudes
from certkit.engine.evidence.loads import allowables
from certkit.engine.evidence.yaw import yaw_evidence
from certkit.engine.registry import Criterion, Loads, SimulationRule, rule
from certkit.engine.results import LoadsRun
from certkit.models.loads.capability import declared_capabilities
from certkit.models.loads.model import airplane_loads
from certkit.models.loads.response import LoadEnvelope, response_loads
from certkit.models.loads.yaw import YAW_PHASES, simulate_yaw, yaw_phase_loads
from certkit.models.performance.stall import stall_speed_eas
from certkit.units import KN

REG = "14 CFR 25.351(a)(2) (verified, docs/regulation-notes.md §25.351)"
SPEEDS = ("low", "VA", "VC", "VD")
PHASES = (
    ("a", "sudden rudder"),
    ("b", "overswing sideslip"),
    ("c", "steady sideslip"),
    ("d", "rudder returned to neutral"),
)
SURFACE = "vertical_tail"
PEDAL_NOTE = (
    "no control-force model is declared (control_forces.rudder): the pedal-force limit of §25.351(a)(2) cannot "
    "reduce the deflection; the rudder stop (travel: §25.351(a)(1), control system stops) bounds it"
)
VMC_NOTE = "VMC is not declared: the lowest speed is 1.13 VSR clean at the condition's weight"


def pedal_force_limit(v, va, vc, crit) -> float:
    """Limit pilot pedal force (lbf) of §25.351(a)(2) at EAS v: 300 up to VA, 200 from VC, linear between."""
    if v <= va:
        return float(crit.pedal_force_low)
    if v >= vc:
        return float(crit.pedal_force_high)
    f = (v - va) / max(vc - va, 1e-9)
    return float(crit.pedal_force_low + f * (crit.pedal_force_high - crit.pedal_force_low))


@rule
class YawManeuver(SimulationRule):
    id = "25.351"
    produces = (Loads("vertical_tail"),)
    cost = 4  # relative evaluation time (orders work over --jobs processes)
    symbol = "yaw-maneuver"
    title = "Yaw manoeuvre: sudden rudder, overswing, steady sideslip, rudder returned"
    amendment = "25-91"
    requirement = """
        From unaccelerated flight at zero yaw, at speeds from VMC to VD: (a) the cockpit rudder control is
        suddenly displaced to the rudder deflection limited by the control system stops or by a limit pilot
        force of 300 lbf from VMC to VA and 200 lbf from VC/MC to VD/MD (linear between); (b) held while the
        airplane yaws to the overswing sideslip; (c) held at the static equilibrium sideslip; (d) returned
        suddenly to neutral from it. The vertical tail carries the loads (limit) and 1.5 × them (ultimate).
    """
    margin = """
        Per condition and phase: the smallest of (allowable limit load − |limit load|) and (allowable ultimate
        load − 1.5 × |limit load|) over the declared vertical-tail stations and quantities, the loads at the
        phase's critical instant (rudder fully applied; |β| peak; settled sideslip; peak after the return);
        without a declared structural capability the condition is not evaluated and reports its loads.
    """
    references = ("25.353", "25.397", "25.303", "25.305")
    requires = ("speeds.VA", "speeds.VC", "speeds.VD", "geometry.vertical_tail")
    criteria = {
        "pedal_force_low": Criterion(300.0, "lbf", REG, "limit pilot force from VMC to VA"),
        "pedal_force_high": Criterion(200.0, "lbf", REG, "limit pilot force from VC/MC to VD/MD (linear VA→VC)"),
        "lowest_speed_factor": Criterion(
            1.13, "", "certkit assumption: VMC not declared; 1.13 VSR clean", "lowest speed / VSR (clean, 1 g, CLmax)"
        ),
        "ramp_time": Criterion(
            0.2,
            "s",
            "certkit assumption: 'suddenly' with no declared actuator rate",
            "time to reach the rudder deflection (and to return it)",
        ),
        "settle_tolerance": Criterion(0.02, "", "certkit numerical choice", "sideslip settled: within this × |β|"),
        "settle_window": Criterion(4.0, "s", "certkit numerical choice", "time the sideslip stays within the band"),
        "max_time": Criterion(20.0, "s", "certkit numerical choice (Dutch roll ζ 0.06–0.14)", "longest hold"),
        "return_time": Criterion(3.0, "s", "certkit numerical choice", "time simulated after the return"),
        "time_step": Criterion(
            0.04, "s", "certkit numerical choice (0.02 s changes peak β by < 0.05 %)", "simulation step"
        ),
        **SAFETY,
    }
    conditions = ConditionSpace(
        loading=CgCorners(),
        configurations=("clean",),
        altitudes=EnvelopeAltitudes(2),
        extra=(("speed_point", SPEEDS),),
        note="1.13 VSR clean (VMC not declared), VA (≤ VC), VC and VD in EAS, Mach-limited at "
        "altitude; rudder to its negative stop (travel) (nose-right yaw) only: the airplane is "
        "symmetric, the other direction mirrors the loads.",
    )
    limitations = (
        "Pedal-force limit of (a)(2) applied with control_forces.rudder at the initial zero-yaw state (the "
        "deflection is then held as the sideslip builds); "
        + PEDAL_NOTE
        + "; "
        + VMC_NOTE
        + "; roll held wings level by the ailerons as an idealised restraint "
        "(deflection reported, not limited; spoilers not modelled); one rudder direction (symmetric airplane); "
        "rigid airplane, quasi-steady strip aerodynamics."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.351",
            "roll is held wings level by an idealised restraint (spoilers not modelled); one rudder direction"
            " (symmetric airplane); rigid airplane",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return yaw_maneuvers(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        if self.run is None or not self.run.simulated:
            return []
        return yaw_evidence(self.run, allowables(ctx, crit.ultimate_factor))


def yaw_speed(ctx, cond, crit) -> float:
    name = cond.get("speed_point")
    if name == "low":
        clmax = ctx.aircraft.configurations["clean"].CLmax
        return float(crit.lowest_speed_factor * stall_speed_eas(cond.mass, ctx.aircraft.reference.area, clmax))
    return entry_speeds(ctx, cond.altitude, [name])[name]


@dataclass
class YawRun(LoadsRun):
    """The yaw manoeuvres: the held and returned simulations (``yaw``:
    :class:`certkit.models.loads.yaw.YawRuns`), the fin's loads along each ((n_t, n, 3, S)) and the rudder's index
    among the controls."""

    yaw: object = None
    held_loads: object = None
    returned_loads: object = None
    rudder_index: int = -1


def yaw_maneuvers(ctx, conditions, crit) -> YawRun:
    conds = [c.with_(speed=yaw_speed(ctx, c, crit), speed_kind="EAS") for c in conditions]
    batch = trimmed_batch(ctx, conds)
    findings = refusal_findings(batch.refusals(conds), lambda c: [f"({p}) {name}" for p, name in PHASES])
    if not batch.n:
        return YawRun(findings, reason="no condition could be trimmed (see the findings)")
    lim = control_stops(ctx, "rudder")
    va = ctx.design_speed_eas_at("VA", 0.0)
    vc = ctx.design_speed_eas_at("VC", 0.0)
    pedal_limit = np.array([pedal_force_limit(c.speed, va, vc, crit) for c in batch.conditions])
    target, force_limited = force_limited_deflection(
        ctx, "rudder", batch.conditions, batch.control("rudder"), lim[0], pedal_limit
    )
    amplitude = target - batch.control("rudder")
    dt = float(crit.time_step)
    run = simulate_yaw(
        batch.model,
        batch.x,
        batch.u,
        amplitude,
        dt=dt,
        ramp=float(crit.ramp_time),
        t_max=float(crit.max_time),
        window=float(crit.settle_window),
        tolerance=float(crit.settle_tolerance),
        return_time=float(crit.return_time),
        aileron_limits=(-np.pi, np.pi),
    )
    loads = airplane_loads(ctx)
    held = response_loads(loads, run.held, batch.model, (SURFACE,))[SURFACE]
    back = response_loads(loads, run.returned, batch.model, (SURFACE,))[SURFACE]
    t = run.held.t
    phase_peaks, phase_times = yaw_phase_loads(run, held, back)
    labels = [c.label() for c in batch.conditions]
    parts, peaks = [], {}
    for (p, name), phase in zip(PHASES, YAW_PHASES):
        peaks[p] = phase_peaks[phase]
        parts.append(
            LoadEnvelope(
                {SURFACE: loads[SURFACE].station_names},
                {SURFACE: peaks[p]},
                {SURFACE: phase_times[phase]},
                [f"{lab} — ({p}) {name}" for lab in labels],
            )
        )
    env = LoadEnvelope.merge(parts)
    stations = loads[SURFACE].station_names
    caps = declared_capabilities(ctx, SURFACE)
    beta, jr = run.held["beta"], batch.model.control_index("rudder")
    ja = batch.model.control_index("aileron")
    aileron_peak = np.nanmax(
        np.abs(np.concatenate([run.held.controls[:, :, ja], run.returned.controls[:, :, ja]])), axis=0
    )
    k_over = np.minimum(np.searchsorted(t, run.t_overswing - 1e-9), len(t) - 1)
    k_end = np.minimum(np.searchsorted(t, run.t_steady - 1e-9), len(t) - 1)
    for i, c in enumerate(batch.conditions):
        common = dict(
            V_kn_EAS=round(float(c.speed / KN), 1),
            rudder_deg=round(float(np.degrees(amplitude[i] + batch.u[i, jr])), 2),
            pedal_force_limit_lbf=round(float(pedal_limit[i]), 1),
            pilot_effort=PEDAL_NOTE
            if force_limited is None
            else (
                "rudder limited by the pedal force (control_forces.rudder)"
                if force_limited[i]
                else "rudder at its stop (travel, control system stops) below the pedal-force limit"
            ),
            overswing_beta_deg=round(float(np.degrees(beta[k_over[i], i])), 3),
            overswing_time_s=round(float(run.t_overswing[i]), 2),
            steady_beta_deg=round(float(np.degrees(beta[k_end[i], i])), 3),
            steady_time_s=round(float(run.t_steady[i]), 2),
            settled=bool(run.settled[i]),
            steady_beta_band_deg=round(float(np.degrees(run.beta_band[i])), 3),
            roll_hold_aileron_peak_deg=round(float(np.degrees(aileron_peak[i])), 1),
        )
        if c.get("speed_point") == "low":
            common["lowest_speed"] = VMC_NOTE
        beyond_mach = beyond_mach_range(loads, condition_mach(c))
        for p, name in PHASES:
            findings.append(
                set_aside_finding(c, f"({p}) {name}", beyond_mach, peaks[p][i], stations, **common)
                if beyond_mach
                else capability_finding(
                    c, f"({p}) {name}", SURFACE, peaks[p][i], stations, caps, crit.ultimate_factor, **common
                )
            )
    return YawRun(
        findings,
        batch.conditions,
        failed=[(conds[i].label(), r) for i, r in batch.failed],
        envelope=env,
        yaw=run,
        held_loads=held,
        returned_loads=back,
        rudder_index=jr,
    )

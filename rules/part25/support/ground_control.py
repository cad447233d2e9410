"""The §25.149(e) minimum control speed on the ground VMCG as the regulation's conditions define it, shared by §25.149
(which reports it) and §25.107 (VEF ≥ VMCG) and the simulated takeoff (regulation content, no rule here).

§25.149(e): VMCG is the calibrated airspeed on the takeoff run at which, when the critical engine is suddenly made
inoperative, control can be kept with the rudder alone (no nose-wheel steering), the lateral control keeping the
wings level, and the path from the failure to the recovery to a direction parallel to the centreline deviates no
more than 30 ft laterally from the centreline; in each takeoff configuration, maximum takeoff thrust, the most
unfavourable CG and weight, the airplane trimmed for takeoff. The procedure is
:func:`certkit.models.dynamics.ground_control.ground_minimum_control_speed`: the critical engine cut with the engine's
spool-down (``propulsion.failure_decay_time``), the castering nose wheel, the stabiliser (if any) at the takeoff trim
of V2, the pilot holding the rudder for the reaction time of the criteria after the failure, then moving it at the
declared ``takeoff_pilot.rudder_rate`` on the heading and centreline; over every corner of the weight–CG envelope.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
from certkit_rules.part25.support.structural_checks import force_limited_deflection
from certkit_rules.part25.support.thrust_trims import critical_engine, takeoff_trim

from certkit.atmosphere import RHO0, convert_speed
from certkit.engine.conditions import Altitudes, CgCorners, ConditionSpace
from certkit.engine.registry import Criterion
from certkit.engine.results import Condition
from certkit.engine.scheduler import criteria_for
from certkit.models.control_force import control_force_model
from certkit.models.dynamics.ground_control import ground_minimum_control_speed
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN, LBF

VMCG_RULE_ID = "25.149"
SOURCE = "14 CFR 25.149(e) (Amdt. 25-108; verified, docs/regulation-notes.md)"
VMCG_CRITERIA = {
    "vmcg_deviation_max_ft": Criterion(
        30.0,
        "ft",
        SOURCE,
        "largest lateral deviation from the centreline between "
        "the engine failure and the recovery to a parallel direction",
    ),
    "vmcg_reaction_time_s": Criterion(
        1.0,
        "s",
        "AC 25-7D §25.149 VMCG test technique: the engine is cut without "
        "warning and the pilot recovers with normal piloting skill, no anticipation; "
        "1 s from the failure to the first rudder input, the recognition interval of "
        "§25.107(a)(2) practice (the AC's own wording not retrieved: unverified)",
        "time from the engine cut to the pilot's first rudder input",
    ),
    "vmcg_departure_factor": Criterion(
        3.0,
        "",
        "project choice: a run three times the bound off the centreline is "
        "beyond it and ends there (the search needs only which side of the bound a "
        "failure speed lies near VMCG; saves a third of the simulated time)",
        "deviation, in multiples of the bound, at which an engine-cut run ends",
    ),
    "vmcg_rudder_force_lbf": Criterion(
        150.0,
        "lbf",
        SOURCE,
        "rudder pedal force that limits the rudder in the VMCG runs (with control_forces.rudder)",
    ),
    "vmcg_low_kn": Criterion(
        60.0,
        "kn",
        "project choice: the search starts at 60 KCAS (below any transport's VMCG)",
        "lowest failure speed searched (CAS)",
    ),
}
#: what the VMCG procedure needs from the aircraft file
VMCG_REQUIRES = (
    "speeds.VR",
    "speeds.V2",
    "geometry.landing_gear",
    "geometry.vertical_tail.controls.rudder",
    "cg_envelope",
)
VMCG_CONDITIONS = ConditionSpace(
    loading=CgCorners(),
    configurations=("takeoff",),
    altitudes=Altitudes((0.0,)),
    note="Sea level ISA, maximum takeoff thrust, the critical engine cut; every corner of "
    "the weight–CG envelope (the most unfavourable weight and CG).",
)


@dataclass
class Vmcg:
    speed_cas: np.ndarray  # (n,) m/s CAS per condition (nan: no run decided, every one lifted off still swinging)
    below: np.ndarray  # (n,) within the bound at the lowest speed searched: VMCG no higher
    above: np.ndarray  # (n,) beyond the bound at the highest speed searched (VR): no VMCG on the runway
    search: object  # GroundControlSpeed
    engine: str
    high_cas: float  # m/s CAS, the highest failure speed searched (VR)
    basis: dict


def vmcg_runs(ctx, conditions, crit) -> Vmcg:
    """The memoised VMCG search of ``conditions`` with the criteria ``crit`` (module docstring)."""

    def compute():
        ac = ctx.aircraft
        sp = ac.speeds
        pilot = ac.takeoff_pilot
        tas = lambda v: float(convert_speed(v, "CAS", "TAS", 0.0))  # noqa: E731
        vr_cas = float(convert_speed(sp.VR.value, sp.VR.kind, "CAS", 0.0))
        _, settings = takeoff_trim(ctx, conditions)
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        model = flight_model(ac, ctx.aero("takeoff").model, loadings, ground=ground_model(ac, nose_wheel="castering"))
        engine = critical_engine(ctx)
        n = len(conditions)
        travel = control_limits(ac, design=False)
        travel["rudder"], rudder_limit = _force_limited_rudder(
            ctx, travel["rudder"], vr_cas, crit.vmcg_rudder_force_lbf
        )
        search = ground_minimum_control_speed(
            model,
            engine,
            tas(crit.vmcg_low_kn * KN),
            tas(vr_cas),
            crit.vmcg_deviation_max_ft * FT,
            crit.vmcg_reaction_time_s,
            pilot.rudder_rate,
            decay_time=ac.propulsion.failure_decay_time,
            lateral_limits=travel,
            elevator_limits=travel["elevator"],
            settings=settings,
            departure=crit.vmcg_departure_factor * crit.vmcg_deviation_max_ft * FT,
        )
        cas = np.array([float(convert_speed(v, "TAS", "CAS", 0.0)) if np.isfinite(v) else np.nan for v in search.speed])
        basis = {
            "engine": engine,
            "nose_wheel": "castering (no nose-wheel steering)",
            "reaction_time_s": crit.vmcg_reaction_time_s,
            "rudder_rate_deg_s": round(float(np.degrees(pilot.rudder_rate)), 1),
            "spool_down": (
                f"τ = {ac.propulsion.failure_decay_time:g} s"
                if ac.propulsion.failure_decay_time
                else "windmilling at once"
            ),
            "rudder_limit": rudder_limit,
            "held_settings": sorted(settings) or None,
            "conditions": n,
        }
        return Vmcg(cas, search.below, search.above, search, engine, vr_cas, basis)

    key = ("vmcg", tuple((c.mass, c.x_cg) for c in conditions), tuple(float(getattr(crit, k)) for k in VMCG_CRITERIA))
    return ctx.memo(key, compute)


def _force_limited_rudder(ctx, stops, vr_cas: float, force_lbf: float):
    """The rudder travel of the VMCG runs, "as limited by 150 pounds of force" (§25.149(e)): each stop, or the
    deflection the pedal force ``force_lbf`` holds from the neutral (rudder trim neutral), whichever is smaller
    (:func:`~certkit_rules.part25.support.structural_checks.force_limited_deflection`); a q-feel or hinge-moment
    force taken at VR, the highest speed of the search (where a given force holds the least rudder), at zero
    sideslip. Returns ((low, high) rad, how the limit was set, for the report)."""
    at_vr = [Condition(speed=vr_cas, speed_kind="CAS", altitude=0.0)]
    bounds = [force_limited_deflection(ctx, "rudder", at_vr, [0.0], stop, force_lbf) for stop in stops]
    limits = (float(bounds[0][0][0]), float(bounds[1][0][0]))
    if bounds[0][1] is None:
        return (
            limits,
            f"the rudder's stops; the {force_lbf:g} lbf pedal force is not modelled (no control_forces.rudder)",
        )
    if not any(bool(limited[0]) for _, limited in bounds):
        model = control_force_model(ctx.aircraft, "rudder")
        qbar = 0.5 * RHO0 * float(convert_speed(vr_cas, "CAS", "EAS", 0.0)) ** 2
        at_stop = max(abs(float(model.force(qbar, 0.0, stop))) / LBF for stop in stops)
        return limits, f"the rudder's stops (pedal force there {at_stop:.0f} lbf < {force_lbf:g} lbf)"
    return limits, f"{force_lbf:g} lbf pedal force: rudder {np.degrees(limits[0]):.1f}° / {np.degrees(limits[1]):.1f}°"


def computed_vmcg(ctx):
    """(VMCG m/s CAS, the condition's loading name, the Vmcg) as §25.149 computes it with its criteria (and the file's
    overrides): the highest over its conditions; (None, None, None) when the inputs are missing."""
    if ctx.missing(VMCG_REQUIRES):
        return None, None, None
    crit, _ = criteria_for(SimpleNamespace(id=VMCG_RULE_ID, criteria=VMCG_CRITERIA), ctx)
    conds = VMCG_CONDITIONS.expand(ctx.aircraft)
    res = vmcg_runs(ctx, conds, crit)
    speeds = np.where(res.above, np.inf, res.speed_cas)
    if not np.isfinite(np.nan_to_num(speeds, nan=-np.inf)).any() and not res.above.any():
        return None, None, res
    k = int(np.nanargmax(np.where(np.isnan(speeds), -np.inf, speeds)))
    return float(speeds[k]), conds[k].loading, res


__all__ = ["VMCG_RULE_ID", "VMCG_CRITERIA", "VMCG_REQUIRES", "VMCG_CONDITIONS", "Vmcg", "vmcg_runs", "computed_vmcg"]

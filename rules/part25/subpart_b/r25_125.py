"""§25.125 Landing — simulated stabilised −3° approach at VREF, flare and touchdown.

What is simulated: the landing configuration at MLW and the forward, reference and aft CG, ISA
sea-level runway, trimmed on a −3° glide path at VREF 150 ft above the runway (CG height), flown
by the TECS pilot model (certkit.models.dynamics.controllers.TECSApproach: constant airspeed on
the path down to the flare height, then the exponential flare ḣ = −(h + h_aim)/τ with τ from the
approach sink rate and the flare height, throttle to idle at the flare height) until the first
gear contact (certkit.models.dynamics.procedures.approach_and_landing).

Criteria (docs/regulation-notes.md carries § 25.125(b)(2): "A stabilized approach, with a
calibrated airspeed of not less than VREF, must be maintained down to the 50-foot height"):
* rate of descent at touchdown ≤ 6 ft/s. § 25.125 itself is qualitative here (the landing must be
  made without excessive vertical acceleration — § 25.125(b)(4) wording from memory, unverified);
  the number is the limit descent velocity of § 25.473(a)(2)(ii), 6 ft/s at the design takeoff
  weight (with 10 ft/s at the design landing weight, (a)(2)(i); § 25.473 text from memory,
  unverified, not in docs/regulation-notes.md). 6 ft/s is the conservative choice: a demonstrated
  landing is expected to touch down well inside the gear's limit sink rates. Overridable in the
  aircraft file (``criteria: "25.125": {values: {touchdown_sink_rate: …}}``) with a justification.
* the most nose-up elevator of the approach and flare against the elevator's design limit.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.minimum_control import computed_vmcl
from certkit_rules.part25.support.reference_speeds import declared_cas, ratio_check, reference_stall_speed

from certkit.atmosphere import convert_speed
from certkit.engine.conditions import ConditionSpace, DesignWeight
from certkit.engine.evidence import Axis, Limit
from certkit.engine.evidence.performance import time_histories
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Evidence, Finding
from certkit.models.dynamics.procedures import approach_and_landing
from certkit.models.flight import control_limits, flight_model, ground_model
from certkit.units import FT, KN

START_HEIGHT = 150 * FT  # m, CG height above the runway at the start of the simulated approach


def _landing(ctx, conditions, crit):
    def compute():
        ac = ctx.aircraft
        vref = ac.speeds.VREF
        on_path = [
            c.with_(altitude=START_HEIGHT, speed=vref.value, speed_kind=vref.kind, speed_name="VREF")
            for c in conditions
        ]
        trims = ctx.trim(on_path, gamma=np.radians(crit.glide_slope))
        loadings = [ctx.loading(c.mass, c.x_cg, c.loading or "") for c in conditions]
        model = flight_model(ac, ctx.aero("landing").model, loadings, ground=ground_model(ac))
        travel = control_limits(ac, design=False)
        run = approach_and_landing(
            model,
            trims.x,
            trims.u,
            glide=np.radians(crit.glide_slope),
            elevator_limits=travel["elevator"],
            lateral_limits=travel,
        )
        return trims, run

    key = ("25.125 landing", tuple((c.mass, c.x_cg) for c in conditions), crit.glide_slope)
    return ctx.memo(key, compute)


def _elevator_design_min(ac) -> float:
    el = ac.geometry.horizontal_tail.controls["elevator"]
    return float(np.degrees((el.design_limits or el.travel).min))


@rule
class LandingTouchdown(Rule):
    id = "25.125"
    cost = 3  # relative evaluation time (orders work over --jobs processes)
    symbol = "landing-approach-and-touchdown"
    title = "Landing: stabilised approach at VREF, flare and touchdown (simulated)"
    amendment = "25-121"
    implementation = "partial"
    requirement = """
        A stabilised approach at not less than VREF is maintained down to 50 ft, and the landing is made
        without excessive vertical acceleration. certkit flies a −3° approach at VREF in the landing
        configuration at MLW and flares to touchdown with the throttle at idle from the flare height, and
        checks the rate of descent at touchdown and that the elevator stays within its design limit.
        VREF may not be less than 1.23 VSR0 ((b)(2)(i)(A)) nor VMCL ((b)(2)(i)(B)).
    """
    margin = """
        Rate of descent: the criterion (6 ft/s) minus the rate of descent at touchdown (ft/s; ≥ 0 complies).
        Elevator: most nose-up elevator of the approach and flare minus its design limit (deg; ≥ 0 complies).
        VREF: VREF/VSR0 − 1.23 (VSR0 of the landing configuration at the condition's weight, §25.103); VREF/VMCL − 1
        (VMCL computed as §25.149(f) does, the landing configuration at MLW and the aft CG).
    """
    limitations = """
        The landing distance (§ 25.125(a)), the VREF minimum of (b)(2)(i)(C) (§ 25.143(h)) and icing are not
        evaluated here; VMCL is the static one of §25.149's search; ground effect on the wing's lift and induced
        drag (image-vortex factor, certkit/models/aero/ground_effect.py) and on the downwash at the tail (the wing's
        vortices and their image, span load solved with the image, certkit/models/aero/tail_ground_effect.py; within
        0.02 of AVL's ground plane), which takes 2.5–6° more nose-up elevator in the baseline's flare; not modelled:
        the wake's displacement near the ground, the flaps' own span load, the tail's own ground effect, the lower
        stall angle in ground effect; the approach starts from a free-air trim at 150 ft (h/b ≈ 0.7, already
        slightly inside both ground effects); the flare is the TECS pilot model's (flare height 15 m, aim point 1 m
        below the runway); the 6 ft/s criterion is from § 25.473 (text from memory).
    """
    references = ("25.473", "25.143", "25.149")
    requires = ("speeds.VREF", "mass.MLW", "geometry.landing_gear", "geometry.horizontal_tail.controls.elevator")
    criteria = {
        "touchdown_sink_rate": Criterion(
            6.0,
            "ft/s",
            "14 CFR 25.473(a)(2)(ii) limit descent velocity at the design takeoff weight (text from memory, "
            "unverified); quantifies 25.125's 'without excessive vertical acceleration'",
            "maximum rate of descent at touchdown",
        ),
        "vref_over_vsr0": Criterion(
            1.23, "", "14 CFR 25.125(b)(2)(i)(A)", "VREF/VSR0, VSR0 of the landing configuration"
        ),
        "vref_over_vmcl": Criterion(
            1.0, "", "14 CFR 25.125(b)(2)(i)(B)", "VREF/VMCL, VMCL of the landing configuration (§25.149(f))"
        ),
        "glide_slope": Criterion(
            -3.0,
            "deg",
            "14 CFR 25.125 / AC 25-7 (the standard stabilised approach path; the -3 deg of 25.143(h)'s landing row)",
            "flight-path angle of the stabilised approach",
        ),
    }
    conditions = ConditionSpace(
        loading=DesignWeight("MLW", ("forward", "reference", "aft")),
        configurations=("landing",),
        note="ISA, sea-level runway, −3° approach at VREF from 150 ft, flare to touchdown.",
    )

    unevaluated = (
        ("25.125(a)", "the landing distance from 50 ft to a full stop (non-icing and icing) is not computed"),
        (
            "25.125(b)(2)(i)(C)",
            "the §25.143(h) manoeuvring capability at VREF is not judged here (§25.143(h) flies its turns)",
        ),
        ("25.125(b)(2)(ii)", "the VREF minima with the landing ice accretion are not checked"),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        trims, run = _landing(ctx, conditions, crit)
        lo = _elevator_design_min(ac)
        vref_kn = float(convert_speed(ac.speeds.VREF.value, ac.speeds.VREF.kind, "CAS", 0.0)) / KN
        vmcl = computed_vmcl(ctx, "landing")
        out = []
        for i, cond in enumerate(conditions):
            vmcl_check = "(b)(2)(i)(B) VREF ≥ VMCL"
            if vmcl is None:
                out.append(
                    Finding.not_evaluated(
                        cond.with_(altitude=0.0),
                        vmcl_check,
                        "VMCL (§25.149(f)) is not determined: a one-engine-inoperative trim of its search failed above "
                        "the stall, or the landing configuration's inputs are missing",
                    )
                )
            else:
                out.append(
                    ratio_check(
                        cond.with_(altitude=0.0),
                        vmcl_check,
                        {"VREF": declared_cas(ctx, "VREF"), "VMCL": vmcl[0]},
                        "VREF",
                        "VMCL",
                        crit.vref_over_vmcl,
                        basis=f"VMCL computed as §25.149(f) does (aft CG at MLW, go-around thrust, bank ≤ 5°), "
                        f"limited by {vmcl[1]}",
                    )
                )
            vsr0, source = reference_stall_speed(ctx, "landing", cond.mass)
            out.append(
                ratio_check(
                    cond.with_(altitude=0.0),
                    "(b)(2)(i)(A) VREF ≥ 1.23 VSR0",
                    {"VREF": declared_cas(ctx, "VREF"), "VSR0": vsr0},
                    "VREF",
                    "VSR0",
                    crit.vref_over_vsr0,
                    basis=source,
                )
            )
            c0 = cond.with_(
                altitude=0.0,
                speed=ac.speeds.VREF.value,
                speed_kind=ac.speeds.VREF.kind,
                speed_name="VREF",
                thrust="idle from the flare",
            )
            tr = trims.results[i]
            if not tr.converged:
                out.append(
                    Finding.not_evaluated(
                        c0, "touchdown rate of descent", f"no trim on the approach path: {tr.summary()}"
                    )
                )
                continue
            reason = "; ".join(e.message for e in tr.limits_exceeded)
            details = dict(
                approach_sink_fps=round(float(run.approach_sink[i]) / FT, 3),
                flare_tau_s=round(float(run.tau[i]), 3),
                trim_elevator_deg=round(float(np.degrees(tr.controls["elevator"])), 2),
                vref_kn=vref_kn,
            )
            out.append(
                Finding.compare(
                    c0,
                    "elevator during the approach and flare within its design limit",
                    np.degrees(run.elevator_min[i]),
                    lo,
                    at_least=True,
                    unit="deg",
                    reason=f"the approach trim already {reason}" if reason else "",
                    **details,
                )
            )
            if not run.touched_down[i]:
                out.append(
                    Finding.not_evaluated(
                        c0,
                        "touchdown rate of descent",
                        "the simulated approach did not reach the runway within the run",
                    )
                )
                continue
            touchdown_kn = float(convert_speed(run.speed[i], "TAS", "CAS", 0.0)) / KN
            out.append(
                Finding.compare(
                    c0,
                    "touchdown rate of descent",
                    run.sink_rate[i] / FT,
                    crit.touchdown_sink_rate,
                    at_least=False,
                    unit="ft/s",
                    touchdown_speed_kn=round(touchdown_kn, 2),
                    **details,
                )
            )
        return out

    def evidence(self, ctx, findings, crit):
        conds = self.conditions.expand(ctx.aircraft)
        sinks = [f for f in findings if f.check == "touchdown rate of descent" and f.margin is not None]
        if not sinks:
            return []
        trims, run = _landing(ctx, conds, crit)
        worst = min(sinks, key=lambda f: f.margin)
        k = next(i for i, c in enumerate(conds) if c.x_cg == worst.condition.x_cg)
        sim = run.sim
        hdot = np.gradient(sim["h"], sim.t, axis=0) if sim.t.size > 1 else np.zeros_like(sim["h"])
        je = sim.control_names.index("elevator")
        chart = time_histories(
            sim.t,
            [
                (Axis("true airspeed V", "m/s"), sim["V"], [], []),
                (Axis("CG height", "m"), sim["h"], [], []),
                (
                    Axis("rate of descent", "m/s", "ft/s"),
                    -hdot,
                    [Limit(crit.touchdown_sink_rate * FT, f"{crit.touchdown_sink_rate:g} ft/s")],
                    [],
                ),
                (
                    Axis("elevator", "rad"),
                    sim.controls[:, :, je],
                    [Limit(np.radians(_elevator_design_min(ctx.aircraft)), "design limit", kind="allowable")],
                    [],
                ),
            ],
            [c.loading for c in conds],
            critical=k,
            ends=sim.stop_time,
            title="§25.125 approach, flare and touchdown",
        )
        return [
            Evidence(
                "Approach and landing time histories",
                chart,
                f"Critical condition {conds[k].loading} (touchdown {worst.value:.2f} ft/s) and its neighbours; "
                "each line ends at its touchdown.",
            )
        ]

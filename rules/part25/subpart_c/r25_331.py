"""§25.331(c) Pitch maneuver conditions: (c)(1) maximum pitch control displacement at VA and (c)(2)
the checked manoeuvre between VA and VD, as rigid-airplane batch simulations with the strip loads
model of the horizontal tail (:mod:`certkit.models.loads`).

The regulation text of (c)(2) is only partly verified (docs/regulation-notes.md): t₂ = t₁ + Δt,
t_max = t₂ + π/ω and Δt ≤ 5 s are verified; the sinusoid δ₁ sin ωt, t_max = 3π/(2ω) without hold and
ω ≥ πV/(2VA) are from memory — they are criteria here, overridable in the aircraft file.

Each condition's horizontal-tail limit loads are compared with the capabilities declared in the aircraft
file's ``structure.horizontal_tail`` (limit, and 1.5 × limit against ultimate, §25.303/§25.305); without
one the condition reports its loads and is not evaluated with the reason "no structural capability declared". The
structural checks it shares with §§25.341, 25.349 and 25.351 are in
:mod:`certkit_rules.part25.support.structural_checks`.

(c)(2) reports the load factor each manoeuvre reaches and the §25.337 limit at its speed (n₊ nose up; nose
down n₋ = −1.0 up to VC, linearly to 0 at VD) in the details: the input is scaled to reach that limit, so being
on it is the manoeuvre's construction, not a verdict. Only a peak beyond the limit (+ the search tolerance) is a
finding: "fails" after a converged search, not evaluated when the search did not converge (its loads are
conservative). In (c)(1) the load factor may exceed the limit (loads after that need not be considered).
"""

from __future__ import annotations

from certkit_rules.part25.support.pitch_runs import (
    CHECKED_CONDITIONS,
    CHECKED_CRITERIA,
    DISPLACEMENT_CONDITIONS,
    DISPLACEMENT_CRITERIA,
    PRODUCED,
    PitchManeuverRun,
    checked_runs,
    displacement_runs,
)

from certkit.engine.evidence.loads import allowables, envelope_evidence, maneuver_evidence
from certkit.engine.registry import SimulationRule, rule


@rule
class CheckedPitchManeuver(SimulationRule):
    id = "25.331(c)(2)"
    produces = PRODUCED
    cost = 5  # relative evaluation time (orders work over --jobs processes)
    run_with = "discrete-gust"  # §25.427(b) splits these runs' tail loads: one process simulates them once
    symbol = "checked-pitch-maneuver"
    title = "Checked pitch manoeuvre between VA and VD"
    amendment = "25-141"
    requirement = """
        From unaccelerated flight at speeds from VA to VD the cockpit pitch control is moved as
        δ(t) = δ₁ sin ωt for 0 ≤ t ≤ t_max = 3π/(2ω), ω the undamped short-period frequency but not less
        than πV/(2VA); δ₁ such that the positive limit load factor (nose up) or 0 g (nose down) is reached
        but not exceeded — nose up, where the entry speed lies below the +C_N,max line's speed at n₊, the
        stall line's load factor at that speed, where the manoeuvring envelope ends (§25.333(b); as the
        balanced points of §25.331(b)). Where the sinusoid at the available deflection does not reach it, the peak is
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
    criteria = CHECKED_CRITERIA
    conditions = CHECKED_CONDITIONS
    limitations = (
        "Rigid airplane, quasi-steady strip aerodynamics; the pilot effort limits the deflection only with "
        "control_forces.elevator (force at the trim's angle of attack, at the instant of the input), else the "
        "elevator goes to its stop (travel); the structural comparison needs capabilities declared in the aircraft "
        "file's `structure` section. Out of trim (§25.331(a)(2), with a declared stabiliser trim rate): from VC and VD "
        "(the §25.255 speeds; VA lies below the cruise speeds §25.255 trims at), each direction from the mistrim in "
        "its own sense — the 1 g entry trimmed with the stabiliser of the trim at the entry speed (at most VMO/MMO) "
        "moved by 3 s of the rate within the trim limits and held, the elevator holding 1 g and making the input; the "
        "opposite pairings leave the elevator less travel toward the manoeuvre's stop and are not flown. The pull is "
        "bounded by C_N,max (the clean CLmax, against Mach where configurations.clean.CLmax_by_mach declares it; "
        "without it the low-speed value holds at every Mach number), not by a buffet-onset boundary."
    )
    implementation = "partial"

    unevaluated = (
        (
            "25.331(c)(2)",
            "fuselage and vertical-tail loads of the checked manoeuvre are not reported (wing and horizontal-"
            "tail loads only)",
        ),
    )

    def simulate(self, ctx, conditions, crit):
        return checked_runs(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return pitch_evidence(self.run, ctx, crit, "checked manoeuvre")


def pitch_evidence(run: PitchManeuverRun | None, ctx, crit, what: str) -> list:
    """Evidence of a pitch manoeuvre run: the tail's critical time histories, envelope and table, the wing's table,
    each against the declared allowables."""
    if run is None or not run.simulated:
        return []
    allow = allowables(ctx, crit.ultimate_factor)
    return maneuver_evidence(run, "horizontal_tail", "elevator", allow=allow) + envelope_evidence(
        run.envelope, ("wing",), what, plot=False, allow=allow
    )


@rule
class MaximumPitchControlDisplacement(SimulationRule):
    id = "25.331(c)(1)"
    produces = PRODUCED
    cost = 4  # relative evaluation time (orders work over --jobs processes)
    run_with = "discrete-gust"  # its runs are shared with §25.427(b), which splits their tail loads
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
    criteria = DISPLACEMENT_CRITERIA
    conditions = DISPLACEMENT_CONDITIONS
    limitations = (
        "Rigid airplane, quasi-steady strip aerodynamics; the pilot effort limits the deflection only with "
        "control_forces.elevator (force at the trim's angle of attack, at the instant of the input), else the "
        "elevator goes to its stop (travel); the structural comparison needs capabilities declared in the aircraft "
        "file's `structure` section."
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
        return displacement_runs(ctx, conditions, crit)

    def evidence(self, ctx, findings, crit):
        return pitch_evidence(self.run, ctx, crit, "maximum pitch control displacement")

"""§25.143(h) Controllability and manoeuvrability: manoeuvring capability in coordinated turns.

Every row of the paragraph's table (V2 30°, V2 + XX 40°, VFTO 40° en route, VREF 40° landing) is trimmed as a steady
coordinated turn by :mod:`certkit_rules.part25.support.maneuvering` (the table, the thrusts and the trims; shared
with §25.107(g)(2), which asks that VFTO give the en-route row's capability). The elevator, aileron and rudder of
each trim are reported against their design limits, the lift coefficient against the stall-warning onset.
"""

from __future__ import annotations

from certkit_rules.part25.support.maneuvering import (
    CASES,
    MANEUVERING_CRITERIA,
    case_spec,
    turn_findings,
)

from certkit.engine.conditions import ConditionSpace
from certkit.engine.evidence.performance import margins_evidence
from certkit.engine.registry import ControlCase, ControlResponses, Rule, rule

#: each case's control deflections as design responses (``control.25.143(h).<name>.<control>``), named after the
#: table's row: configuration, engines, speed and bank
CASE_RESPONSES = {
    "takeoff V2": "takeoff OEI V2 30deg",
    "takeoff V2+XX": "takeoff AEO V2+XX 40deg",
    "en route VFTO": "en route OEI VFTO 40deg",
    "landing VREF": "landing AEO VREF 40deg",
}


@rule
class ManeuveringCapability(Rule):
    id = "25.143(h)"
    offers = (ControlResponses(tuple(ControlCase(name, f"(h) {case} ") for case, name in CASE_RESPONSES.items())),)
    cost = 2  # relative evaluation time (orders work over --jobs processes)
    run_with = "coordinated turns"  # §25.107(g)(2) judges the en-route case's turns, memoised in one process
    symbol = "maneuvering-capability"
    title = "Controllability: manoeuvring capability in coordinated turns"
    amendment = "25-140"  # (h) came with 25-108; the section was last amended by 25-140 (2014)
    requirement = """
        (Table rows verified against the GPO print; footnotes not read.) The manoeuvring capabilities in a
        constant-speed coordinated turn at
        forward CG must be free of stall warning or other characteristics that might interfere with normal
        manoeuvring: takeoff configuration, V2, 30° bank, asymmetric WAT-limited thrust; takeoff, V2 + XX (the
        all-engines initial-climb speed), 40°, all-engines climb thrust; en route, VFTO, 40°, asymmetric
        WAT-limited thrust; landing, VREF, 40°, symmetric thrust for a −3° flight path. certkit checks that
        each turn can be trimmed with the elevator, aileron and rudder within their design limits, at the
        forward, reference and aft CG, and that the lift coefficient it needs stays below the stall-warning onset
        (the declared one, or the latest §25.207(c) allows).
    """
    margin = """Each trim control's design limit on the side it is deflected − |deflection| (deg), for every
        case, CG and turn direction; a control beyond its limit fails with the trim's message. Stall warning: the
        warning-onset 1-g lift coefficient − the turn's CL = n W/(q S) (≥ 0: free of warning)."""
    references = ("25.107", "25.121", "25.125", "25.147")
    requires = ("mass.MTOW", "configurations.takeoff")
    criteria = dict(MANEUVERING_CRITERIA)
    conditions = ConditionSpace(
        extra=(("case", CASES),),
        note="MTOW (takeoff and en-route cases) or MLW (landing case) at the forward, reference and aft CG; sea level "
        "(and 1500 ft en route); turns toward and away from the inoperative (critical) engine for the asymmetric cases",
    )
    implementation = "partial"
    limitations = """
        The footnotes of the (h) table were not read. Without a declared stall-warning onset the warning is taken at
        the latest speed §25.207(c) allows (VSR + the greater of 5 kn and 5 %, the stall identified at VSR), which
        is the most favourable reading for the turns; other characteristics that might interfere with normal
        manoeuvring (buffet) are not modelled. "WAT-limited" is read as MTOW at
        sea level (and 1500 ft en route) with the operating engine's thrust set so that straight flight climbs at
        exactly the §25.121(b) (V2) or §25.121(c) (VFTO) minimum gradient (at most takeoff or maximum continuous
        thrust). A movable stabiliser is trimmed in wings-level flight at the
        case's speed and thrust and held; the elevator pulls into the turn. Without one the stabiliser is fixed at its
        declared incidence and the elevator carries the whole trim. A coordinated turn is flown at zero sideslip.
    """

    unevaluated = (
        (
            "25.143(h)",
            "characteristics other than stall warning that might interfere with normal manoeuvring (buffet "
            "onset) are not evaluated",
        ),
    )

    def evaluate(self, ctx, conditions, crit):
        out = []
        for cond in conditions:
            case = cond.get("case")
            out += turn_findings(ctx, cond, case_spec(case, crit), f"(h) {case}")
        return out

    def evidence(self, ctx, findings, crit):
        return margins_evidence(
            findings,
            "§25.143(h) manoeuvring capability",
            "Coordinated-turn trims: controls against their design limits.",
            (
                "bank_deg",
                "load_factor",
                "CL_over_CLmax",
                "flight_path_deg",
                "elevator_deg",
                "aileron_deg",
                "rudder_deg",
            ),
        )

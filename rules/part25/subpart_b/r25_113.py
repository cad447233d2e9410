"""§25.113 Takeoff distance — from the simulated takeoffs of §25.111 (certkit_rules.part25.support.takeoff).

§25.113(a) (text from memory, not in docs/regulation-notes.md: *unverified*): on a dry runway the takeoff distance is
the greater of (1) the horizontal distance along the takeoff path from the start of the takeoff to the point at which
the airplane is 35 ft above the takeoff surface, determined under §25.111, and (2) 115 % of the horizontal distance
along the takeoff path, with all engines operating, from the start of the takeoff to the point at which the airplane
is 35 ft above the takeoff surface.

Per loading (MTOW at the forward, reference and aft CG, sea level ISA, the same batched run as §25.111): the
engine-out distance to 35 ft with the critical engine failed at VEF (the accelerate-go distance), the all-engines
distance to 35 ft and 115 % of it, and the takeoff distance, the greater. With a declared
``performance.takeoff_field_length`` the takeoff distance is checked against it (margin ft: field length − takeoff
distance ≥ 0; an engine-out run that had not reached 35 ft when it had rolled past the field length fails on that
lower bound); without one the distances are reported and the check is not evaluated. A run that is not a
takeoff (no lift-off, the tail on the runway) earns no verdict (a ground track off the centreline is §25.111's check); a
late lift-off lengthens the distance and is judged.
"""

from __future__ import annotations

import numpy as np
from certkit_rules.part25.support.reference_speeds import declared_cas
from certkit_rules.part25.support.takeoff import (
    PROCEDURE_CRITERIA,
    TAKEOFF_REQUIRES,
    distances,
    not_a_takeoff,
    run_summary,
    simulated_takeoffs,
    takeoff_conditions,
    unrepresentative,
)

from certkit.engine.registry import Rule, rule
from certkit.engine.results import Finding
from certkit.units import FT, KN


@rule
class TakeoffDistance(Rule):
    id = "25.113"
    cost = 1  # the §25.111 run, memoised
    run_with = "takeoff"  # §25.111, §25.113 and §25.107(e)(1)(iv) fly the same runs: one process simulates them
    symbol = "takeoff-distance"
    title = "Takeoff distance: engine-out and 115 % all-engines distances to 35 ft (simulated)"
    amendment = "25-121"
    implementation = "partial"
    requirement = """
        On a dry runway the takeoff distance is the greater of the distance from the start of the takeoff to 35 ft
        with the critical engine failed at VEF (the §25.111 path) and 115 % of that distance with all engines
        operating. certkit simulates both and, with a declared takeoff field length, checks that the takeoff
        distance does not exceed it.
    """
    margin = "Declared takeoff field length minus the takeoff distance (ft; ≥ 0 complies)."
    limitations = """
        Dry runway only ((b) wet runway and (c)-(d) takeoff run with clearway are not computed); sea level ISA at MTOW;
        ground effect on the wing and on the tail's downwash as in §25.111; the pilot and engine models of §25.111
        (rotation at 2.5°/s below the tail-strike attitude,
        the takeoff_pilot's pedals on heading and centreline, first-order spool-down of the failed engine). Runs that
        are not takeoffs (no lift-off, the tail on the runway) are not evaluated; a ground track off the centreline is
        judged by §25.111, not here; a late
        lift-off is judged. The paragraph's text is from memory (not in
        docs/regulation-notes.md).
    """
    references = ("25.111", "25.107", "25.109")
    requires = TAKEOFF_REQUIRES
    criteria = {**PROCEDURE_CRITERIA}
    conditions = takeoff_conditions("Sea level ISA, takeoff thrust from brake release; the §25.111 runs.")
    unevaluated = (
        ("25.113(b)", "the wet-runway takeoff distance is not computed"),
        ("25.113(c)", "the takeoff run (clearway credit) is not computed"),
    )

    def evaluate(self, ctx, conditions, crit):
        ac = ctx.aircraft
        to = simulated_takeoffs(ctx, conditions, crit)
        n = len(conditions)
        vr_kn, v2_kn = (declared_cas(ctx, name) / KN for name in ("VR", "V2"))
        field = ac.performance.takeoff_field_length if ac.performance is not None else None
        check = "(a) takeoff distance within the declared takeoff field length"
        out = []
        for i, cond in enumerate(conditions):
            c0 = cond.with_(altitude=0.0, thrust="takeoff")
            details = {
                **distances(to, i, n),
                "engine_out": run_summary(to, i, vr_kn, v2_kn),
                "all_engines": run_summary(to, n + i, vr_kn, v2_kn),
                "critical_engine": to.engine,
                "rotation_basis": to.basis["rotation"],
                "spool_down_basis": to.basis["spool_down"],
            }
            if details["takeoff_distance_ft"] is None:
                run_ft = details["engine_out_run_length_ft"]
                if field is not None and to.run.reached[n + i] and run_ft > float(field) / FT:
                    # the engine-out takeoff had not reached 35 ft when it had rolled past the field length
                    out.append(
                        Finding.compare(
                            c0,
                            check,
                            run_ft,
                            round(float(field) / FT, 0),
                            at_least=False,
                            unit="ft",
                            reason=f"the engine-out takeoff had not reached "
                            f"{crit.screen_height:.0f} ft after {run_ft:,.0f} ft (a lower bound of "
                            "its distance)",
                            **details,
                        )
                    )
                else:
                    out.append(
                        Finding.not_evaluated(
                            c0,
                            check,
                            f"a simulated takeoff did not reach {crit.screen_height:.0f} ft within the run",
                            **details,
                        )
                    )
                continue
            why = [
                f"engine out: {w}"
                for w in unrepresentative(details["engine_out"], tail_strike_deg=to.basis["tail_strike_deg"])
            ]
            why += [
                f"all engines: {w}"
                for w in unrepresentative(details["all_engines"], tail_strike_deg=to.basis["tail_strike_deg"])
            ]
            if why:
                out.append(
                    Finding.not_evaluated(
                        c0,
                        check,
                        not_a_takeoff(why),
                        **details,
                    )
                )
            elif field is None:
                out.append(
                    Finding.not_evaluated(
                        c0,
                        check,
                        "no performance.takeoff_field_length declared: takeoff "
                        f"distance {details['takeoff_distance_ft']:,.0f} ft reported, not "
                        "checked",
                        **details,
                    )
                )
            else:
                out.append(
                    Finding.compare(
                        c0,
                        check,
                        float(np.float64(details["takeoff_distance_ft"])),
                        round(float(field) / FT, 0),
                        at_least=False,
                        unit="ft",
                        **details,
                    )
                )
        return out

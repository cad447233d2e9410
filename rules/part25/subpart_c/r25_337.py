"""§25.337 Limit maneuvering load factors.

(b) The positive limit maneuvering load factor n may not be less than 2.1 + 24,000/(W + 10,000)
(W the design maximum takeoff weight in lb), except that n may not be less than 2.5 and need not
be greater than 3.8. (c) The negative limit maneuvering load factor may not be less than −1.0 at
speeds up to VC, and varies linearly to zero at VD.
"""

from __future__ import annotations

from certkit.engine.conditions import ConditionSpace, EnvelopeWeights
from certkit.engine.registry import Criterion, Rule, rule
from certkit.engine.results import Finding
from certkit.units import LB

SOURCE = "14 CFR 25.337(b)-(c), Amdt. 25-23"


def required_positive_load_factor(mtow_kg: float, a: float, b: float, c: float, floor: float, cap: float) -> float:
    """n = a + b/(W + c) with W in lb, bounded to [floor, cap] (§25.337(b))."""
    w_lb = mtow_kg / LB
    return min(max(a + b / (w_lb + c), floor), cap)


@rule
class LimitManeuveringLoadFactors(Rule):
    id = "25.337"
    symbol = "limit-maneuvering-load-factors"
    title = "Limit maneuvering load factors"
    amendment = "25-23"
    requirement = """
        The airplane is designed for symmetrical manoeuvres to limit load factors not lower than those
        of this paragraph: a positive factor of at least 2.1 + 24,000/(W + 10,000), W the design maximum
        takeoff weight in pounds, but not less than 2.5 (and never required above 3.8); and a negative
        factor of at least −1.0 at speeds up to VC, reducing linearly to zero at VD.
    """
    margin = """
        Positive: declared design factor minus the required factor (≥ 0 complies). Negative: −1.0 minus
        the declared negative factor (≥ 0 complies, i.e. the declared factor is −1.0 or more negative).
        Normalised by the magnitude of the requirement.
    """
    references = ("25.333", "25.335")
    requires = ("mass.MTOW", "envelope.limit_load_factors")
    criteria = {
        "n_formula_a": Criterion(2.1, "", SOURCE, "constant term of the positive factor formula"),
        "n_formula_b": Criterion(24000.0, "lb", SOURCE, "numerator of the weight term"),
        "n_formula_c": Criterion(10000.0, "lb", SOURCE, "weight offset"),
        "n_positive_floor": Criterion(2.5, "", SOURCE, "positive factor may not be less than"),
        "n_positive_cap": Criterion(3.8, "", SOURCE, "positive factor need not be greater than"),
        "n_negative": Criterion(-1.0, "", "14 CFR 25.337(c)(1)", "negative factor at speeds up to VC"),
    }
    conditions = ConditionSpace(
        loading=EnvelopeWeights(), note="The required factor uses the design MTOW, as the paragraph says."
    )

    def evaluate(self, ctx, conditions, crit):
        n = ctx.aircraft.envelope.limit_load_factors
        required = required_positive_load_factor(
            ctx.aircraft.mass.MTOW,
            crit.n_formula_a,
            crit.n_formula_b,
            crit.n_formula_c,
            crit.n_positive_floor,
            crit.n_positive_cap,
        )
        findings = []
        for cond in conditions:
            findings.append(
                Finding.compare(
                    cond,
                    "(b) positive limit load factor",
                    n.positive,
                    required,
                    at_least=True,
                    unit="g",
                    mtow_lb=ctx.aircraft.mass.MTOW / LB,
                )
            )
            findings.append(
                Finding.compare(
                    cond,
                    "(c)(1) negative limit load factor up to VC",
                    n.negative,
                    crit.n_negative,
                    at_least=False,
                    unit="g",
                )
            )
        return findings

"""One line per rule saying why it has its status: the worst failing check, the reason it was not evaluated, the
sub-paragraphs a partial rule leaves out, or the critical check of a rule that complies."""

from __future__ import annotations

from certkit.engine.results import COMPLIES_PARTIAL, FAILS, NOT_EVALUATED
from certkit.report.display import format_value, unit_and_factor


def margin_text(value, unit: str) -> str:
    """A margin in the unit a reviewer reads (kn, ft, lb, lbf, kN·m, g), signed; an em dash when missing."""
    if value is None:
        return "—"
    if abs(value) < 1e-9:  # round-off of a value on its limit reads 0, not "+0.000000 Mach"
        value = 0.0
    shown, factor = unit_and_factor(unit or "")
    text = format_value(value / factor)
    if not text.startswith(("-", "—")):
        text = "+" + text
    return f"{text} {shown}" if shown not in ("", "1") else text


def reason_line(result) -> str:
    """The one-line reason of the rule's status (see the module docstring)."""
    if result.status == FAILS:
        f = result.worst_failure
        by = margin_text(-f.margin, f.unit).lstrip("+") if f.margin is not None else "—"  # "fails by 0.90 deg"
        return f"fails by {by} at {f.condition.label(numbers=False)}: {f.check}"
    if result.status == NOT_EVALUATED:
        return "not evaluated: " + result.not_evaluated_reason
    crit = result.critical
    where = f"critical {crit.check} at {crit.condition.label(numbers=False)}" if crit else "complies"
    if result.status == COMPLIES_PARTIAL:
        return where + "; not evaluated: " + ", ".join(f"§{p}" for p, _ in result.unevaluated)
    return where


def reason_condition(result) -> str:
    """The full condition behind :func:`reason_line` (masses, CG and speeds in aviation units), for a tooltip."""
    f = result.worst_failure if result.status == FAILS else result.critical
    return f.condition.label() if f is not None else ""

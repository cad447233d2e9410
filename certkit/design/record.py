"""The flat responses of one design: rule margins, named sub-checks, control travel used, handling levels.

Names (all numbers SI, normalised margins ≥ 0 comply):

* ``rule.<id>.margin`` — the rule's smallest normalised margin (margin / |limit|) over its findings;
* ``subcheck.<id>.<check>.margin`` and ``.value`` — per named check of a rule (the finding's check text up to
  its first ": ", slugged: ``subcheck.25.143(h).h_takeoff_v2_rudder_within_design_limit.margin``), the smallest
  normalised margin over the conditions and the value at that condition (the finding's unit);
* ``travel.<id>.<control>`` — the largest fraction of the mechanical travel (in the deflection's direction) any
  finding of the rule reports for the elevator, aileron or rudder, and ``travel.<control>`` over all rules (the
  seed study constrains the elevator to 70 % of its travel);
* ``level.<mode>.<corner>.<configuration>`` — the MIL-F-8785C level (1–3, 4 worse than 3) of each mode, the
  worst over the speeds and altitudes of §25.181's conditions at that CG corner and configuration.

Statuses accompany the rule names ("complies", "complies_partial", "fails", "not_evaluated") and the sub-check
names (a finding's: "complies", "fails", "not_evaluated").
"""

from __future__ import annotations

import math
import re

CONTROLS = ("elevator", "aileron", "rudder")
_DEG = math.pi / 180.0


def slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def check_name(check: str) -> str:
    """The named sub-check of a finding: its check text before the first ': ' (the loads rules append the
    critical station and quantity after it), slugged."""
    return slug(check.split(": ", 1)[0])


def _finite(x) -> float | None:
    return float(x) if x is not None and math.isfinite(float(x)) else None


def _worse(status_a: str | None, status_b: str) -> str:
    order = {"fails": 2, "not_evaluated": 1, "complies": 0}
    return status_b if status_a is None or order[status_b] > order[status_a] else status_a


def rule_responses(results, travel: dict[str, tuple[float, float]]) -> tuple[dict, dict]:
    """(responses, statuses) of rule results (:class:`certkit.engine.results.RuleResult`); ``travel`` maps a control name
    to its mechanical (min, max) deflection in rad."""
    responses: dict[str, float | None] = {}
    statuses: dict[str, str] = {}
    overall: dict[str, float] = {}
    for r in results:
        crit = r.critical
        responses[f"rule.{r.id}.margin"] = _finite(crit.normalized_margin) if crit else None
        statuses[f"rule.{r.id}"] = r.status
        best: dict[str, tuple] = {}
        used: dict[str, float] = {}
        for f in r.findings:
            name = check_name(f.check)
            key = f"subcheck.{r.id}.{name}"
            statuses[key] = _worse(statuses.get(key), f.status)
            nm = f.normalized_margin
            if nm is not None and math.isfinite(nm) and (best.get(key, (None,))[0] is None or nm < best[key][0]):
                best[key] = (nm, f.value)
            else:
                best.setdefault(key, (None, None))
            if f.unit == "deg" and f.value is not None and math.isfinite(f.value):
                for control in CONTROLS:
                    if control in f.check.lower() and control in travel:
                        lo, hi = travel[control]
                        end = hi if f.value >= 0 else lo
                        if end != 0:
                            used[control] = max(used.get(control, 0.0), abs(f.value * _DEG / end))
        for key, (nm, value) in best.items():
            responses[f"{key}.margin"] = _finite(nm)
            responses[f"{key}.value"] = _finite(value)
        for control, frac in used.items():
            responses[f"travel.{r.id}.{control}"] = frac
            overall[control] = max(overall.get(control, 0.0), frac)
    for control, frac in overall.items():
        responses[f"travel.{control}"] = frac
    return responses, statuses


def handling_levels(results) -> dict[str, int]:
    """``level.<mode>.<corner>.<configuration>`` from the §25.181 findings' mode tables (worst level)."""
    out: dict[str, int] = {}
    for r in results:
        if r.id != "25.181":
            continue
        for f in r.findings:
            modes = f.details.get("modes") if f.details else None
            cond = f.condition
            if not modes or cond.loading is None or cond.configuration is None:
                continue
            for mode, row in modes.items():
                levels = [v for k, v in row.items() if k.startswith("level_") and not k.endswith("_by")]
                if not levels:
                    continue
                key = f"level.{mode}.{cond.loading}.{cond.configuration}"
                out[key] = max(out.get(key, 0), max(int(v) for v in levels))
    return out

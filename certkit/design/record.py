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
  worst over the speeds and altitudes of the conditions at that CG corner and configuration, from the rules that
  offer mode responses (``Rule.offers``: :class:`certkit.engine.registry.ModeResponses`);
* ``mode.<mode>.<quantity>.<corner>.<configuration>`` — the quantities of the condition that sets that level (the
  lowest damping among equal levels): ``zeta``, ``wn_rad_s``, ``period_s``, ``t_half_s``, ``t_double_s`` (None where
  the mode has none) and, for the short period, ``cap`` (ω²/(n/α), (rad/s²)/g). The level follows from them:
  ``certkit_rules.part25.support.handling_levels.configuration_level(mode, configuration, zeta=…, wn=…, t_half=…,
  t_double=…, cap=…)`` (MIL-F-8785C tables); and ``level1_margin``, ``level2_margin``, ``level3_margin``, the least
  over the conditions of the offer's level margin (``ModeResponses.level_margin``, clipped to ±10): Level ≤ L exactly
  where it is ≥ 0, continuous where the condition that sets the level changes — what a study derives the level from;
* ``control.<rule id>.<case>.<control>`` — per case a rule offers (:class:`certkit.engine.registry.ControlResponses`:
  §25.143(h)'s four manoeuvring cases, §25.145(b)'s changes, §25.121's segments, §25.111's engine-out takeoff), the
  largest fraction of the control's mechanical travel (in the deflection's direction) over the case's conditions.

Statuses accompany the rule names ("complies", "complies_partial", "fails", "not_evaluated") and the sub-check
names (a finding's: "complies", "fails", "not_evaluated").
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import numpy as np

from certkit.engine.registry import ControlResponses, ModeResponses

if TYPE_CHECKING:
    from certkit.engine.results import RuleResult

CONTROLS = ("elevator", "aileron", "rudder")
_DEG = math.pi / 180.0


@functools.lru_cache(maxsize=4096)
def slug(text: str) -> str:
    """Lower case, every run of other characters one underscore (remembered: a record slugs the same few hundred
    check texts for every design)."""
    return _NON_WORD.sub("_", text.lower()).strip("_")


_NON_WORD = re.compile(r"[^a-z0-9]+")


def check_name(check: str) -> str:
    """The named sub-check of a finding: its check text before the first ': ' (the loads rules append the
    critical station and quantity after it), slugged."""
    return slug(check.split(": ", 1)[0])


def _finite(x: float | None) -> float | None:
    return float(x) if x is not None and math.isfinite(float(x)) else None


def _worse(status_a: str | None, status_b: str) -> str:
    order = {"fails": 2, "not_evaluated": 1, "complies": 0}
    return status_b if status_a is None or order[status_b] > order[status_a] else status_a


def rule_responses(
    results: Iterable[RuleResult], travel: dict[str, tuple[float, float]]
) -> tuple[dict[str, float | None], dict[str, str]]:
    """(responses, statuses) of rule results (:class:`certkit.engine.results.RuleResult`); ``travel`` maps a control
    name
    to its mechanical (min, max) deflection in rad."""
    responses: dict[str, float | None] = {}
    statuses: dict[str, str] = {}
    overall: dict[str, float] = {}
    for r in results:
        crit = r.critical
        responses[f"rule.{r.id}.margin"] = _finite(crit.normalized_margin) if crit else None
        statuses[f"rule.{r.id}"] = r.status
        best: dict[str, tuple[float | None, float | None]] = {}
        used: dict[str, float] = {}
        for f in r.findings:
            name = check_name(f.check)
            key = f"subcheck.{r.id}.{name}"
            statuses[key] = _worse(statuses.get(key), f.status)
            nm = f.normalized_margin
            known = best.get(key, (None, None))[0]
            if nm is not None and math.isfinite(nm) and (known is None or nm < known):
                best[key] = (nm, f.value)
            else:
                best.setdefault(key, (None, None))
            if f.unit == "deg" and f.value is not None and math.isfinite(f.value):
                for control in CONTROLS:
                    frac = travel_fraction(control, f.value, travel) if control in f.check.lower() else None
                    if frac is not None:
                        used[control] = max(used.get(control, 0.0), frac)
        for key, (nm, value) in best.items():
            responses[f"{key}.margin"] = _finite(nm)
            responses[f"{key}.value"] = _finite(value)
        for control, frac in used.items():
            responses[f"travel.{r.id}.{control}"] = frac
            overall[control] = max(overall.get(control, 0.0), frac)
    for control, frac in overall.items():
        responses[f"travel.{control}"] = frac
    return responses, statuses


def offered_responses(
    results: Iterable[RuleResult], rules: Iterable[Any], travel: dict[str, tuple[float, float]] | None = None
) -> dict[str, float | None]:
    """The responses the rules offer by declaration (``Rule.offers``), from their results (``rules``: the rule
    classes, or anything with their ``id`` and ``offers``; ``travel`` as in :func:`rule_responses`)."""
    offers = {r.id: r.offers for r in rules}
    out: dict[str, float | None] = {}
    worst: dict[str, tuple[Any, ...]] = {}
    for res in results:
        for offer in offers.get(res.id, ()):
            if isinstance(offer, ModeResponses):
                handling_levels(res, offer, out, worst)
            elif isinstance(offer, ControlResponses):
                control_responses(res, offer, travel or {}, out)
    for key, (_, _, mode, row) in worst.items():
        corner_config = key.split(".", 2)[2]
        for quantity, field in MODE_QUANTITIES.items():
            if quantity == "cap" and mode != "short_period":
                continue
            value = row.get(field)
            out[f"mode.{mode}.{quantity}.{corner_config}"] = _finite(value) if value is not None else None
    return out


#: the mode quantities of a design record (``mode.<mode>.<quantity>.<corner>.<configuration>``) and the mode-table
#: column each comes from: damping ratio, undamped natural frequency (rad/s), period (s, oscillatory modes), times to
#: half and to double amplitude (s, convergent or divergent modes), the short period's control anticipation
#: parameter ω²/(n/α) ((rad/s²)/g)
MODE_QUANTITIES = {
    "zeta": "zeta",
    "wn_rad_s": "wn_rad_s",
    "period_s": "period_s",
    "t_half_s": "t_half_s",
    "t_double_s": "t_double_s",
    "cap": "cap",
}


def offered_prefixes(rule: Any) -> tuple[str, ...]:
    """The beginnings of the response names a rule offers (``level.<mode>.``, ``mode.<mode>.``,
    ``control.<rule id>.<case>.``)."""
    out: list[str] = []
    for offer in rule.offers:
        if isinstance(offer, ModeResponses):
            out += [f"{kind}.{mode}." for mode in offer.modes for kind in ("level", "mode")]
        elif isinstance(offer, ControlResponses):
            out += [f"control.{rule.id}.{slug(case.name)}." for case in offer.cases]
    return tuple(out)


def handling_levels(
    result: RuleResult, offer: ModeResponses, out: dict[str, float | None], worst: dict[str, tuple[Any, ...]]
) -> None:
    """``level.<mode>.<corner>.<configuration>`` into ``out`` from the mode tables of ``result``'s findings (the
    worst level, also over the levels already in ``out``); ``worst`` keeps, per level name, the row of the condition
    that sets it (the lowest damping among equal levels), whose quantities the record gives."""
    margins: dict[tuple[str, str, str, bool], list[dict[str, Any]]] = {}
    for f in result.findings:
        modes = f.details.get(offer.key) if f.details else None
        cond = f.condition
        if not modes or cond.loading is None or cond.configuration is None:
            continue
        for mode, row in modes.items():
            if mode not in offer.modes:
                continue
            levels = [v for k, v in row.items() if k.startswith("level_") and not k.endswith("_by")]
            if not levels:
                continue
            key = f"level.{mode}.{cond.loading}.{cond.configuration}"
            level = max(int(v) for v in levels)
            out[key] = max(out.get(key) or 0, level)
            if row.get("zeta") is not None and row.get("wn_rad_s") is not None:
                group = (mode, cond.loading, cond.configuration, row.get("cap") is None)
                margins.setdefault(group, []).append(row)
            rank = (level, -float(row.get("zeta", 0.0)))
            if key not in worst or rank > worst[key][:2]:
                worst[key] = (*rank, mode, row)
    for (mode, corner, configuration, _), rows in margins.items():
        _least_level_margins(offer, mode, corner, configuration, rows, out)


#: the recorded level margins are clipped to ±this (a relative distance to a level's boundary; ∞ where unbounded)
LEVEL_MARGIN_CLIP = 10.0


def _least_level_margins(
    offer: ModeResponses,
    mode: str,
    corner: str,
    configuration: str,
    rows: list[dict[str, Any]],
    out: dict[str, float | None],
) -> None:
    """``mode.<mode>.level<L>_margin.<corner>.<configuration>`` for L = 1, 2, 3 into ``out``: the least, over the
    conditions (``rows``, each with its ``zeta`` and ``wn_rad_s``, all with or all without ``cap``), of the offer's
    level margin of the row's quantities (≥ 0 exactly where every condition is Level L or better). Unlike the
    quantities of the condition that sets the level, it stays continuous where that condition changes, so a study
    can fit it."""
    if offer.level_margin is None:
        return
    zeta = np.array([float(r["zeta"]) for r in rows])
    wn = np.array([float(r["wn_rad_s"]) for r in rows])
    cap = None if rows[0].get("cap") is None else np.array([float(r["cap"]) for r in rows])
    for level in (1, 2, 3):
        margin = np.asarray(offer.level_margin(mode, configuration, level, zeta=zeta, wn=wn, cap=cap), dtype=float)
        m = min(max(float(margin.min()), -LEVEL_MARGIN_CLIP), LEVEL_MARGIN_CLIP)
        key = f"mode.{mode}.level{level}_margin.{corner}.{configuration}"
        previous = out.get(key)
        out[key] = m if previous is None else min(previous, m)


def control_responses(
    result: RuleResult, offer: ControlResponses, travel: dict[str, tuple[float, float]], out: dict[str, float | None]
) -> None:
    """``control.<rule id>.<case>.<control>`` into ``out``: the largest fraction of the control's mechanical travel
    (in the deflection's direction) over the case's findings (:class:`certkit.engine.registry.ControlCase`)."""
    for case in offer.cases:
        for f in result.findings:
            for control, deg in case.deflections(f).items():
                frac = travel_fraction(control, deg, travel)
                if frac is not None:
                    key = f"control.{result.id}.{slug(case.name)}.{control}"
                    out[key] = max(out.get(key) or 0.0, frac)


def travel_fraction(control: str, deflection_deg: float, travel: dict[str, tuple[float, float]]) -> float | None:
    """|deflection| over the mechanical stop on its side (None without the control's travel or a zero stop)."""
    if control not in travel:
        return None
    lo, hi = travel[control]
    end = hi if deflection_deg >= 0 else lo
    return abs(deflection_deg * _DEG / end) if end != 0 else None

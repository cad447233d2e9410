"""``certkit diff OLD/results.json NEW/results.json``: what changed between two checks, per rule and condition.

Per rule: added or removed rules, status flips, the change of the critical (normalised) margin. Per condition
(a finding is identified by its rule, check and condition): status flips, findings that appeared or disappeared,
and margin changes larger than the tolerance (``1e-6 × max(1, |limit|)`` in the finding's unit by default, so
that round-off does not show). Margins are shown in aviation units (:mod:`certkit.report.reasons`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from certkit.errors import UserError
from certkit.report.reasons import margin_text
from certkit.engine.results_json import SCHEMA_VERSION

#: how bad a status is: a change to a larger rank is a regression
RANK = {"complies": 0, "complies_partial": 1, "not_evaluated": 2, "fails": 3, None: -1}


@dataclass
class FindingChange:
    check: str
    condition: str
    old_status: str | None
    new_status: str | None
    old_margin: float | None
    new_margin: float | None
    unit: str

    @property
    def flipped(self) -> bool:
        return self.old_status != self.new_status

    @property
    def delta(self) -> float | None:
        if self.old_margin is None or self.new_margin is None:
            return None
        return self.new_margin - self.old_margin


@dataclass
class RuleChange:
    id: str
    title: str
    old_status: str | None
    new_status: str | None
    old_margin: float | None
    new_margin: float | None
    unit: str
    findings: list[FindingChange] = field(default_factory=list)

    @property
    def flipped(self) -> bool:
        return self.old_status != self.new_status

    @property
    def regression(self) -> bool:
        return RANK[self.new_status] > RANK[self.old_status] and self.new_status is not None


def load(path: str | Path) -> dict:
    """A results.json, checked to be one this certkit reads (same schema major version)."""
    p = Path(path)
    try:
        data = json.loads(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise UserError(f"{p}: cannot be read ({exc.strerror or exc})") from None
    except json.JSONDecodeError as exc:
        raise UserError(f"{p}: not JSON (line {exc.lineno}: {exc.msg})") from None
    version = data.get("schema_version") if isinstance(data, dict) else None
    if not isinstance(version, str) or version.split(".")[0] != SCHEMA_VERSION.split(".")[0]:
        raise UserError(f"{p}: schema_version {version!r}, expected {SCHEMA_VERSION.split('.')[0]}.x "
                        "(a results.json written by this certkit version; rerun `certkit check`)")
    return data


_SI_FIELDS = {"loading": "loading", "mass_kg": "mass", "x_cg_m": "x_cg", "configuration": "configuration",
              "altitude_m": "altitude", "speed_m_s": "speed", "speed_kind": "speed_kind", "speed_name": "speed_name"}


def _label(condition: dict) -> str:
    """The condition as the report labels it (aviation units), from its results.json form."""
    from certkit.engine.results import Condition

    known = {_SI_FIELDS[k]: v for k, v in condition.items() if k in _SI_FIELDS}
    extra = tuple((k, v) for k, v in condition.items() if k not in _SI_FIELDS)
    return Condition(**known, extra=extra).label()


def _findings(rule: dict) -> dict:
    """Findings by (check, condition); a repeated key (same check and condition) gets a running number."""
    out: dict = {}
    for f in rule["findings"]:
        key = (f["check"], json.dumps(f["condition"], sort_keys=True))
        n = 0
        while (key + (n,)) in out:
            n += 1
        out[key + (n,)] = f
    return out


def compare(old: dict, new: dict, tolerance: float = 1e-6) -> list[RuleChange]:
    """The rules that changed (status, margin or any finding), in the new run's order then removed ones."""
    old_rules = {r["id"]: r for r in old["rules"]}
    new_rules = {r["id"]: r for r in new["rules"]}
    order = [r["id"] for r in new["rules"]] + [i for i in old_rules if i not in new_rules]
    changes = []
    for rid in order:
        a, b = old_rules.get(rid), new_rules.get(rid)
        change = RuleChange(rid, (b or a)["title"], a and a["status"], b and b["status"], a and a["min_margin"],
                            b and b["min_margin"], (b or a)["unit"] or "")
        fa, fb = (_findings(a), _findings(b)) if a and b else ({}, {})  # a rule added or removed is one line
        for key in list(fb) + [k for k in fa if k not in fb]:
            x, y = fa.get(key), fb.get(key)
            ref = y or x
            limit = max(abs(v["limit"]) for v in (x, y) if v and v["limit"] is not None) if any(
                v and v["limit"] is not None for v in (x, y)) else 1.0
            fc = FindingChange(key[0], _label(ref["condition"]), x and x["status"], y and y["status"],
                               x and x["margin"], y and y["margin"], ref["unit"] or "")
            moved = fc.delta is not None and abs(fc.delta) > tolerance * max(1.0, limit)
            appeared = (x is None) != (y is None) or (fc.old_margin is None) != (fc.new_margin is None)
            if fc.flipped or moved or appeared:
                change.findings.append(fc)
        margin_moved = (change.old_margin is not None and change.new_margin is not None and
                        abs(change.new_margin - change.old_margin) > tolerance * max(1.0, abs(change.old_margin)))
        if change.flipped or margin_moved or change.findings or (change.old_margin is None) != (change.new_margin is None):
            changes.append(change)
    return changes


def text_lines(changes: list[RuleChange], old: dict, new: dict, limit: int = 20) -> list[str]:
    """The changes as terminal lines: one per rule, then up to ``limit`` changed findings each."""
    if not changes:
        return [f"no change in {len(new['rules'])} rules"]
    lines = []
    for c in changes:
        status = (f"{c.old_status or 'absent'} → {c.new_status or 'absent'}" if c.flipped else (c.new_status or ""))
        margin = f"{margin_text(c.old_margin, c.unit)} → {margin_text(c.new_margin, c.unit)}"
        lines.append(f"§{c.id:<13} {status:<32} critical margin {margin}")
        for f in c.findings[:limit]:
            what = (f"{f.old_status or 'absent'} → {f.new_status or 'absent'}" if f.flipped
                    else f"margin {margin_text(f.old_margin, f.unit)} → {margin_text(f.new_margin, f.unit)}")
            lines.append(f"    {what}: {f.check} at {f.condition}")
        if len(c.findings) > limit:
            lines.append(f"    … {len(c.findings) - limit} more changed findings (see --html)")
    flips = sum(c.flipped for c in changes)
    lines.append(f"\n{len(changes)} rules changed, {flips} changed status, "
                 f"{sum(c.regression for c in changes)} got worse")
    return lines


def render_html(changes: list[RuleChange], old: dict, new: dict, old_path: str, new_path: str) -> str:
    from jinja2 import Environment, PackageLoader, select_autoescape

    env = Environment(loader=PackageLoader("certkit.report", "templates"), autoescape=select_autoescape(["html"]),
                      trim_blocks=True, lstrip_blocks=True)
    env.filters["margin"] = margin_text
    return env.get_template("diff.html").render(changes=changes, old=old, new=new, old_path=old_path,
                                                 new_path=new_path)

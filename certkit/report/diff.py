"""``certkit diff OLD/results.json NEW/results.json``: what changed between two checks, per rule and condition.

First what was changed: the criteria in force (by their YAML path ``criteria.<rule>.values.<name>`` when the aircraft
file overrides them) and the aircraft file's inputs (by YAML path, from ``aircraft.inputs``); then what changed as a
result, with status words as the report writes them ("complies in part", "not evaluated").
Per rule: added or removed rules, status flips, the change of the critical (normalised) margin. Per condition
(a finding is identified by its rule, check and condition): status flips, findings that appeared or disappeared,
and margin changes larger than the tolerance (``1e-6 × max(1, |limit|)`` in the finding's unit by default, so
that round-off does not show). Margins are shown in aviation units (:mod:`certkit.report.reasons`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from certkit.aircraft.yaml_source import read_regular_file
from certkit.engine.results import Condition
from certkit.engine.results_json import SCHEMA_VERSION
from certkit.errors import UserError
from certkit.report.reasons import margin_text

#: the largest results.json read (a full check writes about 10 MB)
MAX_RESULTS_BYTES = 512 * 1024**2

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
        raw = read_regular_file(p, MAX_RESULTS_BYTES)
    except OSError as exc:
        raise UserError(f"{p}: cannot be read ({exc.strerror or exc})") from None
    if len(raw) > MAX_RESULTS_BYTES:
        raise UserError(f"{p}: larger than {MAX_RESULTS_BYTES // 1024**2} MB, not a results.json of certkit")
    try:
        data = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise UserError(
            f"{p}: not a results.json (not UTF-8 text: byte {exc.start} is "
            f"{raw[exc.start : exc.start + 1]!r}); give the results.json a `certkit check` wrote"
        ) from None
    except json.JSONDecodeError as exc:
        raise UserError(f"{p}: not JSON (line {exc.lineno}: {exc.msg})") from None
    version = data.get("schema_version") if isinstance(data, dict) else None
    if not isinstance(version, str) or version.split(".")[0] != SCHEMA_VERSION.split(".")[0]:
        raise UserError(
            f"{p}: schema_version {version!r}, expected {SCHEMA_VERSION.split('.')[0]}.x "
            "(a results.json written by this certkit version; rerun `certkit check`)"
        )
    return data


_SI_FIELDS = {
    "loading": "loading",
    "mass_kg": "mass",
    "x_cg_m": "x_cg",
    "configuration": "configuration",
    "altitude_m": "altitude",
    "speed_m_s": "speed",
    "speed_kind": "speed_kind",
    "speed_name": "speed_name",
}


def _label(condition: dict) -> str:
    """The condition as the report labels it (aviation units), from its results.json form."""
    known = {_SI_FIELDS[k]: v for k, v in condition.items() if k in _SI_FIELDS}
    extra = tuple((k, v) for k, v in condition.items() if k not in _SI_FIELDS)
    return Condition(**known, extra=extra).label()


#: status words of a diff (as the report writes them; "absent" for a rule or finding one run lacks)
STATUS_WORDS = {
    "complies": "complies",
    "complies_partial": "complies in part",
    "not_evaluated": "not evaluated",
    "fails": "fails",
    None: "absent",
}


@dataclass
class CriterionChange:
    rule_id: str
    name: str
    old: object
    new: object
    unit: str
    overridden: bool

    @property
    def path(self) -> str:
        """Where the value in force is written: its override's YAML path, else the rule's default."""
        return f"criteria.{self.rule_id}.values.{self.name}" if self.overridden else f"§{self.rule_id} default"


def criteria_changes(old: dict, new: dict) -> list[CriterionChange]:
    """The criteria whose value in force differs between two runs, for the rules both ran."""
    old_rules = {r["id"]: r for r in old["rules"]}
    out = []
    for r in new["rules"]:
        before = old_rules.get(r["id"], {}).get("criteria") or {}
        for name, c in (r.get("criteria") or {}).items():
            b = before.get(name)
            if b is not None and (b["value"] != c["value"] or b.get("overridden") != c.get("overridden")):
                out.append(
                    CriterionChange(
                        r["id"],
                        name,
                        b["value"],
                        c["value"],
                        c.get("unit", "1"),
                        bool(c.get("overridden") or b.get("overridden")),
                    )
                )
    return out


def input_changes(old: dict, new: dict) -> list[tuple[str, object, object]]:
    """(YAML path, old, new) of every aircraft-file value that differs (None: absent); empty when a run does not
    carry its inputs (a results.json of an older certkit)."""
    a, b = old["aircraft"].get("inputs"), new["aircraft"].get("inputs")
    if not a or not b:
        return []
    missing = object()
    return [(k, a.get(k), b.get(k)) for k in sorted(set(a) | set(b)) if a.get(k, missing) != b.get(k, missing)]


def _findings(rule: dict) -> dict:
    """Findings by (check, condition); a repeated key (same check and condition) gets a running number. The check
    is read as written with the criteria's defaults (``check_default``), so that an override pairs the findings."""
    out: dict = {}
    for f in rule["findings"]:
        check = (f.get("details") or {}).get("check_default", f["check"])
        key = (check, json.dumps(f["condition"], sort_keys=True))
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
        change = RuleChange(
            rid,
            (b or a)["title"],
            a and a["status"],
            b and b["status"],
            a and a["min_margin"],
            b and b["min_margin"],
            (b or a)["unit"] or "",
        )
        fa, fb = (_findings(a), _findings(b)) if a and b else ({}, {})  # a rule added or removed is one line
        for key in list(fb) + [k for k in fa if k not in fb]:
            x, y = fa.get(key), fb.get(key)
            ref = y or x
            limit = (
                max(abs(v["limit"]) for v in (x, y) if v and v["limit"] is not None)
                if any(v and v["limit"] is not None for v in (x, y))
                else 1.0
            )
            fc = FindingChange(
                ref["check"],
                _label(ref["condition"]),
                x and x["status"],
                y and y["status"],
                x and x["margin"],
                y and y["margin"],
                ref["unit"] or "",
            )
            moved = fc.delta is not None and abs(fc.delta) > tolerance * max(1.0, limit)
            appeared = (x is None) != (y is None) or (fc.old_margin is None) != (fc.new_margin is None)
            if fc.flipped or moved or appeared:
                change.findings.append(fc)
        margin_moved = (
            change.old_margin is not None
            and change.new_margin is not None
            and abs(change.new_margin - change.old_margin) > tolerance * max(1.0, abs(change.old_margin))
        )
        if (
            change.flipped
            or margin_moved
            or change.findings
            or (change.old_margin is None) != (change.new_margin is None)
        ):
            changes.append(change)
    return changes


def text_lines(changes: list[RuleChange], old: dict, new: dict, limit: int = 20) -> list[str]:
    """The changes as terminal lines: the criteria and inputs changed (by YAML path), then one line per rule and up
    to ``limit`` changed findings each."""
    lines = []
    criteria = criteria_changes(old, new)
    if criteria:
        lines.append("criteria changed:")
        lines += [
            f"  {c.path}: {_criterion_value(c.old, c.unit)} → {_criterion_value(c.new, c.unit)}"
            + ("" if c.overridden else f" (§{c.rule_id} {c.name})")
            for c in criteria
        ]
    inputs = input_changes(old, new)
    if inputs:
        lines.append("inputs changed:")
        lines += [f"  {path}: {_input(a)} → {_input(b)}" for path, a, b in inputs[:limit]]
        if len(inputs) > limit:
            lines.append(f"  … {len(inputs) - limit} more changed inputs")
    if lines:
        lines.append("")
    if not changes:
        return lines + [f"no change in the results of {len(new['rules'])} rules"]
    for c in changes:
        status = (
            f"{STATUS_WORDS[c.old_status]} → {STATUS_WORDS[c.new_status]}" if c.flipped else STATUS_WORDS[c.new_status]
        )
        margin = f"{margin_text(c.old_margin, c.unit)} → {margin_text(c.new_margin, c.unit)}"
        lines.append(f"§{c.id:<13} {status:<32} critical margin {margin}")
        for f in c.findings[:limit]:
            what = (
                f"{STATUS_WORDS[f.old_status]} → {STATUS_WORDS[f.new_status]}"
                if f.flipped
                else f"margin {margin_text(f.old_margin, f.unit)} → {margin_text(f.new_margin, f.unit)}"
            )
            lines.append(f"    {what}: {f.check} at {f.condition}")
        if len(c.findings) > limit:
            lines.append(f"    … {len(c.findings) - limit} more changed findings (see --html)")
    flips = sum(c.flipped for c in changes)
    lines.append(
        f"\n{len(changes)} rules changed, {flips} changed status, {sum(c.regression for c in changes)} got worse"
    )
    return lines


def _criterion_value(value, unit: str) -> str:
    return f"{value:g}{'' if unit in ('', '1') else ' ' + unit}" if isinstance(value, float) else f"{value}"


def _input(value) -> str:
    return "absent" if value is None else str(value)


def render_html(changes: list[RuleChange], old: dict, new: dict, old_path: str, new_path: str) -> str:
    from certkit.report.pages import page_environment  # deferred: jinja2 only when an HTML diff is asked for

    env = page_environment({})
    env.filters["margin"] = margin_text
    env.filters["status"] = lambda status: STATUS_WORDS.get(status, status)
    return env.get_template("diff.html").render(
        changes=changes,
        old=old,
        new=new,
        old_path=old_path,
        new_path=new_path,
        criteria=criteria_changes(old, new),
        inputs=input_changes(old, new),
        value=_criterion_value,
    )

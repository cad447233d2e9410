"""The HTML report: one self-contained folder (inline CSS, SVG and a little script) that opens offline.

Every string that comes from the aircraft file or a plugin is escaped (jinja2 autoescape); only the SVG that
matplotlib produced is inserted as markup, and its text is XML-escaped by matplotlib. Paragraph references in the
text (``§25.337``, ``14 CFR 25.303``) become links (:mod:`certkit.report.links`). Numbers are shown in aviation
units (:mod:`certkit.report.display`); results.json keeps SI.
"""

from __future__ import annotations

import base64
import inspect
import re
import zlib
from pathlib import Path

from jinja2 import Environment
from markupsafe import Markup, escape

from certkit.engine.registry import Rule
from certkit.engine.results import (
    COMPLIES,
    COMPLIES_PARTIAL,
    FAILS,
    NOT_EVALUATED,
    STATUS_LABEL,
    RuleResult,
    RunResult,
)
from certkit.report.ci_formats import subpart
from certkit.report.display import format_value as format_number
from certkit.report.display import in_display_units, unit_and_factor
from certkit.report.figures import render_result
from certkit.report.links import ecfr_url, resolve, slug
from certkit.report.output import prepare_output, write_set
from certkit.report.pages import page_environment
from certkit.report.reasons import reason_condition, reason_line
from certkit.report.tables import formatted

#: order of the summary: what needs a reviewer first
STATUS_ORDER = {FAILS: 0, NOT_EVALUATED: 1, COMPLIES_PARTIAL: 2, COMPLIES: 3}
#: criterion bases that earn a rule a badge (the verdict may rest on them)
FLAGGED_BASES = {
    "unverified": "unverified criterion",
    "project": "project-chosen criterion",
    "override": "criterion overridden",
}
#: a paragraph of Part 25 cited in a text ("§25.335(a)", "14 CFR 25.1505"): only Part 25 links to its eCFR page or
#: rule (a textbook's "§16.3", Raymer's chapter, is not a CFR section)
_REFERENCE = re.compile(r"(§§?\s?|14 CFR\s|CFR\s)(25\.\d+[a-z]?(?:\([a-z0-9]+\))*)")
#: a shape beside each status colour (readable without colour vision)
STATUS_MARK = {FAILS: "✕", NOT_EVALUATED: "?", COMPLIES_PARTIAL: "◐", COMPLIES: "✓"}


def format_value(value, unit: str) -> str:
    """A number in the unit a reviewer reads (m/s → kn, m → ft, kg → lb, N → lbf, N·m → kN·m, rad → deg)."""
    if value is None:
        return "—"
    if abs(value) < 1e-9:  # round-off noise of a difference (5.551e-17 Mach) and -0 read 0
        value = 0.0
    shown, factor = unit_and_factor(unit or "")
    text = format_number(value / factor)
    return f"{text} {shown}" if shown not in ("", "1") and text != "—" else text


def margin_value(value, unit: str, limit) -> str:
    """A margin: round-off of a value sitting on its limit (within 1e-9 × |limit|) reads 0."""
    if value is not None and limit is not None and abs(value) <= 1e-9 * max(1.0, abs(limit)):
        value = 0.0
    return format_value(value, unit)


def _environment(rule_ids) -> Environment:
    env = page_environment({})
    env.filters["value"] = format_value
    env.filters["margin"] = margin_value
    env.filters["slug"] = slug
    env.filters["status"] = lambda status: STATUS_LABEL.get(status, status)
    env.filters["table"] = formatted
    env.filters["mark"] = lambda status: STATUS_MARK.get(status, "")
    env.filters["titled"] = titled_svg
    env.filters["shown_unit"] = lambda unit: {"": "no unit", "1": "no unit"}.get(unit or "", unit_and_factor(unit)[0])
    env.filters["pct"] = _pct
    env.filters["ecfr"] = ecfr_url
    env.filters["refs"] = lambda text: linkify(text, rule_ids)
    env.filters["finding_rows"] = lambda findings, critical: finding_rows(findings, critical, rule_ids)
    return env


#: what markupsafe's escape replaces, for str.translate (the same text, without a Markup object per number)
_ESCAPES = str.maketrans({"&": "&amp;", "<": "&lt;", ">": "&gt;", "'": "&#39;", '"': "&#34;"})


def _pct(x) -> str:
    return "—" if x is None else f"{100 * x:+.1f} %".replace("-0.0 %", "+0.0 %")


def finding_rows(findings, critical, rule_ids) -> Markup:
    """The rows of a findings table (condition, check, value, limit, margin, normalised margin, status, reason), the
    critical finding marked; a rule's findings share conditions and check texts, so each is written once."""
    labels: dict[int, str] = {}
    texts: dict[str | None, str] = {}

    def linked(text: str | None) -> str:
        out = texts.get(text)
        if out is None:
            out = texts[text] = str(linkify(text, rule_ids))
        return out

    rows = []
    for f in findings:
        label = labels.get(id(f.condition))
        if label is None:
            label = labels[id(f.condition)] = str(escape(f.condition.label()))
        unit, mark = f.unit, ' class="critical"' if f is critical else ""
        rows.append(
            f"<tr{mark}><td>{label}</td><td>{linked(f.check)}</td>\n"
            f'<td class="num">{format_value(f.value, unit).translate(_ESCAPES)}</td>'
            f'<td class="num">{format_value(f.limit, unit).translate(_ESCAPES)}</td>'
            f'<td class="num">{margin_value(f.margin, unit, f.limit).translate(_ESCAPES)}</td>\n'
            f'<td class="num">{_pct(f.normalized_margin)}</td><td class="{escape(f.status)}">'
            f"{escape(str(f.status).replace('_', ' '))}</td><td>{linked(f.reason)}</td></tr>\n"
        )
    return Markup("".join(rows))


def titled_svg(svg: str | None, title: str) -> Markup:
    """An inline SVG figure with an accessible name: ``role="img"``, ``aria-label`` and a ``<title>`` first child."""
    if not svg:
        return Markup("")
    start = svg.find("<svg")
    end = svg.find(">", start)
    if start < 0 or end < 0:
        return Markup(svg)
    name = str(escape(title))
    head = svg[start:end].rstrip("/")
    closing = "/>" if svg[end - 1] == "/" else ">"
    if closing == "/>":
        return Markup(svg)
    head = re.sub(r'\s(role|aria-label)="[^"]*"', "", head)
    return Markup(f'{svg[:start]}{head} role="img" aria-label="{name}"><title>{name}</title>{svg[end + 1 :]}')


def linkify(text, rule_ids) -> Markup:
    """``text`` escaped, each paragraph reference a link to its rule's section or its eCFR page."""

    def link(m):
        href, _ = resolve(m[2], rule_ids)
        external = "" if href.startswith("#") else ' class="ecfr" rel="noopener"'
        return f'<a href="{escape(href)}"{external}>{m[0]}</a>'

    return Markup(_REFERENCE.sub(link, str(escape("" if text is None else text))))


def _referenced_by(rules: list[type[Rule]]) -> dict[str, list[str]]:
    """Rule id → the ids of the rules whose references resolve to it (the report's "Referenced by")."""
    by_id = {r.id: r for r in rules}
    referenced_by: dict[str, list[str]] = {}
    for cls in rules:
        for ref in cls.references:
            _, target = resolve(ref, by_id)
            if target and target != cls.id and cls.id not in referenced_by.setdefault(target, []):
                referenced_by[target].append(cls.id)
    return referenced_by


def _section(result: RuleResult, by_id: dict[str, type[Rule]], referenced_by: dict[str, list[str]]) -> dict:
    """What the report shows of one rule (its section and its line in the triage table)."""
    cls = by_id[result.id]
    flags: dict[str, list[str]] = {}
    for name, c in cls.criteria.items():
        if c.basis in FLAGGED_BASES and name not in result.overrides:
            flags.setdefault(c.basis, []).append(f"{name}: {c.source}")
    for name, o in result.overrides.items():
        flags.setdefault("override", []).append(f"{name} {o['default']} → {o['value']}: {o['justification']}")
    return {
        "result": result,
        "rule": cls,
        "critical": result.critical,
        "subpart": subpart(result.id).upper(),
        "rank": STATUS_ORDER[result.status],
        "reason": reason_line(result),
        "where": reason_condition(result),
        "flags": {FLAGGED_BASES[k]: v for k, v in flags.items()},
        "requirement": _paragraphs(cls.requirement),
        "margin": in_display_units(_paragraphs(cls.margin)),
        "conditions": cls.conditions.describe(),
        "references": [{"id": ref, "href": resolve(ref, by_id)[0]} for ref in cls.references],
        "referenced_by": referenced_by.get(result.id, []),
        "criteria": [{"name": k, "criterion": c, "override": result.overrides.get(k)} for k, c in cls.criteria.items()],
    }


class ReportFinish:
    """The report's work on a rule's result where the rule was evaluated (a check's ``finish``,
    :func:`certkit.engine.scheduler.run`): its figures drawn and its HTML section rendered, in parallel with the other
    rules; the report then puts the sections together (the same page as rendering them there)."""

    def __init__(self, rules: list[type[Rule]]):
        self.rules = rules
        self._by_id: dict[str, type[Rule]] | None = None
        self._referenced_by: dict[str, list[str]] = {}
        self._env: Environment | None = None

    def __getstate__(self) -> dict:
        return {"rules": self.rules, "_by_id": None, "_referenced_by": {}, "_env": None}

    def section(self, result: RuleResult) -> dict:
        if self._by_id is None:
            self._by_id = {r.id: r for r in self.rules}
            self._referenced_by = _referenced_by(self.rules)
            self._env = _environment(self._by_id)
        return _section(result, self._by_id, self._referenced_by)

    def section_html(self, result: RuleResult, data: dict | None = None) -> str:
        data = self.section(result) if data is None else data
        assert self._env is not None
        return pack_tables(self._env.get_template("rule_section.html").render(s=data))

    def __call__(self, result: RuleResult) -> None:
        render_result(result)
        result.section = self.section_html(result)


def render_html(run: RunResult, rules: list[type[Rule]]) -> str:
    finish = ReportFinish(rules)
    sections = []
    for result in run.rules:
        render_result(result)  # figures not drawn yet (those drawn by the workers of a check are kept)
        data = finish.section(result)
        data["html"] = Markup(result.section if result.section is not None else finish.section_html(result, data))
        sections.append(data)
    order = sorted(
        sections,
        key=lambda s: (
            STATUS_ORDER[s["result"].status],
            s["critical"].normalized_margin
            if s["critical"] and s["critical"].normalized_margin is not None
            else float("inf"),
        ),
    )
    overrides = [(r.id, k, v) for r in run.rules for k, v in r.overrides.items()]
    return pack_tables(
        _environment({r.id: r for r in rules})
        .get_template("report.html")
        .render(
            run=run,
            summary=run.summary(),
            sections=sections,
            triage=order,
            overrides=overrides,
            subparts=sorted({s["subpart"] for s in sections}),
        )
    )


#: a table larger than this (bytes of HTML) is stored compressed in the report and drawn when shown
PACK_THRESHOLD = 8192
_TABLE_OPEN, _TABLE_CLOSE = '<div class="table-wrap"><table>', "</table></div>"


def pack_tables(html: str, threshold: int = PACK_THRESHOLD) -> str:
    """The report within its size budget without losing a finding: each table larger than ``threshold`` (the
    per-condition findings and evidence tables, up to 1,445 rows) becomes a zlib block (base64) in a
    ``<script type="application/x-certkit-table">`` that the page's script inflates (``DecompressionStream``) when
    its section is opened, and every block in the background after loading, so that search and print see them.
    Deterministic: the same report gives the same bytes."""

    def pack(table: str) -> str:
        if len(table) <= threshold:
            return table
        rows = table.count("<tr") - table.count("<thead><tr")
        data = base64.b64encode(zlib.compress(table.encode("utf-8"), 6)).decode("ascii")
        return (
            f'<div class="packed" data-rows="{rows}"><p class="meta packed-note">A table of {rows} rows, stored '
            "compressed in this file: it opens with its section<noscript> when scripts are enabled (every value "
            "is also in results.json)</noscript>.</p>"
            f'<script type="application/x-certkit-table">{data}</script></div>'
        )

    parts, at = [], 0
    while (start := html.find(_TABLE_OPEN, at)) >= 0:
        end = html.find(_TABLE_CLOSE, start)
        if end < 0:
            break
        end += len(_TABLE_CLOSE)
        parts += [html[at:start], pack(html[start:end])]
        at = end
    return "".join(parts) + html[at:]


def _paragraphs(text: str) -> str:
    return " ".join(inspect.cleandoc(text).split())


def write_report(run: RunResult, rules: list[type[Rule]], out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``results.json`` and ``index.html`` into ``out_dir`` as one set (:func:`certkit.report.output.write_set`:
    the previous set stays whole until the new one replaces it); return both paths."""
    out = Path(out_dir)
    texts = {"results.json": [*run.json_chunks(), "\n"], "index.html": render_html(run, rules)}
    write_set(prepare_output(out), texts)
    return out / "results.json", out / "index.html"


__all__ = ["ReportFinish", "render_html", "write_report", "format_value", "slug", "linkify"]

"""The HTML report: one self-contained folder (inline CSS and SVG) that opens offline.

Every string that comes from the aircraft file or a plugin is escaped (jinja2 autoescape); only
the SVG that matplotlib produced is inserted as markup, and its text is XML-escaped by matplotlib.
"""

from __future__ import annotations

import re
from pathlib import Path

from jinja2 import Environment, PackageLoader, select_autoescape

from certkit.registry import Rule
from certkit.report.figures import render_result
from certkit.report.output import prepare_output, write_set
from certkit.report.tables import formatted
from certkit.results import STATUS_LABEL, RunResult
from certkit.units import KN

#: display conversions for units used in findings (SI value → extra unit shown beside it)
DISPLAY = {"m/s": ("kn", KN), "m": ("ft", 0.3048), "kg": ("lb", 0.45359237), "N": ("lbf", 4.4482216152605)}


def format_value(value: float | None, unit: str) -> str:
    if value is None:
        return "—"
    if abs(value) < 1e-9:  # round-off noise of a difference (5.551e-17 Mach) and -0 read 0
        value = 0.0
    text = f"{value:.4g}" if abs(value) < 1e5 else f"{value:,.0f}"
    if unit in DISPLAY:
        other, factor = DISPLAY[unit]
        return f"{text} {unit} ({value / factor:.4g} {other})"
    return f"{text} {unit}".strip()


def slug(rule_id: str) -> str:
    return "r" + re.sub(r"[^0-9a-z]+", "-", rule_id.lower()).strip("-")


def _environment() -> Environment:
    env = Environment(loader=PackageLoader("certkit.report", "templates"), autoescape=select_autoescape(["html"]),
                      trim_blocks=True, lstrip_blocks=True)
    env.filters["value"] = format_value
    env.filters["slug"] = slug
    env.filters["status"] = lambda status: STATUS_LABEL.get(status, status)
    env.filters["table"] = formatted
    env.filters["pct"] = lambda x: "—" if x is None else f"{100 * x:+.1f} %"
    return env


def render_html(run: RunResult, rules: list[type[Rule]]) -> str:
    by_id = {r.id: r for r in rules}
    sections = []
    for result in run.rules:
        render_result(result)  # figures not drawn yet (those drawn by the workers of a check are kept)
        cls = by_id[result.id]
        crit = result.critical
        sections.append({
            "result": result, "rule": cls, "critical": crit,
            "requirement": _paragraphs(cls.requirement), "margin": _paragraphs(cls.margin),
            "conditions": cls.conditions.describe(),
            "references": [{"id": ref, "present": ref in by_id or any(k.startswith(ref + "(") for k in by_id),
                            "target": ref if ref in by_id else next((k for k in by_id if k.startswith(ref + "(")), ref)}
                           for ref in cls.references],
            "criteria": [{"name": k, "criterion": c, "override": result.overrides.get(k)} for k, c in cls.criteria.items()],
        })
    overrides = [(r.id, k, v) for r in run.rules for k, v in r.overrides.items()]
    return _environment().get_template("report.html").render(
        run=run, summary=run.summary(), sections=sections, overrides=overrides)


def _paragraphs(text: str) -> str:
    import inspect

    return " ".join(inspect.cleandoc(text).split())


def write_report(run: RunResult, rules: list[type[Rule]], out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``results.json`` and ``index.html`` into ``out_dir`` as one set (:func:`certkit.report.output.write_set`:
    the previous set stays whole until the new one replaces it); return both paths."""
    out = Path(out_dir)
    texts = {"results.json": run.to_json() + "\n", "index.html": render_html(run, rules)}
    write_set(prepare_output(out), texts)
    return out / "results.json", out / "index.html"


__all__ = ["render_html", "write_report", "format_value"]

"""``certkit check --output-format junit|sarif|github``: the run as a CI system reads it (as pytest and ruff do).

- ``junit``: JUnit XML (the Ant/Jenkins/pytest layout: ``testsuites`` > ``testsuite`` > ``testcase`` with
  ``failure`` or ``skipped``); one test case per rule, class name ``part25.subpart_<letter>``; a failing rule is a
  failure, a rule not evaluated is skipped with its reason; a rule that complies in part passes with its
  unevaluated sub-paragraphs in ``system-out``.
- ``sarif``: SARIF 2.1.0 (OASIS): one ``result`` per failing or unevaluated rule (``error`` / ``warning``; a rule
  complying in part is a ``note``) located in the aircraft file, the rules described in ``tool.driver.rules`` with
  their eCFR page as ``helpUri``.
- ``github``: GitHub Actions workflow commands (``::error file=…,title=…::message``), one per failing or
  unevaluated rule, so that the paragraphs show as annotations on the aircraft file.
"""

from __future__ import annotations

import json
from xml.sax.saxutils import escape, quoteattr

from certkit import __version__
from certkit.report.links import ecfr_url
from certkit.report.reasons import margin_text, reason_line
from certkit.engine.results import COMPLIES_PARTIAL, FAILS, NOT_EVALUATED, RunResult

FORMATS = ("junit", "sarif", "github")
#: first section of each subpart of Part 25 (A 25.1, B 25.21, C 25.301, D 25.601, E 25.901, F 25.1301, G 25.1501)
_SUBPARTS = ((1501, "g"), (1301, "f"), (901, "e"), (601, "d"), (301, "c"), (21, "b"), (0, "a"))


def message(result) -> str:
    """One line saying why a rule has its status (:func:`certkit.report.reasons.reason_line`)."""
    return f"§{result.id} {result.title}: {reason_line(result)}"


def subpart(rule_id: str) -> str:
    """The Part 25 subpart (letter) of a paragraph, from its section number."""
    number = int(rule_id.split(".")[1].split("(")[0].rstrip("abcdefghijklmnopqrstuvwxyz"))
    return next(letter for first, letter in _SUBPARTS if number >= first)


def junit(run: RunResult) -> str:
    cases = []
    counts = {"failures": 0, "skipped": 0}
    for r in run.rules:
        t = f"{r.seconds:.3f}" if r.seconds is not None else "0"
        head = (f"    <testcase classname={quoteattr('part25.subpart_' + subpart(r.id))} "
                f"name={quoteattr('§' + r.id + ' ' + r.title)} time=\"{t}\"")
        text = message(r)
        if r.status == FAILS:
            counts["failures"] += 1
            cases.append(f"{head}>\n      <failure message={quoteattr(text)} type=\"fails\">{escape(_failed_lines(r))}"
                         f"</failure>\n    </testcase>")
        elif r.status == NOT_EVALUATED:
            counts["skipped"] += 1
            cases.append(f"{head}>\n      <skipped message={quoteattr(text)}/>\n    </testcase>")
        elif r.status == COMPLIES_PARTIAL:
            cases.append(f"{head}>\n      <system-out>{escape(text)}</system-out>\n    </testcase>")
        else:
            cases.append(f"{head}/>")
    total = sum(r.seconds or 0.0 for r in run.rules)
    suite = (f"  <testsuite name={quoteattr('certkit ' + run.aircraft_name)} tests=\"{len(run.rules)}\" "
             f"failures=\"{counts['failures']}\" errors=\"0\" skipped=\"{counts['skipped']}\" time=\"{total:.3f}\">")
    return ("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<testsuites>\n" + suite + "\n" + "\n".join(cases)
            + "\n  </testsuite>\n</testsuites>\n")


def _failed_lines(result) -> str:
    return "\n".join(f"{f.check} at {f.condition.label()}: margin {margin_text(f.margin, f.unit)}"
                     for f in result.findings if f.status == FAILS)


_LEVEL = {FAILS: "error", NOT_EVALUATED: "warning", COMPLIES_PARTIAL: "note"}


def artifact_path(path: str) -> str:
    """The aircraft file as CI annotations locate it: relative to the working folder (the repository root in CI)
    when it lies below it, with forward slashes."""
    import os

    rel = os.path.relpath(os.path.abspath(path))
    return (path if rel.startswith("..") else rel).replace(os.sep, "/")


def sarif(run: RunResult) -> str:
    uri = artifact_path(run.source_path)
    results = [{"ruleId": r.id, "level": _LEVEL[r.status], "message": {"text": message(r)},
                "locations": [{"physicalLocation": {"artifactLocation": {"uri": uri},
                                                    "region": {"startLine": 1}}}],
                "properties": {"status": r.status}}
               for r in run.rules if r.status in _LEVEL]
    rules = [{"id": r.id, "name": r.symbol, "shortDescription": {"text": r.title}, "helpUri": ecfr_url(r.id),
              "properties": {"implementation": r.implementation}} for r in run.rules]
    log = {"$schema": "https://json.schemastore.org/sarif-2.1.0.json", "version": "2.1.0",
           "runs": [{"tool": {"driver": {"name": "certkit", "version": __version__,
                                         "informationUri": "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25",
                                         "rules": rules}},
                     "artifacts": [{"location": {"uri": uri}}], "results": results}]}
    return json.dumps(log, indent=2, ensure_ascii=False) + "\n"


STATUS_WORD = {FAILS: "fails", NOT_EVALUATED: "not evaluated", COMPLIES_PARTIAL: "complies in part"}


def github(run: RunResult) -> str:
    kind = {FAILS: "error", NOT_EVALUATED: "warning", COMPLIES_PARTIAL: "notice"}
    lines = []
    for r in run.rules:
        if r.status in kind:
            lines.append(f"::{kind[r.status]} file={_gh_property(artifact_path(run.source_path))},line=1,"
                         f"title={_gh_property('§' + r.id + ' ' + STATUS_WORD[r.status])}::{_gh_data(message(r))}")
    return "\n".join(lines) + ("\n" if lines else "")


def _gh_data(text: str) -> str:
    """Escaping of a workflow command's message (GitHub's toolkit: %, CR, LF)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _gh_property(text: str) -> str:
    """Escaping of a workflow command's property value (also : and ,)."""
    return _gh_data(text).replace(":", "%3A").replace(",", "%2C")


def render(fmt: str, run: RunResult) -> str:
    return {"junit": junit, "sarif": sarif, "github": github}[fmt](run)

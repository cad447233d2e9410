"""``certkit check --output-format junit|sarif|github``: the run as a CI system reads it (as pytest and ruff do).

- ``junit``: JUnit XML (the Ant/Jenkins/pytest layout: ``testsuites`` > ``testsuite`` > ``testcase`` with
  ``failure`` or ``skipped``); one test case per rule, class name ``part25.subpart_<letter>``; a failing rule is a
  failure, a rule not evaluated or complying only in part is skipped with its reason — so ``failures`` > 0 exactly
  when certkit exits 1 and ``skipped`` > 0 when it exits 3; the exit code is a property of the suite.
- ``sarif``: SARIF 2.1.0 (OASIS): one ``result`` per failing or unevaluated rule (``error`` / ``warning``; a rule
  complying in part is a ``note``), the rules described in ``tool.driver.rules`` with their eCFR page as
  ``helpUri``, the exit code in ``invocations``.
- ``github``: GitHub Actions workflow commands (``::error file=…,line=…,title=…::message``), one per failing or
  unevaluated rule, so that the paragraphs show as annotations on the aircraft file.

Each result is located at the line of the aircraft file holding the datum it depends on (:func:`datum_lines`): an
overridden criterion (``criteria.<rule>.values.<name>``) first, then the inputs the rule requires (a missing one at
its parent section); line 1 only when the rule names nothing in the file. Paths are relative to the working folder.
"""

from __future__ import annotations

import json
import os
from urllib.parse import quote
from xml.sax.saxutils import escape, quoteattr

from certkit import __version__
from certkit.engine.results import COMPLIES_PARTIAL, FAILS, NOT_EVALUATED, RunResult
from certkit.report.links import ecfr_url
from certkit.report.reasons import margin_text, reason_line

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


def junit(run: RunResult, lines: dict | None = None) -> str:
    cases = []
    counts = {"failures": 0, "skipped": 0}
    uri = artifact_path(run.source_path)
    for r in run.rules:
        t = f"{r.seconds:.3f}" if r.seconds is not None else "0"
        head = (
            f"    <testcase classname={quoteattr('part25.subpart_' + subpart(r.id))} "
            f'name={quoteattr("§" + r.id + " " + r.title)} time="{t}" file={quoteattr(uri)} '
            f'line="{_primary(lines, r.id)[1]}"'
        )
        text = message(r)
        if r.status == FAILS:
            counts["failures"] += 1
            cases.append(
                f'{head}>\n      <failure message={quoteattr(text)} type="fails">{escape(_failed_lines(r))}'
                f"</failure>\n    </testcase>"
            )
        elif r.status in (NOT_EVALUATED, COMPLIES_PARTIAL):  # certkit exits 3 for either: not a pass
            counts["skipped"] += 1
            word = STATUS_WORD[r.status]
            cases.append(
                f"{head}>\n      <skipped message={quoteattr(word + ': ' + text)}/>\n"
                f"      <system-out>{escape(text)}</system-out>\n    </testcase>"
            )
        else:
            cases.append(f"{head}/>")
    total = sum(r.seconds or 0.0 for r in run.rules)
    suite = (
        f'  <testsuite name={quoteattr("certkit " + run.aircraft_name)} tests="{len(run.rules)}" '
        f'failures="{counts["failures"]}" errors="0" skipped="{counts["skipped"]}" time="{total:.3f}">\n'
        f'    <properties>\n      <property name="exit_code" value="{run.exit_code()}"/>\n'
        f"    </properties>"
    )
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n<testsuites>\n'
        + suite
        + "\n"
        + "\n".join(cases)
        + "\n  </testsuite>\n</testsuites>\n"
    )


def _failed_lines(result) -> str:
    return "\n".join(
        f"{f.check} at {f.condition.label()}: margin {margin_text(f.margin, f.unit)}"
        for f in result.findings
        if f.status == FAILS
    )


_LEVEL = {FAILS: "error", NOT_EVALUATED: "warning", COMPLIES_PARTIAL: "note"}


def artifact_path(path: str) -> str:
    """The aircraft file as CI annotations locate it: relative to the working folder (the repository root in CI),
    ``../`` included when it lies beside it, with forward slashes; absolute only on another drive (Windows)."""
    try:
        rel = os.path.relpath(os.path.abspath(path))
    except ValueError:
        rel = os.path.abspath(path)
    return rel.replace(os.sep, "/")


def datum_lines(source, rule_classes, rules) -> dict[str, list[tuple[str, int]]]:
    """Per rule id, the (YAML path, line) of the data its results depend on, most specific first: each overridden
    criterion, then each input the rule requires that the file lacks (at its parent section's line), then the ones
    it has. ``source`` is the file's :class:`~certkit.aircraft.yaml_source.YamlSource`."""
    requires = {c.id: tuple(getattr(c, "requires", ())) for c in rule_classes}
    out = {}
    for r in rules:
        locs = [(f"criteria.{r.id}.values.{name}", ("criteria", r.id, "values", name)) for name in r.overrides]
        needed = [(p, tuple(int(k) if k.isdigit() else k for k in p.split("."))) for p in requires.get(r.id, ())]
        locs += [n for n in needed if n[1] not in source.lines] + [n for n in needed if n[1] in source.lines]
        out[r.id] = [(path, source.line_of(loc) or 1) for path, loc in locs]
    return out


def _primary(lines: dict | None, rule_id: str) -> tuple[str, int]:
    found = (lines or {}).get(rule_id)
    return found[0] if found else ("", 1)


def _location(uri: str, path: str, line: int, index: int | None = None) -> dict:
    loc = {"physicalLocation": {"artifactLocation": {"uri": uri}, "region": {"startLine": line}}}
    if path:
        loc["message"] = {"text": path}
    if index is not None:
        loc["id"] = index
    return loc


def sarif(run: RunResult, lines: dict | None = None) -> str:
    uri = quote(artifact_path(run.source_path), safe="/:")
    results = []
    for r in run.rules:
        if r.status not in _LEVEL:
            continue
        found = (lines or {}).get(r.id) or [("", 1)]
        result = {
            "ruleId": r.id,
            "level": _LEVEL[r.status],
            "message": {"text": message(r)},
            "locations": [_location(uri, *found[0])],
            "properties": {"status": r.status},
        }
        if len(found) > 1:
            result["relatedLocations"] = [_location(uri, p, n, i) for i, (p, n) in enumerate(found[1:])]
        results.append(result)
    rules = [
        {
            "id": r.id,
            "name": r.symbol,
            "shortDescription": {"text": r.title},
            "helpUri": ecfr_url(r.id),
            "properties": {"implementation": r.implementation},
        }
        for r in run.rules
    ]
    log = {
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "certkit",
                        "version": __version__,
                        "informationUri": "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25",
                        "rules": rules,
                    }
                },
                "invocations": [{"executionSuccessful": True, "exitCode": run.exit_code()}],
                "artifacts": [{"location": {"uri": uri}}],
                "results": results,
            }
        ],
    }
    return json.dumps(log, indent=2, ensure_ascii=False) + "\n"


STATUS_WORD = {FAILS: "fails", NOT_EVALUATED: "not evaluated", COMPLIES_PARTIAL: "complies in part"}


def github(run: RunResult, lines: dict | None = None) -> str:
    kind = {FAILS: "error", NOT_EVALUATED: "warning", COMPLIES_PARTIAL: "notice"}
    out = []
    for r in run.rules:
        if r.status in kind:
            out.append(
                f"::{kind[r.status]} file={_gh_property(artifact_path(run.source_path))},"
                f"line={_primary(lines, r.id)[1]},"
                f"title={_gh_property('§' + r.id + ' ' + STATUS_WORD[r.status])}::{_gh_data(message(r))}"
            )
    return "\n".join(out) + ("\n" if out else "")


def _gh_data(text: str) -> str:
    """Escaping of a workflow command's message (GitHub's toolkit: %, CR, LF)."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def _gh_property(text: str) -> str:
    """Escaping of a workflow command's property value (also : and ,)."""
    return _gh_data(text).replace(":", "%3A").replace(",", "%2C")


def render(fmt: str, run: RunResult, lines: dict | None = None) -> str:
    """The run in ``fmt``; ``lines`` (:func:`datum_lines`) locates each rule in the aircraft file (else line 1)."""
    return {"junit": junit, "sarif": sarif, "github": github}[fmt](run, lines)

"""--output-format junit|sarif|github: JUnit XML with the structure of the Ant/Jenkins JUnit schema, SARIF valid
against the SARIF 2.1.0 constraints (tests/report/sarif-2.1.0-subset.schema.json, written from the OASIS
standard's text), GitHub workflow commands as GitHub's toolkit writes them."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from jsonschema import Draft202012Validator, FormatChecker

from certkit.report.ci_formats import subpart
from certkit.report.links import ecfr_url
from tests.conftest import BASELINE, ROOT
from tests.report.report_run import SELECTION, results

#: Ant/Jenkins JUnit XML (the junit-10.xsd of the Jenkins xunit plugin, as pytest writes it): element → (required
#: attributes, allowed attributes, allowed children)
JUNIT = {
    "testsuites": (set(), {"name", "tests", "failures", "errors", "skipped", "time", "disabled"}, {"testsuite"}),
    "testsuite": ({"name", "tests", "failures", "errors"},
                  {"name", "tests", "failures", "errors", "skipped", "time", "timestamp", "hostname", "id", "package",
                   "disabled"}, {"testcase", "properties", "system-out", "system-err"}),
    "testcase": ({"name", "classname"}, {"name", "classname", "time", "assertions", "status", "file", "line"},
                 {"skipped", "error", "failure", "system-out", "system-err", "properties"}),
    "failure": (set(), {"message", "type"}, set()),
    "skipped": (set(), {"message"}, set()),
    "system-out": (set(), set(), set()),
}


def _junit_problems(element, path="") -> list[str]:
    where = f"{path}/{element.tag}"
    if element.tag not in JUNIT:
        return [f"{where}: element not in the JUnit schema"]
    required, allowed, children = JUNIT[element.tag]
    out = [f"{where}: missing attribute {a}" for a in required - set(element.attrib)]
    out += [f"{where}: attribute {a} not in the schema" for a in set(element.attrib) - allowed]
    for a in ("tests", "failures", "errors", "skipped"):
        if a in element.attrib and not element.attrib[a].isdigit():
            out.append(f"{where}: {a}={element.attrib[a]!r} is not a count")
    if "time" in element.attrib and not re.fullmatch(r"\d+(\.\d+)?", element.attrib["time"]):
        out.append(f"{where}: time={element.attrib['time']!r} is not a decimal")
    if element.tag == "testcase" and len([c for c in element if c.tag in ("skipped", "error", "failure")]) > 1:
        out.append(f"{where}: more than one outcome")
    for child in element:
        if child.tag not in children:
            out.append(f"{where}: child {child.tag} not allowed")
        out += _junit_problems(child, where)
    return out


def _output(folder: Path, fmt: str) -> tuple[str, int]:
    proc = subprocess.run([sys.executable, "-m", "certkit.cli", "check", str(BASELINE), "--out", str(folder),
                           "--select", SELECTION, "--output-format", fmt], capture_output=True, text=True, cwd=ROOT)
    return proc.stdout, proc.returncode


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ci")
    return {fmt: _output(folder, fmt) for fmt in ("junit", "sarif", "github")}, results(folder)


def test_junit_follows_the_schema_and_counts_the_statuses(outputs):
    (text, code), data = outputs[0]["junit"], outputs[1]
    root = ET.fromstring(text)
    assert _junit_problems(root) == []
    suite = root.find("testsuite")
    s = data["summary"]
    assert int(suite.get("tests")) == s["rules"] and int(suite.get("failures")) == s["fails"]
    assert int(suite.get("skipped")) == s["not_evaluated"]
    failed = [c.get("name") for c in suite if c.find("failure") is not None]
    assert failed == [f"§{r['id']} {r['title']}" for r in data["rules"] if r["status"] == "fails"]
    assert code == 1


def test_junit_checker_can_fail():
    bad = ET.fromstring('<testsuites><testsuite name="x" tests="a" failures="0"><testcase name="n">'
                        '<failure/><skipped/></testcase><bogus/></testsuite></testsuites>')
    problems = "\n".join(_junit_problems(bad))
    for expected in ("missing attribute errors", "tests='a'", "missing attribute classname", "more than one outcome",
                     "child bogus"):
        assert expected in problems


def test_sarif_is_valid_and_names_the_failing_paragraphs(outputs):
    (text, code), data = outputs[0]["sarif"], outputs[1]
    log = json.loads(text)
    schema = json.loads((Path(__file__).parent / "sarif-2.1.0-subset.schema.json").read_text())
    errors = list(Draft202012Validator(schema, format_checker=FormatChecker()).iter_errors(log))
    assert not errors, [e.message for e in errors]
    by_rule = {r["ruleId"]: r for r in log["runs"][0]["results"]}
    for r in data["rules"]:
        expected = {"fails": "error", "not_evaluated": "warning", "complies_partial": "note"}.get(r["status"])
        assert (by_rule[r["id"]]["level"] if r["id"] in by_rule else None) == expected
    helps = {d["id"]: d["helpUri"] for d in log["runs"][0]["tool"]["driver"]["rules"]}
    assert helps["25.121(b)"].endswith("/part-25/section-25.121#p-25.121(b)")
    assert code == 1


def test_github_annotations(outputs):
    (text, _), data = outputs[0]["github"], outputs[1]
    lines = text.splitlines()
    pattern = re.compile(r"^::(error|warning|notice) file=aircraft/lta\.yaml,line=1,title=[^:,\n]+::[^\n]+$")
    assert lines and all(pattern.match(ln) for ln in lines), lines
    errors = [ln for ln in lines if ln.startswith("::error")]
    assert len(errors) == data["summary"]["fails"]
    assert all("%3A" not in ln.split("::")[2] for ln in lines)  # messages keep their colons (only properties escape)


def test_subparts_and_ecfr_links():
    assert [subpart(p) for p in ("25.21", "25.181", "25.255", "25.301", "25.581", "25.601", "25.1309")] == \
        ["b", "b", "b", "c", "c", "d", "f"]
    assert ecfr_url("25.121(b)") == ("https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/"
                                     "section-25.121#p-25.121(b)")
    assert ecfr_url("25.337") == "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/section-25.337"

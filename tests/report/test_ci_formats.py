"""--output-format junit|sarif|github: JUnit XML with the structure of the Ant/Jenkins JUnit schema, SARIF valid
against the official SARIF 2.1.0 JSON schema (tests/report/sarif-schema-2.1.0.json: OASIS SARIF TC,
github.com/oasis-tcs/sarif-spec, sarif-2.1/schema/sarif-schema-2.1.0.json at commit e0583813, the errata01 schema),
GitHub workflow commands as GitHub's toolkit writes them; each result located at the YAML line of its datum."""

from __future__ import annotations

import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from jsonschema import Draft4Validator, FormatChecker

from certkit.report.ci_formats import subpart
from certkit.report.links import ecfr_url
from tests.conftest import BASELINE, ROOT
from tests.report.report_run import SELECTION, results

#: Ant/Jenkins JUnit XML (the junit-10.xsd of the Jenkins xunit plugin, as pytest writes it): element → (required
#: attributes, allowed attributes, allowed children)
JUNIT = {
    "testsuites": (set(), {"name", "tests", "failures", "errors", "skipped", "time", "disabled"}, {"testsuite"}),
    "testsuite": (
        {"name", "tests", "failures", "errors"},
        {
            "name",
            "tests",
            "failures",
            "errors",
            "skipped",
            "time",
            "timestamp",
            "hostname",
            "id",
            "package",
            "disabled",
        },
        {"testcase", "properties", "system-out", "system-err"},
    ),
    "testcase": (
        {"name", "classname"},
        {"name", "classname", "time", "assertions", "status", "file", "line"},
        {"skipped", "error", "failure", "system-out", "system-err", "properties"},
    ),
    "properties": (set(), set(), {"property"}),
    "property": ({"name", "value"}, {"name", "value"}, set()),
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
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "check",
            str(BASELINE),
            "--out",
            str(folder),
            "--select",
            SELECTION,
            "--output-format",
            fmt,
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
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
    assert int(suite.get("skipped")) == s["not_evaluated"] + s["complies_partial"]  # both make certkit exit 3
    assert suite.find("properties/property[@name='exit_code']").get("value") == str(code)
    assert all(c.get("file") == "aircraft/lta.yaml" and int(c.get("line")) >= 1 for c in suite.iter("testcase"))
    failed = [c.get("name") for c in suite if c.find("failure") is not None]
    assert failed == [f"§{r['id']} {r['title']}" for r in data["rules"] if r["status"] == "fails"]
    assert code == 1


def test_junit_checker_can_fail():
    bad = ET.fromstring(
        '<testsuites><testsuite name="x" tests="a" failures="0"><testcase name="n">'
        "<failure/><skipped/></testcase><bogus/></testsuite></testsuites>"
    )
    problems = "\n".join(_junit_problems(bad))
    for expected in (
        "missing attribute errors",
        "tests='a'",
        "missing attribute classname",
        "more than one outcome",
        "child bogus",
    ):
        assert expected in problems


def test_sarif_is_valid_and_names_the_failing_paragraphs(outputs):
    (text, code), data = outputs[0]["sarif"], outputs[1]
    log = json.loads(text)
    schema = json.loads((Path(__file__).parent / "sarif-schema-2.1.0.json").read_text())
    errors = list(Draft4Validator(schema, format_checker=FormatChecker()).iter_errors(log))
    assert not errors, [e.message for e in errors]
    by_rule = {r["ruleId"]: r for r in log["runs"][0]["results"]}
    for r in data["rules"]:
        expected = {"fails": "error", "not_evaluated": "warning", "complies_partial": "note"}.get(r["status"])
        assert (by_rule[r["id"]]["level"] if r["id"] in by_rule else None) == expected
    helps = {d["id"]: d["helpUri"] for d in log["runs"][0]["tool"]["driver"]["rules"]}
    assert helps["25.121(b)"].endswith("/part-25/section-25.121#p-25.121(b)")
    assert log["runs"][0]["invocations"][0]["exitCode"] == code == 1
    assert all(r["locations"][0]["physicalLocation"]["region"]["startLine"] > 1 for r in log["runs"][0]["results"])


def test_github_annotations(outputs):
    (text, _), data = outputs[0]["github"], outputs[1]
    lines = text.splitlines()
    pattern = re.compile(r"^::(error|warning|notice) file=aircraft/lta\.yaml,line=\d+,title=[^:,\n]+::[^\n]+$")
    assert lines and all(pattern.match(ln) for ln in lines), lines
    errors = [ln for ln in lines if ln.startswith("::error")]
    assert len(errors) == data["summary"]["fails"]
    assert all("%3A" not in ln.split("::")[2] for ln in lines)  # messages keep their colons (only properties escape)


def test_subparts_and_ecfr_links():
    assert [subpart(p) for p in ("25.21", "25.181", "25.255", "25.301", "25.581", "25.601", "25.1309")] == [
        "b",
        "b",
        "b",
        "c",
        "c",
        "d",
        "f",
    ]
    assert ecfr_url("25.121(b)") == (
        "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/section-25.121#p-25.121(b)"
    )
    assert ecfr_url("25.337") == "https://www.ecfr.gov/current/title-14/chapter-I/subchapter-C/part-25/section-25.337"


def test_the_schema_check_can_fail():
    schema = json.loads((Path(__file__).parent / "sarif-schema-2.1.0.json").read_text())
    bad = {
        "version": "2.1.0",
        "runs": [
            {
                "tool": {"driver": {"name": "certkit"}},
                "results": [
                    {
                        "ruleId": "25.335(a)",
                        "level": "fatal",
                        "message": {"text": "x"},
                        "locations": [{"physicalLocation": {"region": {"startLine": 0}}}],
                    }
                ],
            }
        ],
    }
    messages = " ".join(e.message for e in Draft4Validator(schema).iter_errors(bad))
    assert "'fatal' is not one of" in messages and "0 is less than the minimum of 1" in messages


#: a line-number fixture: the baseline with a criterion override appended at known lines, a required speed removed
OVERRIDE = """
criteria:
  "25.335(a)":
    justification: a stricter gust allowance for a line-number test
    values:
      gust_factor: 1.40
"""


@pytest.fixture(scope="module")
def located(tmp_path_factory):
    folder = tmp_path_factory.mktemp("located")
    text = BASELINE.read_text(encoding="utf-8")
    assert "\ncriteria:" not in text
    text = text.rstrip("\n") + "\n" + OVERRIDE
    override_line = text.splitlines().index("      gust_factor: 1.40") + 1
    vd_line = next(i for i, ln in enumerate(text.splitlines(), 1) if ln.startswith("  VD:"))
    speeds_line = next(i for i, ln in enumerate(text.splitlines(), 1) if ln.startswith("speeds:"))
    text = text.replace(text.splitlines()[vd_line - 1] + "\n", "  # VD removed\n")
    (folder / "sub").mkdir()
    aircraft = folder / "aircraft.yaml"
    aircraft.write_text(text, encoding="utf-8")
    out = {}
    for fmt in ("sarif", "github", "junit"):
        proc = subprocess.run(
            [
                sys.executable,
                "-m",
                "certkit.cli",
                "check",
                str(aircraft),
                "--out",
                str(folder / fmt),
                "--select",
                "25.335(a),25.335(b),25.335(c)",
                "--output-format",
                fmt,
                "-j",
                "1",
            ],
            capture_output=True,
            text=True,
            cwd=folder / "sub",
        )
        assert proc.returncode in (1, 3), proc.stderr
        out[fmt] = proc.stdout
    return out, override_line, speeds_line


def test_sarif_locates_the_override_and_the_missing_input(located):
    out, override_line, speeds_line = located
    log = json.loads(out["sarif"])
    by_rule = {r["ruleId"]: r for r in log["runs"][0]["results"]}
    primary = by_rule["25.335(a)"]["locations"][0]
    assert primary["physicalLocation"]["region"]["startLine"] == override_line
    assert primary["message"]["text"] == "criteria.25.335(a).values.gust_factor"
    related = {
        loc["message"]["text"]: loc["physicalLocation"]["region"]["startLine"]
        for loc in by_rule["25.335(a)"].get("relatedLocations", [])
    }
    assert set(related) == {"speeds.VC", "speeds.VB"}
    # §25.335(b) needs VD, which the file lacks: located at the speeds section
    assert by_rule["25.335(b)"]["locations"][0]["physicalLocation"]["region"]["startLine"] == speeds_line
    uris = {loc["physicalLocation"]["artifactLocation"]["uri"] for r in by_rule.values() for loc in r["locations"]}
    assert uris == {"../aircraft.yaml"}  # relative to the working folder, even outside it


def test_github_and_junit_use_the_same_lines(located):
    out, override_line, speeds_line = located
    lines = {m[2]: int(m[1]) for m in re.finditer(r"line=(\d+),title=§(\S+)", out["github"])}
    assert lines["25.335(a)"] == override_line and lines["25.335(b)"] == speeds_line
    assert "file=../aircraft.yaml," in out["github"]
    cases = {c.get("name").split()[0]: c for c in ET.fromstring(out["junit"]).iter("testcase")}
    assert int(cases["§25.335(a)"].get("line")) == override_line
    assert int(cases["§25.335(b)"].get("line")) == speeds_line

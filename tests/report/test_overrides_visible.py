"""An overridden criterion is visible wherever a verdict is read: the check text states the value in force, the
criterion's basis is "override" in results.json (with the rule's default beside it), the terminal table and the
report's summary carry a badge, and `certkit diff` names the changed criterion and input by YAML path before the
margins, in status words and units.

Reference: the override mechanism's own contract (criteria.<rule>.values.<name> in the aircraft file) and
14 CFR 25.335(a)(2) (VC ≥ VB + 1.32 U_ref) for the default that the override replaces. No margin is pinned.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from certkit.engine.scheduler import check_in_force
from tests.conftest import BASELINE, ROOT

OVERRIDE = """
criteria:
  "25.335(a)":
    justification: a stricter gust allowance
    values:
      gust_factor: 1.40
"""


def test_check_text_takes_the_value_in_force():
    o = {"gust_factor": {"default": 1.32, "value": 1.4, "justification": "x"}}
    assert check_in_force("(a)(2) VC ≥ VB + 1.32 U_ref", o) == "(a)(2) VC ≥ VB + 1.4 U_ref"
    assert check_in_force("(a)(2) VC ≥ VB + 11.32 U_ref", o) == "(a)(2) VC ≥ VB + 11.32 U_ref"  # another number
    two = {"n": {"default": 2, "value": 3, "justification": "x"}}
    assert check_in_force("(a)(2) n ≥ 2 g", two) == "(a)(2) n ≥ 3 g"  # a paragraph label is not the number


def _check(folder, aircraft, fmt="text"):
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "check",
            str(aircraft),
            "--out",
            str(folder),
            "--select",
            "25.335(a)",
            "-j",
            "1",
            "--output-format",
            fmt,
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert proc.returncode in (0, 1, 3), proc.stderr
    return proc.stdout


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("overrides")
    aircraft = folder / "overridden.yaml"
    aircraft.write_text(BASELINE.read_text(encoding="utf-8").rstrip("\n") + "\n" + OVERRIDE, encoding="utf-8")
    base_text = _check(folder / "base", BASELINE)
    over_text = _check(folder / "over", aircraft)
    return folder, base_text, over_text


def test_results_json_names_the_override(runs):
    folder, _, _ = runs
    data = json.loads((folder / "over" / "results.json").read_text())
    (rule,) = data["rules"]
    c = rule["criteria"]["gust_factor"]
    assert (c["basis"], c["value"], c["default"], c["default_basis"]) == ("override", 1.4, 1.32, "regulation")
    assert c["justification"] == "a stricter gust allowance" and c["overridden"] is True
    checks = {f["check"] for f in rule["findings"] if "U_ref" in f["check"]}
    assert checks == {"(a)(2) VC ≥ VB + 1.4 U_ref"}
    assert all(
        f["details"]["check_default"] == "(a)(2) VC ≥ VB + 1.32 U_ref"
        for f in rule["findings"]
        if "U_ref" in f["check"]
    )
    base = json.loads((folder / "base" / "results.json").read_text())
    assert base["rules"][0]["criteria"]["gust_factor"]["basis"] == "regulation"
    assert "1.32 U_ref" in json.dumps(base["rules"][0]["findings"])


def test_terminal_and_report_show_a_badge(runs):
    folder, base_text, over_text = runs
    assert "[override]" in over_text and "[override]" not in base_text
    html = (folder / "over" / "index.html").read_text()
    summary = html[html.index('id="summary"') : html.index('id="rules"')]
    assert 'title="gust_factor 1.32 → 1.4: a stricter gust allowance">criterion overridden</span>' in summary
    assert "override (default: regulation)" in html
    assert "gust_factor 1.32 →" not in (folder / "base" / "index.html").read_text()


def test_diff_names_the_criterion_and_the_input_before_the_margins(runs):
    folder, _, _ = runs
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "diff",
            str(folder / "base" / "results.json"),
            str(folder / "over" / "results.json"),
            "--html",
            str(folder / "d.html"),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert proc.returncode in (0, 1), proc.stderr
    out = proc.stdout
    assert "criteria.25.335(a).values.gust_factor: 1.32 → 1.4" in out
    inputs = out.index("inputs changed:")
    assert "criteria.25.335(a).values.gust_factor: absent → 1.4" in out[inputs:]
    assert "criteria.25.335(a).justification: absent → a stricter gust allowance" in out
    if "§25.335(a)" in out:  # the margins moved: listed after what was changed
        assert out.index("§25.335(a)") > inputs
    assert not re.search(r"\b(complies_partial|not_evaluated)\b", out)
    assert "appeared" not in out and "absent → complies" not in out  # the findings pair across the override
    html = (folder / "d.html").read_text()
    assert "criteria.25.335(a).values.gust_factor" in html and "complies_partial" not in html


def test_diff_prints_a_round_off_margin_as_zero():
    from certkit.report.reasons import margin_text

    assert margin_text(5.551e-17, "Mach") == "+0 Mach"
    assert margin_text(-2.0e-3, "Mach") == "-0.002000 Mach"


def test_an_override_the_check_text_does_not_show_is_named_after_it():
    """A criterion the check's words do not write as a number (the factor of safety of a loads check, a damping
    minimum) is named after the text of every computed finding, so the verdict never reads as the regulation's."""
    o = {
        "ultimate_factor": {"default": 1.5, "value": 1.65, "unit": "", "justification": "x"},
        "gust_factor": {"default": 1.32, "value": 1.4, "unit": "", "justification": "x"},
    }
    text = "(a) discrete gust, up, wing: ultimate bending at side of body (max)"
    assert check_in_force(text, o, name_the_rest=True) == text + " [override: ultimate_factor 1.65, gust_factor 1.4]"
    assert check_in_force(text, o) == text  # not-evaluated rows keep their words
    shown = check_in_force("(a)(2) VC ≥ VB + 1.32 U_ref", o, name_the_rest=True)
    assert shown == "(a)(2) VC ≥ VB + 1.4 U_ref [override: ultimate_factor 1.65]"
    speed = {"max_hold": {"default": 5.0, "value": 4.0, "unit": "s", "justification": "x"}}
    assert check_in_force("held input", speed, name_the_rest=True) == "held input [override: max_hold 4 s]"


def test_every_overridden_criterion_shows_in_the_checks_it_computes(tmp_path):
    """Each numeric criterion of §25.335(a) overridden in turn (to 1.1 × its default): every computed finding's
    text states the value in force, in its words or after them."""
    from certkit.aircraft import load_aircraft
    from certkit.engine.context import Context
    from certkit.engine.registry import discover
    from certkit.engine.scheduler import evaluate_rule

    (rule,) = [r for r in discover() if r.id == "25.335(a)"]
    for name, c in rule.criteria.items():
        if isinstance(c.value, bool) or not isinstance(c.value, (int, float)) or c.value == 0:
            continue
        value = round(1.1 * c.value, 6)
        path = tmp_path / f"{name}.yaml"
        path.write_text(
            BASELINE.read_text()
            + '\ncriteria:\n  "25.335(a)":\n    justification: a test of the override text\n'
            + f"    values:\n      {name}: {value}\n"
        )
        res = evaluate_rule(rule, Context(load_aircraft(path)))
        computed = [f for f in res.findings if f.margin is not None]
        assert computed and all(f"{value:g}" in f.check for f in computed), (name, [f.check for f in computed])

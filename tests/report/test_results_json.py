"""results.json: valid against the schema certkit ships, versioned, rounded, strict JSON, the same bytes for the
same input whatever --jobs (apart from its one `run` line), and written by the C encoder."""

from __future__ import annotations

import json
import math

import pytest
from jsonschema import Draft202012Validator

from certkit.engine.results import Condition, Finding, RuleResult, RunResult
from certkit.engine.results_json import SCHEMA_VERSION, SIGNIFICANT_DIGITS, clean, encode, schema, stable_lines
from tests.report.report_run import results

# the tests of the session's small check run on one pytest-xdist worker, which makes it once
pytestmark = pytest.mark.xdist_group("small-check")


def test_schema_is_a_valid_draft_2020_12_schema():
    Draft202012Validator.check_schema(schema())


def test_results_validate_against_the_shipped_schema(small_check):
    folder, code = small_check
    data = results(folder)
    errors = sorted(Draft202012Validator(schema()).iter_errors(data), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors[:10])
    assert data["schema_version"] == SCHEMA_VERSION
    # the partial selection is recorded, so that "4 rules comply" is never read as the whole airplane
    assert data["selection"]["partial"] is True and data["selection"]["select"] == [
        "25.335",
        "25.181",
        "25.173",
        "25.121(b)",
        "25.161",
    ]
    assert data["selection"]["rules_selected"] == len(data["rules"]) < data["selection"]["rules_registered"]
    statuses = {r["status"] for r in data["rules"]}
    assert statuses == {"fails", "complies", "complies_partial", "not_evaluated"}  # the fixture covers them all
    assert code == 1
    r181 = next(r for r in data["rules"] if r["id"] == "25.181")
    bases = {c["basis"] for c in r181["criteria"].values()}
    assert "unverified" in bases  # the MIL-F-8785C numbers (rules/part25/subpart_b/r25_181.py)
    assert all(c["source"] for c in r181["criteria"].values())


def test_every_margin_has_a_unit_word(small_check):
    """No margin is printed without its unit: §25.181's damping ratios read ζ (they had none)."""
    data = results(small_check[0])
    bare = [
        (r["id"], f["check"])
        for r in data["rules"]
        for f in r["findings"]
        if f["margin"] is not None and f["unit"] in (None, "", "1")
    ]
    assert not bare, bare[:5]
    assert {
        f["unit"] for r in data["rules"] if r["id"] == "25.181" for f in r["findings"] if f["margin"] is not None
    } == {"ζ"}


def test_a_schema_violation_is_caught(small_check):
    """The schema can fail: a finding with an empty unit string or a status outside the enum is refused."""
    data = results(small_check[0])
    finding = next(f for r in data["rules"] for f in r["findings"] if f["unit"])
    finding["unit"] = ""
    data["rules"][0]["status"] = "passes"
    messages = [e.message for e in Draft202012Validator(schema()).iter_errors(data)]
    assert any("'passes' is not one of" in m for m in messages)
    assert any("should be non-empty" in m or "too short" in m for m in messages)


def test_numbers_are_rounded_and_strict():
    data, n = clean({"a": 1 / 3, "b": [float("nan"), -0.0, float("-inf")], "c": 123456789.987654321, "d": 5})
    assert n == 2
    assert data["a"] == float(f"{1 / 3:.{SIGNIFICANT_DIGITS}g}") and str(data["a"]) == "0.333333333"
    assert data["b"] == [None, 0.0, None] and math.copysign(1.0, data["b"][1]) == 1.0
    assert data["c"] == 123456790.0 and data["d"] == 5 and isinstance(data["d"], int)


def test_one_finding_per_line_and_the_volatile_line_last():
    finding = Finding(
        Condition(loading="fwd", mass=1000.0), "c", "complies", 2.0, 1.0, 1.0, "m/s", details={"x_m": [1.0, 2.0]}
    )
    run = RunResult("v", "n", "0" * 64, "p", "2026-01-01T00:00:00+00:00", [RuleResult("25.1", "s", "t", [finding] * 3)])
    text = run.to_json()
    lines = text.splitlines()
    finding_lines = [ln for ln in lines if ln.lstrip().startswith('{"condition"')]
    assert len(finding_lines) == 3 and all(json.loads(ln.strip().rstrip(",")) for ln in finding_lines)
    assert lines[-2].startswith('  "run": {"created"') and lines[-1] == "}"
    assert "run" not in stable_lines(text) and json.loads(text)["rules"][0]["findings"][0]["unit"] == "m/s"


def test_encoded_text_is_what_the_standard_encoder_reads():
    data, _ = clean({"a": [{"b": 1.5, "c": "N·m"}], "d": {"e": {"f": {"g": {"h": [1, 2]}}}}, "empty": {}, "l": []})
    assert json.loads(encode(data)) == data


def test_jobs_do_not_change_results_json(small_check, small_check_two_jobs):
    one = (small_check[0] / "results.json").read_text(encoding="utf-8")
    two = (small_check_two_jobs[0] / "results.json").read_text(encoding="utf-8")
    assert json.loads(one)["run"]["jobs"] == 1 and json.loads(two)["run"]["jobs"] == 2
    assert stable_lines(one) == stable_lines(two)
    assert one != two  # only the run line differs, and it does


def _stable_html(folder) -> str:
    import re

    html = (folder / "index.html").read_text(encoding="utf-8")
    html = re.sub(r'<p class="meta" id="run-info">.*?</p>', "", html)
    return re.sub(r"<svg.*?</svg>", "<svg/>", html, flags=re.S)


def test_jobs_do_not_change_the_report(small_check, small_check_two_jobs):
    """The report of --jobs 1 and --jobs 2: equal apart from the run line (SVG compared apart, see below)."""
    assert _stable_html(small_check[0]) == _stable_html(small_check_two_jobs[0])


def test_two_runs_give_the_same_report(small_check, tmp_path):
    """The HTML report of two runs of the same input and options: equal once the run line (time stamp, duration)
    is left out. SVG ids are matplotlib's until evidence is drawn deterministically (evidence as data),
    so the SVG elements are compared apart."""
    from tests.report.report_run import checked

    again, _ = checked(str(tmp_path / "again"), 1)
    assert _stable_html(small_check[0]) == _stable_html(again)
    assert stable_lines((small_check[0] / "results.json").read_text()) == stable_lines(
        (again / "results.json").read_text()
    )


@pytest.mark.parametrize("volatile", ["created", "duration_s", "jobs"])
def test_volatile_fields_are_only_in_run(small_check, volatile):
    data = results(small_check[0])
    assert volatile in data["run"]
    flat = json.dumps({k: v for k, v in data.items() if k != "run"})
    assert f'"{volatile}"' not in flat


def test_schema_command_prints_the_shipped_schema(cli):
    out = cli("schema", "--results")
    assert out.exit_code == 0 and json.loads(out.output) == schema()


@pytest.mark.parametrize("n_rules", [0, 1, 3])
def test_results_json_written_in_pieces_is_the_whole_encoded_at_once(n_rules, tmp_path):
    """The report's writer takes results.json in pieces (each rule's text as a worker encoded it, never joined into
    one string): the file holds exactly the text of encoding the whole run at once, whatever the number of rules."""
    from certkit.report.output import prepare_output, write_set

    finding = Finding(Condition(loading="fwd", mass=1000.0), "c", "fails", 0.5, 1.0, -0.5, "m/s", reason="é · ≥")
    rules = [RuleResult(f"25.{k}", "s", "t", [finding] * (k + 1)) for k in range(n_rules)]
    run = RunResult("v", "n", "0" * 64, "p", "2026-01-01T00:00:00+00:00", rules)
    whole = encode(clean(run.as_dict())[0])
    assert run.to_json() == whole
    out = tmp_path / "out"
    write_set(prepare_output(out), {"results.json": [*run.json_chunks(), "\n"]})
    assert (out / "results.json").read_text(encoding="utf-8") == whole + "\n"

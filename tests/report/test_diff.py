"""certkit diff: status flips and margin changes per rule and condition, an HTML view, exit 1 on a regression."""

from __future__ import annotations

import copy
import json

import pytest

from certkit.report.diff import compare, load
from tests.report.report_run import results

# the tests of the session's small check run on one pytest-xdist worker, which makes it once
pytestmark = pytest.mark.xdist_group("small-check")


def _write(tmp_path, name, data):
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


def test_identical_results_have_no_change(small_check, small_check_two_jobs, cli):
    out = cli("diff", small_check[0] / "results.json", small_check_two_jobs[0] / "results.json")
    assert out.exit_code == 0 and out.output.startswith("no change in")


def test_flips_and_margin_changes_are_listed_per_condition(small_check, tmp_path, cli):
    old = results(small_check[0])
    new = copy.deepcopy(old)
    r335 = next(r for r in new["rules"] if r["id"] == "25.335(a)")
    moved = r335["findings"][1]
    moved["margin"] += 0.5  # m/s: 0.97 kn more margin at the second altitude
    flipped = r335["findings"][0]
    flipped["status"], flipped["margin"] = "fails", -1.0
    r335["status"] = "fails"
    changes = compare(old, new)
    assert [c.id for c in changes] == ["25.335(a)"]
    c = changes[0]
    assert (c.old_status, c.new_status, c.regression) == ("complies", "fails", True)
    assert [(f.flipped, round(f.delta, 6)) for f in c.findings] == [
        (
            True,
            round(-1.0 - old["rules"][[r["id"] for r in old["rules"]].index("25.335(a)")]["findings"][0]["margin"], 6),
        ),
        (False, 0.5),
    ]
    out = cli(
        "diff", _write(tmp_path, "old.json", old), _write(tmp_path, "new.json", new), "--html", tmp_path / "d.html"
    )
    assert out.exit_code == 1
    assert "complies → fails: (a)(2)" in out.output
    assert sum(line.strip().startswith("margin +") and " kn → +" in line for line in out.output.splitlines()) == 1
    html = (tmp_path / "d.html").read_text()
    assert "§25.335(a)" in html and 'class="worse"' in html


def test_round_off_is_not_a_change(small_check):
    old = results(small_check[0])
    new = copy.deepcopy(old)
    for r in new["rules"]:
        for f in r["findings"]:
            if f["margin"] is not None:
                f["margin"] *= 1 + 1e-12
    assert compare(old, new) == []


def test_a_foreign_file_is_a_user_error(tmp_path, cli):
    bad = _write(tmp_path, "old.json", {"rules": []})
    out = cli("diff", bad, bad)
    assert out.exit_code == 2 and "schema_version None" in out.output
    with pytest.raises(Exception, match="not JSON"):
        (tmp_path / "x.json").write_text("{")
        load(tmp_path / "x.json")

"""The terminal: progress lines when piped, rows fitted to the width with the not-evaluated reason, --quiet, the
trim/modes echo of the condition in the units given, with thrust."""

from __future__ import annotations

import io

from certkit.engine.results import Condition, Finding, RuleResult
from certkit.report.terminal import Progress, rule_rows
from tests.conftest import BASELINE
from tests.engine.test_pipeline import write_rule


class _Rule:
    def __init__(self, rid, cost):
        self.id, self.cost = rid, cost


def _result(rid, status, seconds=1.0):
    if status == "not_evaluated":
        f = Finding.not_evaluated(Condition(), "inputs", "needs speeds.VMC (declare it in the aircraft file)")
    else:
        margin = 1.0 if status == "complies" else -1.0
        f = Finding(
            Condition(loading="fwd_mrw", mass=298_000.0, altitude=9000.0),
            "(a) a very long check name " * 3,
            status,
            10.0,
            10.0 - margin,
            margin,
            "m/s",
        )
    r = RuleResult(rid, "s", "A title long enough to be cut at a narrow terminal width", [f])
    r.seconds = seconds
    return r


def test_plain_progress_when_piped_with_eta_by_cost():
    stream = io.StringIO()
    p = Progress([_Rule("25.1", 1.0), _Rule("25.2", 3.0)], stream=stream)
    assert not p.live  # a StringIO is not a terminal
    p.started(["25.1"])
    p.finished([_result("25.1", "complies", 0.5)])
    eta = p.eta()
    assert eta is not None and eta > 0
    p.started(["25.2"])
    p.finished([_result("25.2", "fails", 1.5)])
    lines = stream.getvalue().splitlines()
    assert lines[0].startswith("[1/2] §25.1") and "complies" in lines[0] and "0.5 s" in lines[0] and "ETA" in lines[0]
    assert lines[1].startswith("[2/2] §25.2") and "fails" in lines[1] and "ETA" not in lines[1]


def test_quiet_progress_prints_nothing():
    stream = io.StringIO()
    p = Progress([_Rule("25.1", 1.0)], quiet=True, stream=stream)
    p.started(["25.1"])
    p.finished([_result("25.1", "complies")])
    p.close()
    assert stream.getvalue() == ""


def test_rows_fit_the_width_and_show_the_reason():
    results = [_result("25.1", "complies"), _result("25.149", "not_evaluated"), _result("25.2", "fails")]
    for width in (80, 120):
        rows = rule_rows(results, width=width)
        assert all(len(r) <= width for r in rows), [len(r) for r in rows]
    rows = rule_rows(results, width=200)
    assert "reason: needs speeds.VMC" in rows[1] and "+1.944 kn" in rows[0] and "-1.944 kn" in rows[2]


def test_check_quiet_prints_the_summary_only(cli, tmp_path):
    folder = write_rule(tmp_path / "r")
    out = cli("check", BASELINE, "--rules", folder, "--select", "25.9", "--out", tmp_path / "o", "--quiet")
    lines = [ln for ln in out.output.strip().splitlines() if not ln.startswith("warning: ")]  # the input's warnings
    assert len(lines) == 1 and lines[0].startswith("1 rules (a partial selection: 1 of ")


def test_trim_echoes_the_condition_as_given_and_thrust(cli):
    out = cli("trim", BASELINE, "--weight", "500000 lb", "--altitude", "9000 m", "--speed", "272 kn EAS")
    first = out.output.splitlines()[0]
    assert first.startswith("500000 lb · ") and "9000 m (29,528 ft)" in first and "272 kn EAS (TAS" in first
    thrust = [ln for ln in out.output.splitlines() if ln.strip().startswith("thrust ")]
    assert len(thrust) == 3 and "lbf" in thrust[-1] and "kN" in thrust[-1]

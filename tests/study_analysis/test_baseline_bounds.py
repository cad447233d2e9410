"""Constraints bounded by the baseline's own value (`min: baseline`): parsed, refused before they are read, read from
the baseline design's case (evaluated once through the study runner and kept), and used by the analysis."""

from __future__ import annotations

import json

import pandas as pd
import pytest
from click.testing import CliRunner

from certkit.cli.study_analysis import report_command
from certkit.errors import UserError
from certkit.study.analysis.baseline_bounds import with_baseline_bounds
from certkit.study.analysis.cases import RESP_PREFIX, VAR_PREFIX
from certkit.study.runner import run_study
from certkit.study.spec import Constraint, load_study
from certkit.study.store import Store
from tests.study import evaluators
from tests.study.conftest import EVALUATORS, write_study

FT2 = 0.09290304
RELATIVE = """  - {name: no longer range loss than the baseline, response: constraint.range_margin_m, min: baseline}
"""


def test_a_baseline_bound_is_parsed_and_refused_until_read():
    c = Constraint.model_validate({"name": "a", "response": "r", "min": "baseline"})
    assert c.min is None and c.min_from_baseline and c.needs_baseline
    assert c.describe() == "r ≥ baseline"
    with pytest.raises(ValueError, match="baseline bound has not been read"):
        c.feasible(pd.Series([1.0]).to_numpy())
    read = c.model_copy(update={"min": -0.5})
    assert not read.needs_baseline and read.describe() == "r ≥ -0.5 (the baseline's)"
    assert list(read.feasible(pd.Series([-0.6, -0.5, 0.0]).to_numpy())) == [False, True, True]
    with pytest.raises(ValueError, match="needs a min or a max"):
        Constraint.model_validate({"name": "a", "response": "r"})


def _row(study, point, status="ok", margin=None):
    values = dict(zip([v.path for v in study.variables], point))
    area = values["geometry.horizontal_tail.area"]
    return {
        "key": "k",
        "status": status,
        "block": "baseline",
        **{VAR_PREFIX + p: v for p, v in values.items()},
        RESP_PREFIX + "constraint.range_margin_m": 1.0e5 - 900.0 * area if margin is None else margin,
    }


def test_the_bound_is_read_from_the_baseline_case_run_once(tmp_path):
    study = load_study(write_study(tmp_path, extra=RELATIVE))
    calls = []

    def run_cases(study, store, points, block, role):
        calls.append((block, role))
        return pd.DataFrame([_row(study, [p[v.path] for v in study.variables]) for p in points])

    read = with_baseline_bounds(study, pd.DataFrame(), object(), run_cases=run_cases)
    (c,) = [c for c in read.constraints if c.min_from_baseline]
    assert c.min == pytest.approx(1.0e5 - 900.0 * 1119.2 * FT2, rel=1e-12)
    assert calls == [("baseline", "check")]
    # a case of the baseline design already held: read, not evaluated
    held = pd.DataFrame([_row(study, study.baseline)])
    assert with_baseline_bounds(study, held, object(), run_cases=run_cases).constraints[1].min == c.min
    assert len(calls) == 1


def test_without_a_baseline_case_or_a_value_the_bound_is_an_error(tmp_path):
    study = load_study(write_study(tmp_path, extra=RELATIVE))
    with pytest.raises(UserError, match="no case of the baseline design"):
        with_baseline_bounds(study, pd.DataFrame(), None)

    def failing(study, store, points, block, role):
        return pd.DataFrame([_row(study, study.baseline, status="failed")])

    with pytest.raises(UserError, match="baseline design's case failed"):
        with_baseline_bounds(study, pd.DataFrame(), object(), run_cases=failing)
    no_value = pd.DataFrame([_row(study, study.baseline, margin=float("nan"))])
    with pytest.raises(UserError, match=r"constraints\[1\] \(no longer range loss than the baseline\)"):
        with_baseline_bounds(study, no_value, None)


def test_the_report_judges_designs_against_the_baseline_and_keeps_its_case(tmp_path):
    """The analytic range margin 10⁵ − 900·area falls with the tail area, so "no worse than the baseline" is
    area ≤ 1119.2 ft² on [1000, 1240] ft²: P = 119.2/240 = 0.4967 (the absolute constraint, margin ≥ 0, is
    area ≤ 10⁵/900 m² = 1196.0 ft²: P = 0.8166). The Monte Carlo's 2·10⁴ samples give each within 0.015 (four
    binomial standard errors)."""
    study_file = write_study(tmp_path, lhs=24, extra=RELATIVE)
    store_path = tmp_path / "small.sqlite"
    with Store.open(store_path, create=True) as store:
        run_study(load_study(study_file), store, "serial", evaluator=f"{EVALUATORS}:analytic")
    evaluators.CALLS.clear()
    args = [str(study_file), "--store", str(store_path), "--samples", "2e4", "--executor", "serial"]
    result = CliRunner().invoke(report_command, [*args, "--out", str(tmp_path / "r1")])
    assert result.exit_code == 0, result.output
    summary = json.loads((tmp_path / "r1" / "summary.json").read_text())
    p = {c["name"]: c["p"] for c in summary["constraints"]}
    assert p["no longer range loss than the baseline"] == pytest.approx(119.2 / 240.0, abs=0.015)
    assert p["range"] == pytest.approx((1.0e5 / 900.0 / FT2 - 1000.0) / 240.0, abs=0.015)
    with Store.open(store_path) as store:
        assert "baseline" in set(store.frame()["block"])
    # the constrained optimum, re-evaluated, is confirmed (the analytic surrogates are near exact) and shown so
    confirmed = summary["confirmed_optima"]
    assert confirmed and all(c["status"] == "confirmed" and not c["design"]["violated"] for c in confirmed)
    assert "Optima confirmed by the true model" in (tmp_path / "r1" / "index.html").read_text()
    evaluators.CALLS.clear()
    again = CliRunner().invoke(report_command, [*args, "--out", str(tmp_path / "r2"), "--no-check"])
    assert again.exit_code == 0, again.output
    assert evaluators.CALLS == []  # the baseline's case read back from the store

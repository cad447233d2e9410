"""`certkit study report` runs its true-model checks (the direct check of the probabilities and the re-evaluated
optima) on the executor it is given, shows their progress, and does not evaluate again the designs a report made
before already put in the store."""

from __future__ import annotations

from click.testing import CliRunner

from certkit.cli.study_analysis import report_command
from certkit.study.runner import run_study
from certkit.study.spec import load_study
from certkit.study.store import Store
from tests.study import evaluators
from tests.study.conftest import EVALUATORS, write_study


def _report(study_file, store_path, out, *options):
    return CliRunner().invoke(
        report_command,
        [str(study_file), "--store", str(store_path), "--out", str(out), "--samples", "2e4", *options],
    )


def test_checks_run_on_the_given_executor_show_progress_and_reuse_the_store(tmp_path):
    study_file = write_study(tmp_path, lhs=24)
    store_path = tmp_path / "small.sqlite"
    with Store.open(store_path, create=True) as store:
        run_study(load_study(study_file), store, "serial", evaluator=f"{EVALUATORS}:analytic")
        trained = len(store.frame())
    evaluators.CALLS.clear()

    first = _report(study_file, store_path, tmp_path / "r1", "--executor", "serial")
    assert first.exit_code == 0, first.output
    checked = len(evaluators.CALLS)  # the serial executor evaluates in this process: every call is seen
    assert checked >= 100  # the direct check's 100 designs, then the optima and a sample of the fronts
    assert "small: check" in first.stderr and "done" in first.stderr  # the runner's progress lines
    with Store.open(store_path) as store:
        frame = store.frame()
    assert len(frame) == trained + checked and set(frame["block"]) >= {"check", "optima"}

    evaluators.CALLS.clear()
    again = _report(study_file, store_path, tmp_path / "r2", "--executor", "serial")
    assert again.exit_code == 0, again.output
    assert evaluators.CALLS == []  # the same designs: read from the store, not evaluated again
    with Store.open(store_path) as store:
        assert len(store.frame()) == trained + checked


def test_scheduler_without_dask_is_refused_before_the_analysis(tmp_path):
    study_file = write_study(tmp_path)
    with Store.open(tmp_path / "small.sqlite", create=True) as store:
        run_study(load_study(study_file), store, "serial", evaluator=f"{EVALUATORS}:analytic")
    result = _report(study_file, tmp_path / "small.sqlite", tmp_path / "r", "--scheduler", "tcp://nowhere:8786")
    assert result.exit_code == 2 and "--scheduler is for --executor dask" in result.output
    assert not (tmp_path / "r").exists()


def test_a_check_point_the_plan_already_holds_is_found_in_its_own_block():
    """An optimum on a corner of the box is a case of the plan (a CCD corner): the runner returns that case, stored
    in its own block, and the check reads its record there instead of reporting the design as missing."""
    import numpy as np
    import pandas as pd

    from certkit.study.analysis.checks import run_true_model
    from tests.study_analysis.synthetic import synthetic_study

    study = synthetic_study()
    corner = np.array([v.upper for v in study.variables])
    columns = {f"var:{v.path}": [float(c)] for v, c in zip(study.variables, corner)}
    stored = pd.DataFrame({"key": ["k-corner"], "block": ["ccd"], "status": ["ok"], **columns, "resp:x": [1.0]})

    class Store:
        def frame(self):
            return stored

    def run_cases(study_, store_, points, block, role):
        assert block == "optima" and len(points) == 1
        return [{"key": "k-corner", "block": "ccd", "status": "ok"}]

    out = run_true_model(study, Store(), corner[None, :], block="optima", run_cases=run_cases)
    assert list(out["status"]) == ["ok"] and out["resp:x"].iloc[0] == 1.0

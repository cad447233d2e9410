"""The runner and the store: failed cases are data, resume runs only what has no result, blocks added later
run alone, the frame and the exports, progress lines when not on a terminal, local processes = serial."""

from __future__ import annotations

import io
import re

import pandas as pd
import pytest

from certkit.errors import UserError
from certkit.study.runner import run_study, run_study_cases
from certkit.study.spec import load_study
from certkit.study.store import Store
from tests.study import evaluators
from tests.study.conftest import EVALUATORS, write_study

ANALYTIC = f"{EVALUATORS}:analytic"
FLAKY = f"{EVALUATORS}:flaky"
AREA = evaluators.AREA


def _run(study_file, store_path, evaluator=ANALYTIC, executor="serial", **kw):
    with Store.open(store_path, create=True) as store:
        return run_study(load_study(study_file), store, executor, evaluator=evaluator, **kw)


def test_failed_case_recorded_with_its_reason_and_study_continues(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    summary = _run(small_study, db, FLAKY)
    with Store.open(db) as store:
        frame = store.frame()
    assert summary.total == len(frame) == 9 + 6  # face-centred CCD of 2 factors (4 + 4 + 1) + 6 LHS
    failed = frame[frame.status == "failed"]
    ok = frame[frame.status == "ok"]
    assert len(failed) == (frame[f"var:{AREA}"] > 104.0).sum() > 0 and len(ok) > 0
    assert all(
        re.fullmatch(
            r"RuntimeError: trim did not converge at area 1\d\d\.\d{3} m\^2 "
            r"\(at evaluators\.py:\d+ in flaky\)",
            e,
        )
        for e in failed.error
    )
    assert failed["resp:objective.cruise_CD"].isna().all() and ok["resp:objective.cruise_CD"].notna().all()
    # not retried on resume ...
    assert _run(small_study, db, FLAKY).submitted == 0
    # ... unless asked
    assert _run(small_study, db, FLAKY, retry_failed=True).submitted == len(failed)


def test_resume_runs_only_cases_without_result(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    _run(small_study, db)
    with Store.open(db) as store:  # as a coordinator killed mid-run leaves them: 5 cases pending
        store._db.execute(
            "UPDATE cases SET status = 'pending', record = NULL WHERE rowid IN "
            "(SELECT rowid FROM cases ORDER BY seq DESC LIMIT 5)"
        )
    evaluators.CALLS.clear()
    summary = _run(small_study, db)
    assert summary.submitted == len(evaluators.CALLS) == 5
    with Store.open(db) as store:
        assert (store.frame().status == "ok").all()


def test_adding_a_validation_block_runs_only_its_points(tmp_path):
    study = write_study(tmp_path)
    db = tmp_path / "s.sqlite"
    _run(study, db)
    text = study.read_text().replace(
        "  - {name: lhs, generator: lhs, n: 6, seed: 3}\n",
        "  - {name: lhs, generator: lhs, n: 6, seed: 3}\n"
        "  - {name: check, generator: random, n: 4, seed: 9, role: validation}\n",
    )
    study.write_text(text)
    evaluators.CALLS.clear()
    summary = _run(study, db)
    assert summary.submitted == len(evaluators.CALLS) == 4
    with Store.open(db) as store:
        frame = store.frame()
    assert list(frame.groupby("block", sort=False).size().items()) == [("ccd", 9), ("lhs", 6), ("check", 4)]
    assert set(frame[frame.block == "check"].role) == {"validation"}


def test_changed_aircraft_content_is_a_new_study(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    _run(small_study, db)
    (tmp_path / "aircraft.yaml").write_text("name: stand-in, edited\n")
    assert _run(small_study, db).submitted == 15
    with Store.open(db) as store:
        assert len(store.frame()) == 15 and store.stale() == 15


def test_user_error_stops_the_run_without_recording(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    with pytest.raises(UserError, match="no such aircraft-file path"):
        _run(small_study, db, f"{EVALUATORS}:mistaken")
    with pytest.raises(UserError, match="cannot be found"):
        _run(small_study, db, "no_such_package.module:evaluate")
    with Store.open(db) as store:
        assert set(store.frame().status) == {"pending"}


def test_frame_and_study_as_the_analysis_reads_them(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    _run(small_study, db)
    with Store.open(db) as store:
        frame = store.frame()
        study = store.study()
    assert list(frame.columns[:9]) == [
        "key",
        "block",
        "role",
        "status",
        "error",
        "wall_s",
        "worker",
        f"var:{AREA}",
        f"var:{evaluators.SWEEP}",
    ]
    assert {"resp:objective.cruise_CD", "resp:constraint.range_margin_m"} <= set(frame.columns)
    assert frame["resp:level.short_period.fwd_mrw.clean"].isna().all()  # None in the record → NaN
    assert study == load_study(small_study)
    row = frame.iloc[0]
    area, sweep = row[f"var:{AREA}"], row[f"var:{evaluators.SWEEP}"]
    assert row["resp:objective.cruise_CD"] == 0.02 + 1e-5 * area + 0.01 * (sweep - 0.6) ** 2
    assert study.variables[0].lower == pytest.approx(1000 * 0.3048**2, rel=1e-12) == frame[f"var:{AREA}"].min()


def test_run_study_cases_for_extra_points(small_study, tmp_path):
    db = tmp_path / "s.sqlite"
    _run(small_study, db)
    with Store.open(db) as store:
        study = store.study()
        existing = store.rows()[0]["variables"]
        points = [{AREA: 95.0, evaluators.SWEEP: 0.6}, existing, {AREA: 110.0, evaluators.SWEEP: 0.55}]
        evaluators.CALLS.clear()
        rows = run_study_cases(study, store, points, executor="serial")
        assert len(evaluators.CALLS) == 2  # the point the study already has is not evaluated again
        assert [r["variables"] for r in rows] == points
        assert [r["block"] for r in rows] == ["check", "ccd", "check"]
        assert rows[0]["record"]["responses"]["objective.OEW_kg"] == 1.4e5 + 30.0 * 95.0
        frame = store.frame()
    assert list(frame.role).count("check") == 2
    assert _run(small_study, db).submitted == 0  # a rerun of the study keeps the check rows and their results
    with Store.open(db) as store:
        assert list(store.frame().role).count("check") == 2


def test_export_csv_and_parquet(small_study, tmp_path, cli):
    cli("study", "run", small_study, "--executor", "serial", "--evaluator", FLAKY)
    with Store.open(tmp_path / "small.sqlite") as store:
        frame = store.frame()
    result = cli("study", "export", small_study, "--format", "csv")
    assert result.exit_code == 0
    csv = pd.read_csv(tmp_path / "small.csv")
    assert list(csv.columns) == list(frame.columns) and len(csv) == 15
    assert (csv[f"var:{AREA}"] == frame[f"var:{AREA}"]).all()  # floats round-trip through the text
    cli("study", "export", tmp_path / "small.sqlite", "--format", "parquet", "--out", tmp_path / "x.parquet")
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "x.parquet"), frame)


def test_status(small_study, tmp_path, cli):
    cli("study", "run", small_study, "--executor", "serial", "--evaluator", FLAKY)
    small_study.write_text(
        small_study.read_text().replace(
            "n: 6, seed: 3", "n: 6, seed: 3}\n  - {name: v, generator: random, n: 3, seed: 1, role: validation"
        )
    )
    out = cli("study", "status", small_study).output
    lines = {line.split()[0]: line.split()[1:] for line in out.splitlines() if line.strip()}
    n_failed = int(lines["ccd"][3]) + int(lines["lhs"][3])
    assert lines["ccd"][:2] == ["training", "9"] and lines["lhs"][:2] == ["training", "6"]
    assert lines["v"] == ["validation", "3", "0", "0", "0", "3"]
    assert lines["total"] == ["18", str(15 - n_failed), str(n_failed), "0", "3"]
    assert re.search(rf"\n\s+{n_failed} × RuntimeError: trim did not converge", out) is None  # one reason per area
    assert "RuntimeError: trim did not converge" in out


def test_progress_lines_when_not_a_terminal(small_study, tmp_path, cli):
    result = cli("study", "run", small_study, "--executor", "serial", "--evaluator", FLAKY, "--progress-interval", "0")
    lines = [line for line in result.output.splitlines() if line.startswith("[")]
    pattern = r"\[\d\d:\d\d:\d\d\] small: (\d+)/15 done, (\d+) failed · [0-9.e+]+ cases/s · ETA \S+"
    assert all(re.fullmatch(pattern, line) for line in lines), lines
    done = [int(re.fullmatch(pattern, line).group(1)) for line in lines]
    assert done[:15] == list(range(1, 16)) and done[-1] == 15
    assert "\x1b[" not in result.output  # no terminal control sequences in a log
    assert re.search(r"small: 15 cases — \d+ ok, \d+ failed, 0 pending; this run evaluated 15", result.output)


def test_live_bar_on_a_terminal():
    from certkit.study.progress import make_progress

    class Tty(io.StringIO):
        def isatty(self):
            return True

    stream = Tty()
    with make_progress(10, 2, 1, "small", stream) as bar:
        for status in ("ok", "failed", "ok"):
            bar.advance(status)
    text = stream.getvalue()
    assert "5/10" in text and "2 failed" in text and "cases/s" in text and "ETA" in text


def test_local_processes_give_the_serial_records(small_study, tmp_path):
    _run(small_study, tmp_path / "serial.sqlite", FLAKY)
    summary = _run(small_study, tmp_path / "local.sqlite", FLAKY, executor="local", workers=2)
    assert summary.workers == 2
    with Store.open(tmp_path / "serial.sqlite") as a, Store.open(tmp_path / "local.sqlite") as b:
        assert a.raw_records() == b.raw_records()
        errors = lambda s: dict(zip(s.frame().key, s.frame().error.fillna("")))  # noqa: E731
        assert errors(a) == errors(b)
        workers = set(b.frame().worker)
    assert len(workers) >= 1 and all(re.fullmatch(r".+:\d+", w) for w in workers)


def test_a_case_that_kills_its_worker_is_failed_once_and_the_others_run(small_study, tmp_path):
    summary = _run(small_study, tmp_path / "s.sqlite", f"{EVALUATORS}:crashing", executor="local", workers=2)
    with Store.open(tmp_path / "s.sqlite") as store:
        frame = store.frame()
    big = frame[f"var:{AREA}"] > 104.0
    assert (frame[big].status == "failed").all() and (frame[~big].status == "ok").all()
    assert all(e.startswith("the worker process died while evaluating this case") for e in frame[big].error)
    assert summary.submitted == 15 and frame[~big].wall_s.notna().all()


@pytest.mark.parametrize(
    "failure",
    [OSError("handle is closed"), ValueError("bad value(s) in fds_to_keep")],
    ids=["closed pipe", "reused descriptor"],
)
def test_a_pool_that_cannot_start_a_worker_is_restarted_and_no_case_is_lost(
    small_study, tmp_path, monkeypatch, failure
):
    """While a worker dies the pool may not know yet that it is broken, and starting its replacement fails on the
    pool's closed pipe (OSError from ``submit``), or on the dead worker's pipe whose descriptor number a new pipe has
    taken again (Python's spawn refuses the duplicate: ValueError naming ``fds_to_keep``): the local executor treats
    either as a broken pool — restarts it and runs the task that never started — so every case still has its
    result."""
    from concurrent.futures import ProcessPoolExecutor

    real, calls = ProcessPoolExecutor.submit, {"n": 0}

    def failing_once(self, fn, *args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 4:  # after the start-up probe and two cases
            raise failure
        return real(self, fn, *args, **kwargs)

    monkeypatch.setattr(ProcessPoolExecutor, "submit", failing_once)
    summary = _run(small_study, tmp_path / "s.sqlite", executor="local", workers=2)
    with Store.open(tmp_path / "s.sqlite") as store:
        frame = store.frame()
    assert calls["n"] > 4 and summary.total == len(frame) == 15 and (frame.status == "ok").all()


def test_another_error_starting_a_case_is_not_taken_for_a_broken_pool(small_study, tmp_path, monkeypatch):
    """Only the spawn's refusal of a reused descriptor stands for a dying pool: any other ValueError from ``submit`` is
    certkit's bug and surfaces (no endless restarts)."""
    from concurrent.futures import ProcessPoolExecutor

    real, calls = ProcessPoolExecutor.submit, {"n": 0}

    def failing(self, fn, *args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 3:
            raise ValueError("something else")
        return real(self, fn, *args, **kwargs)

    monkeypatch.setattr(ProcessPoolExecutor, "submit", failing)
    with pytest.raises(ValueError, match="something else"):
        _run(small_study, tmp_path / "s.sqlite", executor="local", workers=2)

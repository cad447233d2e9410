"""Killing the coordinator: SIGKILL or SIGINT at any moment loses no committed case and duplicates none; a
resumed run ends with every case once and the records of an uninterrupted run; workers die with it."""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from certkit.study.runner import run_study
from certkit.study.spec import load_study
from certkit.study.store import Store
from tests.study.conftest import EVALUATORS, write_study

ROOT = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


def _start(study: Path, evaluator: str, env: dict | None = None) -> subprocess.Popen:
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "study",
            "run",
            str(study),
            "--workers",
            "2",
            "--evaluator",
            f"{EVALUATORS}:{evaluator}",
            "--progress-interval",
            "0",
        ],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env={**os.environ, **(env or {})},
    )


def _by_values(store: Store) -> dict[str, str]:
    """Record text of each ok case, keyed by its variables (the keys differ between evaluators)."""
    return {
        json.dumps(r["variables"], sort_keys=True): json.dumps(r["record"], sort_keys=True)
        for r in store.rows()
        if r["status"] == "ok"
    }


def _ok_records(path: Path) -> dict[str, str]:
    if not path.exists():
        return {}
    with Store.open(path) as store:
        return {k: v for k, v in store.raw_records().items() if v is not None}


def test_killed_at_random_moments_then_resumed_equals_an_uninterrupted_run(tmp_path):
    study = write_study(tmp_path, lhs=12)
    with Store.open(tmp_path / "reference.sqlite", create=True) as ref:  # uninterrupted, in this process
        run_study(load_study(study), ref, "serial", evaluator=f"{EVALUATORS}:analytic")
        reference = _by_values(ref)
    assert len(reference) == 21
    db = tmp_path / "small.sqlite"
    rng = random.Random(14)
    committed: dict[str, str] = {}
    progress = []
    # the first kill falls anywhere in the start-up (imports, plan, store, worker spawn), the others after a
    # random number of committed cases plus a random fraction of a case (between commits or during one)
    for sig, lines in (
        (signal.SIGKILL, 0),
        (signal.SIGKILL, rng.randint(2, 4)),
        (signal.SIGINT, rng.randint(2, 4)),
        (signal.SIGKILL, rng.randint(2, 4)),
    ):
        process = _start(study, "sleepy")
        if lines == 0:
            time.sleep(rng.uniform(0.3, 2.0))
        else:
            for _ in range(lines):
                process.stdout.readline()
            time.sleep(rng.uniform(0.0, 0.2))
        process.send_signal(sig)
        output = process.communicate(timeout=30)[0]
        if sig == signal.SIGINT and process.returncode != 0:
            assert process.returncode == 130, output
            assert "interrupted: every finished case is saved" in output
        now = _ok_records(db)
        assert all(now.get(key) == text for key, text in committed.items())  # nothing committed is lost or changed
        committed = now
        progress.append(len(committed))
    assert progress[1] < progress[2] < progress[3] < 21, progress  # each mid-run kill left committed cases
    process = _start(study, "sleepy")
    output = process.communicate(timeout=60)[0]
    assert process.returncode == 0, output
    assert f"this run evaluated {21 - len(committed)} " in output, progress  # only the cases without a result
    with Store.open(db) as store:
        rows = store._db.execute("SELECT key, status FROM cases").fetchall()
        assert len(rows) == len({k for k, _ in rows}) == 21 and {s for _, s in rows} == {"ok"}
        assert _by_values(store) == reference


def _children(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                found.append(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state not in ("Z", "X")  # a zombie has exited; only its parent (now init) has yet to reap it


def test_workers_do_not_outlive_a_killed_coordinator(small_study):
    process = _start(small_study, "slow", env={"CERTKIT_TEST_SLEEP": "60"})
    try:
        deadline = time.monotonic() + 30
        workers: list[int] = []
        while time.monotonic() < deadline:
            workers = _children(process.pid)
            if len(workers) >= 2:
                break
            time.sleep(0.2)
        assert len(workers) >= 2, "the worker processes did not start"
        time.sleep(1.0)  # the workers are inside their 60 s case
        workers = _children(process.pid)
        process.kill()
        process.wait(timeout=10)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline and any(_alive(pid) for pid in workers):
            time.sleep(0.1)
        assert not [pid for pid in workers if _alive(pid)]
    finally:
        if process.poll() is None:
            process.kill()

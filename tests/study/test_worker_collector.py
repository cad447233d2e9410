"""The worker's cyclic garbage collector around a case (certkit.study.worker.run_case): paused while a case runs in a
settled worker process, enabled and collected after it, also when the case fails; untouched in the coordinating
process."""

from __future__ import annotations

import gc
import multiprocessing

import pytest

from certkit.study import worker

SEEN: list[bool] = []


def observing(aircraft_path, values, responses):
    """Records whether the collector runs during the case; fails when asked to."""
    SEEN.append(gc.isenabled())
    if values.get("fail"):
        raise RuntimeError("deliberate failure")
    return {"schema": "certkit.design-record/2", "responses": {}}


def _task(fail: bool) -> worker.Task:
    return worker.Task("k", f"{__name__}:observing", "unused.yaml", {"fail": float(fail)}, None)


@pytest.fixture
def settled(monkeypatch):
    """A settled worker process (its first case done), the collector restored afterwards."""
    monkeypatch.setitem(worker._SETTLED, "done", True)
    was = gc.isenabled()
    SEEN.clear()
    yield monkeypatch
    (gc.enable if was else gc.disable)()


@pytest.mark.parametrize("fail", [False, True])
def test_paused_during_a_case_of_a_worker_process_and_enabled_after(settled, fail):
    settled.setattr(multiprocessing, "parent_process", lambda: object())
    gc.enable()
    result = worker.run_case(_task(fail))
    assert result.status == ("failed" if fail else "ok"), result.error
    assert SEEN == [False]
    assert gc.isenabled()


def test_the_coordinating_process_keeps_its_collector(settled):
    settled.setattr(multiprocessing, "parent_process", lambda: None)
    gc.enable()
    worker.run_case(_task(False))
    assert SEEN == [True] and gc.isenabled()
    gc.disable()  # a caller that disabled it keeps it disabled
    worker.run_case(_task(False))
    assert SEEN == [True, False] and not gc.isenabled()

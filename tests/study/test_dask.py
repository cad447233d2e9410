"""A small study on a real dask.distributed LocalCluster (2 worker processes) gives the local executor's records
byte for byte."""

from __future__ import annotations

import pytest

from certkit.study.runner import run_study
from certkit.study.spec import load_study
from certkit.study.store import Store
from tests.study.conftest import EVALUATORS

pytest.importorskip("distributed")


def test_dask_local_cluster_equals_local_processes(small_study, tmp_path):
    study = load_study(small_study)
    results = {}
    for executor in ("local", "dask"):
        with Store.open(tmp_path / f"{executor}.sqlite", create=True) as store:
            summary = run_study(study, store, executor, workers=2, evaluator=f"{EVALUATORS}:flaky")
            assert summary.submitted == 15 and summary.workers == 2
            frame = store.frame()
            results[executor] = (store.raw_records(), dict(zip(frame.key, frame.error.fillna(""))), set(frame.worker))
    (local_records, local_errors, _), (dask_records, dask_errors, dask_workers) = results["local"], results["dask"]
    assert dask_records == local_records  # JSON text of every record, byte for byte
    assert dask_errors == local_errors  # failures with the same reasons
    assert sum(v is not None for v in dask_records.values()) > 0 and any(dask_errors.values())
    assert len(dask_workers) >= 1 and all(w.rsplit(":", 1)[1].isdigit() for w in dask_workers)


def _malloc_environment():
    import os

    return os.environ.get("MALLOC_TRIM_THRESHOLD_"), os.environ.get("OMP_NUM_THREADS")


def test_local_cluster_workers_keep_glibcs_dynamic_malloc(monkeypatch):
    """dask's nannies would start the workers with MALLOC_TRIM_THRESHOLD_=65536 (its pre-spawn environment), which
    switches off glibc's dynamic mmap threshold (mallopt(3): setting M_TRIM_THRESHOLD disables the dynamic
    adjustment): certkit's LocalCluster workers start without it, one BLAS thread each; a user's own setting wins."""
    import dask

    from certkit.study.executors import DaskExecutor

    assert (
        dask.config.get("distributed.nanny.pre-spawn-environ")["MALLOC_TRIM_THRESHOLD_"] is not None
    )  # dask's default
    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with DaskExecutor(1) as executor:
        assert list(executor._client.run(_malloc_environment).values()) == [(None, "1")]
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "1048576")
    with DaskExecutor(1) as executor:
        assert list(executor._client.run(_malloc_environment).values()) == [("1048576", "1")]


def _timer_settings():
    import dask

    return tuple(
        dask.config.get(key)
        for key in (
            "distributed.worker.profile.enabled",
            "distributed.admin.tick.interval",
            "distributed.worker.memory.monitor-interval",
        )
    )


def test_local_cluster_workers_wake_rarely(monkeypatch):
    """A worker's event loop takes the GIL from the case at each of its timers: dask's profiler (every 10 ms), its
    blocked-loop probe (20 ms) and memory monitor (100 ms) together cost 1.1-1.2x the CPU of a design. certkit's
    LocalCluster workers run without the profiler and wake once a second for the others, though the nannies hand the
    workers their own dask config rather than the environment; a user's own DASK_... setting is left alone."""
    import dask

    from certkit.study.executors import DaskExecutor

    defaults = (True, "20ms", "100ms")  # dask's
    assert _timer_settings() == defaults
    for name in ("WORKER__PROFILE__ENABLED", "ADMIN__TICK__INTERVAL", "WORKER__MEMORY__MONITOR_INTERVAL"):
        monkeypatch.delenv(f"DASK_DISTRIBUTED__{name}", raising=False)
    with DaskExecutor(1) as executor:
        assert list(executor._client.run(_timer_settings).values()) == [(False, "1s", "1s")]
    monkeypatch.setenv("DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED", "True")
    monkeypatch.setenv("DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL", "20ms")
    with DaskExecutor(1) as executor:
        assert list(executor._client.run(_timer_settings).values()) == [(True, "20ms", "1s")]
    assert dask.config.get("distributed.admin.tick.interval") == "20ms"  # this process's config untouched

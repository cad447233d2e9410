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

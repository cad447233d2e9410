"""Where cases run: ``serial`` (this process), ``local`` (a pool of worker processes, the default) or ``dask``
(dask.distributed: a LocalCluster of worker processes, or an existing scheduler and its workers).

Each executor is a context manager whose ``map_unordered(tasks)`` yields a :class:`CaseResult` per task as
cases finish, keeping only a few tasks in flight (so that an interrupted run has little to redo and a huge
study costs no memory up front). Leaving the context stops the workers.
"""

from __future__ import annotations

import logging
import multiprocessing
import os
from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any

from certkit.engine.worker_processes import die_with_parent, one_blas_thread
from certkit.errors import UserError
from certkit.models.kernel_warmup import compile_if_cold
from certkit.study.worker import CaseResult, Task, run_case

EXECUTORS = ("local", "dask", "serial")
IN_FLIGHT_PER_WORKER = 2


def available_cores() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def _died(task: Task, where: str) -> CaseResult:
    return CaseResult(task.key, "failed", f"the worker process died while evaluating this case ({where})", 0.0, "")


def _compile_kernels(processes: int) -> None:
    """At the first run after an install, compile certkit's numba kernels ahead in ``processes`` spawned processes
    (:mod:`certkit.models.kernel_warmup`) rather than in every worker on its first case, and so that every case runs
    the kernels loaded from the cache (the same bits at the first run as at the next)."""
    compile_if_cold(processes, context="spawn")


class SerialExecutor:
    """Every case in this process, one after the other (debugging, profiling)."""

    workers = 1

    def __enter__(self) -> SerialExecutor:
        _compile_kernels(1)  # at a first run, by another process: the cases run the cached kernels' bits
        return self

    def __exit__(self, *exc: object) -> None:
        return None

    def map_unordered(self, tasks: Iterable[Task]) -> Iterator[CaseResult]:
        for task in tasks:
            yield run_case(task)


class LocalExecutor:
    """A pool of ``workers`` spawned processes (spawn: no state inherited by forking a threaded process).

    The workers ignore Ctrl-C and die with the coordinator (see
    :func:`~certkit.engine.worker_processes.die_with_parent`).
    A worker that dies in a case (a crash, the kernel's OOM killer) breaks the pool: the pool is restarted and
    the cases that were in flight are run again one at a time, so that the case that kills its worker is
    recorded as failed — once, not retried forever — and the others are not blamed.
    """

    def __init__(self, workers: int):
        self.workers = max(1, workers)
        self._pool: ProcessPoolExecutor | None = None

    def _start(self) -> None:
        one_blas_thread()  # inherited by the spawned workers
        _compile_kernels(self.workers)
        self._pool = ProcessPoolExecutor(
            self.workers,
            mp_context=multiprocessing.get_context("spawn"),
            initializer=die_with_parent,
            initargs=(os.getpid(),),
        )
        try:  # a pool whose workers cannot start is the machine's problem, not the cases': stop, blame no case
            self._pool.submit(os.getpid).result()
        except BrokenProcessPool:
            self._stop()
            raise UserError(
                "the local worker processes die on start-up (see the messages above); "
                "--executor serial runs the cases in this process"
            ) from None

    def _stop(self) -> None:
        if self._pool is None:
            return
        processes = list(getattr(self._pool, "_processes", {}).values())  # no public handle before Python 3.14
        for process in processes:
            if process.is_alive():
                process.terminate()
        self._pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.join(timeout=5)
        self._pool = None

    def __enter__(self) -> LocalExecutor:
        self._start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop()

    def _running(self) -> ProcessPoolExecutor:
        if self._pool is None:
            raise RuntimeError("the local executor's pool is not running (outside its with-block)")
        return self._pool

    def map_unordered(self, tasks: Iterable[Task]) -> Iterator[CaseResult]:
        tasks = iter(tasks)
        in_flight: dict[Future[CaseResult], tuple[Task, bool]] = {}  # future → (task, run alone)
        suspects: deque[Task] = deque()
        limit = IN_FLIGHT_PER_WORKER * self.workers

        def submit(task: Task, alone: bool) -> bool:
            try:
                in_flight[self._running().submit(run_case, task)] = (task, alone)
                return True
            # broken since the last wait: the task never started. While a worker dies the pool may not yet know it is
            # broken, and starting a replacement worker fails on the pool's closed pipe (OSError), or on the dead
            # worker's pipe whose descriptor number a new pipe has taken again (the spawn refuses the duplicate) — the
            # same event
            except (BrokenProcessPool, OSError, ValueError) as exc:
                if isinstance(exc, ValueError) and "fds_to_keep" not in str(exc):
                    raise
                suspects.appendleft(task)
                return False

        while True:
            broken = False
            if suspects:
                if not in_flight:
                    broken = not submit(suspects.popleft(), True)
            else:
                while not broken and len(in_flight) < limit and (task := next(tasks, None)) is not None:
                    broken = not submit(task, False)
            if not in_flight and not broken:
                return
            done = wait(in_flight, return_when=FIRST_COMPLETED)[0] if not broken else ()
            for future in done:
                task, alone = in_flight.pop(future)
                try:
                    yield future.result()
                except BrokenProcessPool:
                    broken = True
                    if alone:
                        yield _died(task, "alone in the pool")
                    else:
                        suspects.append(task)
            if broken:
                for future, (task, _alone) in list(in_flight.items()):
                    if future.done() and future.exception() is None:
                        yield future.result()
                    else:
                        suspects.append(task)
                in_flight.clear()
                self._stop()
                self._start()


class DaskExecutor:
    """dask.distributed: the given scheduler's workers, or a LocalCluster of ``workers`` processes with one
    thread each. The workers need certkit (and the evaluator) importable. A worker lost in a case is retried
    by dask up to ``distributed.scheduler.allowed-failures`` times, then the case is recorded as failed."""

    def __init__(self, workers: int, scheduler: str | None = None):
        self.workers = max(1, workers)
        self.scheduler = scheduler
        self._cluster: Any = None  # dask.distributed carries no types
        self._client: Any = None

    def __enter__(self) -> DaskExecutor:
        try:
            import dask  # deferred: dask (study extra, 0.25 s) only for --executor dask
            import distributed  # deferred: dask (study extra, 0.25 s) only for --executor dask
        except ImportError:
            raise UserError("--executor dask needs dask.distributed: pip install 'dask[distributed]'") from None
        if self.scheduler:
            try:
                self._client = _untyped(distributed).Client(self.scheduler, timeout="20s")
            except (OSError, TimeoutError) as exc:
                raise UserError(f"cannot reach the dask scheduler at {self.scheduler}: {exc}") from None
            self.workers = max(1, sum(self._client.nthreads().values()))
        else:
            _compile_kernels(self.workers)  # at a first run: once, ahead, not in every worker
            with dask.config.set(_local_cluster_settings()):
                self._cluster = _untyped(distributed).LocalCluster(
                    n_workers=self.workers,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=None,
                    silence_logs=logging.ERROR,
                )
            self._client = _untyped(distributed).Client(self._cluster)
        return self

    def __exit__(self, *exc: object) -> None:
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()

    def map_unordered(self, tasks: Iterable[Task]) -> Iterator[CaseResult]:
        import distributed  # deferred: dask (study extra, 0.25 s) only for --executor dask
        from distributed.scheduler import KilledWorker  # deferred: dask (study extra, 0.25 s) only for --executor dask

        tasks = iter(tasks)
        running = _untyped(distributed).as_completed()
        by_future: dict[str, Task] = {}

        def submit(n: int) -> None:
            for _ in range(n):
                task = next(tasks, None)
                if task is None:
                    return
                future = self._client.submit(run_case, task, key=f"certkit-case-{task.key}", pure=False, retries=0)
                by_future[future.key] = task
                running.add(future)

        submit(IN_FLIGHT_PER_WORKER * self.workers)
        for future in running:
            task = by_future.pop(future.key)
            try:
                yield future.result()
            except KilledWorker as exc:
                yield _died(task, f"dask: {exc}")
            finally:
                future.release()
            submit(1)


def _local_cluster_settings() -> dict[str, object]:
    """dask settings for certkit's LocalCluster, handed to the workers by their nannies (which pass the nanny's dask
    config, not the environment, so an environment variable set after dask's import does not reach them). A user's own
    environment setting (``DASK_...``, ``MALLOC_TRIM_THRESHOLD_``) is kept.

    A worker computes in one thread while its event loop wakes on timers; each wake takes the GIL from the case being
    evaluated (seed-study sample, one worker, CPU per design against a local process; docs/performance.md):

    - dask's statistical profiler samples the computing thread's stack every 10 ms: off;
    - the event loop's blocked-loop probe (``admin.tick``, every 20 ms) and the memory monitor (every 100 ms): once a
      second (a case takes seconds; the memory limits still act within a second);
    - dask's nannies start their workers with MALLOC_TRIM_THRESHOLD_=65536, which switches off glibc's dynamic mmap
      threshold, so every large numpy temporary is a fresh mmap and its page faults (one baseline design 1.2x the
      CPU): left unset, the workers inherit the environment's.
    """
    settings: dict[str, object] = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
    for key, value in (
        ("distributed.worker.profile.enabled", False),
        ("distributed.admin.tick.interval", "1s"),
        ("distributed.worker.memory.monitor-interval", "1s"),
    ):
        if "DASK_" + key.upper().replace(".", "__").replace("-", "_") not in os.environ:
            settings[key] = value
    return settings


def _untyped(module: object) -> Any:
    """A module whose API carries no types (dask.distributed), as such for the type checker."""
    return module


def make_executor(
    name: str, workers: int | None = None, scheduler: str | None = None
) -> SerialExecutor | LocalExecutor | DaskExecutor:
    if name not in EXECUTORS:
        raise UserError(f"unknown executor {name!r} (one of {', '.join(EXECUTORS)})")
    if scheduler and name != "dask":
        raise UserError("--scheduler is for --executor dask")
    if workers is not None and workers < 1:
        raise UserError(f"--workers must be 1 or more (got {workers})")
    workers = workers or available_cores()
    if name == "serial":
        return SerialExecutor()
    if name == "local":
        return LocalExecutor(workers)
    return DaskExecutor(workers, scheduler)


__all__ = ["EXECUTORS", "make_executor", "available_cores", "SerialExecutor", "LocalExecutor", "DaskExecutor"]

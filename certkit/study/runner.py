"""Running a study: plan its cases, record them in the store, evaluate those without a result.

Resuming is the same call: a case whose key already has a result (ok or failed) is not submitted again;
failed cases run again only when asked (``retry_failed``). The coordinator (this process) is the store's only
writer and commits each case as it finishes.
"""

from __future__ import annotations

import importlib.util
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TextIO

from certkit.errors import UserError
from certkit.study.executors import make_executor
from certkit.study.plan import DEFAULT_EVALUATOR, Case, CaseContext, cases_for_points, plan_study
from certkit.study.progress import make_progress
from certkit.study.spec import Study
from certkit.study.store import Store
from certkit.study.worker import Task


@dataclass
class RunSummary:
    total: int = 0  # cases of the study
    submitted: int = 0  # cases this run had to evaluate
    ok: int = 0  # of this run
    failed: int = 0  # of this run
    duplicates: int = 0  # points an earlier block already had
    elapsed_s: float = 0.0
    workers: int = 1


def _check_evaluator(name: str) -> None:
    """Fail early (exit 2) on an evaluator that cannot be found, before any worker starts."""
    module = name.partition(":")[0] if ":" in name else name.rpartition(".")[0]
    try:
        found = importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        found = False
    if not found:
        raise UserError(f"the evaluator {name!r} cannot be found (no module {module!r})")


def execute(
    store: Store,
    context: CaseContext,
    cases: Sequence[Case],
    executor: str = "local",
    workers: int | None = None,
    scheduler: str | None = None,
    progress: TextIO | None = None,
    label: str = "study",
    total: int | None = None,
    interval: float = 10.0,
) -> RunSummary:
    """Evaluate ``cases`` and commit each as it finishes. ``progress``: a stream for the progress display
    (None: no display). A case that reports a user error stops the run (its case stays pending)."""
    summary = RunSummary(total=total if total is not None else len(cases), submitted=len(cases))
    if not cases:
        return summary
    _check_evaluator(context.evaluator)
    tasks = (Task(c.key, context.evaluator, context.aircraft_path, c.values, context.responses) for c in cases)
    done_before = summary.total - len(cases)
    start = time.monotonic()
    display = (
        make_progress(summary.total, done_before, _failed_count(store), label, progress, interval)
        if progress is not None
        else None
    )
    with make_executor(executor, workers, scheduler) as pool:
        summary.workers = pool.workers
        if display is not None:
            display.__enter__()
        try:
            for result in pool.map_unordered(tasks):
                if result.status == "user_error":
                    raise UserError(result.error)
                store.commit(result, time.time())
                summary.ok += result.status == "ok"
                summary.failed += result.status == "failed"
                if display is not None:
                    display.advance(result.status)
        finally:
            summary.elapsed_s = time.monotonic() - start
            if display is not None:
                display.__exit__(None, None, None)
    return summary


def _failed_count(store: Store) -> int:
    return sum(n for _block, _role, status, n in store.counts() if status == "failed")


def run_study(
    study: Study,
    store: Store,
    executor: str = "local",
    workers: int | None = None,
    scheduler: str | None = None,
    evaluator: str = DEFAULT_EVALUATOR,
    retry_failed: bool = False,
    progress: TextIO | None = None,
    interval: float = 10.0,
) -> RunSummary:
    """Plan ``study``, record the plan in ``store`` and evaluate every case without a result."""
    _check_evaluator(evaluator)
    context = CaseContext.of(study, evaluator)
    plan = plan_study(study, context)
    with store.writer():
        store.sync_plan(study, context, plan)
        if retry_failed:
            store.reset_failed()
        cases = store.pending()
        summary = execute(
            store,
            context,
            cases,
            executor,
            workers,
            scheduler,
            progress,
            study.name,
            total=len(plan.cases),
            interval=interval,
        )
    summary.total = len(plan.cases)
    summary.duplicates = sum(plan.duplicates.values())
    return summary


def run_study_cases(
    study: Study,
    store: Store,
    points: Sequence[Mapping[str, float]],
    block: str = "check",
    role: str = "check",
    executor: str = "local",
    workers: int | None = None,
    scheduler: str | None = None,
    evaluator: str | None = None,
    progress: TextIO | None = None,
) -> list[dict[str, Any]]:
    """Evaluate extra points (``{path: SI value}``, e.g. a fresh random sample to check a surrogate) with the
    study's aircraft, responses and evaluator, record them in ``store`` as block ``block``, and return one row
    per point, in order (see :meth:`Store.rows`). Points the store already has are not evaluated again."""
    context = CaseContext.of(study, evaluator or store.meta("evaluator") or DEFAULT_EVALUATOR)
    cases = cases_for_points(context, [dict(p) for p in points], block, role)
    with store.writer():
        store.add_cases(context, cases)
        todo = store.pending([c.key for c in cases])
        execute(
            store, context, todo, executor, workers, scheduler, progress, f"{study.name}: {block}", total=len(cases)
        )
    rows = {row["key"]: row for row in store.rows([c.key for c in cases])}
    return [rows[context.key({k: float(v) for k, v in p.items()})] for p in points]

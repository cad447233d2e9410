"""What runs in a worker process: one case → one :class:`CaseResult`, never an exception.

The evaluator is named by a dotted path ("package.module:function") and imported once per process, so that
what it keeps between calls (the parsed aircraft, compiled kernels, influence blocks) serves every case the
process evaluates. A :class:`~certkit.errors.UserError` is a mistake of the study (a bad variable path), not of
the design: it comes back as ``user_error`` and stops the run; any other exception is a failed case.
This module imports only the standard library and certkit.errors: a worker process starts fast.
"""

from __future__ import annotations

import gc
import importlib
import json
import multiprocessing
import os
import socket
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from certkit.errors import InfeasibleDesign, UserError

_EVALUATORS: dict[str, Callable[..., Any]] = {}


@dataclass(frozen=True)
class CaseResult:
    """What a worker returns for one case."""

    key: str
    status: str  # "ok" | "failed" | "user_error" (a mistake of the study, not of the design)
    error: str | None
    wall_s: float
    worker: str
    record: str | None = None  # canonical JSON
    timings: str | None = None


@dataclass(frozen=True)
class Task:
    key: str
    evaluator: str
    aircraft_path: str
    values: dict[str, float]
    responses: tuple[str, ...] | None


def resolve_evaluator(name: str) -> Callable[..., Any]:
    """``"pkg.module:function"`` (or ``"pkg.module.function"``) → the function, imported once per process."""
    if name not in _EVALUATORS:
        module, _, attr = name.partition(":") if ":" in name else name.rpartition(".")
        try:
            _EVALUATORS[name] = getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError, ValueError) as exc:
            raise UserError(f"cannot load the evaluator {name!r}: {exc}") from None
    return _EVALUATORS[name]


def canonical_json(value: object) -> str:
    """Sorted keys, no spaces, no NaN (the record contract uses None for what was not computed)."""
    return json.dumps(value, sort_keys=True, separators=(",", ":"), allow_nan=False, ensure_ascii=False)


def worker_id() -> str:
    return f"{socket.gethostname()}:{os.getpid()}"


def _where(exc: BaseException) -> str:
    frames = traceback.extract_tb(exc.__traceback__)
    if not frames:
        return ""
    last = frames[-1]
    return f" (at {os.path.basename(last.filename)}:{last.lineno} in {last.name})"


_SETTLED = {"done": False}


def _freeze_long_lived() -> None:
    """After a process's first case, what it keeps for the next ones (imports, compiled kernels, the parsed aircraft,
    the declared airplane's lattice and loads) is moved out of the cyclic garbage collector's reach (``gc.freeze``,
    after one full collection so no garbage is kept). Scanning those ~200,000 objects again and again cost about
    0.4 s of every design's 3.5 s (measured with ``gc.callbacks`` on the benchmark sample)."""
    if not _SETTLED["done"]:
        _SETTLED["done"] = True
        gc.collect()
        gc.freeze()


def run_case(task: Task) -> CaseResult:
    """One case. In a settled worker process (:func:`_freeze_long_lived`) the cyclic collector is paused while the
    case runs and collects once after it: a design allocates millions of short-lived containers, nearly all freed by
    reference counting, and the youngest generation's collections every few thousand allocations cost about 0.04 s
    of each design against 0.003 s for the one collection after it (``gc.callbacks`` on four redesigned tails of
    ``benchmarks/bench_evaluate.py``; the process's peak memory the same). A case run in the coordinating process (the
    serial executor) leaves that process's collector as it was."""
    pause = _SETTLED["done"] and gc.isenabled() and multiprocessing.parent_process() is not None
    if pause:
        gc.disable()
    try:
        return _run_case(task)
    finally:
        if pause:
            gc.enable()
            gc.collect()
        _freeze_long_lived()


def _run_case(task: Task) -> CaseResult:
    start = time.perf_counter()

    def elapsed() -> float:
        return time.perf_counter() - start

    try:
        evaluate = resolve_evaluator(task.evaluator)
        record = dict(evaluate(task.aircraft_path, dict(task.values), list(task.responses) if task.responses else None))
        timings = record.pop("timings", None)
        text = canonical_json(record)
        return CaseResult(
            task.key, "ok", None, elapsed(), worker_id(), text, None if timings is None else canonical_json(timings)
        )
    except InfeasibleDesign as exc:  # this design's values make an impossible aircraft: a failed case
        return CaseResult(task.key, "failed", f"infeasible design: {exc}", elapsed(), worker_id())
    except UserError as exc:
        return CaseResult(task.key, "user_error", str(exc), elapsed(), worker_id())
    except Exception as exc:  # a failed design is data: its reason is recorded, the study goes on
        return CaseResult(task.key, "failed", f"{type(exc).__name__}: {exc}{_where(exc)}", elapsed(), worker_id())

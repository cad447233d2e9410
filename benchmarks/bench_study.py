"""Benchmark: the cost of one design of the seed study and the projected time of its 993-case plan.

Evaluates a sample of studies/ht-redesign.yaml (50 cases spread over all its blocks, fixed seed) with the
real evaluator (certkit.design.evaluate:evaluate_design) on local worker processes, then the same sample on a
dask.distributed LocalCluster with as many workers, each into a fresh store. Reports:

- seconds per design per core: the run's wall time × workers / cases (what a study costs), and the mean
  case wall time without each worker's first case (start-up: imports, compiled kernels, the parsed aircraft);
- the cost split, from each record's "timings" (mean seconds per part and share of "total_s");
- the projection of the 993-case plan on this machine's cores, against the target of 1.5 s per design per core
  (docs/performance.md; the 993 cases in 12.4 min on 2 cores);
- the throughput of local processes and of dask (cases per second), and whether their records agree.

Run from the repository root:  python benchmarks/bench_study.py [--cases 50] [--workers N] [--skip-dask]
(--evaluator tests.study.evaluators:sleepy exercises the benchmark without the real evaluator.)
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from certkit.errors import UserError  # noqa: E402
from certkit.study.executors import available_cores  # noqa: E402
from certkit.study.plan import DEFAULT_EVALUATOR, CaseContext, plan_study  # noqa: E402
from certkit.study.runner import run_study_cases  # noqa: E402
from certkit.study.spec import load_study  # noqa: E402
from certkit.study.store import Store  # noqa: E402

STUDY = Path(__file__).resolve().parents[1] / "studies" / "ht-redesign.yaml"
TARGET_S_PER_DESIGN_CORE = 1.5  # s per design per core (docs/performance.md)


def sample(study, evaluator: str, n: int, seed: int = 50) -> list[dict[str, float]]:
    import numpy as np

    cases = plan_study(study, CaseContext.of(study, evaluator)).cases
    chosen = np.sort(np.random.default_rng(seed).choice(len(cases), size=min(n, len(cases)), replace=False))
    return [cases[i].values for i in chosen], len(cases)


def measure(study, points, executor: str, workers: int, evaluator: str, folder: Path) -> dict:
    with Store.open(folder / f"{executor}.sqlite", create=True) as store:
        start = time.perf_counter()
        rows = run_study_cases(
            study,
            store,
            points,
            block="bench",
            executor=executor,
            workers=workers,
            evaluator=evaluator,
            progress=sys.stdout,
        )
        elapsed = time.perf_counter() - start
    return {"rows": rows, "elapsed": elapsed, "workers": workers}


def report(label: str, run: dict, plan_size: int) -> None:
    rows = run["rows"]
    ok = [r for r in rows if r["status"] == "ok"]
    failed = len(rows) - len(ok)
    per_core = run["elapsed"] * run["workers"] / len(rows)
    by_worker = defaultdict(list)
    for r in sorted(rows, key=lambda r: r["finished_at"] or 0):
        by_worker[r["worker"]].append(r["wall_s"])
    steady = [w for walls in by_worker.values() for w in walls[1:]]
    first = [walls[0] for walls in by_worker.values()]
    print(
        f"\n{label}: {len(rows)} cases ({failed} failed) in {run['elapsed']:.1f} s on {run['workers']} workers: "
        f"{len(rows) / run['elapsed']:.3g} cases/s"
    )
    print(
        f"  {per_core:.2f} s per design per core (end to end); mean case {sum(steady) / max(1, len(steady)):.2f} s "
        f"after each worker's first (first cases: {', '.join(f'{w:.1f}' for w in first)} s)"
    )
    cores = available_cores()
    print(
        f"  projection of the {plan_size}-case plan: {plan_size * per_core / cores / 60:.1f} min on {cores} cores, "
        f"{plan_size * per_core / 2 / 60:.1f} min on 2 (target {TARGET_S_PER_DESIGN_CORE:.2f} s/design/core: "
        f"{'met' if per_core <= TARGET_S_PER_DESIGN_CORE else 'NOT met'})"
    )
    # a whole plan pays each worker's start-up (its first case's excess over the mean case) once, not every 50 cases
    startup = sum(first) - len(first) * sum(steady) / max(1, len(steady))
    steady_per_core = (run["elapsed"] * run["workers"] - startup) / len(rows)
    print(
        f"  without the workers' start-up ({startup:.1f} s in all): {steady_per_core:.2f} s per design per core; the "
        f"{plan_size}-case plan on 2 cores, start-up paid once per worker: "
        f"{(plan_size * steady_per_core + startup) / 2 / 60:.1f} min"
    )
    parts = defaultdict(float)
    for r in ok:
        for name, value in (r["timings"] or {}).items():
            if isinstance(value, (int, float)):
                parts[name] += value
    cpu = parts.pop("cpu_s", None)
    if cpu is not None and ok:
        print(
            f"  CPU time per design {cpu / len(ok):.2f} s (the evaluating process's own; on a loaded machine the wall "
            f"time above grows, this does not)"
        )
    if parts:
        total = parts.get("total_s") or sum(parts.values())
        print("  cost split (records' timings, mean per design):")
        for name, value in sorted(parts.items(), key=lambda kv: -kv[1]):
            print(f"    {name:<28}{value / len(ok):>9.3f} s {100 * value / total:>6.1f} %")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=50)
    parser.add_argument("--workers", type=int, default=available_cores())
    parser.add_argument("--evaluator", default=DEFAULT_EVALUATOR)
    parser.add_argument("--skip-dask", action="store_true")
    args = parser.parse_args()
    study = load_study(STUDY)
    points, plan_size = sample(study, args.evaluator, args.cases)
    runs = {}
    try:
        with tempfile.TemporaryDirectory() as folder:
            for executor in ("local",) + (() if args.skip_dask else ("dask",)):
                runs[executor] = measure(study, points, executor, args.workers, args.evaluator, Path(folder))
                report(f"{executor} executor", runs[executor], plan_size)
    except UserError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    if "dask" in runs:
        same = [r["record"] for r in runs["local"]["rows"]] == [r["record"] for r in runs["dask"]["rows"]]
        ratio = runs["local"]["elapsed"] / runs["dask"]["elapsed"]
        print(f"\ndask / local throughput: {ratio:.2f}; records {'identical' if same else 'DIFFERENT'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

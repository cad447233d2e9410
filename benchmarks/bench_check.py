"""Benchmark: wall time of `certkit check aircraft/lta.yaml` (subprocess, best of 3: all rules with the
default --jobs (the cores available) and with --jobs 1; the Subpart B set and the Subpart C set
``--select 25.3 --select 25.4`` alone) and of each
rule evaluated in-process on one shared Context (so memoised models are shared as in a check run), and the timeline of
one check's units of work on its worker processes as the coordinating process sees them (where a check's wall time
goes: the unit that ends last is its critical path). The
numba kernels are compiled (or loaded from their disk cache) by a first, untimed run. The commands run as an
installed package runs: with their modules' bytecode cached (``PYTHONDONTWRITEBYTECODE`` unset for them, so the
first run writes it); with ``PYTHONDONTWRITEBYTECODE=1`` inherited, an editable install compiles certkit's modules at
every start (about 0.3 s of a check).

With ``--against DIR`` (another checkout of certkit, e.g. the code before a change): only whole checks of both trees,
alternating, ``--pairs`` of them, and the medians of their ratios.

Run from the repository root:  python benchmarks/bench_check.py [--against DIR [--pairs N]]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from bench_first_run import INSTALLED_ENV, ROOT, rules_package, run_check  # noqa: E402

from certkit.aircraft import load_aircraft  # noqa: E402
from certkit.engine.context import Context  # noqa: E402
from certkit.engine.registry import discover  # noqa: E402
from certkit.engine.scheduler import evaluate_rule  # noqa: E402

BASELINE = os.path.join(ROOT, "aircraft", "lta.yaml")


def check_subprocess(*args: str, repeats: int = 3) -> list[float]:
    times = []
    with tempfile.TemporaryDirectory() as out:
        for _ in range(repeats):
            t0 = time.perf_counter()
            subprocess.run(
                [sys.executable, "-m", "certkit.cli", "check", BASELINE, "--out", out, *args],
                env=INSTALLED_ENV,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            times.append(time.perf_counter() - t0)
    return times


def rules_in_process():
    t0 = time.perf_counter()
    ctx = Context(load_aircraft(BASELINE))
    rows = [("(load aircraft)", time.perf_counter() - t0, "")]
    for rule in discover():
        t0 = time.perf_counter()
        res = evaluate_rule(rule, ctx)
        rows.append((rule.id, time.perf_counter() - t0, res.status))
    return rows


class _Timeline:
    """A check's progress receiver noting when each unit of work starts (a worker free for it; the first units at
    submission, worker start-up included) and ends, seconds from its creation."""

    def __init__(self) -> None:
        self.t0 = time.perf_counter()
        self.start_at: dict[str, float] = {}
        self.end_at: dict[str, float] = {}

    def started(self, rule_ids) -> None:
        for rid in rule_ids:
            self.start_at[rid] = time.perf_counter() - self.t0

    def finished(self, results) -> None:
        for res in results:
            self.end_at[res.id] = time.perf_counter() - self.t0


def timeline(jobs: int = 2) -> None:
    """One check in this process (:func:`certkit.engine.scheduler.run` with the report's drawing and the missions,
    as ``certkit check`` runs it, without writing the report): each unit's start, end and length, longest first."""
    import functools

    from certkit.cli.main import MISSION_COST, _mission_for_report
    from certkit.engine.scheduler import run, work_units
    from certkit.report.html import ReportFinish

    rules = discover()
    t0 = time.perf_counter()
    loaded = load_aircraft(BASELINE)
    progress = _Timeline()
    mission = {"mission": functools.partial(_mission_for_report, loaded.model)}
    run(
        loaded,
        rules,
        jobs=jobs,
        finish=ReportFinish(rules),
        progress=progress,
        alongside=mission,
        alongside_cost={"mission": MISSION_COST},
    )
    wall = time.perf_counter() - t0
    rows = []
    for unit in work_units(rules):
        start, end = progress.start_at[unit[0].id], max(progress.end_at[r.id] for r in unit)
        rows.append((end - start, start, end, " ".join(r.id for r in unit)))
    print(f"\ntimeline of one check in this process, --jobs {jobs}: {wall:.2f} s from the aircraft's load")
    print(f"{'unit (rules sharing their runs)':<64}{'start':>8}{'end':>8}{'length':>8}")
    for length, start, end, ids in sorted(rows, reverse=True):
        print(f"{ids[:63]:<64}{start:>8.2f}{end:>8.2f}{length:>8.2f}")
    summed, last = sum(r[0] for r in rows) / jobs, max(r[2] for r in rows)
    print(f"summed unit lengths / jobs: {summed:.2f} s; last unit ends at {last:.2f} s")


def subpart_c_selection() -> tuple[str, ...]:
    """``--select 25.3 --select 25.4``: the Subpart C flight-loads set with its §25.4xx rules (§25.427(b)) when any
    is registered (a pattern matching no rule is a user error)."""
    ids = [r.id for r in discover()]
    return ("--select", "25.3") + (("--select", "25.4") if any(i.startswith("25.4") for i in ids) else ())


def paired(against: str, pairs: int, jobs: int = 2) -> None:
    """Whole checks of this code and of the checkout ``against`` (its own source tree and rules, this interpreter),
    alternating, each tree with its own warm kernel cache: medians of wall and CPU (the process and its workers) and
    the median of the pairs' ratios."""
    import statistics

    trees = {"this code": ROOT, "--against": os.path.abspath(against)}
    links = {name: rules_package(tree, tempfile.mkdtemp()) for name, tree in trees.items()}
    caches = {name: tempfile.mkdtemp() for name in trees}
    for name, tree in trees.items():  # untimed: bytecode written, kernels compiled into the tree's cache
        for _ in range(2):
            run_check(tree, links[name], caches[name], jobs)
    runs: dict[str, list[tuple[float, float]]] = {name: [] for name in trees}
    for i in range(pairs):
        for name in list(trees)[:: 1 if i % 2 == 0 else -1]:
            runs[name].append(run_check(trees[name], links[name], caches[name], jobs))
    print(f"\nwhole checks, --jobs {jobs}, {pairs} alternating pairs with {trees['--against']}:")
    for name, r in runs.items():
        print(
            f"  {name:>10}: wall median {statistics.median(w for w, _ in r):.2f} s, "
            f"CPU median {statistics.median(c for _, c in r):.2f} s"
        )
    wall = statistics.median(a[0] / b[0] for a, b in zip(runs["this code"], runs["--against"]))
    cpu = statistics.median(a[1] / b[1] for a, b in zip(runs["this code"], runs["--against"]))
    print(f"  this code / --against (median of the pairs' ratios): wall {wall:.3f}, CPU {cpu:.3f}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--against", help="another certkit checkout: whole checks of both, alternating, in this run")
    parser.add_argument("--pairs", type=int, default=10)
    args = parser.parse_args()
    if args.against:
        paired(args.against, args.pairs)
        return
    check_subprocess(repeats=1)  # compiles the kernels or loads them from the cache
    sub_c = subpart_c_selection()
    for label, args in (
        ("all rules, default --jobs", ()),
        ("all rules, --jobs 1", ("--jobs", "1")),
        ("Subpart B (--select 25.1)", ("--select", "25.1")),
        (f"Subpart C ({' '.join(sub_c)}), target 6 s", sub_c),
    ):
        times = check_subprocess(*args)
        print(
            f"certkit check aircraft/lta.yaml, {label}: best {min(times):.2f} s of "
            f"{', '.join(f'{t:.2f}' for t in times)}"
        )
    timeline()
    rows = rules_in_process()
    print(f"\n{'rule':<16}{'wall s':>9}  status")
    for rid, t, status in rows:
        print(f"{rid:<16}{t:>9.3f}  {status}")
    print(f"{'total':<16}{sum(r[1] for r in rows):>9.3f}")


if __name__ == "__main__":
    main()

"""Benchmark: wall time of `certkit check aircraft/lta.yaml` (subprocess, best of 3) and of each rule
evaluated in-process on one shared Context (so memoised models are shared as in a check run).

Run from the repository root:  python benchmarks/bench_check.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from certkit.aircraft import load_aircraft  # noqa: E402
from certkit.context import Context  # noqa: E402
from certkit.registry import discover  # noqa: E402
from certkit.scheduler import evaluate_rule  # noqa: E402

BASELINE = os.path.join(os.path.dirname(__file__), "..", "aircraft", "lta.yaml")


def check_subprocess(repeats: int = 3) -> list[float]:
    times = []
    with tempfile.TemporaryDirectory() as out:
        for _ in range(repeats):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "certkit.cli", "check", BASELINE, "--out", out],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
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


def main():
    times = check_subprocess()
    print(f"certkit check aircraft/lta.yaml (subprocess): best {min(times):.2f} s of {', '.join(f'{t:.2f}' for t in times)}")
    rows = rules_in_process()
    print(f"\n{'rule':<16}{'wall s':>9}  status")
    for rid, t, status in rows:
        print(f"{rid:<16}{t:>9.3f}  {status}")
    print(f"{'total':<16}{sum(r[1] for r in rows):>9.3f}")


if __name__ == "__main__":
    main()

"""Benchmark: fuzz the aircraft loader with the strategies of tests/hardening/fuzz.py for a long budget and report
counts (target 0 unexpected exceptions in 10^4 variants). Every variant is classified: loads, user error
(certkit.errors.UserError, exit 2) or unexpected (any other exception, or a non-finite number accepted); each
unexpected one is printed with its first message. A slow variant (over 2 s) is counted too.

Run from the repository root:  python benchmarks/bench_fuzz.py [VARIANTS] [SEED]   (default 10000, 17; about
40 % of the variants are text mutations)
"""

from __future__ import annotations

import os
import sys
import time
from collections import Counter

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from hypothesis import HealthCheck, given, seed, settings  # noqa: E402

from tests.hardening.fuzz import data_variants, outcome, tally, text_variants  # noqa: E402


def fuzz(strategy, n: int, random_seed: int) -> tuple[Counter, list[str], int, float]:
    results: list[str] = []
    slow = [0, 0.0]

    @seed(random_seed)
    @settings(
        max_examples=n, database=None, deadline=None, phases=["generate"], suppress_health_check=list(HealthCheck)
    )
    @given(strategy)
    def run(variant):
        start = time.perf_counter()
        results.append(outcome(variant))
        took = time.perf_counter() - start
        slow[1] = max(slow[1], took)
        if took > 2.0:
            slow[0] += 1

    run()
    unexpected = sorted({r for r in results if r.startswith("unexpected")})
    return tally(results), unexpected, slow[0], slow[1]


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 10_000
    random_seed = int(sys.argv[2]) if len(sys.argv) > 2 else 17
    total = Counter()
    for name, strategy, share in (("data", data_variants(), 0.6), ("text", text_variants(), 0.4)):
        start = time.perf_counter()
        counts, unexpected, n_slow, worst = fuzz(strategy, int(n * share), random_seed)
        took = time.perf_counter() - start
        total += counts
        print(
            f"{name:5} {sum(counts.values()):6d} variants in {took:7.1f} s: "
            + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
            + f"; slowest {worst * 1e3:.0f} ms, {n_slow} over 2 s"
        )
        for u in unexpected:
            print("   ", u)
    print(f"total {sum(total.values())} variants: " + ", ".join(f"{k} {v}" for k, v in sorted(total.items())))


if __name__ == "__main__":
    main()

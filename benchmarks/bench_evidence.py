"""Benchmark: CPU time of the evidence of the Subpart C set (``--select 25.3 --select 25.4``): building the evidence
data (``Rule.evidence``) and drawing it (``certkit.report.figures.render_evidence``), per rule, after the rule's
evaluation (untimed). CPU time (``time.process_time``), not wall time: the machine may be shared.

Run from the repository root:  python benchmarks/bench_evidence.py [rule-id prefix ...]
"""

from __future__ import annotations

import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from certkit.aircraft import load_aircraft  # noqa: E402
from certkit.engine.context import Context  # noqa: E402
from certkit.engine.registry import discover  # noqa: E402
from certkit.engine.scheduler import criteria_for  # noqa: E402
from certkit.report.figures import figure_prefix, render_evidence  # noqa: E402

BASELINE = os.path.join(os.path.dirname(__file__), "..", "aircraft", "lta.yaml")


def main(prefixes=("25.3", "25.4")):
    ctx = Context(load_aircraft(BASELINE))
    total_data = total_draw = 0.0
    figures = 0
    for rule in discover():
        if not rule.id.startswith(tuple(prefixes)):
            continue
        instance = rule()
        criteria, _ = criteria_for(rule, ctx)
        findings = instance.evaluate(ctx, rule.conditions.expand(ctx.aircraft), criteria)
        t0 = time.process_time()
        evidence = instance.evidence(ctx, findings, criteria)
        t1 = time.process_time()
        render_evidence(evidence, figure_prefix(rule.id))
        t2 = time.process_time()
        n = sum(1 for e in evidence if e.figure is not None)
        figures += n
        total_data += t1 - t0
        total_draw += t2 - t1
        print(f"{rule.id:14s} data {t1 - t0:6.3f} s  drawing {t2 - t1:6.3f} s  ({n} figures)")
    print(f"{'total':14s} data {total_data:6.3f} s  drawing {total_draw:6.3f} s  ({figures} figures)")


if __name__ == "__main__":
    main(sys.argv[1:] or ("25.3", "25.4"))

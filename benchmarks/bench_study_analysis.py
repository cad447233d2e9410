"""Benchmark: the study analysis at the seed study's size — 793 training and 200 validation cases, eight
variables, three objectives and a dozen constraint responses (synthetic smooth responses, integer levels) —
surrogate fitting, then the 10⁶-sample Monte Carlo on every surrogate (target: under 30 s on the 2-core
machine), then the whole report (no true-model checks).

Run: ``python benchmarks/bench_study_analysis.py [--samples 1000000] [--report]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from certkit.report.study_report import write_study_report  # noqa: E402
from certkit.study.analysis.cases import cases  # noqa: E402
from certkit.study.analysis.montecarlo import run_monte_carlo  # noqa: E402
from certkit.study.analysis.surrogates import fit_all  # noqa: E402
from tests.study_analysis.synthetic import frame_of, sample, study_dict, study_of, unit  # noqa: E402

EXTRA_RULES = ["25.331(c)(1)", "25.331(c)(2)", "25.333", "25.349(b)", "25.143(h)", "25.111", "25.125", "25.145(a)"]


def seed_sized_study():
    study = study_dict(
        level_relaxation=[{"responses": "level.*.cg2*.*", "max_level": 2}],
        uncertainty=[{"responses": "rule.25.331*", "percent": 10, "distribution": "uniform"}],
    )
    study["constraints"] += [{"name": f"§{r}", "response": f"rule.{r}.margin", "min": 0.0} for r in EXTRA_RULES]
    frames = []
    for x, block, role, seed in (
        (sample(793, 1), "ccd+lhs", "training", 1),
        (sample(200, 2), "random", "validation", 2),
    ):
        df = frame_of(x, block, role, fail_every=40, noise=0.002, seed=seed)
        u = unit(x)
        for k, rule in enumerate(EXTRA_RULES):  # smooth margins with different active variables
            w = np.cos(np.arange(8) * (k + 1))
            df[f"resp:rule.{rule}.margin"] = 0.1 + 0.15 * u @ w / 4 + 0.05 * u[:, k % 8] ** 2
            df.loc[df["status"] == "failed", f"resp:rule.{rule}.margin"] = np.nan
        frames.append(df)
    import pandas as pd

    return study_of(study), pd.concat(frames, ignore_index=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=float, default=1e6)
    ap.add_argument("--report", action="store_true", help="also write the whole report (to /tmp)")
    args = ap.parse_args()
    study, frame = seed_sized_study()
    view = study
    t0 = time.perf_counter()
    surrogates, not_fitted = fit_all(view, cases(frame, view), lambda m: None)
    t_fit = time.perf_counter() - t0
    kinds = {}
    for s in surrogates.values():
        kinds[s.kept.label] = kinds.get(s.kept.label, 0) + 1
    print(f"surrogates: {len(surrogates)} responses in {t_fit:.1f} s; kept {kinds}; not fitted {not_fitted}")
    t0 = time.perf_counter()
    mc = run_monte_carlo(view, surrogates, n=int(args.samples))
    t_mc = time.perf_counter() - t0
    p, se = mc.stage_p("constrained")
    print(
        f"Monte Carlo: {mc.n} samples × {len(surrogates)} surrogates in {t_mc:.1f} s (target < 30 s); "
        f"joint P {p:.4f} ± {se:.4f}"
    )
    if args.report:
        t0 = time.perf_counter()
        path = write_study_report(study, frame, "/tmp/bench_study_report", samples=int(args.samples), check=False)
        print(f"whole report: {time.perf_counter() - t0:.1f} s, {path} ({path.stat().st_size / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()

"""One small study report, built once per test session (shared by the report and browser tests)."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from certkit.report.study_report import render
from certkit.study.analysis.analyse import analyse
from tests.study_analysis.synthetic import store_frame, synthetic_study

OPTIONS = {
    "level_relaxation": [{"responses": "level.*.cg2*.*", "max_level": 2}],
    "uncertainty": [{"responses": "subcheck.*", "percent": 5, "distribution": "normal"}],
    "gp_max_cases": 150,
}


@lru_cache(maxsize=1)
def small_report():
    """(analysis, html) of a synthetic study: 200 training and 60 validation cases, 1 in 25 failed."""
    analysis = analyse(synthetic_study(**OPTIONS), store_frame(n_train=200, n_val=60), samples=20_000, check=False)
    return analysis, render(analysis)


def write_small_report(folder: Path) -> Path:
    path = folder / "index.html"
    path.write_text(small_report()[1], encoding="utf-8")
    return path

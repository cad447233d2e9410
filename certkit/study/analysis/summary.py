"""The headline of a study's analysis as plain data (``summary.json`` beside the study report): the cases, the
probability of success of every constraint ranked (least first) with its 95 % Wilson interval and, where a level
relaxation applies, the relaxed one; which constraints are active at the constrained optima; the show-stoppers
with their reasons; the joint probabilities per stage; the true-model check of the probabilities; the optima with
surrogate and true values. What a reader of the README or a CI job needs without opening the page."""

from __future__ import annotations

import math
from typing import Any

from certkit.study.analysis.analyse import Analysis
from certkit.study.analysis.montecarlo import STAGES

#: the summary's format
SUMMARY_SCHEMA = "certkit.study-summary/1"


def _number(value: float | None, digits: int = 6) -> float | None:
    if value is None or not math.isfinite(value):
        return None
    return float(f"{value:.{digits}g}")


def _interval(iv: tuple[float, float] | None) -> list[float | None] | None:
    return None if iv is None else [_number(iv[0]), _number(iv[1])]


def study_summary(a: Analysis) -> dict[str, Any]:
    """The summary of an analysis (module doc); probabilities are among possible designs (the masked ones apart)."""
    mc = a.mc
    stoppers = {s.name: s.reason for s in a.show_stoppers}
    summary: dict[str, Any] = {
        "schema": SUMMARY_SCHEMA,
        "study": a.view.name,
        "study_sha256": a.sha256,
        "cases": {str(k): int(v) for k, v in a.n_cases.items()},
    }
    if mc is None:
        summary["monte_carlo"] = None
        summary["note"] = a.mc_note
        return summary
    summary["monte_carlo"] = {"samples": mc.n, "drawn": mc.n_drawn, "masked_impossible": mc.masked}
    summary["stages"] = {
        stage: {"p": _number(mc.stage_p(stage)[0]), "interval95": _interval(mc.stage_interval(stage))}
        for stage in STAGES
    }
    summary["constraints"] = [
        {
            "name": o.constraint.name,
            "response": o.constraint.response,
            "p": _number(o.p),
            "interval95": _interval(o.interval),
            "p_relaxed": _number(o.p_relaxed),
            "interval95_relaxed": _interval(o.interval_relaxed),
            "fails_alone_samples": o.sole_violations,
            "active_for": a.active.get(o.constraint.name, []),
            "show_stopper": stoppers.get(o.constraint.name),
            "surrogate_flagged": o.flagged,
        }
        for o in mc.ranked()
    ]
    if a.check is not None:
        summary["true_model_check"] = {
            "designs": a.check.n_requested,
            "ok": a.check.n_ok,
            "joint": None
            if a.check.joint is None
            else {
                "p_true": _number(a.check.joint.p_true),
                "interval95_true": _interval(a.check.joint.interval_true),
                "p_monte_carlo": _number(a.check.joint.p_mc),
            },
        }
    summary["optima"] = [
        {
            "objective": c.optimum.objective,
            "stage": c.optimum.stage,
            "method": c.optimum.method,
            "status": c.status,
            "predicted": {k: _number(v) for k, v in c.predicted.items()},
            "true": {k: _number(v) for k, v in c.true.items()},
        }
        for c in a.optima
    ]
    return summary

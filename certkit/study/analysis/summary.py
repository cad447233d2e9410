"""The headline of a study's analysis as plain data (``summary.json`` beside the study report): the cases, the
probability of success of every constraint ranked (least first) with its 95 % Wilson interval and, where a level
relaxation applies, the relaxed one; which constraints are active at the constrained optima (or, where no design
meets them all, which conflict at the design of least violation); the show-stoppers with their reasons; the joint
probabilities per stage; the handling-quality levels derived from the mode quantities with their agreement; the
true-model check of the probabilities; the optima with surrogate and true values, and the constrained optima as
confirmed by the true model. What a reader of the README or a
CI job needs without opening the page."""

from __future__ import annotations

from typing import Any

from certkit.engine.results_json import clean
from certkit.study.analysis.analyse import Analysis
from certkit.study.analysis.confirm import Confirmation
from certkit.study.analysis.montecarlo import STAGES
from certkit.study.spec import Study

#: the summary's format
SUMMARY_SCHEMA = "certkit.study-summary/1"


def study_summary(a: Analysis) -> dict[str, Any]:
    """The summary of an analysis (module doc) as plain JSON data (numbers rounded, non-finite ones null, as in
    results.json: :func:`certkit.engine.results_json.clean`); probabilities are among possible designs (the masked
    ones apart)."""
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
        return _plain(summary)
    summary["monte_carlo"] = {"samples": mc.n, "drawn": mc.n_drawn, "masked_impossible": mc.masked}
    summary["stages"] = {stage: {"p": mc.stage_p(stage)[0], "interval95": mc.stage_interval(stage)} for stage in STAGES}
    summary["constraints"] = [
        {
            "name": o.constraint.name,
            "response": o.constraint.response,
            "p": o.p,
            "interval95": o.interval,
            "p_relaxed": o.p_relaxed,
            "interval95_relaxed": o.interval_relaxed,
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
                "p_true": a.check.joint.p_true,
                "interval95_true": a.check.joint.interval_true,
                "p_monte_carlo": a.check.joint.p_mc,
            },
        }
    summary["conflicts"] = dict(a.conflicts)
    summary["levels"] = [
        {
            "response": name,
            "derived_from": dict(d.source.sources),
            "validation_agreement": d.agreement,
            "n_validation": d.n_validation,
            "reproduced_from_record": [d.n_reproduced, d.n_recorded],
            "flagged": d.flagged,
        }
        for name, d in a.levels.items()
    ]
    summary["optima"] = [
        {
            "objective": c.optimum.objective,
            "stage": c.optimum.stage,
            "method": c.optimum.method,
            "status": c.status,
            "predicted": dict(c.predicted),
            "true": dict(c.true),
        }
        for c in a.optima
    ]
    summary["confirmed_optima"] = [_confirmation(c, a.view) for c in a.confirmations]
    return _plain(summary)


def _confirmation(c: Confirmation, view: Study) -> dict[str, Any]:
    design = c.design
    return {
        "objective": c.optimum.objective,
        "stage": c.optimum.stage,
        "status": c.status,
        "reason": c.reason,
        "true_model_evaluations": c.evaluations,
        "gradient_evaluations": c.probes,
        "steps": [
            {"violated": list(s.violated), "violation": s.violation, "objective": s.true.get(c.optimum.objective)}
            for s in c.steps
        ],
        "surrogate_optimum": {
            "variables": _variables(c.optimum.x, view),
            "true": dict(c.steps[0].true) if c.steps else {},
        },
        "design": None
        if design is None
        else {"variables": _variables(design.x, view), "true": dict(design.true), "violated": list(design.violated)},
    }


def _variables(x: Any, view: Study) -> dict[str, float]:
    return {v.path: float(val) for v, val in zip(view.variables, x)}


def _plain(summary: dict[str, Any]) -> dict[str, Any]:
    """The summary with its numbers as results.json writes them (a mapping stays a mapping)."""
    data, _ = clean(summary)
    assert isinstance(data, dict)
    return data

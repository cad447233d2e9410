"""Every analysis of a finished study: :func:`analyse` runs them on the store's frame (surrogates, Monte Carlo,
Pareto fronts, optima, Sobol indices, and — unless switched off — the true-model checks through the study runner)
and returns them as data (:class:`Analysis`); the report layer draws the page.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from certkit.study.analysis.baseline_bounds import with_baseline_bounds
from certkit.study.analysis.cases import cases, study_hash
from certkit.study.analysis.checks import CheckedOptimum, DirectCheck, RunCases, direct_check, reevaluate_optima
from certkit.study.analysis.confirm import CONFIRMED, Confirmation, confirm_optima
from certkit.study.analysis.derived_levels import DerivedLevel, fit_predictors
from certkit.study.analysis.montecarlo import MonteCarloResult, Optimum, run_monte_carlo
from certkit.study.analysis.optimise import front_points, optimise, pareto_fronts
from certkit.study.analysis.profiler import profiler_data
from certkit.study.analysis.ranking import (
    ShowStopper,
    active_constraints,
    conflicting_constraints,
    show_stoppers,
    without_unattainable,
)
from certkit.study.analysis.sensitivity import SobolTable, sobol_indices
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.analysis.validity import Validity, fit_validity
from certkit.study.spec import Study
from certkit.study.store import Store

#: points of each NSGA-II front re-evaluated with the true model
FRONT_CHECKED = 5


@dataclass
class Analysis:
    view: Study
    sha256: str
    counts: pd.DataFrame
    failed: pd.DataFrame
    n_cases: dict[str, int]
    surrogates: dict[str, Surrogate]
    not_fitted: dict[str, str]
    mc: MonteCarloResult | None
    mc_note: str
    sobol: list[SobolTable]
    check: DirectCheck | None
    check_note: str
    optima: list[CheckedOptimum]
    profiler: dict[str, Any]
    timings: dict[str, float] = field(default_factory=dict)
    validity: Validity | None = None
    nsga_fronts: list[dict[str, Any]] = field(default_factory=list)
    front_checks: list[CheckedOptimum] = field(default_factory=list)
    show_stoppers: list[ShowStopper] = field(default_factory=list)
    active: dict[str, list[str]] = field(default_factory=dict)
    levels: dict[str, DerivedLevel] = field(default_factory=dict)
    conflicts: dict[str, list[str]] = field(default_factory=dict)
    #: the constrained and preferred optima searched again until the true model accepts a design
    confirmations: list[Confirmation] = field(default_factory=list)


def _run_checks(
    usable: Study,
    every: Study,
    store: Store | None,
    surrogates: dict[str, Surrogate],
    mc: MonteCarloResult,
    optima: list[Optimum],
    run_cases: RunCases | None,
) -> tuple[DirectCheck | None, list[CheckedOptimum], str]:
    if store is None:
        return None, [], "not run: no study store to record the true-model cases in"
    check = direct_check(usable, store, surrogates, mc, run_cases=run_cases)
    checked = reevaluate_optima(every, store, surrogates, optima, run_cases=run_cases)
    return check, checked, ""


def analyse(
    study: Study,
    frame: pd.DataFrame,
    *,
    store: Store | None = None,
    samples: int = 1_000_000,
    check: bool = True,
    sha256: str | None = None,
    chunk: int = 100_000,
    log: Callable[[str], object] = lambda msg: None,
    run_cases: RunCases | None = None,
) -> Analysis:
    """Run every analysis of the study report on the store's ``frame``. ``run_cases``: how the true-model checks
    run (see :func:`~certkit.study.analysis.checks.run_true_model`)."""
    timings: dict[str, float] = {}
    t = time.perf_counter()
    view = with_baseline_bounds(study, frame, store if check else None, run_cases=run_cases, log=log)
    cs = cases(frame, view)
    fitted, levels, not_fitted = fit_predictors(view, cs, log)
    # the levels derived from the mode quantities predict where a regressed level would
    surrogates: dict[str, Any] = {**fitted, **levels}
    timings["surrogates_s"] = time.perf_counter() - t
    usable = view.model_copy(
        update={
            "objectives": [o for o in view.objectives if o.response in surrogates],
            "constraints": [c for c in view.constraints if c.response in surrogates],
        }
    )
    mc_note = "; ".join(f"{r} left out: {not_fitted[r]}" for r in not_fitted)
    t = time.perf_counter()
    validity = fit_validity(frame, view)
    log(f"possible designs: {validity.note}")
    mc = run_monte_carlo(usable, surrogates, n=samples, chunk=chunk, valid=validity.valid)
    every = usable  # show-stoppers are ranked and reported; the stages, fronts and optima are of the rest
    usable, mc = without_unattainable(
        usable,
        surrogates,
        mc,
        lambda rest: run_monte_carlo(rest, surrogates, n=samples, chunk=chunk, valid=validity.valid),
        cs,
    )
    timings["monte_carlo_s"] = time.perf_counter() - t
    log(f"Monte Carlo: {samples} samples in {mc.seconds:.1f} s")
    t = time.perf_counter()
    sobol = [sobol_indices(view, fitted[r]) for r in view.analysed_responses() if r in fitted]
    timings["sobol_s"] = time.perf_counter() - t
    t = time.perf_counter()
    margin = validity.margin if validity.estimator is not None else None
    optima = optimise(usable, surrogates, mc, margin)
    nsga = pareto_fronts(usable, surrogates, margin)
    points = optima + front_points(nsga, FRONT_CHECKED)
    timings["optimiser_s"] = time.perf_counter() - t
    log(f"optimiser: {len(optima)} optima, {len(nsga)} NSGA-II fronts in {timings['optimiser_s']:.1f} s")
    checked: list[CheckedOptimum] = []
    confirmations: list[Confirmation] = []
    direct: DirectCheck | None = None
    check_note = "not run (--no-check)"
    if check:
        t = time.perf_counter()
        direct, checked, check_note = _run_checks(usable, every, store, surrogates, mc, points, run_cases)
        timings["true_model_s"] = time.perf_counter() - t
        if store is not None:
            t = time.perf_counter()
            confirmations = confirm_optima(
                usable, store, surrogates, checked[: len(optima)], margin, run_cases=run_cases
            )
            timings["confirm_s"] = time.perf_counter() - t
            n_ok = sum(c.status == CONFIRMED for c in confirmations)
            designs = {tuple(np.round(s.x, 12)) for c in confirmations for s in c.steps[1:]}
            log(
                f"confirmation: {n_ok} of {len(confirmations)} constrained optima confirmed by the true model "
                f"({len(designs)} further designs, and their gradients) in {timings['confirm_s']:.1f} s"
            )
    if not checked:
        checked = [
            CheckedOptimum(
                o,
                "not evaluated",
                check_note,
                {},
                {
                    r: float(surrogates[r].predict(o.x[None, :])[0])
                    for r in every.analysed_responses()
                    if r in surrogates
                },
            )
            for o in points
        ]
    counts = cs.counts()
    n_cases = {"total": len(frame), **frame["status"].value_counts().to_dict()}
    return Analysis(
        view,
        sha256 or study_hash(view),
        counts,
        cs.failed(),
        n_cases,
        fitted,
        not_fitted,
        mc,
        mc_note,
        sobol,
        direct,
        check_note,
        checked[: len(optima)],
        profiler_data(every, fitted, validity=validity, levels=levels),
        timings,
        validity,
        nsga,
        checked[len(optima) :],
        show_stoppers(every, mc, cs, not_fitted),
        active_constraints(usable, surrogates, optima),
        levels,
        conflicting_constraints(usable, surrogates, optima),
        confirmations,
    )


__all__ = ["Analysis", "analyse"]

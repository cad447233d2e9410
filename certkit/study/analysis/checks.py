"""The true model behind the surrogates: a direct check of the Monte Carlo probabilities on a fresh random
sample of designs, and the re-evaluation of the optima. Both go through the study runner,
``certkit.study.runner.run_study_cases`` (the same case machinery, key and store as the study itself)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd

from certkit.study import runner
from certkit.study.analysis.cases import RESP_PREFIX, VAR_PREFIX
from certkit.study.analysis.intervals import wilson
from certkit.study.analysis.montecarlo import MonteCarloResult, Optimum, binomial_se
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.spec import Constraint, Study
from certkit.study.store import Store

#: how true-model cases run: (study, store, points, block=, role=) → the cases as rows (the study runner's call) or
#: as a frame
RunCases = Callable[..., "pd.DataFrame | list[dict[str, Any]]"]


def at_point(table: np.ndarray, point: np.ndarray) -> np.ndarray:
    """Mask of the rows of ``table`` (cases' variables, SI) that are the design ``point`` (to 1e-9 relative)."""
    return np.asarray(np.all(np.abs(table - point) <= 1e-9 * np.maximum(np.abs(point), 1e-12), axis=1))


def run_true_model(
    study: Study,
    store: Store,
    x: np.ndarray,
    *,
    block: str,
    role: str = "check",
    run_cases: RunCases | None = None,
) -> pd.DataFrame:
    """Evaluate the designs ``x`` (rows, SI, in the order of the study's variables) with the true model through
    the study runner; returns the cases in the store's frame format, in the order of ``x``. ``run_cases``: the
    runner call with the study's executor and progress display (default: local processes, no display); designs
    the store already holds are not evaluated again."""
    points = [{v.path: float(val) for v, val in zip(study.variables, row)} for row in np.atleast_2d(x)]
    frame = (run_cases or runner.run_study_cases)(study, store, points, block=block, role=role)
    if not isinstance(frame, pd.DataFrame):  # the runner's rows: their cases in the store's frame, whatever block
        keys = {row["key"] for row in frame}  # first held them (a design already in the plan is not run again)
        frame = store.frame()
        frame = frame[frame["key"].isin(keys)]
    columns = [VAR_PREFIX + v.path for v in study.variables]
    # match the returned cases to the requested points (a resumed check may return them in another order)
    table = frame[columns].to_numpy(dtype=float)
    rows = []
    for point in np.atleast_2d(x):
        hits = np.flatnonzero(at_point(table, point))
        rows.append(
            frame.iloc[hits[0]]
            if hits.size
            else pd.Series({"status": "missing", "error": "the runner returned no case for this point"})
        )
    return pd.DataFrame(rows).reset_index(drop=True)


@dataclass
class CheckedConstraint:
    constraint: Constraint
    n: int
    p_true: float
    p_surrogate_same: float
    p_mc: float
    se_true: float
    se_mc: float

    @property
    def interval_true(self) -> tuple[float, float]:
        """95 % Wilson interval of the true model's probability of success on its n designs."""
        return wilson(round(self.p_true * self.n), self.n)

    @property
    def difference(self) -> float:
        return self.p_true - self.p_mc

    @property
    def se_difference(self) -> float:
        return float(np.hypot(self.se_true, self.se_mc))


@dataclass
class DirectCheck:
    n_requested: int
    n_ok: int
    n_failed: int
    failures: list[tuple[str, str]]
    constraints: list[CheckedConstraint]
    joint: CheckedConstraint | None


def _feasible_all(study: Study, values: dict[str, np.ndarray], n: int) -> np.ndarray:
    ok = np.ones(n, dtype=bool)
    for c in study.constraints:
        ok &= study.holds(c, values[c.response])
    return ok


def direct_check(
    study: Study,
    store: Store,
    surrogates: dict[str, Surrogate],
    mc: MonteCarloResult,
    *,
    n: int = 100,
    seed: int = 7,
    run_cases: RunCases | None = None,
) -> DirectCheck:
    """Draw ``n`` fresh uniform designs (a seed other than the Monte Carlo's), evaluate them with the true model
    and compare each constraint's probability of success (and the joint one) with the Monte Carlo estimate."""
    bounds = study.bounds
    rng = np.random.default_rng([seed, mc.seed])
    x = bounds[:, 0] + (bounds[:, 1] - bounds[:, 0]) * rng.random((n, len(bounds)))
    frame = run_true_model(study, store, x, block="check", role="check", run_cases=run_cases)
    ok = (frame["status"] == "ok").to_numpy()
    failures = [(str(r.get("key", "")), str(r.get("error", ""))) for _, r in frame[~ok].iterrows()]
    x_ok = x[ok]
    truth = {
        c.response: frame.loc[ok, RESP_PREFIX + c.response].to_numpy(dtype=float)
        if RESP_PREFIX + c.response in frame.columns
        else np.full(int(ok.sum()), np.nan)
        for c in study.constraints
    }
    predicted = {r: surrogates[r].predict(x_ok) for r in truth}
    k = int(ok.sum())
    checked = []
    by_name = {o.constraint.name: o for o in mc.constraints}
    for c in study.constraints:
        p_true = float(np.mean(study.holds(c, truth[c.response]))) if k else float("nan")
        p_same = float(np.mean(study.holds(c, predicted[c.response]))) if k else float("nan")
        out = by_name[c.name]
        p_mc = out.p_relaxed if out.p_relaxed is not None else out.p
        checked.append(CheckedConstraint(c, k, p_true, p_same, p_mc, binomial_se(p_true, k), binomial_se(p_mc, mc.n)))
    joint = None
    if study.constraints and k:
        p_true = float(np.mean(_feasible_all(study, truth, k)))
        p_same = float(np.mean(_feasible_all(study, predicted, k)))
        p_mc, se_mc = mc.stage_p("constrained")
        joint = CheckedConstraint(
            Constraint.model_construct(name="all constraints", response="joint", min=None, max=None),
            k,
            p_true,
            p_same,
            p_mc,
            binomial_se(p_true, k),
            se_mc,
        )
    return DirectCheck(n, k, len(frame) - k, failures, checked, joint)


@dataclass
class CheckedOptimum:
    optimum: Optimum
    status: str
    error: str
    true: dict[str, float | None]
    predicted: dict[str, float]


def reevaluate_optima(
    study: Study,
    store: Store,
    surrogates: dict[str, Surrogate],
    optima: list[Optimum],
    *,
    run_cases: RunCases | None = None,
) -> list[CheckedOptimum]:
    """Evaluate each optimum's design with the true model; objectives and constraint responses, predicted and
    true, side by side."""
    if not optima:
        return []
    x = np.array([o.x for o in optima])
    frame = run_true_model(study, store, x, block="optima", role="check", run_cases=run_cases)
    names = study.analysed_responses()
    out = []
    for i, opt in enumerate(optima):
        row = frame.iloc[i]
        ok = row.get("status") == "ok"
        true = {
            r: (
                float(row[RESP_PREFIX + r])
                if ok and RESP_PREFIX + r in row.index and np.isfinite(row[RESP_PREFIX + r])
                else None
            )
            for r in names
        }
        predicted = {r: float(surrogates[r].predict(opt.x[None, :])[0]) for r in names if r in surrogates}
        out.append(
            CheckedOptimum(opt, str(row.get("status")), "" if ok else str(row.get("error") or ""), true, predicted)
        )
    return out

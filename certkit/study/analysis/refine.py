"""Adaptive refinement: new training cases where the surrogates are least sure of a constraint or a front.

For a candidate design x and a constraint with threshold t, the surrogate's prediction ŷ(x) and its
cross-validated RMSE σ give the chance that the true response lies on the other side of t,
Φ(−|ŷ − t| / σ) (a Gaussian error model: the "probability of misclassification" criterion of reliability-based
adaptive sampling, Echard, Gayton & Lemaire 2011, *Structural Safety* 33: 145–154, with the surrogate's
cross-validated error in place of a kriging variance). A candidate scores the largest of these over the
constraints; points of the NSGA-II fronts score ½ (the front's position is as uncertain as a boundary). The
new cases are chosen greedily by score among uniform candidates classed as possible designs, each at least
a fixed distance from the study's cases and from the others chosen (so that they spread along the boundary).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.special import ndtr

from certkit.study.analysis.baseline_bounds import with_baseline_bounds
from certkit.study.analysis.cases import VAR_PREFIX, cases
from certkit.study.analysis.derived_levels import fit_predictors
from certkit.study.analysis.montecarlo import MonteCarloResult, run_monte_carlo
from certkit.study.analysis.optimise import pareto_fronts
from certkit.study.analysis.surrogates import Surrogate, to_unit
from certkit.study.analysis.validity import Validity, fit_validity
from certkit.study.runner import run_study_cases
from certkit.study.spec import Study
from certkit.study.store import Store

if TYPE_CHECKING:
    import pandas as pd

    from certkit.study.analysis.checks import RunCases

#: uniform candidates drawn per refinement
CANDIDATES = 20_000


def _relative_error(level: Any) -> float:
    """The largest cross-validated RMSE of a derived level's quantities relative to their mean magnitude."""
    out = 1e-12
    for q in level.quantities.values():
        y = q.plot_data.get("train", (np.empty(0),))[0]
        scale = float(np.mean(np.abs(y))) if len(y) else 0.0
        if q.cv.rmse and scale > 0:
            out = max(out, q.cv.rmse / scale)
    return out


def misclassification(study: Study, surrogates: dict[str, Surrogate], x: np.ndarray) -> np.ndarray:
    """Per design, the largest chance over the constraints that the surrogate puts it on the wrong side."""
    score = np.zeros(len(x))
    for c in study.constraints:
        s = surrogates.get(c.response)
        if s is None:
            continue
        upper = study.allowed_max(c)
        if hasattr(s, "level_margin") and upper is not None:
            # a derived level: its margin is a relative distance to the level's boundaries, uncertain by about the
            # quantities' relative cross-validated error
            score = np.maximum(score, ndtr(-np.abs(s.level_margin(x, int(upper))) / _relative_error(s)))
            continue
        y = s.predict(x)
        sigma = max(s.cv.rmse or 0.0, 1e-12 * max(1.0, float(np.nanmax(np.abs(y)))))
        half = 0.5 if c.is_level else 0.0  # a level L counts up to L + ½
        for t in (None if c.min is None else c.min - half, None if upper is None else upper + half):
            if t is not None:
                score = np.maximum(score, ndtr(-np.abs(y - t) / sigma))
    return score


def refinement_points(
    study: Study,
    surrogates: dict[str, Surrogate],
    existing: np.ndarray,
    n: int,
    *,
    valid: Callable[[np.ndarray], np.ndarray] | None = None,
    front_x: np.ndarray | None = None,
    seed: int = 0,
    candidates: int = CANDIDATES,
) -> np.ndarray:
    """``n`` new designs (rows, SI) where the constraint boundaries and the fronts are least certain."""
    bounds = study.bounds
    rng = np.random.default_rng(seed)
    x = bounds[:, 0] + (bounds[:, 1] - bounds[:, 0]) * rng.random((candidates, len(bounds)))
    if valid is not None:
        x = x[valid(x)]
    score = misclassification(study, surrogates, x)
    if front_x is not None and len(front_x):
        x = np.vstack([x, front_x])
        score = np.concatenate([score, np.maximum(misclassification(study, surrogates, front_x), 0.5)])
    u = to_unit(x, bounds)
    taken = to_unit(np.atleast_2d(existing), bounds) if len(existing) else np.empty((0, len(bounds)))
    # spacing: a fraction of the mean distance between n + existing points spread over the box
    spacing = 0.5 * 2.0 * (len(taken) + n) ** (-1.0 / len(bounds))
    chosen: list[int] = []
    for i in np.argsort(-score, kind="stable"):
        if len(chosen) == n:
            break
        if len(taken) and np.min(np.max(np.abs(taken - u[i]), axis=1)) < spacing:
            continue
        chosen.append(int(i))
        taken = np.vstack([taken, u[i]])
    points: np.ndarray = x[chosen]
    return points


@dataclass
class Movement:
    """How one constraint's probability of success moved with the refinement."""

    name: str
    p_before: float
    interval_before: tuple[float, float]
    p_after: float
    interval_after: tuple[float, float]


@dataclass
class Refinement:
    block: str
    added: int
    ok: int
    movements: list[Movement]
    joint: Movement


def _state(
    study: Study, frame: pd.DataFrame, samples: int, log: Callable[[str], object]
) -> tuple[Study, dict[str, Surrogate], Validity, MonteCarloResult, np.ndarray | None]:
    """Surrogates, validity, the Monte Carlo result and the fronts' designs of the cases in ``frame``."""
    fitted, levels, not_fitted = fit_predictors(study, cases(frame, study), log)
    surrogates: dict[str, Any] = {**fitted, **levels}
    usable = study.model_copy(
        update={
            "objectives": [o for o in study.objectives if o.response in surrogates],
            "constraints": [c for c in study.constraints if c.response in surrogates],
        }
    )
    validity = fit_validity(frame, study)
    mc = run_monte_carlo(usable, surrogates, n=samples, chunk=min(samples, 100_000), valid=validity.valid)
    margin = validity.margin if validity.estimator is not None else None
    fronts = pareto_fronts(usable, surrogates, margin) if len(usable.objectives) >= 2 else []
    front_x = np.vstack([f["x"] for f in fronts]) if fronts and any(len(f["x"]) for f in fronts) else None
    return usable, surrogates, validity, mc, front_x


def refine(
    study: Study,
    store: Store,
    n: int,
    *,
    samples: int = 200_000,
    run_cases: RunCases | None = None,
    log: Callable[[str], object] = lambda msg: None,
) -> Refinement:
    """Add ``n`` training cases where the constraint boundaries and the fronts are least certain, evaluate them
    with the true model through the study runner (block ``refine-K``), refit, and report how each constraint's
    probability of success moved."""
    if run_cases is None:
        run_cases = run_study_cases
    study = with_baseline_bounds(study, store.frame(), store, run_cases=run_cases, log=log)
    frame = store.frame()
    usable, surrogates, validity, mc, front_x = _state(study, frame, samples, log)
    existing = frame[[VAR_PREFIX + v.path for v in study.variables]].to_numpy(dtype=float)
    x = refinement_points(usable, surrogates, existing, n, valid=validity.valid, front_x=front_x)
    rounds = {b for b in frame["block"].unique() if str(b).startswith("refine-")}
    block = f"refine-{len(rounds) + 1}"
    log(f"refine: {len(x)} new training cases in block {block}")
    rows = run_cases(
        study,
        store,
        [{v.path: float(val) for v, val in zip(study.variables, row)} for row in x],
        block=block,
        role="training",
    )
    ok = sum(1 for r in rows if (r.get("status") if isinstance(r, dict) else None) == "ok")
    after_usable, _, _, after, _ = _state(study, store.frame(), samples, log)
    moved = []
    for o in mc.constraints:
        a = next((c for c in after.constraints if c.constraint.name == o.constraint.name), None)
        if a is not None:
            moved.append(Movement(o.constraint.name, o.p, o.interval, a.p, a.interval))
    joint = Movement(
        "all constraints",
        mc.stage_counts["constrained"] / mc.n,
        mc.stage_interval("constrained"),
        after.stage_counts["constrained"] / after.n,
        after.stage_interval("constrained"),
    )
    return Refinement(block, len(x), ok, moved, joint)

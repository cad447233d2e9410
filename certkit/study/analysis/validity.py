"""Which designs of the box are possible aircraft: a classifier of the study's own infeasible cases.

A case whose variables make an impossible aircraft (a tail tip behind the fuselage end, …) fails with the
reason ``infeasible design: …`` (:class:`certkit.errors.InfeasibleDesign`); the check needs the whole aircraft
file, so it cannot be evaluated on 10⁶ samples. Instead a logistic regression on a polynomial of the inputs
(mapped to [−1, 1]; degree 1 or 2 and the regularisation chosen by stratified cross-validation, scikit-learn
``LogisticRegressionCV``) learns the boundary from the cases: possible (ok, or failed for another reason)
against impossible. Samples it classes as impossible are masked before Monte Carlo, Pareto fronts and optima.
Its cross-validated confusion counts are reported; with no impossible case among the cases nothing is masked.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
import pandas as pd
from sklearn.exceptions import ConvergenceWarning
from sklearn.linear_model import LogisticRegressionCV
from sklearn.model_selection import StratifiedKFold, cross_val_predict
from sklearn.pipeline import Pipeline, make_pipeline
from sklearn.preprocessing import PolynomialFeatures, StandardScaler

from certkit.study.analysis.cases import VAR_PREFIX
from certkit.study.analysis.surrogates import to_unit
from certkit.study.spec import Study

INFEASIBLE = "infeasible design"
DEGREES = (1, 2)
#: fewer impossible cases than this: too few to learn a boundary from
MIN_INFEASIBLE = 3


@dataclass
class Validity:
    """The classifier of possible designs (None: every design taken as possible) and how it scored."""

    bounds: np.ndarray
    estimator: Pipeline | None
    n_cases: int
    n_infeasible: int
    missed: int = 0  # impossible cases the cross-validated classifier took as possible
    false_alarms: int = 0  # possible cases it took as impossible
    note: str = ""

    def valid(self, x: np.ndarray) -> np.ndarray:
        """Mask of the designs ``x`` (rows, SI) classed as possible aircraft."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        if self.estimator is None:
            return np.ones(len(x), dtype=bool)
        possible: np.ndarray = np.asarray(self.estimator.predict(to_unit(x, self.bounds))) == 0
        return possible

    def export(self) -> dict[str, Any] | None:
        """The classifier as data the profiler page evaluates (None: every design taken as possible): the inputs
        mapped to [−1, 1] over ``lo``/``hi``, the polynomial ``terms`` ([[variable, power], …] per feature), the
        scaler's ``mean``/``scale`` and the logistic ``coef``/``intercept``; the log-odds of impossible is
        intercept + Σ coef (feature − mean) / scale, impossible where it is positive (:func:`validity_log_odds`)."""
        if self.estimator is None:
            return None
        poly, scaler, logistic = (step for _, step in self.estimator.steps)
        return {
            "lo": [float(v) for v in self.bounds[:, 0]],
            "hi": [float(v) for v in self.bounds[:, 1]],
            "terms": [[[int(i), int(p)] for i, p in enumerate(row) if p] for row in poly.powers_],
            "mean": [float(v) for v in scaler.mean_],
            "scale": [float(v) for v in scaler.scale_],
            "coef": [float(v) for v in logistic.coef_[0]],
            "intercept": float(logistic.intercept_[0]),
        }

    def margin(self, x: np.ndarray) -> np.ndarray:
        """A smooth margin, ≥ 0 where the design is classed as possible (minus the classifier's log-odds of
        impossible): the optimiser's constraint."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        if self.estimator is None:
            return np.ones(len(x))
        margin: np.ndarray = -np.asarray(self.estimator.decision_function(to_unit(x, self.bounds)), dtype=float)
        return margin


def infeasible_mask(frame: pd.DataFrame) -> np.ndarray:
    """Cases that failed because their variables make an impossible aircraft."""
    error = frame["error"].fillna("").astype(str)
    mask: np.ndarray = ((frame["status"] == "failed") & error.str.startswith(INFEASIBLE)).to_numpy()
    return mask


def _classifier(degree: int, folds: int) -> Pipeline:
    return make_pipeline(
        PolynomialFeatures(degree, include_bias=False),
        StandardScaler(),
        LogisticRegressionCV(Cs=np.logspace(-1, 4, 6), cv=folds, max_iter=2000, scoring="neg_log_loss"),
    )


def fit_validity(frame: pd.DataFrame, study: Study) -> Validity:
    """The classifier of possible designs from every case with an outcome (ok, or failed with a reason)."""
    bounds = study.bounds
    done = frame[frame["status"].isin(["ok", "failed"])]
    x = done[[VAR_PREFIX + v.path for v in study.variables]].to_numpy(dtype=float)
    y = infeasible_mask(done).astype(int)
    n_bad = int(y.sum())
    if n_bad < MIN_INFEASIBLE or n_bad == len(y):
        note = (
            "no impossible design among the cases: nothing masked"
            if n_bad == 0
            else f"{n_bad} impossible design{'s' if n_bad != 1 else ''} among {len(y)} cases, too few to learn a "
            f"boundary from: nothing masked"
        )
        return Validity(bounds, None, len(y), n_bad, note=note)
    u = to_unit(x, bounds)
    folds = min(5, n_bad)
    best: tuple[int, int, np.ndarray] | None = None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        warnings.simplefilter("ignore", FutureWarning)
        for degree in DEGREES:
            if math.comb(u.shape[1] + degree, degree) > len(y) / 2:
                break
            predicted = cross_val_predict(
                _classifier(degree, folds), u, y, cv=StratifiedKFold(folds, shuffle=True, random_state=0)
            )
            errors = int(np.sum(predicted != y))
            if best is None or errors < best[1]:
                best = (degree, errors, predicted)
        if best is None:
            return Validity(
                bounds,
                None,
                len(y),
                n_bad,
                note=f"{len(y)} cases are too few for a linear classifier of {u.shape[1]} variables: nothing masked",
            )
        degree, _, predicted = best
        estimator = _classifier(degree, folds).fit(u, y)
    missed, alarms = int(np.sum((y == 1) & (predicted == 0))), int(np.sum((y == 0) & (predicted == 1)))
    note = (
        f"logistic regression on a degree-{degree} polynomial of the variables (degree by cross-validation), "
        f"learnt from {n_bad} impossible designs among {len(y)} cases; {folds}-fold cross-validation: {missed} "
        f"impossible taken as possible, {alarms} possible taken as impossible"
    )
    return Validity(bounds, estimator, len(y), n_bad, missed, alarms, note)


def validity_log_odds(doc: dict[str, Any], x: np.ndarray) -> np.ndarray:
    """The log-odds of impossible of an exported classifier (:meth:`Validity.export`) at the rows of ``x`` (SI),
    with the arithmetic of the profiler page."""
    x = np.atleast_2d(np.asarray(x, dtype=float))
    lo, hi = np.asarray(doc["lo"]), np.asarray(doc["hi"])
    u = (x - lo) * (2.0 / (hi - lo)) - 1.0
    out = np.full(len(x), doc["intercept"])
    for k, term in enumerate(doc["terms"]):
        feature = np.ones(len(x))
        for i, p in term:
            feature = feature * u[:, i] ** p
        out += doc["coef"][k] * (feature - doc["mean"][k]) / doc["scale"][k]
    return out

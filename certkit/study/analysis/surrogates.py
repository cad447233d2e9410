"""Surrogate models of the study's responses (scikit-learn), chosen by validation error, with goodness of fit.

Per response three families are fitted on the training cases, every input first mapped linearly from its
bounds to [−1, 1]:

- multivariate polynomial regression: ``PolynomialFeatures`` (degree 1 up to the highest whose term count
  stays below half the training cases, at most 4) + ``RidgeCV`` (a tiny, cross-validated ridge keeps the
  normal equations well posed); each degree once on the response and once on its logarithm where the response
  is positive (a multiplicative response is linear in its logarithm);
- a neural network: ``MLPRegressor`` (two tanh layers of 16, L-BFGS) with the outputs standardised
  (``TransformedTargetRegressor`` + ``StandardScaler``) on the transform the best polynomial chose;
- a Gaussian process (constant × anisotropic RBF + white noise, ``normalize_y``; its hyperparameters maximise the
  log marginal likelihood, :mod:`.gp_likelihood`); above ``gp_max_cases``
  training cases it is fitted on a space-filling subsample of that many (greedy maximin, farthest-point
  selection from the case nearest the centre; the fit is O(n³) and its prediction O(n) per point).

The candidate with the least k-fold cross-validation RMSE on the training cases is kept; the others are
reported. The validation block never takes part in the choice: it only scores the kept model, so its R² is a
held-out estimate (Hastie, Tibshirani & Friedman, *The Elements of Statistical Learning*, 2nd ed., §7.2 and
§7.10: a set that selects the model no longer estimates its error). Validation cases whose inputs repeat a
training case's are a leak: they are counted and left out of the validation score. Goodness of fit (R², RMSE,
maximum error) is given on training and validation cases and by the kept model's cross-validation, as in a
DoE/RSM fit table (Myers, Montgomery & Anderson-Cook, *Response Surface Methodology*, 4th ed., §2.5 and §7.4).
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from joblib import Parallel, delayed
from scipy.spatial import cKDTree
from scipy.spatial.distance import cdist
from sklearn import config_context
from sklearn.base import BaseEstimator, RegressorMixin, clone
from sklearn.compose import TransformedTargetRegressor
from sklearn.exceptions import ConvergenceWarning
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.linear_model import RidgeCV
from sklearn.model_selection import KFold, cross_val_predict
from sklearn.neural_network import MLPRegressor
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import PolynomialFeatures, StandardScaler

from certkit.study.analysis.gp_likelihood import LikelihoodSearch, kernel
from certkit.study.executors import available_cores

if TYPE_CHECKING:
    from certkit.study.analysis.cases import Cases
    from certkit.study.spec import AnalysisOptions, Study

#: fewer validation cases than this: the flag is judged on the cross-validated R² instead
MIN_VALIDATION = 10
K_FOLDS = 5
MAX_DEGREE = 4
#: points per prediction chunk (bounds the polynomial feature matrix and the GP cross-covariance)
PREDICT_CHUNK = 20_000


def to_unit(x: np.ndarray, bounds: np.ndarray) -> np.ndarray:
    """Map inputs from their bounds to [−1, 1] (column-wise)."""
    lo, hi = bounds[:, 0], bounds[:, 1]
    return np.asarray((np.asarray(x, dtype=float) - lo) * (2.0 / (hi - lo)) - 1.0)


# scikit-learn's estimators carry no types: they travel as Any
def _log_target(estimator: Any, log: bool) -> Any:
    return (
        TransformedTargetRegressor(regressor=estimator, func=np.log, inverse_func=np.exp, check_inverse=False)
        if log
        else estimator
    )


def _polynomial(degree: int) -> Any:
    return make_pipeline(PolynomialFeatures(degree, include_bias=False), RidgeCV(alphas=np.logspace(-10, 1, 12)))


def _mlp() -> Any:
    net = MLPRegressor(
        hidden_layer_sizes=(16, 16), activation="tanh", solver="lbfgs", alpha=1e-4, max_iter=1000, random_state=0
    )
    return TransformedTargetRegressor(regressor=net, transformer=StandardScaler())


def _gp(n_inputs: int, search: LikelihoodSearch) -> Any:
    """The GP regressor whose hyperparameters ``search`` fits (the likelihood of its own training cases)."""
    return GaussianProcessRegressor(kernel(n_inputs), normalize_y=True, optimizer=search, random_state=0)


def maximin_subsample(u: np.ndarray, m: int) -> np.ndarray:
    """Indices of ``m`` rows of ``u`` chosen greedily far apart (farthest-point selection, started at the row
    nearest the centre of the box): a space-filling subsample, deterministic for given cases."""
    n = len(u)
    if m >= n:
        return np.arange(n)
    chosen = [int(np.argmin(np.sum(u**2, axis=1)))]
    dist = np.sum((u - u[chosen[0]]) ** 2, axis=1)
    for _ in range(m - 1):
        j = int(np.argmax(dist))
        chosen.append(j)
        dist = np.minimum(dist, np.sum((u - u[j]) ** 2, axis=1))
    return np.sort(np.array(chosen))


#: bytes of the distance block of a GP prediction evaluated at once: small enough that its four passes (distances,
#: scaling, exponentials, product) stay in the processor's cache (2 MB: 416 rows of distances to 600 cases; 1.7× faster
#: than 96 MB blocks on 10⁵ rows on the 2-core reference machine, 16 MB of L3)
GP_BLOCK_BYTES = 2_000_000


def gp_block_rows(n_cases: int) -> int:
    """Rows per block of a GP prediction against ``n_cases`` training cases (:data:`GP_BLOCK_BYTES`)."""
    return max(64, GP_BLOCK_BYTES // (8 * max(n_cases, 1)))


class SubsampledGP(BaseEstimator, RegressorMixin):  # type: ignore[misc]  # scikit-learn carries no types
    """A Gaussian process fitted on at most ``max_cases`` of the cases it is given (a maximin subsample)."""

    def __init__(self, n_inputs: int = 1, max_cases: int = 600):
        self.n_inputs = n_inputs
        self.max_cases = max_cases

    def fit(self, u: npt.ArrayLike, y: npt.ArrayLike) -> SubsampledGP:
        keep = maximin_subsample(np.asarray(u, dtype=float), self.max_cases)
        x, t = np.asarray(u)[keep], np.asarray(y)[keep]
        self.gp_ = _gp(self.n_inputs, LikelihoodSearch(x, t)).fit(x, t)
        self.n_fitted_ = len(keep)
        return self

    def predict(self, u: npt.ArrayLike) -> np.ndarray:
        """The GP's mean at ``u``, as scikit-learn's ``predict`` gives it for this kernel (constant × RBF + white
        noise, the white term zero between distinct points), without building the sum and product kernels' full
        matrices: c exp(−½ |u − x|²/ℓ²) α in blocks of rows (about 4.7× faster on 10⁵ rows and 600 cases, equal to
        scikit-learn's to round-off; a Monte Carlo of 10⁶ samples predicts every GP surrogate)."""
        gp = self.gp_
        k = gp.kernel_
        constant, rbf = k.k1.k1.constant_value, k.k1.k2
        scale = np.atleast_1d(np.asarray(rbf.length_scale, dtype=float))
        x_train = gp.X_train_ / scale
        alpha = np.asarray(gp.alpha_, dtype=float).ravel()
        u = np.atleast_2d(np.asarray(u, dtype=float))
        out = np.empty(len(u))
        rows = gp_block_rows(len(x_train))

        def block(start: int) -> None:
            d = cdist(u[start : start + rows] / scale, x_train, "sqeuclidean")
            np.multiply(d, -0.5, out=d)
            np.exp(d, out=d)
            np.multiply(d, constant, out=d)  # c K before the product with α, as scikit-learn orders it
            out[start : start + rows] = d @ alpha

        starts = range(0, len(u), rows)
        threads = min(len(starts), available_cores())
        if threads > 1:  # distances, exponentials and products release the GIL: blocks in parallel, same values
            with ThreadPoolExecutor(threads) as pool:
                list(pool.map(block, starts))
        else:
            for start in starts:
                block(start)
        return np.asarray(out * gp._y_train_std + gp._y_train_mean)


def n_polynomial_terms(n_inputs: int, degree: int) -> int:
    """Terms of a full polynomial of ``degree`` in ``n_inputs`` variables, the constant excluded."""
    return math.comb(n_inputs + degree, degree) - 1


@dataclass(frozen=True)
class Fit:
    """Goodness of fit of predictions against actual values."""

    n: int
    r2: float | None
    rmse: float | None
    max_error: float | None

    @staticmethod
    def of(actual: np.ndarray, predicted: np.ndarray) -> "Fit":
        n = len(actual)
        if n == 0:
            return Fit(0, None, None, None)
        err = predicted - actual
        ss_res = float(np.sum(err**2))
        ss_tot = float(np.sum((actual - actual.mean()) ** 2))
        r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 and np.all(np.isfinite(err)) else None
        finite = np.all(np.isfinite(err))
        return Fit(
            n, r2, float(np.sqrt(ss_res / n)) if finite else None, float(np.max(np.abs(err))) if finite else None
        )


@dataclass
class Candidate:
    """One fitted model: family, label, estimator (on inputs in [−1, 1]) and its selection error."""

    family: str
    label: str
    estimator: Any
    log: bool = False
    degree: int | None = None
    selection_rmse: float | None = None
    selection_r2: float | None = None
    note: str = ""
    cv: Fit | None = None

    def predict_unit(self, u: np.ndarray) -> np.ndarray:
        """Predictions at ``u`` (inputs on [−1, 1]). scikit-learn's checks of the inputs and parameters are skipped:
        the inputs are finite arrays made here, the estimator's parameters were checked at its fit (the optimisers
        predict one point at a time, where the checks took most of a prediction's time)."""
        with (
            np.errstate(over="ignore", invalid="ignore"),
            config_context(assume_finite=True, skip_parameter_validation=True),
        ):
            return np.asarray(self.estimator.predict(u), dtype=float).ravel()


@dataclass
class Surrogate:
    """The kept model of one response, with its goodness of fit and the other candidates."""

    response: str
    bounds: np.ndarray
    kept: Candidate
    candidates: list[Candidate]
    training: Fit
    validation: Fit
    cv: Fit
    selection: str
    r2_threshold: float
    n_training: int
    n_validation: int
    n_missing: int
    plot_data: dict[str, Any] = field(default_factory=dict, repr=False)
    n_leaked: int = 0  # validation cases that repeat a training case (left out of the validation score)

    @property
    def r2_judged(self) -> float | None:
        """The R² the threshold is judged on: validation when there are enough cases, else cross-validation."""
        return self.validation.r2 if self.validation.n >= MIN_VALIDATION else self.cv.r2

    @property
    def constant(self) -> bool:
        """The response took one value over every training case (R² undefined; the surrogate reproduces it)."""
        y = self.plot_data.get("train", (np.empty(0),))[0]
        return len(y) > 0 and float(np.ptp(y)) == 0.0

    @property
    def flagged(self) -> bool:
        if self.constant:
            return False
        r2 = self.r2_judged
        return r2 is None or r2 < self.r2_threshold

    def predict(self, x: np.ndarray) -> np.ndarray:
        """Predictions at inputs ``x`` (n, n_variables; SI), evaluated in chunks."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        out = np.empty(len(x))
        for start in range(0, len(x), PREDICT_CHUNK):
            stop = start + PREDICT_CHUNK
            out[start:stop] = self.kept.predict_unit(to_unit(x[start:stop], self.bounds))
        return out


def _score(candidate: Candidate, u_tr: np.ndarray, y_tr: np.ndarray) -> None:
    """Record the candidate's selection error (k-fold cross-validation on the training cases), then fit it on
    every training case."""
    fit = _cross_validated(candidate.estimator, u_tr, y_tr)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        warnings.simplefilter("ignore", RuntimeWarning)
        candidate.estimator.fit(u_tr, y_tr)
    candidate.cv = fit
    candidate.selection_rmse, candidate.selection_r2 = fit.rmse, fit.r2


def leaked(u_train: np.ndarray, u_val: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Mask of validation rows whose inputs repeat a training row's (within ``tol`` on the [−1, 1] scale)."""
    if not len(u_train) or not len(u_val):
        return np.zeros(len(u_val), dtype=bool)

    dist, _ = cKDTree(u_train).query(u_val, k=1, p=np.inf)
    return np.asarray(dist <= tol)


def _cross_validated(estimator: Any, u: np.ndarray, y: np.ndarray) -> Fit:
    folds = KFold(n_splits=min(K_FOLDS, len(y)), shuffle=True, random_state=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        warnings.simplefilter("ignore", RuntimeWarning)
        with np.errstate(over="ignore", invalid="ignore"):
            predicted = cross_val_predict(clone(estimator), u, y, cv=folds)
    return Fit.of(y, np.asarray(predicted, dtype=float).ravel())


def _rank_key(c: Candidate) -> float:
    return math.inf if c.selection_rmse is None or not math.isfinite(c.selection_rmse) else c.selection_rmse


def fit_response(
    response: str,
    bounds: np.ndarray,
    x_train: np.ndarray,
    y_train: np.ndarray,
    x_val: np.ndarray,
    y_val: np.ndarray,
    *,
    r2_threshold: float = 0.9,
    gp_max_cases: int = 600,
    n_missing: int = 0,
    families: tuple[str, ...] = ("polynomial", "neural network", "Gaussian process"),
) -> Surrogate:
    """Fit every candidate family to one response and keep the best by cross-validation on the training cases;
    the validation cases (those not repeating a training case) only score the kept model."""
    bounds = np.asarray(bounds, dtype=float)
    n_in = bounds.shape[0]
    if len(y_train) < n_in + 2:
        raise ValueError(f"{response}: {len(y_train)} training cases with a value; at least {n_in + 2} needed")
    u_tr, u_val = to_unit(x_train, bounds), to_unit(x_val, bounds)
    leak = leaked(u_tr, u_val)
    u_val, y_val = u_val[~leak], np.asarray(y_val)[~leak]
    folds = min(K_FOLDS, len(y_train))
    selection = f"{folds}-fold cross-validation RMSE on the {len(y_train)} training cases"
    positive = bool(np.all(y_train > 0))
    candidates: list[Candidate] = []
    if "polynomial" in families:
        for degree in range(1, MAX_DEGREE + 1):
            if n_polynomial_terms(n_in, degree) >= len(y_train) / 2:
                break
            for log in (False, True) if positive else (False,):
                label = f"polynomial degree {degree}" + (", log response" if log else "")
                c = Candidate("polynomial", label, _log_target(_polynomial(degree), log), log, degree)
                _score(c, u_tr, y_train)
                candidates.append(c)
    best_poly = min((c for c in candidates if c.family == "polynomial"), key=_rank_key, default=None)
    log = bool(best_poly.log) if best_poly else False
    if "neural network" in families:
        c = Candidate(
            "neural network", "MLP 16-16 tanh" + (", log response" if log else ""), _log_target(_mlp(), log), log
        )
        _score(c, u_tr, y_train)
        candidates.append(c)
    if "Gaussian process" in families and gp_max_cases > 0:
        label = "Gaussian process RBF" + (", log response" if log else "")
        note = ""
        if len(y_train) > gp_max_cases:
            note = (
                f"fitted on a maximin subsample of {gp_max_cases} of the {len(y_train)} training cases "
                f"(of each fold's cases in cross-validation)"
            )
            label += f" ({gp_max_cases}-case subsample)"
        c = Candidate("Gaussian process", label, _log_target(SubsampledGP(n_in, gp_max_cases), log), log, note=note)
        _score(c, u_tr, y_train)
        candidates.append(c)
    fitted = [c for c in candidates if c.estimator is not None]
    kept = min(fitted, key=_rank_key)
    train_pred = kept.predict_unit(u_tr)
    val_pred = kept.predict_unit(u_val) if len(y_val) else np.empty(0)
    cv = kept.cv
    if cv is None:
        raise RuntimeError(f"{response}: the kept model {kept.label} was not cross-validated")
    return Surrogate(
        response,
        bounds,
        kept,
        candidates,
        Fit.of(y_train, train_pred),
        Fit.of(y_val, val_pred),
        cv,
        selection,
        r2_threshold,
        len(y_train),
        len(y_val),
        n_missing,
        plot_data={"train": (y_train, train_pred), "validation": (y_val, val_pred)},
        n_leaked=int(leak.sum()),
    )


def _fit_one(name: str, bounds: np.ndarray, data: Any, options: AnalysisOptions) -> tuple[str, Surrogate | None, str]:
    (x_tr, y_tr, miss_tr), (x_val, y_val, miss_val) = data
    try:
        return (
            name,
            fit_response(
                name,
                bounds,
                x_tr,
                y_tr,
                x_val,
                y_val,
                r2_threshold=options.r2_threshold,
                gp_max_cases=options.gp_max_cases,
                n_missing=miss_tr + miss_val,
            ),
            "",
        )
    except ValueError as exc:
        return name, None, str(exc)


def fit_all(
    study: Study, cases: Cases, log: Callable[[str], object] = lambda msg: None, names: list[str] | None = None
) -> tuple[dict[str, Surrogate], dict[str, str]]:
    """One surrogate per analysed response of ``study`` (or per response of ``names``) from ``cases``
    (:class:`.cases.Cases`), the responses fitted in parallel over the cores (each fit is seeded: the same models
    whatever the number of processes); (surrogates, reasons of the responses none could be fitted for)."""
    names = study.analysed_responses() if names is None else names
    if not names:
        return {}, {}
    data = {n: (cases.xy("training", n), cases.xy("validation", n)) for n in names}
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    done = Parallel(n_jobs=min(cores, len(names)) or 1)(
        delayed(_fit_one)(n, study.bounds, data[n], study.analysis) for n in names
    )
    surrogates, not_fitted = {}, {}
    for name, surrogate, error in done:
        if surrogate is None:
            not_fitted[name] = error
        else:
            surrogates[name] = surrogate
            log(f"surrogate {name}: {surrogate.kept.label}")
    return surrogates, not_fitted

"""Surrogates: recovery of known functions to their noise-limited R², log transform choice, failed cases,
flagging, and the exported models (the page's arithmetic) against scikit-learn's predictions."""

from __future__ import annotations

import numpy as np
import pytest

from certkit.study.analysis.cases import cases
from certkit.study.analysis.export import evaluate_export, export_surrogate
from certkit.study.analysis.surrogates import fit_response, n_polynomial_terms
from tests.study_analysis.synthetic import VARIABLES, store_frame, synthetic_study

D = 8
BOX = np.array([[-1.0, 1.0]] * D)


def _quadratic(seed: int = 3):
    """A full quadratic in 8 variables with random coefficients (x ~ U(-1, 1)) and its variance in closed form:
    with E[x²] = 1/3, E[x⁴] = 1/5 and independent inputs, the terms a·x, b·(x² − 1/3) and c·x_i·x_j are
    uncorrelated, so Var f = Σa²/3 + Σb²·(1/5 − 1/9) + Σc²/9."""
    rng = np.random.default_rng(seed)
    a, b = rng.normal(0, 1, D), rng.normal(0, 1, D)
    c = np.triu(rng.normal(0, 0.5, (D, D)), 1)

    def f(x):
        return x @ a + (x**2) @ b + np.einsum("ni,ij,nj->n", x, c, x)

    var = np.sum(a**2) / 3 + np.sum(b**2) * (1 / 5 - 1 / 9) + np.sum(c**2) / 9
    return f, var


def test_quadratic_recovered_to_its_noise_limited_r2():
    f, var_f = _quadratic()
    sigma = np.sqrt(var_f / 9.0)  # noise-limited R² = Var f / (Var f + σ²) = 0.9
    r2_limit = var_f / (var_f + sigma**2)
    rng = np.random.default_rng(5)
    n_tr, n_val = 500, 1000
    x_tr, x_val = rng.uniform(-1, 1, (n_tr, D)), rng.uniform(-1, 1, (n_val, D))
    y_tr = f(x_tr) + rng.normal(0, sigma, n_tr)
    y_val = f(x_val) + rng.normal(0, sigma, n_val)
    s = fit_response("q", BOX, x_tr, y_tr, x_val, y_val, gp_max_cases=0, r2_threshold=0.85)
    polys = [c for c in s.candidates if c.family == "polynomial"]
    assert min(polys, key=lambda c: c.selection_rmse).degree == 2
    # least squares with p coefficients on n random points: expected prediction error σ²(1 + p/(n − p − 1))
    # (random-design OLS, e.g. Hastie, Tibshirani & Friedman, ESL 2nd ed., §7.3 / Breiman & Freedman 1983)
    p = n_polynomial_terms(D, 2) + 1
    expected = 1.0 - sigma**2 * (1 + p / (n_tr - p - 1)) / (var_f + sigma**2)
    # sampling s.e. of a validation R² ≈ (1 − R²)·√(2/n) (χ² of the residual sum of squares)
    se = (1 - expected) * np.sqrt(2 / n_val)
    assert s.validation.r2 == pytest.approx(expected, abs=3 * se)
    assert s.validation.r2 < r2_limit + 3 * se  # cannot beat the noise
    assert s.kept.family == "polynomial" and s.kept.degree == 2
    assert s.cv.r2 == pytest.approx(expected, abs=0.03)
    assert not s.flagged  # threshold 0.85 below the noise limit 0.9


def test_log_transform_chosen_for_a_multiplicative_response_only():
    rng = np.random.default_rng(8)
    beta = np.array([0.9, -0.6, 0.5, 0.4, -0.3, 0.3, 0.2, -0.2])
    x_tr, x_val = rng.uniform(-1, 1, (300, D)), rng.uniform(-1, 1, (200, D))

    def mult(x):
        return 50.0 * np.exp(x @ beta) * np.exp(rng.normal(0, 0.05, len(x)))

    s = fit_response("m", BOX, x_tr, mult(x_tr), x_val, mult(x_val), families=("polynomial",))
    assert s.kept.log
    additive = lambda x: 10.0 + x @ beta + 0.3 * x[:, 0] ** 2 + rng.normal(0, 0.05, len(x))  # noqa: E731
    s = fit_response("a", BOX, x_tr, additive(x_tr), x_val, additive(x_val), families=("polynomial",))
    assert not s.kept.log and s.kept.degree == 2


def test_failed_cases_excluded_and_counted_and_noise_flagged():
    frame = store_frame(n_train=100, n_val=40, fail_every=10)
    view = synthetic_study()
    cs = cases(frame, view)
    x, y, missing = cs.xy("training", "objective.cruise_CD")
    assert len(y) == 90 and missing == 0 and np.isfinite(y).all()
    assert len(cs.failed()) == 14 and set(cs.failed()["error"]) == {"trim did not converge at 25.331(c)(2) condition 3"}
    frame.loc[frame.index[:5], "resp:objective.OEW_kg"] = np.nan
    _, y, missing = cases(frame, view).xy("training", "objective.OEW_kg")
    assert missing == 5 and len(y) == 85
    rng = np.random.default_rng(0)
    noise = fit_response(
        "noise", view.bounds, x, rng.normal(size=len(x)), x[:20], rng.normal(size=20), families=("polynomial",)
    )
    assert noise.flagged


@pytest.mark.parametrize(
    "families,log",
    [(("polynomial",), False), (("polynomial",), True), (("neural network",), False), (("Gaussian process",), True)],
)
def test_exported_model_reproduces_sklearn(families, log):
    rng = np.random.default_rng(2)
    bounds = np.array([[v["lower"], v["upper"]] for v in VARIABLES])
    x = bounds[:, 0] + (bounds[:, 1] - bounds[:, 0]) * rng.random((120, D))
    u = (x - bounds[:, 0]) / (bounds[:, 1] - bounds[:, 0])
    y = np.exp(u @ np.linspace(-1, 1, D) + 0.3 * u[:, 0] * u[:, 1]) if log else np.sin(3 * u[:, 0]) + u[:, 1] ** 2
    s = fit_response("r", bounds, x[:90], y[:90], x[90:], y[90:], families=families)
    assert s.kept.family == families[0]
    if families == ("polynomial",):
        assert s.kept.log == log
    doc = export_surrogate(s)
    probe = bounds[:, 0] + (bounds[:, 1] - bounds[:, 0]) * rng.uniform(-0.1, 1.1, (25, D))
    np.testing.assert_allclose(evaluate_export(doc, probe), s.predict(probe), rtol=1e-9, atol=1e-12)


def test_a_constant_response_is_reproduced_not_flagged():
    """A response that took one value over every case (a handling level the variables never change) has no R²;
    its surrogate reproduces the value and is not flagged as a poor fit."""
    rng = np.random.default_rng(3)
    bounds = np.array([[0.0, 1.0]] * 3)
    x = rng.random((40, 3))
    s = fit_response("level.x", bounds, x, np.full(40, 2.0), x[:0], np.empty(0), families=("polynomial",))
    assert s.constant and not s.flagged
    assert np.allclose(s.predict(rng.random((5, 3))), 2.0)


@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")  # a near-interpolating fit, on purpose
def test_the_gaussian_process_mean_is_scikit_learns():
    """SubsampledGP.predict evaluates the mean without scikit-learn's kernel matrices: equal to
    GaussianProcessRegressor.predict to round-off, on rows spanning several blocks. Round-off of the mean's sum
    Σ_j c k_j α_j is bounded by γ_n Σ_j |c k_j α_j| (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd
    ed., §3.1: γ_n = n u/(1 − n u), u the unit round-off), for each of the two summations compared: a
    near-interpolating fit has large α of both signs, so the bound, not the mean, sets the scale."""
    from certkit.study.analysis import surrogates as sg

    rng = np.random.default_rng(5)
    u = rng.uniform(-1, 1, (150, 4))
    y = np.sin(2 * u[:, 0]) + u[:, 1] * u[:, 2] + 0.3 * u[:, 3] ** 2
    gp = sg.SubsampledGP(4, 120).fit(u, y)
    z = rng.uniform(-1.1, 1.1, (2 * sg.gp_block_rows(120) + 7, 4))
    fitted = gp.gp_
    terms = np.abs(fitted.kernel_(z, fitted.X_train_) @ np.abs(fitted.alpha_).ravel()) * fitted._y_train_std
    n, unit = len(fitted.X_train_), np.finfo(float).eps / 2
    gamma = n * unit / (1 - n * unit)
    assert np.all(np.abs(gp.predict(z) - fitted.predict(z)) <= 2 * gamma * terms + 1e-15)

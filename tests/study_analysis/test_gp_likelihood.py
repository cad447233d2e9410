"""The GP hyperparameters' likelihood (certkit.study.analysis.gp_likelihood) against scikit-learn's own
``GaussianProcessRegressor.log_marginal_likelihood`` (the peer; Rasmussen & Williams 2006, eqs. 5.8–5.9): the same
value and gradient to round-off (ε·κ(K) relative, the Cholesky factorisation's backward error for a kernel matrix of
condition number κ), and a search on it that finds scikit-learn's optimum."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize
from sklearn.gaussian_process import GaussianProcessRegressor

from certkit.study.analysis.gp_likelihood import LikelihoodSearch, RBFLikelihood, kernel, normalised


def _peer(x, y, p):
    return GaussianProcessRegressor(kernel(p), normalize_y=True, optimizer=None).fit(x, y)


def _cases(n=90, p=4, seed=3):
    rng = np.random.default_rng(seed)
    x = rng.uniform(-1, 1, (n, p))
    y = 50.0 + 4 * np.sin(2 * x[:, 0]) + 3 * x[:, 1] ** 2 - x[:, 2] * x[:, 3] + 0.01 * rng.standard_normal(n)
    return x, y


@pytest.mark.parametrize("seed", range(6))
def test_value_and_gradient_are_scikit_learns(seed):
    x, y = _cases()
    peer = _peer(x, y, x.shape[1])
    bounds = peer.kernel_.bounds
    theta = np.random.default_rng(seed).uniform(bounds[:, 0] / 2, bounds[:, 1] / 2)
    value, gradient = peer.log_marginal_likelihood(theta, eval_gradient=True, clone_kernel=False)
    mine, mine_gradient = RBFLikelihood(x, normalised(y))(theta)
    rel = 4 * np.finfo(float).eps * np.linalg.cond(peer.kernel_.clone_with_theta(theta)(x) + 1e-10 * np.eye(len(x)))
    assert rel < 1e-6  # a comparison that means something
    assert -mine == pytest.approx(value, rel=rel)
    assert np.allclose(-mine_gradient, gradient, rtol=rel, atol=rel * np.max(np.abs(gradient)))


@pytest.mark.parametrize("value", [7.5, 0.0011820771720005652])
def test_a_constant_response_is_normalised_as_scikit_learn_does(value):
    """A standard deviation of exactly zero (7.5) and one of round-off, 2.2e-19 (a constant response of the seed
    study, whose mean is not a float): scikit-learn replaces the first only."""
    x, _ = _cases(43)
    y = np.full(43, value)
    assert (np.std(y) == 0.0) == (value == 7.5)
    peer = _peer(x, y, x.shape[1])
    theta = peer.kernel_.theta
    assert -RBFLikelihood(x, normalised(y))(theta)[0] == pytest.approx(peer.log_marginal_likelihood(theta), rel=1e-12)


def test_a_kernel_that_is_not_positive_definite_is_the_least_likely(monkeypatch):
    """As scikit-learn has it: no Cholesky factor, likelihood zero (the search's objective infinite), no gradient."""
    from certkit.study.analysis import gp_likelihood

    def refuse(*args, **kwargs):
        raise np.linalg.LinAlgError("not positive definite")

    monkeypatch.setattr(gp_likelihood, "cholesky", refuse)
    x, y = _cases(30)
    value, gradient = RBFLikelihood(x, normalised(y))(np.zeros(6))
    assert value == np.inf and gradient.shape == (6,) and not gradient.any()


# the signal's variance reaches its bound (10³) on these cases in both fits: scikit-learn says so, for each
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")
def test_the_search_finds_scikit_learns_optimum():
    """The fitted GP's hyperparameters are those scikit-learn's own L-BFGS-B search finds on its likelihood from the
    same start (both converged: log-likelihood within 1e-6, θ within 1e-3)."""
    x, y = _cases()
    p = x.shape[1]

    def peer_search(obj_func, theta, bounds):
        res = minimize(obj_func, theta, method="L-BFGS-B", jac=True, bounds=bounds, options={"maxiter": 200})
        return res.x, res.fun

    peer = GaussianProcessRegressor(kernel(p), normalize_y=True, optimizer=peer_search).fit(x, y)
    mine = GaussianProcessRegressor(kernel(p), normalize_y=True, optimizer=LikelihoodSearch(x, y)).fit(x, y)
    assert mine.log_marginal_likelihood_value_ == pytest.approx(peer.log_marginal_likelihood_value_, abs=1e-6)
    assert np.allclose(mine.kernel_.theta, peer.kernel_.theta, atol=1e-3)
    assert mine.kernel_.theta[-1] < np.log(1e-2)  # it found the smooth fit, not the all-noise one


def test_a_search_given_other_cases_than_the_gp_is_a_bug_raised_as_such():
    x, y = _cases()
    wrong = LikelihoodSearch(x[:-1], y[:-1])
    with pytest.raises(RuntimeError, match="other cases than the GP"):
        GaussianProcessRegressor(kernel(4), normalize_y=True, optimizer=wrong).fit(x, y)

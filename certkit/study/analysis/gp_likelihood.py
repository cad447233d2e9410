"""The log marginal likelihood of the surrogates' Gaussian process and its gradient, for fitting its hyperparameters.

The kernel is c·exp(−½ Σ_d (x_d − x'_d)²/ℓ_d²) + s·δ (scikit-learn's ``ConstantKernel × RBF + WhiteKernel`` with an
anisotropic length scale), with scikit-learn's jitter on the diagonal; the hyperparameters θ = (log c, log ℓ_1 …
log ℓ_p, log s), in scikit-learn's order and scale. Rasmussen & Williams, *Gaussian Processes for Machine Learning*
(2006), eqs. 5.8–5.9: log p(y|X,θ) = −½ yᵀα − Σ log L_ii − n/2 log 2π with K = LLᵀ, α = K⁻¹y, and
∂ log p/∂θ_j = ½ tr((ααᵀ − K⁻¹) ∂K/∂θ_j), where ∂K/∂log c = cR, ∂K/∂log ℓ_d = cR ∘ D_d/ℓ_d² (D_d the squared
distances along input d) and ∂K/∂log s = sI.

The same value and gradient as scikit-learn's ``GaussianProcessRegressor.log_marginal_likelihood`` (to round-off:
``tests/study_analysis/test_gp_likelihood.py``), computed with the squared distances of the fixed training inputs
once per fit and the gradient as one matrix product, instead of the (n, n, p) gradient array built and contracted at
every evaluation (the hyperparameter search evaluates it about 80 times per fit, six fits per response).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.linalg import cho_solve, cholesky
from scipy.optimize import minimize
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel

#: added to the kernel's diagonal, as scikit-learn's ``GaussianProcessRegressor(alpha=1e-10)`` does
JITTER = 1e-10
#: iterations of the hyperparameter search (keeps a fit's time bounded)
MAX_ITERATIONS = 80


def kernel(n_inputs: int) -> Any:
    """The surrogates' GP kernel, whose likelihood this module computes: c × anisotropic RBF + white noise s, with the
    hyperparameters' starting values and bounds (c 1 in [1e-3, 1e3], ℓ 1 in [1e-2, 1e3], s 1e-4 in [1e-10, 1])."""
    return ConstantKernel(1.0, (1e-3, 1e3)) * RBF(np.ones(n_inputs), (1e-2, 1e3)) + WhiteKernel(1e-4, (1e-10, 1e0))


def normalised(y: np.ndarray) -> np.ndarray:
    """``y`` less its mean over its standard deviation, as ``normalize_y=True`` does for one response: a standard
    deviation of exactly zero taken as 1, a round-off one (a constant response whose mean is not a float) kept."""
    y = np.asarray(y, dtype=float)
    std = np.std(y, axis=0)
    return (y - np.mean(y, axis=0)) / (1.0 if std == 0.0 else std)


class RBFLikelihood:
    """The negative log marginal likelihood and its gradient for training inputs ``x`` (n, p) and targets ``y`` (n,),
    as functions of θ (the module's docstring)."""

    def __init__(self, x: np.ndarray, y: np.ndarray):
        x = np.asarray(x, dtype=float)
        self.n = x.shape[0]
        self.squared = ((x[:, None, :] - x[None, :, :]) ** 2).reshape(self.n * self.n, x.shape[1])
        self.y = np.asarray(y, dtype=float)
        self.eye = np.eye(self.n)

    def __call__(self, theta: np.ndarray) -> tuple[float, np.ndarray]:
        n = self.n
        c, noise = math.exp(theta[0]), math.exp(theta[-1])
        inverse = np.exp(-2.0 * theta[1:-1])  # 1/ℓ²
        cr = np.exp(self.squared @ (-0.5 * inverse)).reshape(n, n)
        cr *= c
        k = cr.copy()
        k.flat[:: n + 1] += noise + JITTER
        try:
            lower = cholesky(k, lower=True, check_finite=False)
        except np.linalg.LinAlgError:  # not positive definite at θ: the least likely, as scikit-learn has it
            return math.inf, np.zeros_like(theta)
        alpha = cho_solve((lower, True), self.y, check_finite=False)
        lml = -0.5 * float(self.y @ alpha) - float(np.log(np.diag(lower)).sum()) - 0.5 * n * math.log(2 * math.pi)
        w = np.outer(alpha, alpha)
        w -= cho_solve((lower, True), self.eye, check_finite=False)
        weighted = (w * cr).ravel()
        grad = np.empty(len(theta))
        grad[0] = 0.5 * weighted.sum()
        grad[1:-1] = 0.5 * (weighted @ self.squared) * inverse
        grad[-1] = 0.5 * noise * np.trace(w)
        return -lml, -grad


class LikelihoodSearch:
    """scikit-learn's ``optimizer`` for a GP fitted on ``x``, ``y`` (y as given: normalised here): L-BFGS-B on
    :class:`RBFLikelihood` from the kernel's θ within its bounds, at most :data:`MAX_ITERATIONS` iterations.
    scikit-learn's own objective, handed in, is evaluated once, at the start (its value only: a Cholesky
    factorisation), to make sure the search minimises the same function — a GP given other cases than this
    search's is a bug of certkit's, raised as such."""

    def __init__(self, x: np.ndarray, y: np.ndarray):
        self.x, self.y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)

    def __call__(self, obj_func, initial_theta: np.ndarray, bounds) -> tuple[np.ndarray, float]:
        objective = RBFLikelihood(self.x, normalised(self.y))
        theirs, ours = float(obj_func(initial_theta, eval_gradient=False)), objective(initial_theta)[0]
        if not math.isclose(ours, theirs, rel_tol=1e-6, abs_tol=1e-9):
            raise RuntimeError(
                f"the GP's likelihood search was given other cases than the GP: −log p {ours!r} against "
                f"scikit-learn's {theirs!r} at the initial hyperparameters"
            )
        res = minimize(
            objective, initial_theta, method="L-BFGS-B", jac=True, bounds=bounds, options={"maxiter": MAX_ITERATIONS}
        )
        return np.asarray(res.x), float(res.fun)

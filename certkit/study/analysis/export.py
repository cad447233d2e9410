"""Surrogates exported as plain JSON for evaluation in the report page (JavaScript, offline).

:func:`export_surrogate` reads the fitted scikit-learn estimators' parameters; :func:`evaluate_export` is
the Python mirror of the page's JavaScript evaluator (the profiler's script in the report templates), written with
the same arithmetic point by point, so that a test can show the exported numbers reproduce scikit-learn's predictions.

Formats (``u`` = inputs mapped from their bounds ``lo``/``hi`` to [−1, 1]; ``log``: the result is exp(·)):

- ``polynomial``: intercept + Σ_k coef_k Π_i u_i^p_ki, the powers stored sparsely as [[i, p], ...] per term;
- ``mlp``: h ← tanh(b + Wᵀh) through the hidden layers, z = b + Wᵀh at the output, y = z·scale + mean;
- ``gp``: y = mean + std · Σ_j α_j c exp(−½ Σ_i ((u_i − X_ji)/ℓ_i)²).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt
from sklearn.compose import TransformedTargetRegressor

from certkit.study.analysis.surrogates import Surrogate


def _unwrap_log(estimator: Any) -> tuple[Any, bool]:
    """The regressor inside a log-transformed target (and whether it was), scikit-learn's untyped estimators."""
    if isinstance(estimator, TransformedTargetRegressor) and estimator.func is np.log:
        return estimator.regressor_, True
    return estimator, False


def _floats(a: npt.ArrayLike) -> list[Any]:
    return list(np.asarray(a, dtype=float).tolist())


def export_surrogate(surrogate: Surrogate) -> dict[str, Any]:
    """JSON-serialisable description of the kept model of ``surrogate``."""
    inner, log = _unwrap_log(surrogate.kept.estimator)
    doc: dict[str, Any] = {
        "response": surrogate.response,
        "log": log,
        "lo": _floats(surrogate.bounds[:, 0]),
        "hi": _floats(surrogate.bounds[:, 1]),
    }
    family = surrogate.kept.family
    if family == "polynomial":
        features, ridge = inner.steps[0][1], inner.steps[-1][1]
        terms = [[[int(i), int(p)] for i, p in enumerate(row) if p] for row in features.powers_]
        doc.update(kind="polynomial", intercept=float(ridge.intercept_), coef=_floats(ridge.coef_), terms=terms)
    elif family == "neural network":
        net, scaler = inner.regressor_, inner.transformer_
        if net.activation != "tanh" or net.out_activation_ != "identity":
            raise ValueError(f"export supports tanh hidden layers and an identity output, got {net.activation}")
        doc.update(
            kind="mlp",
            weights=[_floats(w) for w in net.coefs_],
            biases=[_floats(b) for b in net.intercepts_],
            mean=float(scaler.mean_[0]),
            scale=float(scaler.scale_[0]),
        )
    elif family == "Gaussian process":
        inner = getattr(inner, "gp_", inner)  # the GP of a subsampled fit
        kernel = inner.kernel_
        const, rbf = kernel.k1.k1, kernel.k1.k2
        doc.update(
            kind="gp",
            x=_floats(inner.X_train_),
            alpha=_floats(np.ravel(inner.alpha_)),
            constant=float(const.constant_value),
            length_scale=_floats(np.atleast_1d(rbf.length_scale)),
            mean=float(np.ravel(inner._y_train_mean)[0]),
            std=float(np.ravel(inner._y_train_std)[0]),
        )
    else:
        raise ValueError(f"no export for model family {family!r}")
    return doc


def _evaluate_one(doc: dict[str, Any], x: list[float]) -> float:
    """One point, written as the JavaScript evaluator is (plain loops, Math.pow/tanh/exp)."""
    u = [(x[i] - doc["lo"][i]) * (2.0 / (doc["hi"][i] - doc["lo"][i])) - 1.0 for i in range(len(x))]
    kind = doc["kind"]
    if kind == "polynomial":
        y = doc["intercept"]
        for coef, term in zip(doc["coef"], doc["terms"]):
            prod = coef
            for i, p in term:
                prod *= u[i] ** p
            y += prod
    elif kind == "mlp":
        h = u
        layers = len(doc["weights"])
        for k in range(layers):
            w, b = doc["weights"][k], doc["biases"][k]
            z = []
            for j in range(len(b)):
                s = b[j]
                for i in range(len(h)):
                    s += w[i][j] * h[i]
                z.append(math.tanh(s) if k < layers - 1 else s)
            h = z
        y = h[0] * doc["scale"] + doc["mean"]
    elif kind == "gp":
        s = 0.0
        for xj, aj in zip(doc["x"], doc["alpha"]):
            d2 = 0.0
            for i in range(len(u)):
                t = (u[i] - xj[i]) / doc["length_scale"][i if len(doc["length_scale"]) > 1 else 0]
                d2 += t * t
            s += aj * doc["constant"] * math.exp(-0.5 * d2)
        y = doc["mean"] + doc["std"] * s
    else:
        raise ValueError(f"unknown exported model kind {kind!r}")
    return float(math.exp(y) if doc["log"] else y)


def evaluate_export(doc: dict[str, Any], x: np.ndarray) -> np.ndarray:
    """Evaluate an exported model at the rows of ``x`` (SI inputs) exactly as the page does."""
    return np.array([_evaluate_one(doc, [float(v) for v in row]) for row in np.atleast_2d(x)])

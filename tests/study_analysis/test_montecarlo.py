"""Monte Carlo feasibility against closed-form probabilities; level relaxation; model uncertainty; memory;
the direct check through a monkeypatched study runner."""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pandas as pd
import pytest

from certkit.study.analysis import checks
from certkit.study.analysis.checks import direct_check, reevaluate_optima
from certkit.study.analysis.montecarlo import run_monte_carlo
from certkit.study.analysis.surrogates import fit_response
from certkit.study.spec import Study

D = 8


def irwin_hall_cdf(t: float, n: int) -> float:
    """P(U_1 + ... + U_n ≤ t), U_i ~ U(0, 1) independent (Irwin 1927, Hall 1927):
    (1/n!) Σ_{k=0}^{⌊t⌋} (−1)^k C(n, k) (t − k)^n."""
    return sum((-1) ** k * math.comb(n, k) * (t - k) ** n for k in range(int(math.floor(t)) + 1)) / math.factorial(n)


def _view(constraints, objectives=(), **analysis):
    return Study.model_validate(
        {
            "name": "unit-box",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "objectives": [{"response": o} for o in objectives],
            "constraints": constraints,
            "analysis": analysis or None,
        }
    )


def _exact(name, fn, n=60, seed=0):
    """A surrogate fitted to noise-free values of a function a polynomial represents exactly."""
    rng = np.random.default_rng(seed)
    x = rng.random((n, D))
    xv = rng.random((20, D))
    return fit_response(name, np.array([[0.0, 1.0]] * D), x, fn(x), xv, fn(xv), families=("polynomial",))


def _sum(x):
    return x.sum(axis=1)


def test_half_space_probability_matches_irwin_hall():
    t = 3.5
    view = _view([{"name": "sum", "response": "s", "max": t}])
    mc = run_monte_carlo(view, {"s": _exact("s", _sum)}, n=200_000, chunk=30_000, seed=1)
    (o,) = mc.constraints
    exact = irwin_hall_cdf(t, D)
    assert o.p == pytest.approx(exact, abs=3 * o.se)
    assert mc.stage_p("constrained")[0] == o.p
    assert o.histogram.counts.sum() + o.histogram.below + o.histogram.above == 200_000


def test_level_relaxation_and_preferred_stage():
    # a continuous 'level' 1 + 2·x0: Level 1 where < 1.5 (x0 < 0.25), Level ≤ 2 where < 2.5 (x0 < 0.75)
    view = _view(
        [{"name": "sp", "response": "level.short_period.cg2.clean", "max": 1}],
        level_relaxation=[{"responses": "level.*.cg2.*", "max_level": 2}],
    )
    sur = {"level.short_period.cg2.clean": _exact("level.short_period.cg2.clean", lambda x: 1 + 2 * x[:, 0])}
    mc = run_monte_carlo(view, sur, n=100_000, chunk=25_000, seed=2)
    (o,) = mc.constraints
    assert o.p == pytest.approx(0.25, abs=3 * o.se)
    assert o.p_relaxed == pytest.approx(0.75, abs=3 * math.sqrt(0.75 * 0.25 / mc.n))
    assert mc.stage_p("constrained")[0] == o.p_relaxed
    assert mc.stage_p("preferred")[0] == o.p


def test_probability_under_uniform_model_uncertainty():
    # x0·(1 + δ) ≤ 0.5, δ ~ U(−0.2, 0.2): P = (1/0.4)∫ 0.5/(1 + δ) dδ = 1.25 ln 1.5; adverse bound x0 ≤ 0.5/1.2
    view = _view(
        [{"name": "c", "response": "y", "max": 0.5}],
        uncertainty=[{"responses": "y", "percent": 20, "distribution": "uniform"}],
    )
    mc = run_monte_carlo(view, {"y": _exact("y", lambda x: x[:, 0])}, n=200_000, chunk=50_000, seed=3)
    (o,) = mc.constraints
    se = math.sqrt(0.25 / mc.n)
    assert o.p == pytest.approx(0.5, abs=3 * se)
    assert o.p_uncertain == pytest.approx(1.25 * math.log(1.5), abs=3 * se)
    assert o.p_adverse == pytest.approx(0.5 / 1.2, abs=3 * se)
    assert mc.uncertain_joint == o.uncertain_successes


def test_memory_bounded_by_the_chunk():
    view = _view([{"name": "sum", "response": "s", "max": 4.0}], objectives=("a", "b"))
    sur = {
        "s": _exact("s", _sum),
        "a": _exact("a", lambda x: x[:, 0] + x[:, 1]),
        "b": _exact("b", lambda x: 2 - x[:, 0] + 0.5 * x[:, 2]),
    }
    peaks = []
    for n in (100_000, 400_000):
        tracemalloc.start()
        run_monte_carlo(view, sur, n=n, chunk=20_000, cloud=1000)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    assert peaks[1] < 1.3 * peaks[0], peaks  # four times the samples, about the same peak
    assert peaks[1] < 40e6


def _install_runner(monkeypatch, true_fn, fail=lambda x: np.zeros(len(x), dtype=bool)):
    """A stand-in for certkit.study.runner: evaluates ``true_fn`` and returns store-format cases."""
    calls = []

    def run_study_cases(study, store, points, *, block, role, **kw):
        x = np.array([[p[f"v.x{i}"] for i in range(D)] for p in points])
        calls.append((block, role, len(points)))
        bad = fail(x)
        df = pd.DataFrame({f"var:v.x{i}": x[:, i] for i in range(D)})
        for name, vals in true_fn(x).items():
            df[f"resp:{name}"] = np.where(bad, np.nan, vals)
        df["key"] = [f"k{block}{i}" for i in range(len(x))]
        df["block"], df["role"] = block, role
        df["status"] = np.where(bad, "failed", "ok")
        df["error"] = np.where(bad, "sizing loop diverged", None)
        return df.iloc[::-1]  # in another order than asked: the analysis must match them up

    monkeypatch.setattr(checks.runner, "run_study_cases", run_study_cases)
    return calls


def test_direct_check_and_optima_through_the_runner(monkeypatch):
    t = 4.5
    view = _view([{"name": "sum", "response": "s", "max": t}], objectives=("a",))
    sur = {"s": _exact("s", _sum), "a": _exact("a", lambda x: x[:, 0] - x[:, 1])}
    mc = run_monte_carlo(view, sur, n=50_000, chunk=25_000, seed=4)
    calls = _install_runner(
        monkeypatch, lambda x: {"s": x.sum(axis=1), "a": x[:, 0] - x[:, 1]}, fail=lambda x: x[:, 7] > 0.9
    )
    check = direct_check(view, object(), sur, mc, n=400, seed=5)
    assert calls[0] == ("check", "check", 400)
    assert 0 < check.n_failed < 80 and check.n_ok + check.n_failed == 400
    assert all(err == "sizing loop diverged" for _, err in check.failures)
    (k,) = check.constraints
    # the true model's sample: the closed form within 3 s.e. (points with x7 > 0.9 failed, so the ok sample
    # is uniform on [0,1]^7 × [0, 0.9]: P(Σ ≤ t) there = E over x7 ~ U(0, 0.9) of F_7(t − x7))
    xs = np.linspace(0, 0.9, 2001)
    exact = np.trapezoid([irwin_hall_cdf(t - v, 7) for v in xs], xs) / 0.9
    assert k.p_true == pytest.approx(exact, abs=3 * k.se_true)
    assert k.p_surrogate_same == k.p_true  # an exact surrogate agrees case by case
    assert k.p_mc == pytest.approx(irwin_hall_cdf(t, D), abs=3 * k.se_mc)
    assert check.joint.p_true == k.p_true
    optima = [o for o in mc.optima if o.objective == "a"]
    checked = reevaluate_optima(view, object(), sur, optima)
    assert calls[1] == ("optima", "check", len(optima))
    for c in checked:
        assert c.status == "ok"
        assert c.true["a"] == pytest.approx(c.optimum.x[0] - c.optimum.x[1], abs=1e-12)
        assert c.predicted["a"] == pytest.approx(c.true["a"], abs=1e-9)
    unconstrained = next(c for c in checked if c.optimum.stage == "unconstrained")
    assert unconstrained.true["a"] < -0.98  # the sampled minimum of x0 − x1 over the box (−1 at the corner)

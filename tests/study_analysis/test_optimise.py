"""The optimiser on the surrogates finds known constrained optima of analytic problems."""

from __future__ import annotations

import numpy as np
import pytest

from certkit.study.analysis.montecarlo import run_monte_carlo
from certkit.study.analysis.optimise import (
    LEAST_VIOLATION,
    SurrogateProblem,
    front_sample,
    local_optimum,
    nsga2_front,
    optimise,
)
from certkit.study.analysis.ranking import active_constraints, conflicting_constraints
from certkit.study.analysis.surrogates import fit_response
from certkit.study.spec import Study

D = 4


def _study(constraints, objectives) -> Study:
    return Study.model_validate(
        {
            "name": "analytic",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "objectives": [{"response": o} for o in objectives],
            "constraints": constraints,
        }
    )


def _exact(name, fn):
    """A surrogate of a polynomial function, fitted to noise-free values (the polynomial family is exact)."""
    rng = np.random.default_rng(1)
    x = rng.random((80, D))
    return fit_response(name, np.array([[0.0, 1.0]] * D), x, fn(x), x[:0], np.empty(0), families=("polynomial",))


def test_slsqp_finds_the_constrained_minimum_of_a_quadratic():
    """min (x0 − 0.8)² + (x1 − 0.8)² + (x2 − 0.3)² subject to x0 + x1 ≤ 1 on the unit cube: by the KKT conditions
    (the gradient parallel to the constraint's normal at the active constraint) x0 = x1 = 0.5, x2 = 0.3, x3 free,
    f = 0.18. Multi-started SLSQP reaches it to 10⁻⁴; the best of 2000 Monte Carlo samples does not."""
    study = _study([{"name": "sum", "response": "g", "max": 1.0}], ["f"])
    sur = {
        "f": _exact("f", lambda x: (x[:, 0] - 0.8) ** 2 + (x[:, 1] - 0.8) ** 2 + (x[:, 2] - 0.3) ** 2),
        "g": _exact("g", lambda x: x[:, 0] + x[:, 1]),
    }
    mc = run_monte_carlo(study, sur, n=2000, chunk=2000, seed=5)
    sampled = next(o for o in mc.optima if o.stage == "constrained")
    problem = SurrogateProblem(study, sur, "constrained")
    rng = np.random.default_rng(2)
    best = local_optimum(problem, "f", "min", np.vstack([sampled.x, rng.random((4, D))]), fallback=sampled.x)
    assert best.method == "SLSQP on the surrogates"
    assert best.x[:3] == pytest.approx([0.5, 0.5, 0.3], abs=1e-4)
    assert best.value == pytest.approx(0.18, abs=1e-6)
    assert sampled.value > best.value + 1e-4
    assert best.x[0] + best.x[1] <= 1.0 + 1e-9  # feasible on the surrogates
    unconstrained = local_optimum(SurrogateProblem(study, sur, "unconstrained"), "f", "min", rng.random((3, D)))
    assert unconstrained.x[:3] == pytest.approx([0.8, 0.8, 0.3], abs=1e-4)


def test_slsqp_keeps_out_of_an_impossible_region():
    """The same problem with the corner x0 > 0.4 impossible (a validity margin 0.4 − x0): the optimum moves to
    x0 = 0.4, x1 = 0.6 (the sum constraint still active: minimise (0.4 − 0.8)² + (x1 − 0.8)² with x1 ≤ 0.6)."""
    study = _study([{"name": "sum", "response": "g", "max": 1.0}], ["f"])
    sur = {
        "f": _exact("f", lambda x: (x[:, 0] - 0.8) ** 2 + (x[:, 1] - 0.8) ** 2 + (x[:, 2] - 0.3) ** 2),
        "g": _exact("g", lambda x: x[:, 0] + x[:, 1]),
    }
    problem = SurrogateProblem(study, sur, "constrained", valid_margin=lambda x: 0.4 - x[:, 0])
    best = local_optimum(problem, "f", "min", np.random.default_rng(3).random((5, D)) * 0.4)
    assert best.x[:3] == pytest.approx([0.4, 0.6, 0.3], abs=1e-4)


def test_nsga2_front_on_the_analytic_front():
    """min f1 = x0 and f2 = (1 − x0)² + x1² subject to x0 ≥ 0.2: the Pareto front is f2 = (1 − f1)², f1 ∈ [0.2, 1]
    (x1 = 0 on it; x2, x3 free). NSGA-II's points lie on it within 0.02 and span it."""
    study = _study([{"name": "low", "response": "f1", "min": 0.2}], ["f1", "f2"])
    sur = {"f1": _exact("f1", lambda x: x[:, 0]), "f2": _exact("f2", lambda x: (1 - x[:, 0]) ** 2 + x[:, 1] ** 2)}
    problem = SurrogateProblem(study, sur, "constrained")
    f, x = nsga2_front(problem, [("f1", "min"), ("f2", "min")], seed=1, population=60, generations=100)
    assert len(f) >= 20
    assert np.all(f[:, 0] >= 0.2 - 1e-9)
    assert np.abs(f[:, 1] - (1 - f[:, 0]) ** 2).max() < 0.02
    assert f[:, 0].min() < 0.25 and f[:, 0].max() > 0.9
    picks = front_sample(f, 5)
    assert len(picks) == 5 and picks[0] == 0 and picks[-1] == len(f) - 1


def test_non_dominated_points_by_hand():
    """(1, 3), (2, 2), (3, 1) form the front; (2, 3) and (3, 3) are dominated; (1 + 1e-9, 4) is (1, 3)'s near-twin with
    a worse second objective (dominated within the tolerance); a repeated point counts once."""
    from certkit.study.analysis.optimise import non_dominated

    f = np.array([[1, 3], [2, 3], [2, 2], [3, 1], [3, 3], [1 + 1e-9, 4], [2, 2]], dtype=float)
    assert non_dominated(f).tolist() == [0, 2, 3]


def _analytic(constraints, objective="f"):
    return Study.model_validate(
        {
            "name": "analytic-conflict",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(3)],
            "objectives": [{"response": objective}],
            "constraints": constraints,
        }
    )


def _linear_surrogates(study, functions):
    x = np.random.default_rng(0).random((60, 3))
    return {
        n: fit_response(n, study.bounds, x, fn(x), x[:0], np.empty(0), families=("polynomial",))
        for n, fn in functions.items()
    }


def test_conflicting_constraints_named_at_the_design_of_least_violation():
    """x0 ≥ 0.6 and x0 ≤ 0.4 cannot both hold: no sample meets them, the design of least total squared violation
    is x0 = 0.5 (each violated by 0.1), reported as the stage's optimum, and the two are named as the conflict;
    x1 ≤ 0.9, met there, is not."""
    study = _analytic(
        [
            {"name": "above", "response": "a", "min": 0.6},
            {"name": "below", "response": "a", "max": 0.4},
            {"name": "x1 small", "response": "b", "max": 0.9},
        ]
    )
    sur = _linear_surrogates(study, {"a": lambda x: x[:, 0], "b": lambda x: x[:, 1], "f": lambda x: x.sum(axis=1)})
    mc = run_monte_carlo(study, sur, n=20_000, chunk=20_000, seed=1)
    assert mc.stage_counts["constrained"] == 0
    optima = optimise(study, sur, mc)
    (nearest,) = [o for o in optima if o.stage == "constrained"]
    assert nearest.method == LEAST_VIOLATION
    assert nearest.x[0] == pytest.approx(0.5, abs=1e-4) and nearest.x[1] <= 0.9
    conflicts = conflicting_constraints(study, sur, optima)
    assert set(conflicts) == {"above", "below"}
    assert not active_constraints(study, sur, optima)


def test_a_feasible_corner_the_samples_miss_is_found_and_optimised():
    """x0, x1, x2 ≥ 0.999 together hold on 10⁻⁹ of the cube: 20,000 samples miss it, the least-violation search
    finds it, and the least x0 + x1 + x2 there is its corner (2.997)."""
    study = _analytic([{"name": f"x{i} large", "response": f"x{i}", "min": 0.999} for i in range(3)])
    functions = {f"x{i}": (lambda x, i=i: x[:, i]) for i in range(3)}
    sur = _linear_surrogates(study, {**functions, "f": lambda x: x.sum(axis=1)})
    mc = run_monte_carlo(study, sur, n=20_000, chunk=20_000, seed=1)
    assert mc.stage_counts["constrained"] == 0
    (best,) = [o for o in optimise(study, sur, mc) if o.stage == "constrained"]
    assert best.method == "SLSQP on the surrogates"
    assert best.value == pytest.approx(2.997, abs=1e-5)

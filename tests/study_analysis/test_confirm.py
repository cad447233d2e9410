"""A surrogate optimum the true model rejects is searched again on corrected surrogates until the true model accepts
a design (certkit/study/analysis/confirm.py), on analytic problems whose true constrained optimum is known."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import minimize

from certkit.study.analysis.cases import RESP_PREFIX, VAR_PREFIX
from certkit.study.analysis.checks import reevaluate_optima
from certkit.study.analysis.confirm import CONFIRMED, MAX_STEPS, NOT_CONFIRMED, confirm_optima
from certkit.study.analysis.montecarlo import Optimum
from certkit.study.analysis.optimise import SurrogateProblem, local_optimum
from tests.study_analysis.test_optimise import D, _exact, _study


def f_true(x):
    return (x[:, 0] - 0.8) ** 2 + (x[:, 1] - 0.8) ** 2 + (x[:, 2] - 0.3) ** 2


def _true_model(g_true, calls, f=f_true):
    """A true model as the study runner returns it: a frame of cases (objective ``f`` exact, constraint g_true)."""

    def run_cases(study, store, points, block, role):
        rows = []
        for p in points:
            x = np.array([[p[v.path] for v in study.variables]])
            calls.append(block)
            rows.append(
                {
                    "key": str(hash(tuple(x[0]))),
                    "status": "ok",
                    "block": block,
                    **{VAR_PREFIX + v.path: p[v.path] for v in study.variables},
                    RESP_PREFIX + "f": float(f(x)[0]),
                    RESP_PREFIX + "g": float(g_true(x)[0]),
                }
            )
        return pd.DataFrame(rows)

    return run_cases


def _surrogate_optimum(g_bias=0.0):
    """min f subject to x0 + x1 ≤ 1 on exact surrogates: x0 = x1 = 0.5, x2 = 0.3 (KKT), f = 0.18."""
    study = _study([{"name": "sum", "response": "g", "max": 1.0}], ["f"])
    sur = {"f": _exact("f", f_true), "g": _exact("g", lambda x: x[:, 0] + x[:, 1])}
    problem = SurrogateProblem(study, sur, "constrained")
    start = np.array([[0.3, 0.3, 0.5, 0.5]])
    best = local_optimum(problem, "f", "min", start)
    assert best.x[:3] == pytest.approx([0.5, 0.5, 0.3], abs=1e-4)
    return study, sur, best


def _confirm(g_true):
    study, sur, best = _surrogate_optimum()
    calls = []
    run = _true_model(g_true, calls)
    checked = reevaluate_optima(study, None, sur, [best], run_cases=run)
    return confirm_optima(study, None, sur, checked, run_cases=run), calls


def _true_optimum(g_true, f=f_true, start=None):
    """The true problem solved directly (the reference: SLSQP on the true functions, from a feasible ``start``,
    by default 0.2 in every variable)."""
    res = minimize(
        lambda x: float(f(x[None, :])[0]),
        np.full(D, 0.2) if start is None else np.asarray(start, dtype=float),
        method="SLSQP",
        bounds=[(0.0, 1.0)] * D,
        constraints=[{"type": "ineq", "fun": lambda x: 1.0 - float(g_true(x[None, :])[0])}],
        options={"ftol": 1e-12, "maxiter": 200},
    )
    return res.x, res.fun


def test_a_constant_surrogate_error_is_corrected_in_one_step_to_the_true_optimum():
    """True g = x0 + x1 + 0.1: the surrogate optimum (0.5, 0.5) has g = 1.1 (fails). The corrected surrogate is the
    true model, so one step lands on the true optimum x0 = x1 = 0.45 (KKT on x0 + x1 = 0.9), f = 2 × 0.35² = 0.245."""
    (conf,), calls = _confirm(lambda x: x[:, 0] + x[:, 1] + 0.1)
    assert conf.status == CONFIRMED
    assert conf.steps[0].violated == ["sum"] and conf.steps[0].true["g"] == pytest.approx(1.1, abs=1e-6)
    assert conf.evaluations == 2 and calls.count("confirm") == 1
    design = conf.design
    assert design.violated == [] and design.true["g"] <= 1.0 + 1e-9
    assert design.x[:3] == pytest.approx([0.45, 0.45, 0.3], abs=2e-3)
    assert design.true["f"] == pytest.approx(0.245, abs=1e-3)


def test_a_varying_surrogate_error_is_corrected_to_the_true_optimum_with_the_true_gradient():
    """True g = x0 + x1 + 0.1 + 0.3 x0² (an error growing with x0, which moves the true optimum off the diagonal):
    with the true model's gradient in the correction (order one, the default) the search converges on the true
    problem's optimum, solved directly: the design within 0.005 of it and its f within 10⁻⁴ (within the true
    constraint, so never below it)."""

    def g_true(x):
        return x[:, 0] + x[:, 1] + 0.1 + 0.3 * x[:, 0] ** 2

    (conf,), calls = _confirm(g_true)
    x_best, f_best = _true_optimum(g_true)
    assert conf.status == CONFIRMED, conf.reason
    design = conf.design
    assert design.true["g"] <= 1.0 + 1e-9
    assert design.x[:3] == pytest.approx(x_best[:3], abs=0.005)
    assert f_best - 1e-9 <= design.true["f"] <= f_best + 1e-4
    # n probes at each design a search stood on (the start and every accepted step; the last one's show it is done)
    assert calls.count("confirm-gradient") == D * sum(s.accepted for s in conf.steps)


def test_with_the_correction_of_order_zero_the_same_search_only_nears_it():
    """The same problem corrected by values alone: each step's correction is exact only at its design and its
    gradient is the surrogate's (the diagonal's), so the search ends within the true constraint but off the true
    optimum — its f within 0.01 above it (the first design within the constraint, f 0.300, is 0.02 above)."""

    def g_true(x):
        return x[:, 0] + x[:, 1] + 0.1 + 0.3 * x[:, 0] ** 2

    study, sur, best = _surrogate_optimum()
    calls = []
    run = _true_model(g_true, calls)
    checked = reevaluate_optima(study, None, sur, [best], run_cases=run)
    (conf,) = confirm_optima(study, None, sur, checked, run_cases=run, gradients=False)
    _, f_best = _true_optimum(g_true)
    assert conf.status == CONFIRMED and "confirm-gradient" not in calls
    assert conf.design.true["g"] <= 1.0 + 1e-9
    assert f_best - 1e-6 <= conf.design.true["f"] <= f_best + 0.01
    assert 2 <= conf.evaluations <= MAX_STEPS + 1


def test_a_constraint_no_design_meets_is_reported_not_confirmed():
    """True g = 2 + x0 + x1 > 1 everywhere: the search runs out of steps and says which constraint remains."""
    (conf,), calls = _confirm(lambda x: 2.0 + x[:, 0] + x[:, 1])
    assert conf.status == NOT_CONFIRMED
    assert "sum" in conf.reason and conf.design.violated == ["sum"]
    assert calls.count("confirm") <= MAX_STEPS
    # the least-violating design moved toward the constraint (x0 + x1 smaller than at the surrogate optimum)
    assert conf.design.true["g"] < conf.steps[0].true["g"]


def test_an_optimum_the_true_model_accepts_is_confirmed_as_it_is():
    (conf,), calls = _confirm(lambda x: x[:, 0] + x[:, 1] - 0.05)
    assert conf.status == CONFIRMED and conf.evaluations == 1 and "confirm" not in calls


def test_least_violation_and_unconstrained_optima_are_not_searched_again():
    study, sur, best = _surrogate_optimum()
    run = _true_model(lambda x: x[:, 0] + x[:, 1] + 0.1, [])
    others = [
        Optimum("f", "unconstrained", 0.0, np.full(D, 0.8)),
        Optimum("f", "constrained", 0.0, best.x, "least violation: no design meets every constraint of the stage"),
    ]
    from certkit.study.analysis.optimise import LEAST_VIOLATION

    others[1].method = LEAST_VIOLATION
    checked = reevaluate_optima(study, None, sur, others, run_cases=run)
    assert confirm_optima(study, None, sur, checked, run_cases=run) == []


def test_a_derived_level_is_corrected_through_its_least_margins():
    """The two-condition phugoid of tests/study_analysis/test_derived_levels.py (Level 1 where ζ_a = 0.08·x0 and
    ζ_b = 0.08·x1 both reach 0.04; minimise x0 + x1): the true model's ζ_a is 0.004 lower, so Level 1 needs x0 ≥ 0.55
    and the true optimum is x0 + x1 = 1.05. The surrogate optimum (≈ 1.02, fitted to the unbiased cases) is Level 2 on
    the true model; corrected through its least-margin surrogates the search ends at a Level 1 design. The least
    margin over the two conditions has a kink where they trade which one sets it, and a correction of either order is
    exact only on one side of it (a value-only correction charges condition a's deficit to condition b as well): the
    design found lies between the true optimum 1.05 and 1.10 (module doc: the best found, not a proven optimum)."""
    from certkit_rules.part25.support import handling_levels as hq

    from certkit.study.analysis.cases import cases
    from certkit.study.analysis.derived_levels import fit_predictors, mode_offers
    from certkit.study.analysis.montecarlo import run_monte_carlo
    from certkit.study.analysis.optimise import optimise
    from tests.study_analysis import test_derived_levels as dl

    study = dl._study()
    surrogates, levels, _ = fit_predictors(study, cases(dl._two_condition_frame(), study), offers=mode_offers())
    predictors = {**surrogates, **levels}
    mc = run_monte_carlo(study, predictors, n=50_000, chunk=50_000, seed=5)
    (best,) = [o for o in optimise(study, predictors, mc) if o.stage == "constrained"]

    def run_cases(study, store, points, block, role):
        rows = []
        for p in points:
            x = [p[v.path] for v in study.variables]
            conditions = [(0.08 * x[0] - 0.004, 0.10), (0.08 * x[1], 0.20)]
            row = {"key": str(x), "status": "ok", **{VAR_PREFIX + v.path: p[v.path] for v in study.variables}}
            row[RESP_PREFIX + "f"] = x[0] + x[1]
            row[RESP_PREFIX + dl.LEVEL] = max(dl._recorded_level(max(z, 0.0), w) for z, w in conditions)
            for lv in (1, 2, 3):
                m = min(hq.damping_level_margin("phugoid", "takeoff", lv, zeta=z, wn=w) for z, w in conditions)
                row[RESP_PREFIX + f"mode.phugoid.level{lv}_margin.c1.takeoff"] = float(np.clip(m, -10, 10))
            rows.append(row)
        return pd.DataFrame(rows)

    checked = reevaluate_optima(study, None, predictors, [best], run_cases=run_cases)
    assert checked[0].true[dl.LEVEL] == 2.0  # the surrogate optimum fails Level 1 on the true model
    (conf,) = confirm_optima(study, None, predictors, checked, run_cases=run_cases)
    assert conf.status == CONFIRMED, conf.reason
    assert conf.design.true[dl.LEVEL] == 1.0
    assert conf.design.x[0] >= 0.55 - 1e-9
    assert 1.05 - 1e-9 <= conf.design.true["f"] <= 1.10


def test_optima_at_one_design_share_its_evaluations():
    """Two optima at the same design (a stage met by one sample gives every objective that sample) propose the same
    designs: each design is evaluated once, and both confirmations read it."""
    study, sur, best = _surrogate_optimum()
    calls = []
    run = _true_model(lambda x: x[:, 0] + x[:, 1] + 0.1, calls)
    twin = Optimum(best.objective, best.stage, best.value, best.x.copy(), best.method)
    checked = reevaluate_optima(study, None, sur, [best, twin], run_cases=run)
    first, second = confirm_optima(study, None, sur, checked, run_cases=run)
    assert first.status == second.status == CONFIRMED
    assert [s.x.tolist() for s in first.steps] == [s.x.tolist() for s in second.steps]
    assert calls.count("confirm") == first.evaluations - 1


def test_after_a_rejected_step_the_search_restores_feasibility_by_the_least_move():
    """A curved true constraint, g = x0 + x1 + 0.02 + 20 (x0 − x0*)² (x0* the surrogate optimum's x0), against an
    objective that pulls along the boundary, min (x0 − 0.95)² + 0.2 (x1 − 0.9)² + (x2 − 0.3)²: the first corrected
    optimum runs along the linearised boundary into the curvature and the true model rejects it (g 1.08 against the
    start's 1.02). The next step is the restoration — the nearest design the corrected surrogates find feasible, aimed
    as far inside as the start is outside — and the true model accepts it: a confirmed design at the second step,
    where the optimum steps alone reach one at the fourth. The search then improves it to within 0.002 of the true
    problem's optimum, solved directly (0.12616)."""
    study = _study([{"name": "sum", "response": "g", "max": 1.0}], ["f"])

    def f2(x):
        return (x[:, 0] - 0.95) ** 2 + 0.2 * (x[:, 1] - 0.9) ** 2 + (x[:, 2] - 0.3) ** 2

    sur = {"f": _exact("f", f2), "g": _exact("g", lambda x: x[:, 0] + x[:, 1])}
    best = local_optimum(SurrogateProblem(study, sur, "constrained"), "f", "min", np.array([[0.3, 0.3, 0.5, 0.5]]))
    x0 = best.x[0]

    def g_true(x):
        return x[:, 0] + x[:, 1] + 0.02 + 20.0 * (x[:, 0] - x0) ** 2

    run_cases = _true_model(g_true, [], f2)
    checked = reevaluate_optima(study, None, sur, [best], run_cases=run_cases)
    (conf,) = confirm_optima(study, None, sur, checked, run_cases=run_cases)
    first, rejected, restored = conf.steps[:3]
    assert first.true["g"] == pytest.approx(1.02, abs=1e-6)
    assert not rejected.accepted and rejected.true["g"] > first.true["g"]
    assert restored.accepted and restored.violated == [] and restored.true["g"] <= 1.0
    # the least move: within half the rejected step, on the [−1, 1] scale
    span = lambda a, b: float(np.max(np.abs(a - b))) * 2.0  # noqa: E731 (unit bounds: [0, 1] → [−1, 1])
    assert span(restored.x, first.x) <= 0.5 * span(rejected.x, first.x) + 1e-9
    _, best_f = _true_optimum(g_true, f2, start=[0.7, 0.1, 0.3, 0.5])
    assert conf.status == CONFIRMED and conf.design.true["g"] <= 1.0
    assert best_f - 1e-9 <= conf.design.true["f"] <= best_f + 0.002

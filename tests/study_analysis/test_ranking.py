"""Show-stoppers with their reasons, and the constraints active at the constrained optimum, on analytic studies."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from certkit.study.analysis.cases import cases
from certkit.study.analysis.montecarlo import run_monte_carlo
from certkit.study.analysis.optimise import optimise
from certkit.study.analysis.ranking import active_constraints, show_stoppers, without_unattainable
from certkit.study.analysis.surrogates import fit_response
from certkit.study.spec import Study

D = 3
FUNCTIONS = {"s": lambda x: x.sum(axis=1), "a": lambda x: x[:, 0], "f": lambda x: -x[:, 0] - 2.0 * x[:, 1]}


def _study(constraints) -> Study:
    return Study.model_validate(
        {
            "name": "analytic",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "objectives": [{"response": "f"}],
            "constraints": constraints,
        }
    )


def _setup(study):
    x = np.random.default_rng(0).random((60, D))
    frame = pd.DataFrame({f"var:v.x{i}": x[:, i] for i in range(D)})
    for name, fn in FUNCTIONS.items():
        frame[f"resp:{name}"] = fn(x)
    frame["key"], frame["block"], frame["role"], frame["status"], frame["error"] = (
        range(60),
        "lhs",
        "training",
        "ok",
        None,
    )
    sur = {
        n: fit_response(n, study.bounds, x, fn(x), x[:0], np.empty(0), families=("polynomial",))
        for n, fn in FUNCTIONS.items()
    }
    return cases(frame, study), sur


def test_a_constraint_no_design_meets_is_a_show_stopper_with_its_reason():
    """x0 ≥ 2 on the unit cube: P = 0; the least violation over the samples is 2 − max x0 ≈ 1 and no case meets
    it. A constraint whose response has no surrogate is listed as not judged, with the reason."""
    study = _study(
        [
            {"name": "sum", "response": "s", "max": 1.5},
            {"name": "never", "response": "a", "min": 2.0},
            {"name": "unknown", "response": "u", "max": 1.0},
        ]
    )
    cs, sur = _setup(study)
    usable = study.model_copy(update={"constraints": study.constraints[:2]})
    mc = run_monte_carlo(usable, sur, n=20_000, chunk=20_000, seed=1)
    stoppers = show_stoppers(usable, mc, cs, {})
    assert [s.name for s in stoppers] == ["never"]
    (never,) = [o for o in mc.constraints if o.constraint.name == "never"]
    assert never.p == 0 and never.interval[1] > 0  # P = 0 with an interval of non-zero width
    assert never.least_violation == pytest.approx(1.0, abs=1e-3) and never.best_value == pytest.approx(1.0, abs=1e-3)
    assert "0 of the 60 computed cases satisfy it" in stoppers[0].reason
    assert mc.ranked()[0].constraint.name == "never"  # ranked first
    more = show_stoppers(study, mc, cs, {"u": "u: 0 training cases with a value; at least 5 needed"})
    assert [s.name for s in more] == ["never", "unknown"] and "not judged: no surrogate" in more[1].reason


def test_active_constraints_at_the_constrained_optimum():
    """min −x0 − 2x1 subject to x0 + x1 + x2 ≤ 1.5 and x0 ≤ 0.9: the optimum x = (0.5, 1, 0) lies on the sum
    constraint (x1 at its bound, x0 = 0.5 < 0.9), so 'sum' is active and 'cap' is not."""
    study = _study([{"name": "sum", "response": "s", "max": 1.5}, {"name": "cap", "response": "a", "max": 0.9}])
    cs, sur = _setup(study)
    mc = run_monte_carlo(study, sur, n=5000, chunk=5000, seed=2)
    optima = optimise(study, sur, mc)
    constrained = next(o for o in optima if o.stage == "constrained")
    assert constrained.x == pytest.approx([0.5, 1.0, 0.0], abs=1e-4)
    active = active_constraints(study, sur, optima)
    assert "f (constrained)" in active["sum"] and "cap" not in active


def test_stages_and_optima_are_those_of_the_attainable_constraints():
    """With x0 ≥ 2 unattainable every design fails the joint requirement; the stages are then those of the other
    constraint (P(x0 + x1 + x2 ≤ 1.5) = 1/2 by symmetry about 1.5), the ranking keeps both."""
    study = _study([{"name": "sum", "response": "s", "max": 1.5}, {"name": "never", "response": "a", "min": 2.0}])
    _, sur = _setup(study)

    def run(s):
        return run_monte_carlo(s, sur, n=40_000, chunk=20_000, seed=4)

    mc = run(study)
    assert mc.stage_counts["constrained"] == 0
    rest, stages = without_unattainable(study, sur, mc, run)
    assert [c.name for c in rest.constraints] == ["sum"]
    assert [o.constraint.name for o in stages.constraints] == ["sum", "never"]
    p, se = stages.stage_p("constrained")
    assert p == pytest.approx(0.5, abs=3 * se) and p == stages.constraints[0].p
    assert [o.stage for o in stages.optima if o.objective == "f"].count("constrained") == 1


def test_a_region_no_computed_case_confirms_is_set_apart():
    """x0 ≥ 0.9995 holds on 0.05 % of the cube: the surrogate finds it on about that share of the samples, fewer
    than one in the 60 computed cases (1.7 %), and none of the cases meets it — a show-stopper, unconfirmed, set
    apart from the stages; x0 ≥ 0.5, met by computed cases, stays."""
    study = _study([{"name": "half", "response": "a", "min": 0.5}, {"name": "sliver", "response": "a", "min": 0.9995}])
    cs, sur = _setup(study)
    assert np.max(cs.xy("training", "a")[1]) < 0.9995

    def run(s):
        return run_monte_carlo(s, sur, n=200_000, chunk=100_000, seed=4)

    mc = run(study)
    sliver = next(o for o in mc.constraints if o.constraint.name == "sliver")
    assert 0 < sliver.p < 1 / 60
    (stopper,) = show_stoppers(study, mc, cs, {})
    assert stopper.name == "sliver" and "unconfirmed" in stopper.reason
    assert "0 of the 60 computed cases satisfy it" in stopper.reason
    rest, stages = without_unattainable(study, sur, mc, run, cs)
    assert [c.name for c in rest.constraints] == ["half"]
    assert stages.stage_p("constrained")[0] == pytest.approx(0.5, abs=0.01)


def test_a_response_no_design_moves_is_never_active():
    """A constraint on a constant response (0 ≤ c, c ≡ 0: on its limit everywhere, as §25.335(b)'s VD = 1.25 VC
    by declaration) binds no optimum; the sum constraint at the optimum still does."""
    study = _study([{"name": "sum", "response": "s", "max": 1.5}, {"name": "declared", "response": "z", "min": 0.0}])
    cs, sur = _setup(study)
    x = np.random.default_rng(0).random((60, D))
    sur["z"] = fit_response("z", study.bounds, x, np.zeros(60), x[:0], np.empty(0), families=("polynomial",))
    mc = run_monte_carlo(study, sur, n=5000, chunk=5000, seed=2)
    active = active_constraints(study, sur, optimise(study, sur, mc))
    assert "sum" in active and "declared" not in active

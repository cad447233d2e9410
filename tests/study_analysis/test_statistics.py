"""Honest statistics: model selection blind to the validation block, Wilson intervals' coverage on a study of
closed-form probabilities, impossible designs masked, the Gaussian process on a maximin subsample."""

from __future__ import annotations

import math

import numpy as np
import pytest

from certkit.study.analysis.intervals import wilson
from certkit.study.analysis.montecarlo import run_monte_carlo
from certkit.study.analysis.surrogates import fit_response, maximin_subsample, to_unit
from certkit.study.analysis.validity import fit_validity
from certkit.study.spec import Study
from tests.study_analysis.synthetic import frame_of, sample, study_dict, study_of, unit

D = 3
BOX = np.array([[-1.0, 1.0]] * D)


def _quadratic(x):
    return 1.0 + x[:, 0] - 0.5 * x[:, 1] + 0.8 * x[:, 0] ** 2 + 0.6 * x[:, 1] * x[:, 2]


def test_selection_never_sees_the_validation_block():
    """A deliberately leaking split: validation values poisoned with the degree-1 fit's own predictions (a block
    that would crown the straight line with zero error were it used to choose), and validation rows that copy
    training rows. The kept model and every candidate's selection error are those of an honest split; the leaked
    copies are counted and left out of the validation score."""
    rng = np.random.default_rng(4)
    x_tr, x_val = rng.uniform(-1, 1, (80, D)), rng.uniform(-1, 1, (40, D))
    y_tr = _quadratic(x_tr) + rng.normal(0, 0.02, 80)
    honest = fit_response("q", BOX, x_tr, y_tr, x_val, _quadratic(x_val), families=("polynomial",))
    line = next(c for c in honest.candidates if c.degree == 1 and not c.log)
    poisoned_val = np.vstack([x_val, x_tr[:15]])
    poisoned_y = np.concatenate([line.predict_unit(x_val), y_tr[:15] + 5.0])
    leaky = fit_response("q", BOX, x_tr, y_tr, poisoned_val, poisoned_y, families=("polynomial",))
    assert honest.kept.degree == leaky.kept.degree == 2 and honest.kept.label == leaky.kept.label
    assert [c.selection_rmse for c in honest.candidates] == [c.selection_rmse for c in leaky.candidates]
    assert leaky.n_leaked == 15 and honest.n_leaked == 0
    assert leaky.validation.n == 40
    # the poisoned block still scores the kept model (badly: it holds a straight line's values)
    assert leaky.validation.r2 < honest.validation.r2 - 0.05
    assert honest.validation.r2 > 0.99


def _irwin_hall(t: float, n: int) -> float:
    """P(U_1 + … + U_n ≤ t), U_i ~ U(0, 1) (Irwin 1927, Hall 1927)."""
    return sum((-1) ** k * math.comb(n, k) * (t - k) ** n for k in range(int(math.floor(t)) + 1)) / math.factorial(n)


def _unit_study(constraints, objectives=()) -> Study:
    return Study.model_validate(
        {
            "name": "unit-box",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "objectives": [{"response": o} for o in objectives],
            "constraints": constraints,
        }
    )


def _exact(name, fn):
    rng = np.random.default_rng(0)
    x, xv = rng.random((60, D)), rng.random((20, D))
    return fit_response(name, np.array([[0.0, 1.0]] * D), x, fn(x), xv, fn(xv), families=("polynomial",))


def test_wilson_intervals_cover_closed_form_probabilities():
    """A synthetic study of known probabilities (x uniform on the unit cube): P(x0 ≤ 0.02) = 0.02,
    P(x0 + x1 ≤ 0.5) = 1/8 (a triangle), P(x0 + x1 + x2 ≤ 2.2) from the Irwin–Hall distribution, P = 1 and
    P = 0. Over 300 independent Monte Carlo runs of 150 samples, each 95 % interval must cover the true
    probability in 91–99 % of the runs (3 binomial standard deviations of 300 runs around 95 %), and never be of
    zero width. The Wald interval p ± 1.96√(p(1−p)/N) covers P = 0.02 in under 90 % of the runs (Brown, Cai &
    DasGupta 2001, Fig. 1): the test can tell the two apart."""
    constraints = [
        {"name": "rare", "response": "a", "max": 0.02},
        {"name": "triangle", "response": "b", "max": 0.5},
        {"name": "sum", "response": "c", "max": 2.2},
        {"name": "always", "response": "a", "min": -1.0},
        {"name": "never", "response": "a", "min": 2.0},
    ]
    exact = {"rare": 0.02, "triangle": 0.125, "sum": _irwin_hall(2.2, 3), "always": 1.0, "never": 0.0}
    study = _unit_study(constraints)
    sur = {
        "a": _exact("a", lambda x: x[:, 0]),
        "b": _exact("b", lambda x: x[:, 0] + x[:, 1]),
        "c": _exact("c", lambda x: x.sum(axis=1)),
    }
    runs, n = 300, 150
    covered = dict.fromkeys(exact, 0)
    wald_covered = 0
    for r in range(runs):
        mc = run_monte_carlo(study, sur, n=n, chunk=n, seed=1000 + r, cloud=1)
        for o in mc.constraints:
            lo, hi = o.interval
            assert hi - lo > 0 and o.se > 0
            covered[o.constraint.name] += lo <= exact[o.constraint.name] <= hi
            if o.constraint.name == "rare":
                half = 1.959964 * math.sqrt(o.p * (1 - o.p) / n)
                wald_covered += o.p - half <= 0.02 <= o.p + half
    for name, k in covered.items():
        assert 0.91 <= k / runs <= (1.0 if name in ("always", "never") else 0.99), (name, k / runs)
    assert wald_covered / runs < 0.90


def test_wilson_interval_closed_form():
    """Wilson (1927) at k = 0: [0, z²/(n + z²)]; at k = n: [n/(n + z²), 1]; symmetric in k ↔ n − k."""
    z2 = 1.959963984540054**2
    assert wilson(0, 100) == pytest.approx((0.0, z2 / (100 + z2)), abs=1e-12)
    assert wilson(100, 100) == pytest.approx((100 / (100 + z2), 1.0), abs=1e-12)
    lo, hi = wilson(30, 100)
    assert (1 - hi, 1 - lo) == pytest.approx(wilson(70, 100), abs=1e-12)
    # Newcombe (1998), Statistics in Medicine 17: 857, Table I example: 81/263 → 0.2553–0.3662
    assert wilson(81, 263) == pytest.approx((0.2553, 0.3662), abs=5e-5)


def test_impossible_designs_masked_before_monte_carlo_and_optima():
    """Cases with u_AR − u_S > 1 (high aspect ratio on a small tail, on the [−1, 1] scale) fail as impossible
    designs: a triangle of 1/8 of the (AR, S) square. The cruise-drag objective is least in that very corner. The
    classifier learnt from the cases masks ≈ 1/8 of the samples, and no optimum or front point is impossible."""
    x_tr, x_val = sample(400, 1), sample(100, 2)
    frames = []
    for x, block, role in ((x_tr, "lhs", "training"), (x_val, "random", "validation")):
        df = frame_of(x, block, role)
        u = unit(x)
        bad = u[:, 0] - u[:, 4] > 1.0
        df.loc[bad, "status"] = "failed"
        df.loc[bad, "error"] = "infeasible design: geometry.horizontal_tail: tip leading edge behind the fuselage end"
        frames.append(df)
    import pandas as pd

    frame = pd.concat(frames, ignore_index=True)
    data = study_dict()
    data["objectives"] = data["objectives"][:1]
    data["constraints"] = []
    study = study_of(data)
    validity = fit_validity(frame, study)
    assert validity.n_infeasible == int((frame["status"] == "failed").sum()) > 20
    assert validity.missed + validity.false_alarms <= 0.03 * validity.n_cases
    # the classifier as the profiler page evaluates it: the same log-odds as scikit-learn's, the same verdicts
    from certkit.study.analysis.validity import validity_log_odds

    probe = study.bounds[:, 0] + (study.bounds[:, 1] - study.bounds[:, 0]) * np.random.default_rng(9).random((500, 8))
    z = validity_log_odds(validity.export(), probe)
    np.testing.assert_allclose(z, -validity.margin(probe), rtol=1e-9, atol=1e-9)
    assert ((z <= 0) == validity.valid(probe)).all() and (z > 0).any() and (z <= 0).any()
    ok = frame["status"] == "ok"
    x = frame.loc[ok, [f"var:{v.path}" for v in study.variables]].to_numpy()
    y = frame.loc[ok, "resp:objective.cruise_CD"].to_numpy()
    sur = {
        "objective.cruise_CD": fit_response(
            "objective.cruise_CD", study.bounds, x, y, x[:0], y[:0], families=("polynomial",)
        )
    }
    plain = run_monte_carlo(study, sur, n=40_000, chunk=20_000, seed=3)
    masked = run_monte_carlo(study, sur, n=40_000, chunk=20_000, seed=3, valid=validity.valid)
    assert masked.n_drawn == 40_000 and masked.masked / masked.n_drawn == pytest.approx(1 / 8, abs=0.01)

    def impossible(xs):
        u = to_unit(np.atleast_2d(xs), study.bounds)
        return u[:, 0] - u[:, 4] > 1.0

    assert impossible(plain.optima[0].x).all()  # without the mask the optimum is an impossible aircraft
    for o in masked.optima:  # at the learnt boundary, within 2.5 % of the range (500 cases over 8 variables)
        u = to_unit(o.x[None, :], study.bounds)[0]
        assert u[0] - u[4] < 1.05


def test_gaussian_process_on_a_maximin_subsample():
    rng = np.random.default_rng(6)
    x = rng.uniform(-1, 1, (150, D))
    s = fit_response("g", BOX, x, _quadratic(x), x[:0], np.empty(0), families=("Gaussian process",), gp_max_cases=60)
    gp = s.kept.estimator
    assert gp.n_fitted_ == 60 and "60-case subsample" in s.kept.label and "maximin subsample of 60" in s.kept.note
    assert s.cv.r2 > 0.98
    chosen = maximin_subsample(x, 60)

    def min_gap(pts):
        d = np.sqrt(((pts[:, None, :] - pts[None, :, :]) ** 2).sum(-1))
        return d[np.triu_indices(len(pts), 1)].min()

    assert min_gap(x[chosen]) > 2 * min_gap(x[rng.choice(150, 60, replace=False)])


def test_too_few_cases_for_a_classifier_mask_nothing():
    """Ten cases, three of them impossible, eight variables: a degree-1 classifier has 9 terms, more than half the
    cases, so none is fitted; every design is taken as possible and the note says why (no failure)."""
    x = sample(10, 4)
    df = frame_of(x, "lhs", "training")
    df.loc[:2, "status"] = "failed"
    df.loc[:2, "error"] = "infeasible design: geometry.horizontal_tail: tip leading edge behind the fuselage end"
    study = study_of(study_dict())
    validity = fit_validity(df, study)
    assert validity.estimator is None and validity.n_infeasible == 3
    assert "too few" in validity.note and validity.valid(x).all()

"""Handling-quality levels derived from the surrogates of the mode quantities, on an analytic study whose closed
form is known: the takeoff phugoid's damping ratio ζ = 0.08·x0 (x0 uniform on [0, 1]) at ω_n = 0.10 + 0.05·x1
rad/s. MIL-F-8785C 3.2.1.2: Level 1 needs ζ ≥ 0.04, i.e. x0 ≥ ½ — P(Level 1) = ½ exactly, and the least x0
meeting Level 1 is ½; Level 2 needs ζ ≥ 0, met everywhere. The recorded levels come from the rule's mode-table route
(``level_of`` on each mode, the worse of the configuration's categories), not from the function under test.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from certkit_rules.part25.support import handling_levels as hq

from certkit.models.dynamics.modes import Mode
from certkit.study.analysis.cases import cases
from certkit.study.analysis.derived_levels import fit_predictors, mode_offers
from certkit.study.analysis.intervals import wilson
from certkit.study.analysis.montecarlo import run_monte_carlo
from certkit.study.analysis.optimise import optimise
from certkit.study.analysis.ranking import active_constraints
from certkit.study.spec import Study

D = 3
LEVEL = "level.phugoid.c1.takeoff"
ZETA, WN = "mode.phugoid.zeta.c1.takeoff", "mode.phugoid.wn_rad_s.c1.takeoff"


def _recorded_level(zeta: float, wn: float) -> int:
    lam = complex(-zeta * wn, wn * math.sqrt(1.0 - zeta**2))
    mode = Mode("phugoid", lam, wn, zeta, 2 * math.pi / lam.imag, None, None, np.zeros(8))
    return max(hq.level_of("phugoid", mode, cat)[0] for cat in hq.categories_of("takeoff"))


def _study(max_level: int | None = None) -> Study:
    analysis = {"level_relaxation": [{"responses": LEVEL, "max_level": max_level}]} if max_level else None
    return Study.model_validate(
        {
            "name": "analytic-levels",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "objectives": [{"response": "f"}],
            "constraints": [{"name": "takeoff phugoid", "response": LEVEL, "max": 1}],
            "analysis": analysis,
        }
    )


def _frame(n_train: int = 80, n_val: int = 200) -> pd.DataFrame:
    rng = np.random.default_rng(3)
    x = rng.random((n_train + n_val, D))
    zeta, wn = 0.08 * x[:, 0], 0.10 + 0.05 * x[:, 1]
    frame = pd.DataFrame({f"var:v.x{i}": x[:, i] for i in range(D)})
    frame["resp:f"] = x[:, 0]
    frame["resp:" + ZETA], frame["resp:" + WN] = np.round(zeta, 5), np.round(wn, 5)
    frame["resp:" + LEVEL] = [_recorded_level(z, w) for z, w in zip(zeta, wn)]
    frame["key"], frame["block"], frame["status"], frame["error"] = range(len(x)), "lhs", "ok", None
    frame["role"] = ["training"] * n_train + ["validation"] * n_val
    return frame


@pytest.fixture(scope="module")
def fitted():
    study = _study()
    surrogates, levels, not_fitted = fit_predictors(study, cases(_frame(), study), offers=mode_offers())
    return study, surrogates, levels, not_fitted


def test_the_level_is_derived_from_the_quantities_not_regressed(fitted):
    """The level response gets no surrogate of its own; its quantities do, and the derived level agrees with the
    recorded one on the validation cases (a case within the polynomial's error of ζ = 0.04 may differ: allow 2 of
    200) and reproduces every recorded level from the recorded quantities."""
    study, surrogates, levels, not_fitted = fitted
    assert not not_fitted
    assert LEVEL not in surrogates and {ZETA, WN} <= set(surrogates)
    d = levels[LEVEL]
    assert d.source.sources == {"zeta": ZETA, "wn": WN}
    assert d.n_validation == 200 and d.n_agree >= 198
    assert d.n_reproduced == d.n_recorded == 280
    assert not d.flagged
    x = np.array([[0.49, 0.5, 0.5], [0.51, 0.5, 0.5], [0.0, 0.0, 0.0]])
    assert d.predict(x).tolist() == [2.0, 1.0, 2.0]


def test_probability_of_level_one_is_the_closed_form(fitted):
    """P(ζ ≥ 0.04) = P(x0 ≥ ½) = ½: inside the Monte Carlo's 95 % Wilson interval widened by the boundary's
    surrogate error (ζ is linear in x0: the polynomial reproduces it to round-off)."""
    study, surrogates, levels, _ = fitted
    predictors = {**surrogates, **levels}
    mc = run_monte_carlo(study, predictors, n=100_000, chunk=50_000, seed=5)
    (o,) = mc.constraints
    lo, hi = wilson(o.successes, mc.n)
    assert lo - 1e-3 <= 0.5 <= hi + 1e-3


def test_relaxation_to_level_two_accepts_every_design():
    """Relaxed to Level 2 (ζ ≥ 0, true for every x0 ≥ 0), the relaxed probability is 1 but for samples within the
    surrogate's round-off of ζ = 0 at the box's edge x0 = 0 (allowed: 1e-3)."""
    study = _study(max_level=2)
    surrogates, levels, _ = fit_predictors(study, cases(_frame(), study), offers=mode_offers())
    mc = run_monte_carlo(study, {**surrogates, **levels}, n=20_000, chunk=20_000, seed=5)
    (o,) = mc.constraints
    assert o.p == pytest.approx(0.5, abs=0.02) and o.p_relaxed >= 1.0 - 1e-3


def test_optimiser_holds_the_level_by_its_margin_and_names_it_active(fitted):
    """Least x0 at Level 1: the boundary x0 = ½ (ζ = 0.04) to 1e-4, found by SLSQP on the continuous level margin
    (an integer level gives it no gradient), and the level is named active there."""
    study, surrogates, levels, _ = fitted
    predictors = {**surrogates, **levels}
    mc = run_monte_carlo(study, predictors, n=20_000, chunk=20_000, seed=5)
    optima = optimise(study, predictors, mc)
    (best,) = [o for o in optima if o.stage == "constrained"]
    assert best.method == "SLSQP on the surrogates"
    assert best.x[0] == pytest.approx(0.5, abs=1e-4)
    assert "takeoff phugoid" in active_constraints(study, predictors, optima)


def test_the_surrogates_file_carries_the_derived_level(fitted, tmp_path):
    """`certkit study export --surrogates` stores the level as the quantities it comes from; the file predicts the
    same levels as the analysis (the rule's function of the same models)."""
    from certkit.study.analysis.surrogate_file import load_surrogates, surrogates_document, write_surrogates

    study, surrogates, levels, _ = fitted
    path = write_surrogates(tmp_path / "s.json", surrogates_document(study, surrogates, None, "", levels))
    model = load_surrogates(path)
    assert LEVEL in model.responses and model.document["responses"][LEVEL]["derived"]["from"] == {
        "zeta": ZETA,
        "wn": WN,
    }
    probe = np.random.default_rng(9).random((500, D))
    np.testing.assert_array_equal(model.predict(probe, [LEVEL])[LEVEL], levels[LEVEL].predict(probe))
    assert set(np.unique(model.predict(probe, [LEVEL])[LEVEL])) == {1.0, 2.0}


def _two_condition_frame(n_train: int = 150, n_val: int = 200) -> pd.DataFrame:
    """The phugoid at two conditions, ζ_a = 0.08·x0 (ω_n 0.10) and ζ_b = 0.08·x1 (ω_n 0.20): Level 1 where both
    reach 0.04, i.e. x0 ≥ ½ and x1 ≥ ½ (P = ¼). The record's level is the worse, its least level margins the least
    over the two conditions (as certkit.design.record gives them)."""
    rng = np.random.default_rng(5)
    x = rng.random((n_train + n_val, D))
    rows = [(0.08 * x[:, 0], 0.10), (0.08 * x[:, 1], 0.20)]
    frame = pd.DataFrame({f"var:v.x{i}": x[:, i] for i in range(D)})
    frame["resp:f"] = x[:, 0] + x[:, 1]
    frame["resp:" + LEVEL] = [
        max(_recorded_level(za, 0.10), _recorded_level(zb, 0.20)) for za, zb in zip(rows[0][0], rows[1][0])
    ]
    for lv in (1, 2, 3):
        m = [hq.damping_level_margin("phugoid", "takeoff", lv, zeta=z, wn=w) for z, w in rows]
        frame[f"resp:mode.phugoid.level{lv}_margin.c1.takeoff"] = np.clip(np.minimum(*m), -10, 10)
    frame["key"], frame["block"], frame["status"], frame["error"] = range(len(x)), "lhs", "ok", None
    frame["role"] = ["training"] * n_train + ["validation"] * n_val
    return frame


def test_a_level_set_by_different_conditions_is_derived_from_its_least_margins(tmp_path):
    """Where the least level margins are recorded they are preferred to the quantities: the level is the best L whose
    least margin is ≥ 0. P(Level 1) = ¼ (within 0.02: the margin's kink at x0 = x1 is a surrogate's hardest shape),
    the derived level agrees with the recorded one on ≥ 95 % of the held-out cases and reproduces it from the recorded
    margins, and the least x0 + x1 at Level 1 is 1 (to 0.05: the least margin's kink sits on that optimum, where a
    smooth surrogate rounds it off — 1.023 found); the surrogates file predicts the same levels."""
    study = _study()
    surrogates, levels, _ = fit_predictors(study, cases(_two_condition_frame(), study), offers=mode_offers())
    d = levels[LEVEL]
    assert d.source.kind == "margins" and set(d.source.sources) == {"1", "2", "3"}
    assert d.n_reproduced == d.n_recorded == 350
    assert d.n_agree >= 0.95 * d.n_validation
    predictors = {**surrogates, **levels}
    mc = run_monte_carlo(study, predictors, n=100_000, chunk=50_000, seed=5)
    assert mc.constraints[0].p == pytest.approx(0.25, abs=0.02)
    (best,) = [o for o in optimise(study, predictors, mc) if o.stage == "constrained"]
    assert best.value == pytest.approx(1.0, abs=0.05)
    # the surrogates file predicts the same levels from the margins
    from certkit.study.analysis.surrogate_file import load_surrogates, surrogates_document, write_surrogates

    path = write_surrogates(tmp_path / "s.json", surrogates_document(study, surrogates, None, "", levels))
    probe = np.random.default_rng(9).random((500, D))
    np.testing.assert_array_equal(load_surrogates(path).predict(probe, [LEVEL])[LEVEL], d.predict(probe))

"""Adaptive refinement near a known constraint boundary; the surrogates file, its Python API and
`certkit study predict`."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from certkit.cli.study_analysis import predict_command
from certkit.study import load_surrogates
from certkit.study.analysis.refine import refine, refinement_points
from certkit.study.analysis.surrogate_file import surrogates_document, write_surrogates
from certkit.study.analysis.surrogates import fit_response
from certkit.study.analysis.validity import fit_validity
from certkit.study.spec import Study

D = 2
LIMIT = 0.8


def _true(x):
    return np.sin(5.0 * x[:, 0]) + x[:, 1] ** 2


def _study() -> Study:
    return Study.model_validate(
        {
            "name": "boundary",
            "aircraft": "a.yaml",
            "designs": [{"name": "r", "generator": "random", "n": 1, "seed": 0}],
            "variables": [{"path": f"v.x{i}", "bounds": [0.0, 1.0], "baseline": 0.5} for i in range(D)],
            "constraints": [{"name": "y", "response": "y", "max": LIMIT}],
        }
    )


def _near_boundary_rmse(s, rng):
    x = rng.random((20_000, D))
    near = np.abs(_true(x) - LIMIT) < 0.05
    return float(np.sqrt(np.mean((s.predict(x[near]) - _true(x[near])) ** 2)))


def _fit(x):
    return fit_response(
        "y", np.array([[0.0, 1.0]] * D), x, _true(x), x[:0], np.empty(0), families=("Gaussian process",)
    )


def test_refinement_reduces_the_error_near_a_known_boundary():
    """y = sin 5x₀ + x₁² ≤ 0.8 on the unit square (a curved boundary in two branches). From 12 random cases, 12 cases
    chosen by
    refinement bring the surrogate's RMSE within 0.05 of the boundary down to less than half, and below that of
    12 more random cases."""
    study = _study()
    rng = np.random.default_rng(0)
    x0 = rng.random((12, D))
    s0 = _fit(x0)
    before = _near_boundary_rmse(s0, np.random.default_rng(9))
    added = refinement_points(study, {"y": s0}, x0, 12, seed=1)
    assert len(added) == 12
    refined = _near_boundary_rmse(_fit(np.vstack([x0, added])), np.random.default_rng(9))
    random = _near_boundary_rmse(_fit(np.vstack([x0, rng.random((12, D))])), np.random.default_rng(9))
    assert refined < 0.5 * before, (before, refined)
    assert refined < random, (random, refined)
    assert np.median(np.abs(_true(added) - LIMIT)) < 0.2  # the new cases sit near the boundary


class _Store:
    """A stand-in study store: the frame of its cases."""

    def __init__(self, frame):
        self._frame = frame

    def frame(self):
        return self._frame


def _frame(x, block, role):
    df = pd.DataFrame({f"var:v.x{i}": x[:, i] for i in range(D)})
    df["resp:y"] = _true(x)
    df.insert(0, "key", [f"{block}{i}" for i in range(len(x))])
    df.insert(1, "block", block)
    df.insert(2, "role", role)
    df.insert(3, "status", "ok")
    df.insert(4, "error", None)
    return df


def _trained_store() -> _Store:
    """30 training and 10 validation cases of the true function."""
    rng = np.random.default_rng(2)
    return _Store(
        pd.concat(
            [_frame(rng.random((30, D)), "lhs", "training"), _frame(rng.random((10, D)), "validation", "validation")],
            ignore_index=True,
        )
    )


def _runner(calls: list):
    """A stand-in study runner: evaluates the true function at the points into the store (rows as the study
    runner's), noting (block, role, number of points) in ``calls``."""

    def run_cases(study, store_, points, *, block, role):
        x = np.array([[p["v.x0"], p["v.x1"]] for p in points])
        calls.append((block, role, len(points)))
        store_._frame = pd.concat([store_._frame, _frame(x, block, role)], ignore_index=True)
        return [{"status": "ok", "key": f"{block}{i}"} for i in range(len(points))]

    return run_cases


def test_refine_runs_the_true_model_and_reports_the_probabilities():
    store, calls = _trained_store(), []
    run_cases = _runner(calls)
    result = refine(_study(), store, 8, samples=20_000, run_cases=run_cases)
    assert calls == [("refine-1", "training", 8)] and result.block == "refine-1" and result.ok == 8
    (m,) = result.movements
    # P(sin 5x₀ + x₁² ≤ 0.8) by quadrature on a fine grid: the refined estimate is nearer it or within its interval
    g = (np.arange(2000) + 0.5) / 2000
    exact = float(np.mean(np.sin(5 * g[:, None]) + g[None, :] ** 2 <= LIMIT))
    assert m.interval_after[0] - 0.01 <= exact <= m.interval_after[1] + 0.01 or abs(m.p_after - exact) < abs(
        m.p_before - exact
    )
    assert result.joint.p_after == m.p_after
    assert refine(_study(), store, 4, samples=10_000, run_cases=run_cases).block == "refine-2"


def test_surrogates_file_api_and_predict_command(tmp_path):
    """The file's models reproduce the fitted surrogates (scikit-learn's predictions), the classifier its
    possible-design mask; `certkit study predict` prints them as CSV."""
    rng = np.random.default_rng(4)
    study = _study()
    x = rng.random((120, D))
    y = _true(x)
    sur = {
        f"y_{fam[:3]}": fit_response(f"y_{fam[:3]}", study.bounds, x, y, x[:0], y[:0], families=(fam,))
        for fam in ("polynomial", "neural network", "Gaussian process")
    }
    frame = _frame(x, "lhs", "training")
    impossible = x[:, 0] + x[:, 1] > 1.5
    frame.loc[impossible, "status"] = "failed"
    frame.loc[impossible, "error"] = "infeasible design: tail tip behind the fuselage end"
    validity = fit_validity(frame, study)
    path = write_surrogates(tmp_path / "s.json", surrogates_document(study, sur, validity, "abc"))
    model = load_surrogates(path)
    assert model.variables == ["v.x0", "v.x1"] and set(model.responses) == set(sur)
    probe = rng.random((50, D))
    out = model.predict(probe)
    for name, s in sur.items():  # the noise-free GP interpolates: weights α large and of both signs, sums in
        # another order than scikit-learn's agree to ~10⁻⁸ of the response's range (2.6) instead of 10⁻¹⁵
        np.testing.assert_allclose(out[name], s.predict(probe), rtol=1e-9, atol=1e-6 if "Gau" in name else 1e-10)
    np.testing.assert_array_equal(model.possible(probe), validity.valid(probe))
    assert model.predict({"v.x0": 0.2})["y_pol"][0] == pytest.approx(sur["y_pol"].predict([[0.2, 0.5]])[0])
    result = CliRunner().invoke(predict_command, [str(path), "--set", "v.x0=0.2", "--set", "v.x1=0.3"])
    assert result.exit_code == 0, result.output
    header, row = result.output.strip().splitlines()
    values = dict(zip(header.split(","), row.split(",")))
    assert float(values["y_pol"]) == pytest.approx(float(sur["y_pol"].predict([[0.2, 0.3]])[0]), rel=1e-9)
    assert values["possible"] == "true"
    bad = CliRunner().invoke(predict_command, [str(path), "--set", "v.x9=1"])
    assert bad.exit_code != 0 and "not a variable of these surrogates: v.x9" in str(bad.exception or bad.output)


def test_refine_reads_a_baseline_bound_from_the_baseline_case_it_runs():
    """`y ≤ baseline`: the baseline design (0.5, 0.5) is evaluated once (block baseline) and its y,
    sin 2.5 + 0.25 = 0.848, bounds the constraint; the refinement then runs as for a fixed limit."""
    store, calls = _trained_store(), []
    run_cases = _runner(calls)
    relative = _study().model_copy(
        update={
            "constraints": [_study().constraints[0].model_validate({"name": "y", "response": "y", "max": "baseline"})]
        }
    )
    messages = []
    result = refine(relative, store, 4, samples=10_000, run_cases=run_cases, log=messages.append)
    assert calls == [("baseline", "check", 1), ("refine-1", "training", 4)] and result.ok == 4
    assert any(f"y ≤ {np.sin(2.5) + 0.25:g} (the baseline's)" in m for m in messages)

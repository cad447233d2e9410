"""Constraints bounded by the baseline's own value (``min: baseline`` / ``max: baseline``: "no worse than the
baseline"). The analysis reads each such bound from the case of the study's baseline design — every variable at its
``baseline`` — before it uses the constraint: a case of that design already in the store (any block), else one
evaluated through the study runner (block ``baseline``) and kept, so that a report made again reads it back."""

from __future__ import annotations

from collections.abc import Callable

import pandas as pd

from certkit.errors import UserError
from certkit.study.analysis.cases import RESP_PREFIX, VAR_PREFIX
from certkit.study.analysis.checks import RunCases, at_point, run_true_model
from certkit.study.spec import Study
from certkit.study.store import Store


def _held(frame: pd.DataFrame, study: Study) -> pd.Series | None:
    """An ok case of the baseline design in ``frame`` (variables equal to the baselines to 1e-9 relative)."""
    columns = [VAR_PREFIX + v.path for v in study.variables]
    if frame.empty or any(c not in frame.columns for c in columns):
        return None
    hits = at_point(frame[columns].to_numpy(dtype=float), study.baseline)
    ok = frame[hits & (frame["status"] == "ok").to_numpy()]
    return None if ok.empty else ok.iloc[0]


def with_baseline_bounds(
    study: Study,
    frame: pd.DataFrame,
    store: Store | None,
    *,
    run_cases: RunCases | None = None,
    log: Callable[[str], object] = lambda msg: None,
) -> Study:
    """``study`` with its ``baseline`` bounds read from the baseline design's case (module doc); ``store`` None:
    only a case already in ``frame`` is used (a report without the true model), and its absence is an error."""
    if not study.needs_baseline:
        return study
    row = _held(frame, study)
    if row is None:
        if store is None:
            names = ", ".join(c.name for c in study.constraints if c.needs_baseline)
            raise UserError(
                f"study {study.name}: the constraints {names} are bounded by the baseline's value, and the store holds "
                "no case of the baseline design: make the report with the true model once (without --no-check) to "
                "evaluate it"
            )
        row = run_true_model(study, store, study.baseline[None, :], block="baseline", role="check", run_cases=run_cases)
        row = row.iloc[0]
        if row.get("status") != "ok":
            raise UserError(
                f"study {study.name}: the baseline design's case failed ({row.get('error') or row.get('status')}); "
                "the constraints bounded by the baseline's value cannot be read"
            )
    values: dict[str, float | None] = {}
    for c in study.constraints:
        if c.needs_baseline:
            key = RESP_PREFIX + c.response
            v = row.get(key) if key in row.index else None
            values[c.response] = None if v is None or pd.isna(v) else float(v)
    resolved = study.with_baseline_bounds(values)
    log(
        "baseline bounds: "
        + "; ".join(
            f"{c.name} {c.describe()}" for c in resolved.constraints if c.min_from_baseline or c.max_from_baseline
        )
    )
    return resolved


__all__ = ["with_baseline_bounds"]

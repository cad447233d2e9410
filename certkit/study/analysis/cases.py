"""The cases of a study store as the analysis reads them: the store's frame (one row per case, ``var:<path>``
inputs in SI, ``resp:<name>`` responses, NaN where not computed) split by role and status.

The study itself is the validated :class:`certkit.study.spec.Study`; the analysis reads it directly.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np
import pandas as pd

from certkit.errors import UserError
from certkit.study.spec import Study

VAR_PREFIX = "var:"
RESP_PREFIX = "resp:"


def study_hash(study: Study) -> str:
    """SHA-256 of the study's canonical JSON (used when the study file's own hash is not given)."""
    return hashlib.sha256(study.model_dump_json().encode()).hexdigest()


@dataclass(frozen=True)
class Cases:
    """The store's cases split for the analysis: inputs X (n, n_variables, SI) per role, the responses, counts."""

    frame: pd.DataFrame
    x_columns: tuple[str, ...]

    def rows(self, role: str, status: str = "ok") -> pd.DataFrame:
        df = self.frame
        return df[(df["role"] == role) & (df["status"] == status)]

    def xy(self, role: str, response: str) -> tuple[np.ndarray, np.ndarray, int]:
        """Inputs and response values of the ``ok`` cases of ``role`` where the response was computed, and how
        many ``ok`` cases lacked it (NaN: not computed)."""
        rows = self.rows(role)
        column = RESP_PREFIX + response
        if column not in rows.columns:
            return np.empty((0, len(self.x_columns))), np.empty(0), len(rows)
        y = rows[column].to_numpy(dtype=float)
        keep = np.isfinite(y)
        return rows[list(self.x_columns)].to_numpy(dtype=float)[keep], y[keep], int((~keep).sum())

    def counts(self) -> pd.DataFrame:
        """Cases per block, role and status (the DoE summary)."""
        return self.frame.groupby(["block", "role", "status"]).size().rename("cases").reset_index()

    def failed(self) -> pd.DataFrame:
        df = self.frame[self.frame["status"] == "failed"]
        return df[["key", "block", "role", "error"] + list(self.x_columns)]


def cases(frame: pd.DataFrame, study: Study) -> Cases:
    """Check that the store's frame carries every study variable and the bookkeeping columns."""
    needed = ["key", "block", "role", "status", "error"] + [VAR_PREFIX + v.path for v in study.variables]
    missing = [c for c in needed if c not in frame.columns]
    if missing:
        raise UserError(
            f"study store: column(s) {', '.join(missing)} missing; the store does not match the study "
            f"definition (variables {', '.join(v.path for v in study.variables)})"
        )
    return Cases(frame, tuple(VAR_PREFIX + v.path for v in study.variables))

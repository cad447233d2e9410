"""Batch set-up for the loads manoeuvres: trimmed initial states of many conditions in one flight model.

Level flight at high speed may need more thrust than the engines give (VD is reached in a dive): such
conditions are re-trimmed on descending flight paths (``gammas``) and the path angle is recorded.
Conditions that still do not trim, or need a control beyond its design limit, are returned with the
trim's message as the reason; the others form one :class:`AircraftModel` batch ready to simulate.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from certkit.models.flight import flight_model


@dataclass
class TrimmedBatch:
    conditions: list  # the conditions that trimmed (refined with the flight-path angle)
    index: np.ndarray  # their positions in the input list
    model: object
    x: np.ndarray
    u: np.ndarray
    gamma: np.ndarray
    trims: list
    failed: list[tuple[int, str]] = field(default_factory=list)

    @property
    def n(self) -> int:
        return len(self.conditions)

    def control(self, name: str) -> np.ndarray:
        return self.u[:, self.model.control_names.index(name)]

    def distribute(self, conditions, entry_of, speeds):
        """Scheduled ``conditions`` each tied to one trimmed entry (``entry_of(c)`` → position in the entries this
        batch was trimmed from; ``speeds`` the entries' EAS): each refined with its entry's speed (and flight-path
        angle when descending). Returns the batch rows of those that trimmed (array), their refined conditions, and
        (refined condition, reason) of those whose entry did not trim, in the conditions' order."""
        failed = dict(self.failed)
        pos = {int(i): k for k, i in enumerate(self.index)}
        rows, refined_ok, refused = [], [], []
        for c in conditions:
            e = entry_of(c)
            refined = c.with_(speed=speeds[e], speed_kind="EAS")
            if e in failed:
                refused.append((refined, failed[e]))
                continue
            k = pos[e]
            if self.gamma[k]:
                refined = refined.with_(flight_path_deg=round(float(np.degrees(self.gamma[k])), 2))
            rows.append(k)
            refined_ok.append(refined)
        return np.array(rows, dtype=int), refined_ok, refused


def trimmed_batch(ctx, conditions, gammas=(0.0, -0.05, -0.10)) -> TrimmedBatch:
    """Trim ``conditions`` (one configuration) in level flight, then on the descending paths ``gammas``
    for those lacking thrust; one flight model for all that trimmed."""
    conds = list(conditions)
    n = len(conds)
    x = [None] * n
    u = [None] * n
    gamma = np.zeros(n)
    trims = [None] * n
    reason = {}
    todo = list(range(n))
    for g in gammas:
        if not todo:
            break
        batch = ctx.trim([conds[i] for i in todo], gamma=g)
        again = []
        for k, i in enumerate(todo):
            r = batch.results[k]
            if r.converged and not r.limits_exceeded:
                x[i], u[i], gamma[i], trims[i] = batch.x[k], batch.u[k], g, r
                reason.pop(i, None)
            else:
                msg = "; ".join(e.message for e in r.limits_exceeded) or "trim did not converge"
                reason[i] = f"no trim in unaccelerated flight: {msg}"
                if "throttle" in msg or "thrust" in msg or not r.converged:
                    again.append(i)
        todo = again
    ok = np.array([i for i in range(n) if x[i] is not None], dtype=int)
    failed = sorted(reason.items())
    if ok.size == 0:
        return TrimmedBatch([], ok, None, np.zeros((0, 12)), np.zeros((0, 0)), np.zeros(0), [], failed)
    cfg = conds[0].configuration
    loadings = [ctx.loading(conds[i].mass, conds[i].x_cg, conds[i].loading or "") for i in ok]
    model = flight_model(ctx.aircraft, ctx.aero(cfg).model, loadings)
    refined = [conds[i].with_(flight_path_deg=round(float(np.degrees(gamma[i])), 2)) if gamma[i] else conds[i] for i in ok]
    return TrimmedBatch(refined, ok, model, np.array([x[i] for i in ok]), np.array([u[i] for i in ok]), gamma[ok],
                        [trims[i] for i in ok], failed)

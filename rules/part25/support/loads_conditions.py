"""Batch set-up for the loads manoeuvres: trimmed initial states of many conditions in one flight model.

Engine layer: it turns scheduled conditions into trims through the Context and refusals into findings, for every
loads rule (the shared physics it calls stays in :mod:`certkit.models`).

Level flight at high speed may need more thrust than the engines give (VD is reached in a dive): such
conditions fly the path that full thrust holds (a shallow descent), those with too much thrust even at
idle (a light airplane at low speed) the idle-thrust climb, and the path angle is recorded; conditions
without any of these trims are tried on the fallback paths ``gammas``. Conditions that still do not trim, or need a
control beyond its design limit, are returned with the trim's message as the reason;
the others form one :class:`AircraftModel` batch ready to simulate. One policy for every loads rule
(:func:`refusal_findings`): a condition whose 1 g lift coefficient exceeds CLmax has no steady flight at
any thrust — not applicable, with that computed reason; any other refusal is not evaluated with the
trim's reason.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from certkit.atmosphere import density, speed_of_sound
from certkit.engine.conditions import speed_as
from certkit.engine.results import Finding
from certkit.models.flight import flight_model
from certkit.units import G0

#: flight-path angles (rad) tried in turn where neither level flight nor the full/idle-thrust path trims
FALLBACK_PATHS = (-0.05, -0.10, -0.15, 0.03, 0.06)
BELOW_STALL = (
    "no steady flight at this weight, altitude and speed: the 1 g lift coefficient W/(q̄S) = {cl:.3f} "
    "exceeds CLmax = {clmax:.3f} at M {mach:.3f} (below the 1 g stall speed, outside the flight envelope)"
)


@dataclass
class Refusal:
    """A scheduled condition that could not be set up as a steady flight, and why."""

    condition: object
    reason: str
    outside_envelope: bool  # below the 1 g stall speed at its weight and altitude: not applicable


def refusal_findings(refusals, checks) -> list[Finding]:
    """The findings of refused conditions: not applicable outside the envelope (computed reason), else not
    evaluated with the trim's reason; ``checks(condition)`` → the check names of that condition."""
    out = []
    for r in refusals:
        make = Finding.not_applicable if r.outside_envelope else Finding.not_evaluated
        out += [make(r.condition, name, r.reason) for name in checks(r.condition)]
    return out


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
    outside: frozenset = frozenset()  # input positions below the 1 g stall speed (no steady flight at any thrust)

    @property
    def n(self) -> int:
        return len(self.conditions)

    def control(self, name: str) -> np.ndarray:
        return self.u[:, self.model.control_names.index(name)]

    def refusals(self, conditions) -> list[Refusal]:
        """The input ``conditions`` (the list this batch was trimmed from) that did not trim."""
        return [Refusal(conditions[i], reason, i in self.outside) for i, reason in self.failed]

    def distribute(self, conditions, entry_of, speeds):
        """Scheduled ``conditions`` each tied to one trimmed entry (``entry_of(c)`` → position in the entries this
        batch was trimmed from; ``speeds`` the entries' EAS): each refined with its entry's speed (and flight-path
        angle when descending). Returns the batch rows of those that trimmed (array), their refined conditions, and
        the :class:`Refusal` of those whose entry did not trim, in the conditions' order."""
        failed = dict(self.failed)
        pos = {int(i): k for k, i in enumerate(self.index)}
        rows, refined_ok, refused = [], [], []
        for c in conditions:
            e = entry_of(c)
            refined = c.with_(speed=speeds[e], speed_kind="EAS")
            if e in failed:
                refused.append(Refusal(refined, failed[e], e in self.outside))
                continue
            k = pos[e]
            if self.gamma[k]:
                refined = refined.with_(flight_path_deg=round(float(np.degrees(self.gamma[k])), 2))
            rows.append(k)
            refined_ok.append(refined)
        return np.array(rows, dtype=int), refined_ok, refused


def trimmed_batch(ctx, conditions, gammas=FALLBACK_PATHS) -> TrimmedBatch:
    """Trim ``conditions`` (one configuration) in level flight; those short of thrust (or with too much at idle)
    on the flight path that full (idle) thrust holds, the steady flight nearest to level; those still without a
    trim on the paths ``gammas`` in turn. One flight model for all that trimmed."""
    conds = list(conditions)
    n = len(conds)
    x = [None] * n
    u = [None] * n
    gamma = np.zeros(n)
    trims = [None] * n
    reason = {}

    def attempt(todo, **kw):
        """Trim ``todo`` with ``kw``; keep the successes; return the failures with their messages."""
        if not todo:
            return []
        batch = ctx.trim([conds[i] for i in todo], **kw)
        failures = []
        for k, i in enumerate(todo):
            r = batch.results[k]
            if r.converged and not r.limits_exceeded:
                x[i], u[i], gamma[i], trims[i] = batch.x[k], batch.u[k], r.gamma, r
                reason.pop(i, None)
            else:
                msg = "; ".join(e.message for e in r.limits_exceeded) or "trim did not converge"
                reason[i] = f"no trim in unaccelerated flight: {msg}"
                failures.append((i, msg))
        return failures

    failures = attempt(list(range(n)), gamma=0.0)
    short = [i for i, msg in failures if "more than full throttle" in msg]
    excess = [i for i, msg in failures if "less than idle throttle" in msg]
    failures = [f for f in failures if f[0] not in short and f[0] not in excess]
    failures += attempt(short, throttle=1.0) + attempt(excess, throttle=0.0)
    todo = [i for i, _ in failures]
    for g in gammas:
        todo = [i for i, _ in attempt(todo, gamma=g)]
    stalled = {i: below_stall(ctx, conds[i]) for i in reason}
    outside = frozenset(i for i, why in stalled.items() if why)
    reason.update({i: stalled[i] for i in outside})
    ok = np.array([i for i in range(n) if x[i] is not None], dtype=int)
    failed = sorted(reason.items())
    if ok.size == 0:
        return TrimmedBatch([], ok, None, np.zeros((0, 12)), np.zeros((0, 0)), np.zeros(0), [], failed, outside)
    cfg = conds[0].configuration
    loadings = [ctx.loading(conds[i].mass, conds[i].x_cg, conds[i].loading or "") for i in ok]
    model = flight_model(ctx.aircraft, ctx.aero(cfg).model, loadings)
    refined = [
        conds[i].with_(flight_path_deg=round(float(np.degrees(gamma[i])), 2)) if abs(gamma[i]) > 1e-9 else conds[i]
        for i in ok
    ]
    return TrimmedBatch(
        refined,
        ok,
        model,
        np.array([x[i] for i in ok]),
        np.array([u[i] for i in ok]),
        gamma[ok],
        [trims[i] for i in ok],
        failed,
        outside,
    )


def below_stall(ctx, cond) -> str | None:
    """The computed reason when the 1 g lift coefficient W/(q̄S) at the condition's speed exceeds the
    configuration's CLmax at its Mach (no steady flight at any thrust: the speed is below the 1 g stall speed at
    this weight and altitude), else None (also without a stall model)."""
    clmax = getattr(ctx.aero(cond.configuration).model, "clmax", None)
    tas, h = speed_as(cond, "TAS"), cond.altitude or 0.0
    mach = tas / float(speed_of_sound(h))
    value = clmax(np.array([mach])) if callable(clmax) else None
    if value is None:
        return None
    cl = cond.mass * G0 / (0.5 * float(density(h)) * tas**2 * ctx.aircraft.reference.area)
    if cl <= float(value[0]):
        return None
    return BELOW_STALL.format(cl=cl, clmax=float(value[0]), mach=mach)

"""Optima confirmed by the true model: a surrogate optimum the true model finds outside a constraint of its stage is
searched again on surrogates corrected by what the true model said, until a design the true model accepts is found.

Each step makes the surrogates agree with the true model at the current design x_k — in value and, by default, in
slope: every objective and constraint response and every mode quantity a derived level is predicted from becomes ŷ(x)
+ [y(x_k) − ŷ(x_k)] + [∇y(x_k) − ∇ŷ(x_k)]·(x − x_k), the true model's gradient by forward differences (n designs at
x_k + h eᵢ, h = :data:`PROBE_STEP` on the [−1, 1] scale) — then solves the stage's problem on the corrected
surrogates within a trust region around x_k (the optimum of the objective, or where none is feasible the design of
least violation), and evaluates that design with the true model. Until the true model accepts a design, a step that
lowers the true violation (Σ min(g, 0)² of the scaled constraints, as in
:func:`~certkit.study.analysis.optimise.least_violation`) moves x_k; after, a step moves it when the true model
accepts the new design and finds its objective better. A step that does not move x_k shrinks the region to half the
step, and while x_k is outside a constraint the next step is a restoration: the nearest design the corrected
surrogates find feasible, aimed as far inside (in scaled violation) as x_k is outside — the least move, where the
correction is most nearly exact (the feasibility restoration of filter SQP, Fletcher & Leyffer 2002); an objective
step that runs along a linearised boundary into a curved or kinked one is what the true model rejects. The search
ends when the corrected problem's answer is x_k itself (within :data:`STILL` on the [−1, 1] scale) or after
:data:`MAX_STEPS` steps. This is the first-order model management of Alexandrov, Dennis, Lewis & Torczon (1998,
*Structural Optimization* 15: 16–23; corrections of order zero and one, Forrester & Keane 2009, *Progress in
Aerospace Sciences* 45: 50–79, §6): on smooth responses it converges on the true problem's optimum; a least margin
over several conditions has kinks where no correction is exact, and the true model's own numerical noise limits the
finite differences, so the confirmed design is the best the true model accepted, not a proven optimum. The confirmed
optimum is that design with the true model's values; where the true model accepted none, the design of least true
violation and the constraints it still violates. A surrogate optimum the true model already accepts is confirmed as
it is. ``gradients=False`` keeps the correction of order zero (values only: n times fewer evaluations, feasibility
without the optimality conditions).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from certkit.study.analysis.cases import RESP_PREFIX
from certkit.study.analysis.checks import CheckedOptimum, RunCases, run_true_model
from certkit.study.analysis.derived_levels import MARGIN_CLIP, DerivedLevel
from certkit.study.analysis.montecarlo import Optimum
from certkit.study.analysis.optimise import (
    LEAST_VIOLATION,
    SurrogateProblem,
    ValidMargin,
    constraint_scales,
    from_unit,
    least_violation,
    local_optimum,
    nearest_feasible,
)
from certkit.study.analysis.surrogates import Surrogate, to_unit
from certkit.study.spec import Study
from certkit.study.store import Store

#: steps per optimum after the surrogate optimum's own (numerical choice: each costs one design, and n more for the
#: gradient at each design the search moves to)
MAX_STEPS = 6
#: a search ends when the corrected problem's answer lies this close to the current design (on the [−1, 1] scale)
STILL = 1e-3
#: the forward-difference step of the true model's gradient, on the [−1, 1] scale (2.5 % of each variable's range:
#: above the numerical noise of a sized, simulated design, within the trust region; numerical choice)
PROBE_STEP = 0.05
#: the trust region's first half-width on the [−1, 1] scale of every variable (a tenth of its range; numerical choice)
TRUST_RADIUS = 0.2
#: the stages whose optima are confirmed (the unconstrained one has no constraint to confirm)
STAGES = ("constrained", "preferred")
#: statuses
CONFIRMED = "confirmed"
NOT_CONFIRMED = "not confirmed"


@dataclass
class Step:
    """One design evaluated with the true model: its variables (SI), the analysed responses, the constraints of the
    stage it violates and its total scaled violation."""

    x: np.ndarray
    true: dict[str, float | None]
    violated: list[str]
    violation: float
    accepted: bool = True


@dataclass
class Confirmation:
    """The confirmation of one surrogate optimum: the steps (the optimum itself first) and the outcome."""

    optimum: Optimum
    status: str
    reason: str = ""
    steps: list[Step] = field(default_factory=list)
    sense: str = "min"
    #: designs evaluated for the true model's gradient (n at each design the search stood on)
    probes: int = 0

    @property
    def design(self) -> Step | None:
        """The best design the true model accepted (by its objective), or the evaluated design of least true
        violation."""
        sign = -1.0 if self.sense == "max" else 1.0
        good = [s for s in self.steps if not s.violated and s.true.get(self.optimum.objective) is not None]
        if good:
            return min(good, key=lambda s: sign * float(s.true[self.optimum.objective]))  # type: ignore[arg-type]
        return min(self.steps, key=lambda s: s.violation) if self.steps else None

    @property
    def evaluations(self) -> int:
        """The designs of its steps (one evaluation of the true model each, unless another optimum's search
        proposed the same design)."""
        return len(self.steps)


@dataclass
class _Corrected:
    """A surrogate corrected to the true model at u₀: ŷ(x) + shift + slope·(u(x) − u₀), u the inputs on the [−1, 1]
    scale (what the analysis reads of a surrogate, and nothing else)."""

    base: Any
    shift: float
    slope: np.ndarray
    u0: np.ndarray
    bounds: np.ndarray

    def predict(self, x: np.ndarray) -> np.ndarray:
        x = np.atleast_2d(x)
        linear = (to_unit(x, self.bounds) - self.u0) @ self.slope
        return np.asarray(self.base.predict(x), dtype=float) + self.shift + linear

    @property
    def response(self) -> str:
        return str(self.base.response)

    @property
    def plot_data(self) -> dict[str, Any]:
        return dict(self.base.plot_data)


def _true_value(row: pd.Series, response: str) -> float | None:
    key = RESP_PREFIX + response
    if key not in row.index:
        return None
    try:
        v = float(row[key])
    except (TypeError, ValueError):
        return None
    return v if np.isfinite(v) else None


def _corrected(
    surrogates: dict[str, Any],
    names: set[str],
    x: np.ndarray,
    row: pd.Series,
    probes: Probes | None,
    bounds: np.ndarray,
) -> dict[str, Any]:
    """The surrogates ``names`` made equal to the true model's values at ``x`` (a derived level through its
    quantities) and, with ``probes`` (the true model at x + h eᵢ), to its forward-difference gradient; a response the
    true model did not give keeps its surrogate, a gradient component it did not give keeps the surrogate's."""
    u0 = to_unit(x[None, :], bounds)[0]

    def correct(s: Any) -> Any:
        t = _true_value(row, s.response)
        if t is None:
            return s
        shift = t - float(s.predict(x[None, :])[0])
        slope = np.zeros(len(u0))
        if probes is not None:
            surrogate = np.asarray(s.predict(probes.x), dtype=float)
            for i, (prow, h) in enumerate(zip(probes.rows, probes.h)):
                tp = _true_value(prow, s.response)
                if tp is not None and np.isfinite(surrogate[i]):
                    slope[i] = ((tp - surrogate[i]) - shift) / h
        return _Corrected(s, shift, slope, u0, bounds)

    out = dict(surrogates)
    for name in names:
        s = surrogates[name]
        if isinstance(s, DerivedLevel):
            out[name] = dataclasses.replace(s, quantities={kw: correct(q) for kw, q in s.quantities.items()})
        else:
            out[name] = correct(s)
    return out


@dataclass
class Probes:
    """The true model at the forward-difference points x + hᵢ eᵢ of a design (h on the [−1, 1] scale; backward
    where the forward point would leave the box)."""

    x: np.ndarray
    h: np.ndarray
    rows: list[pd.Series]


@dataclass
class _Search:
    """One optimum's search: the design it stands on (its true-model row, its probes once taken) and the trust
    region's radius on the [−1, 1] scale."""

    conf: Confirmation
    problem: SurrogateProblem
    x: np.ndarray
    row: pd.Series
    radius: float = TRUST_RADIUS
    probes: Probes | None = None
    #: the design it stands on is outside a constraint of the stage (the true model's judgement)
    outside: bool = True
    #: a step from that design was rejected: the next one restores feasibility by the least move
    restore: bool = False


def _probe_points(x: np.ndarray, bounds: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    u = to_unit(x[None, :], bounds)[0]
    h = np.where(u + step <= 1.0, step, -step)
    points = np.repeat(u[None, :], len(u), axis=0) + np.diag(h)
    return from_unit(points, bounds), h


def _limit_values(problem: SurrogateProblem, surrogates: dict[str, Any], row: pd.Series) -> np.ndarray:
    """The scaled constraint values g of the problem's limits (≥ 0 within) at the true model's ``row``, a derived level
    by its least level margin where the record holds it; −:data:`MARGIN_CLIP` for a value the record does not give."""
    out = []
    for response, threshold, sign, scale, level in problem.limits:
        s = surrogates[response]
        if level is not None and isinstance(s, DerivedLevel) and s.source.kind == "margins" and level < 4:
            margin = _true_value(row, s.quantities[str(level)].response)
            g = None if margin is None else float(np.clip(margin, -MARGIN_CLIP, MARGIN_CLIP))
        else:
            t = _true_value(row, response)
            g = None if t is None else sign * (t - threshold) / scale
        out.append(-MARGIN_CLIP if g is None else g)
    return np.array(out, dtype=float)


def _judge(problem: SurrogateProblem, surrogates: dict[str, Any], row: pd.Series) -> tuple[list[str], float]:
    """The constraints of the problem's stage the true model's ``row`` violates (by name; a response it did not
    give counts as violated) and the total scaled violation Σ min(g, 0)² over :func:`_limit_values`."""
    study = problem.study
    violated = []
    for c in study.constraints:
        t = _true_value(row, c.response)
        if t is None or not study.holds(c, np.array([t]), problem.stage)[0]:
            violated.append(c.name)
    return violated, float(np.sum(np.minimum(_limit_values(problem, surrogates, row), 0.0) ** 2))


def _step(problem: SurrogateProblem, surrogates: dict[str, Any], x: np.ndarray, row: pd.Series) -> Step:
    names = problem.study.analysed_responses()
    violated, total = _judge(problem, surrogates, row)
    return Step(np.asarray(x, dtype=float), {r: _true_value(row, r) for r in names}, violated, total)


def _next_design(
    study: Study,
    surrogates: dict[str, Any],
    optimum: Optimum,
    sense: str,
    search: _Search,
    valid_margin: ValidMargin | None,
) -> np.ndarray | None:
    """The next design within the trust region around the search's design, on the corrected surrogates: the stage's
    optimum, or — when that design is outside a constraint and a step from it was rejected — the nearest design they
    find feasible (the restoration step); where they find none feasible, the design of least violation; None when
    the search ends at no possible design."""
    x, row, radius = search.x, search.row, search.radius
    names = {c.response for c in study.constraints} | {optimum.objective}
    corrected = _corrected(surrogates, names & set(surrogates), x, row, search.probes, study.bounds)
    problem = SurrogateProblem(study, corrected, optimum.stage, valid_margin, constraint_scales(study, surrogates))
    u = to_unit(x[None, :], study.bounds)[0]
    box = (np.maximum(u - radius, -1.0), np.minimum(u + radius, 1.0))
    if search.outside and search.restore:
        # each violated limit aimed as far inside as the design is outside it: the correction's own error at the
        # design it proposes is of the order of the violation it corrects (a convex constraint would leave a
        # boundary point just outside); the limits the design meets are held at their boundary
        shortfall = np.maximum(-_limit_values(search.problem, surrogates, row), 0.0)
        nearest = nearest_feasible(problem, x, box=box, inside=shortfall)
        if nearest is not None:
            return nearest
    else:
        best = local_optimum(problem, optimum.objective, sense, x[None, :], box=box)
        if best is not None:
            return np.asarray(best.x)
    return least_violation(problem, x[None, :], box=box)


def _probe(study: Study, store: Store, states: list[_Search], run_cases: RunCases | None) -> None:
    """The true model at the forward-difference points of each state's design (one batch for all; a design two
    states share is probed once), kept in the states as :class:`Probes`."""
    if not states:
        return
    points = [_probe_points(s.x, study.bounds, PROBE_STEP) for s in states]
    stacked = np.vstack([p for p, _ in points])
    unique, which = np.unique(stacked, axis=0, return_inverse=True)
    frame = run_true_model(study, store, unique, block="confirm-gradient", role="check", run_cases=run_cases)
    rows = [frame.iloc[int(i)] for i in np.ravel(which)]
    n = len(study.variables)
    for k, (s, (x, h)) in enumerate(zip(states, points)):
        s.probes = Probes(x, h, rows[k * n : (k + 1) * n])
        s.conf.probes += n


def _better(conf: Confirmation, step: Step) -> bool:
    """Whether ``step`` improves on the confirmation's best design: less violation while none is accepted, else
    accepted by the true model with a better objective."""
    best = conf.design
    if best is None:
        return True
    if best.violated:
        return not step.violated or step.violation < best.violation
    if step.violated:
        return False
    sign = -1.0 if conf.sense == "max" else 1.0
    new, old = step.true.get(conf.optimum.objective), best.true.get(conf.optimum.objective)
    return new is not None and old is not None and sign * new < sign * old


def confirm_optima(
    study: Study,
    store: Store,
    surrogates: dict[str, Surrogate],
    checked: list[CheckedOptimum],
    valid_margin: ValidMargin | None = None,
    *,
    run_cases: RunCases | None = None,
    max_steps: int = MAX_STEPS,
    gradients: bool = True,
) -> list[Confirmation]:
    """Confirm each constrained and preferred optimum of ``checked`` (re-evaluated with the true model) as the module
    says; the designs of each step run through the study runner together (block "confirm"), so the store keeps
    them and a later report reads them back. The optima of least violation (no design meets the stage on the
    surrogates) are not searched again: their violations are the stage's conflicts. ``gradients``: the correction
    of order one (the true model probed at n forward-difference points of each design a search stands on, block
    ``confirm-gradient``); False: of order zero."""
    senses = {o.response: o.sense for o in study.objectives}
    out: list[Confirmation] = []
    state: list[_Search] = []
    chosen = []
    for c in checked:
        o = c.optimum
        if o.stage not in STAGES or o.method == LEAST_VIOLATION or o.objective not in surrogates:
            continue
        if c.status != "ok":
            out.append(Confirmation(o, NOT_CONFIRMED, f"the true model did not evaluate the optimum: {c.error}"))
        else:
            chosen.append(o)
    if chosen:  # the optima's own cases, already in the store (block "optima"): read back, not evaluated again
        rows = run_true_model(
            study, store, np.array([o.x for o in chosen]), block="optima", role="check", run_cases=run_cases
        )
        for o, (_, row) in zip(chosen, rows.iterrows()):
            problem = SurrogateProblem(study, surrogates, o.stage, valid_margin, constraint_scales(study, surrogates))
            sense = senses.get(o.objective, "min")
            conf = Confirmation(o, CONFIRMED, steps=[_step(problem, surrogates, o.x, row)], sense=sense)
            out.append(conf)
            if conf.steps[0].violated:  # an optimum the true model accepts is confirmed as it is
                state.append(_Search(conf, problem, o.x, row))
    for _ in range(max_steps):
        if gradients:
            _probe(study, store, [s for s in state if s.probes is None], run_cases)
        moves = []
        for s in state:
            nxt = _next_design(study, surrogates, s.conf.optimum, s.conf.sense, s, valid_margin)
            u = to_unit(np.array([s.x, nxt if nxt is not None else s.x]), study.bounds)
            if nxt is not None and float(np.max(np.abs(u[1] - u[0]))) > STILL:
                moves.append((s, nxt))
        if not moves:
            break
        state = [s for s, _ in moves]
        # optima whose searches propose one design (a stage met by one sample, say) share its evaluation
        unique, which = np.unique(np.array([x for _, x in moves]), axis=0, return_inverse=True)
        frame = run_true_model(study, store, unique, block="confirm", role="check", run_cases=run_cases)
        rows = [frame.iloc[int(i)] for i in np.ravel(which)]
        for (s, x), row in zip(moves, rows):
            step = _step(s.problem, surrogates, x, row)
            step.accepted = row.get("status") == "ok" and _better(s.conf, step)
            s.conf.steps.append(step)
            if step.accepted:
                s.x, s.row, s.probes, s.outside, s.restore = x, row, None, bool(step.violated), False
            else:  # the region shrinks to half the rejected step (on the [−1, 1] scale)
                u = to_unit(np.array([s.x, x]), study.bounds)
                s.radius = 0.5 * float(np.max(np.abs(u[1] - u[0])))
                s.restore = True
    for conf in out:
        if conf.steps and conf.design is not None and conf.design.violated:
            conf.status = NOT_CONFIRMED
            conf.reason = (
                f"after {conf.evaluations} true-model evaluations the design of least violation still violates "
                + ", ".join(conf.design.violated)
            )
    return out


__all__ = ["CONFIRMED", "NOT_CONFIRMED", "Confirmation", "Step", "confirm_optima"]

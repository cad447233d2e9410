"""What limits the design: show-stoppers (constraints no possible design satisfies) with their reasons, and the
constraints active at the constrained optima, or — where no design meets every constraint — those that conflict.

A constraint is a show-stopper when no possible Monte Carlo sample satisfies it on its surrogate (P = 0, the level
relaxation included), or when no computed case satisfies it and its samples that do are fewer than one in the number
of computed cases (a region the cases could not have found and none confirms); the reason gives the least violation
over the samples and the best value, and how many of the study's computed cases satisfy it (the true model's word).
A constraint whose response has no surrogate (never computed, too few cases) is listed too, with the reason it could
not be judged. A constraint is active at an optimum when the optimum's predicted response lies within the
surrogate's cross-validated RMSE of a limit (or 10⁻⁶ of its magnitude), a derived handling-quality level when its
level margin is within 10⁻³ of zero: the optimum sits on that boundary.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from certkit.study.analysis.cases import Cases
from certkit.study.analysis.montecarlo import ConstraintOutcome, MonteCarloResult, Optimum, violation
from certkit.study.analysis.optimise import LEAST_VIOLATION
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.spec import Constraint, Study


@dataclass
class ShowStopper:
    name: str
    requirement: str
    reason: str


#: a derived level is active where its level margin (a relative distance to the level's nearest boundary) is
#: within this of zero
LEVEL_ACTIVE = 1e-3


def _limits(study: Study, c: Constraint) -> list[float]:
    upper = study.allowed_max(c)
    half = 0.5 if c.is_level else 0.0
    return [
        t for t in (None if c.min is None else c.min - half, None if upper is None else upper + half) if t is not None
    ]


def _successes(o: ConstraintOutcome) -> int:
    return o.relaxed_successes if o.relaxed_successes is not None else o.successes


def _computed_successes(study: Study, c: Constraint, cases: Cases) -> tuple[int, np.ndarray]:
    values = np.concatenate([cases.xy(role, c.response)[1] for role in ("training", "validation")])
    return int(np.sum(study.holds(c, values))), values


def unconfirmed(study: Study, o: ConstraintOutcome, cases: Cases | None) -> bool:
    """The surrogate has samples meeting the constraint, but no computed case does and they are fewer than one in
    the number of computed cases (P < 1/N): a region so small that the study's own cases could not have found it,
    which no case confirms — not evidence that a design meets it."""
    if cases is None or not _successes(o):
        return False
    ok, values = _computed_successes(study, o.constraint, cases)
    return ok == 0 and len(values) > 0 and _successes(o) / o.n < 1.0 / len(values)


def unattainable(mc: MonteCarloResult, study: Study | None = None, cases: Cases | None = None) -> list[str]:
    """Names of the constraints no possible sample satisfies (P = 0, the level relaxation included) and, given the
    study and its cases, those whose successes on the surrogate no computed case confirms (:func:`unconfirmed`)."""
    return [
        o.constraint.name
        for o in mc.constraints
        if not _successes(o) or (study is not None and unconfirmed(study, o, cases))
    ]


def without_unattainable(
    study: Study,
    surrogates: dict[str, Surrogate],
    mc: MonteCarloResult,
    run: Callable[[Study], MonteCarloResult],
    cases: Cases | None = None,
) -> tuple[Study, MonteCarloResult]:
    """(study without the show-stoppers, Monte Carlo result of its stages): with a constraint no design meets,
    every design fails the joint requirement, so the stages, fronts and optima are those of the other
    constraints (the show-stoppers are reported apart). ``run(study)`` repeats the Monte Carlo (same samples);
    the per-constraint outcomes of the full run are kept. With ``cases``, a constraint whose successes no computed
    case confirms (:func:`unconfirmed`) is set apart too."""
    names = unattainable(mc, study, cases)
    if not names or len(names) == len(mc.constraints):
        return study, mc
    rest = study.model_copy(update={"constraints": [c for c in study.constraints if c.name not in names]})
    stages = run(rest)
    stages.constraints = mc.constraints
    return rest, stages


def show_stoppers(study: Study, mc: MonteCarloResult, cases: Cases, not_fitted: dict[str, str]) -> list[ShowStopper]:
    out = []
    for o in mc.constraints:
        c = o.constraint
        successes = _successes(o)
        if successes and not unconfirmed(study, o, cases):
            continue
        relaxed = study.analysis.relaxed_max(c)
        ok, values = _computed_successes(study, c, cases)
        best = values[np.nanargmin(violation(c, values, relaxed))] if len(values) else None
        surrogate = (
            f"only {successes} of the {mc.n} possible samples ({successes / mc.n:.3%}) satisfy it on the surrogate, "
            f"fewer than one in the {len(values)} computed cases, and none of those does: unconfirmed"
            if successes
            else f"no possible design of the {mc.n} samples satisfies it on the surrogate (least violation "
            f"{o.least_violation:.4g}, at the value {o.best_value:.4g})"
        )
        reason = f"{surrogate}; {ok} of the {len(values)} computed cases satisfy it" + (
            f" (the best case: {best:.4g})" if best is not None else ""
        )
        out.append(ShowStopper(c.name, c.describe(), reason))
    for c in study.constraints:
        if c.response in not_fitted:
            out.append(ShowStopper(c.name, c.describe(), f"not judged: no surrogate ({not_fitted[c.response]})"))
    return out


def active_constraints(study: Study, surrogates: dict[str, Surrogate], optima: list[Optimum]) -> dict[str, list[str]]:
    """Constraint name → the objectives whose constrained (or preferred) optimum lies on its boundary."""
    out: dict[str, list[str]] = {}
    for opt in optima:
        if opt.stage == "unconstrained" or opt.method == LEAST_VIOLATION:
            continue
        for c in study.constraints:
            s = surrogates.get(c.response)
            if s is None or getattr(s, "constant", False):  # a response no design moves binds no optimum
                continue
            if hasattr(s, "level_margin"):
                allowed = study.allowed_max(c, opt.stage)
                on_boundary = (
                    allowed is not None and abs(float(s.level_margin(opt.x[None, :], int(allowed))[0])) <= LEVEL_ACTIVE
                )
            else:
                y = float(s.predict(opt.x[None, :])[0])
                tol = max(s.cv.rmse or 0.0, 1e-6 * max(1.0, abs(y)))
                on_boundary = any(abs(y - t) <= tol for t in _limits(study, c))
            if on_boundary:
                label = f"{opt.objective} ({opt.stage})"
                out.setdefault(c.name, [])
                if label not in out[c.name]:
                    out[c.name].append(label)
    return out


def conflicting_constraints(
    study: Study, surrogates: dict[str, Surrogate], optima: list[Optimum]
) -> dict[str, list[str]]:
    """Constraint name → the stages whose design of least violation (an optimum of method
    :data:`~.optimise.LEAST_VIOLATION`) it fails, with its predicted value there: where no design meets every
    constraint, the ones that cannot be met together."""
    out: dict[str, list[str]] = {}
    seen = set()
    for opt in optima:
        if opt.method != LEAST_VIOLATION or opt.stage in seen:
            continue
        seen.add(opt.stage)
        for c in study.constraints:
            s = surrogates.get(c.response)
            if s is None:
                continue
            y = s.predict(opt.x[None, :])
            if not study.holds(c, y, opt.stage)[0]:
                out.setdefault(c.name, []).append(f"{opt.stage} ({float(y[0]):.4g})")
    return out

"""Constrained optimisation on the surrogates: local optima of each objective and Pareto fronts.

Single objectives: SLSQP (Kraft 1988, scipy ``minimize``) on the inputs mapped to [−1, 1] (forward-difference
gradients, the
n + 1 points of a gradient predicted in one batch), multi-started from
the best feasible Monte Carlo samples of the stage and from spread random points; the best solution the
surrogates find feasible is kept (the best sample itself when no start improves on it). Fronts: NSGA-II (Deb
et al. 2002, *IEEE Trans. Evol. Comput.* 6(2): 182–197; pymoo) with the constraints as inequalities.

Every constraint becomes g(x) ≥ 0, scaled by the spread of its response over the samples: ``min ≤ y`` →
(y − min)/s, ``y ≤ max`` → (max − y)/s; a handling-quality level derived from the mode quantities
(:mod:`.derived_levels`) is held by its continuous level margin, a regressed level L counts up to L + ½ (as in the
Monte Carlo), each with the stage's relaxation. Impossible designs are kept out by the validity classifier's margin
(≥ 0).
A design the optimiser returns is re-checked with ``Constraint.feasible`` on the surrogates before it is kept.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import Any, cast

import numpy as np
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.core.problem import Problem
from pymoo.optimize import minimize as pymoo_minimize
from scipy.optimize import minimize

from certkit.study.analysis.montecarlo import STAGES, MonteCarloResult, Optimum
from certkit.study.analysis.surrogates import Surrogate, to_unit
from certkit.study.spec import Study

#: starts per objective and stage (the best samples of the stage first, then random points)
STARTS = 4
#: forward-difference step of the gradients, on the [−1, 1] scale (every surrogate evaluated once per batch)
FD_STEP = 1e-6
#: SLSQP keeps each scaled constraint this far inside its limit: an optimum on an active constraint lands within
#: round-off of it, on either side (scipy's SLSQP since 1.16 returns such points a few 1e-12 outside), and the
#: feasibility check that follows is exact (numerical choice: 1e-9 of the constraint's spread)
CONSTRAINT_MARGIN = 1e-9
NSGA_POPULATION = 80
NSGA_GENERATIONS = 120


#: the validity classifier's margin of designs (rows, SI): ≥ 0 where the design is possible
ValidMargin = Callable[[np.ndarray], np.ndarray]
#: lower and upper bounds of a search on the [−1, 1] scale (a trust region)
Box = tuple[np.ndarray, np.ndarray]


def from_unit(u: np.ndarray, bounds: np.ndarray) -> np.ndarray:
    lo, hi = bounds[:, 0], bounds[:, 1]
    return np.asarray(lo + (np.asarray(u, dtype=float) + 1.0) * 0.5 * (hi - lo))


class SurrogateProblem:
    """Objectives and constraints of a study stage on the surrogates, on inputs u ∈ [−1, 1]ⁿ."""

    def __init__(
        self,
        study: Study,
        surrogates: dict[str, Surrogate],
        stage: str,
        valid_margin: ValidMargin | None = None,
        scales: dict[str, float] | None = None,
    ) -> None:
        self.study, self.surrogates, self.stage = study, surrogates, stage
        self.bounds = study.bounds
        self.valid_margin = valid_margin
        # (response, threshold, sign, scale, level: the worst level allowed, derived levels only)
        self.limits: list[tuple[str, float, float, float, int | None]] = []
        if stage != "unconstrained":
            for c in study.constraints:
                lower, upper = c.min, c.max
                level = None
                if c.is_level:
                    upper = study.allowed_max(c, stage)
                    if upper is not None and hasattr(surrogates[c.response], "level_margin"):
                        level = int(upper)
                    upper = None if upper is None else upper + 0.5
                    lower = None if lower is None else lower - 0.5
                scale = (scales or {}).get(c.response, 1.0) or 1.0
                if lower is not None:
                    self.limits.append((c.response, lower, 1.0, scale, None))
                if upper is not None:
                    self.limits.append((c.response, upper, -1.0, scale, level))

    def x(self, u: np.ndarray) -> np.ndarray:
        return from_unit(u, self.bounds)

    def objective(self, name: str, u: np.ndarray, sense: str = "min") -> np.ndarray:
        y = self.surrogates[name].predict(self.x(np.atleast_2d(u)))
        return -y if sense == "max" else y

    def constraints(self, u: np.ndarray) -> np.ndarray:
        """(n, m) values g ≥ 0 where feasible (constraint limits, then the validity margin)."""
        x = self.x(np.atleast_2d(u))
        cols = [
            cast(Any, self.surrogates[r]).level_margin(x, level)  # a DerivedLevel
            if level is not None
            else sign * (self.surrogates[r].predict(x) - t) / s
            for r, t, sign, s, level in self.limits
        ]
        if self.valid_margin is not None:
            cols.append(self.valid_margin(x))
        return np.column_stack(cols) if cols else np.empty((len(x), 0))

    def feasible(self, x: np.ndarray) -> np.ndarray:
        """Feasibility of designs ``x`` (SI) exactly as the Monte Carlo judges it."""
        x = np.atleast_2d(x)
        ok = np.ones(len(x), dtype=bool)
        if self.stage != "unconstrained":
            for c in self.study.constraints:
                ok &= self.study.holds(c, self.surrogates[c.response].predict(x), self.stage)
        if self.valid_margin is not None:
            ok &= self.valid_margin(x) >= 0
        return ok


def _difference_points(n: int) -> np.ndarray:
    """Offsets of a forward-difference gradient in n inputs: the point itself, then FD_STEP along each input."""
    return np.vstack([np.zeros(n), FD_STEP * np.eye(n)])


def _slsqp(
    fun: Callable[[np.ndarray], tuple[float, np.ndarray]],
    u0: np.ndarray,
    cons: list[dict[str, Any]],
    maxiter: int,
    ftol: float,
    box: Box | None = None,
) -> np.ndarray:
    """SLSQP (value and gradient from ``fun``) from ``u0`` on [−1, 1]ⁿ (or within ``box``), its warnings silenced;
    the end point."""
    lo, hi = (np.full(len(u0), -1.0), np.full(len(u0), 1.0)) if box is None else box
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        res = minimize(
            fun,
            np.clip(u0, lo, hi),
            method="SLSQP",
            jac=True,
            bounds=list(zip(lo, hi)),
            constraints=cons,
            options={"maxiter": maxiter, "ftol": ftol},
        )
    return np.asarray(np.clip(res.x, lo, hi))


def local_optimum(
    problem: SurrogateProblem,
    objective: str,
    sense: str,
    starts: np.ndarray,
    fallback: np.ndarray | None = None,
    box: Box | None = None,
) -> Optimum | None:
    """The best feasible SLSQP solution from ``starts`` (rows, SI), within ``box`` (on the [−1, 1] scale) when given;
    the fallback design when none improves."""
    n = problem.bounds.shape[0]
    best_u, best_f = None, np.inf
    if fallback is not None and problem.feasible(fallback[None, :])[0]:
        best_u = to_unit(fallback[None, :], problem.bounds)[0]
        best_f = float(problem.objective(objective, best_u, sense)[0])
    method = "best Monte Carlo sample"
    steps = _difference_points(n)

    def objective_and_gradient(u: np.ndarray) -> tuple[float, np.ndarray]:
        f = problem.objective(objective, u[None, :] + steps, sense)
        return float(f[0]), (f[1:] - f[0]) / FD_STEP

    cons = _feasibility(problem)
    for start in np.atleast_2d(starts):
        u = _slsqp(objective_and_gradient, to_unit(start[None, :], problem.bounds)[0], cons, 100, 1e-10, box)
        f = float(problem.objective(objective, u, sense)[0])
        better = best_u is None or f < best_f - 1e-12 * max(1.0, abs(best_f))
        if np.isfinite(f) and better and problem.feasible(problem.x(u[None, :]))[0]:
            best_u, best_f, method = u, f, "SLSQP on the surrogates"
    if best_u is None:
        return None
    value = -best_f if sense == "max" else best_f
    return Optimum(objective, problem.stage, value, problem.x(best_u[None, :])[0], method)


def _feasibility(problem: SurrogateProblem, inside: float | np.ndarray | None = None) -> list[dict[str, Any]]:
    """SLSQP's inequality for the stage: each scaled constraint at least ``inside`` (one value, or one per limit;
    0 when None) and the validity margin at least 0, each plus :data:`CONSTRAINT_MARGIN`, with the forward-difference
    Jacobian (none without constraints)."""
    if not problem.limits and problem.valid_margin is None:
        return []
    steps = _difference_points(problem.bounds.shape[0])
    targets = np.broadcast_to(0.0 if inside is None else np.asarray(inside, dtype=float), (len(problem.limits),))
    least = CONSTRAINT_MARGIN + np.concatenate([targets, [0.0] if problem.valid_margin is not None else []])

    def jacobian(u: np.ndarray) -> np.ndarray:
        g = problem.constraints(u[None, :] + steps)
        return np.asarray((g[1:] - g[0]) / FD_STEP).T

    return [{"type": "ineq", "fun": lambda u: problem.constraints(u)[0] - least, "jac": jacobian}]


def nearest_feasible(
    problem: SurrogateProblem, x: np.ndarray, box: Box | None = None, inside: float | np.ndarray | None = None
) -> np.ndarray | None:
    """The design (SI) nearest ``x`` on the [−1, 1] scale that the stage's problem finds feasible, each scaled
    constraint at least ``inside`` within its limit (one value, or one per limit): SLSQP on |u − u(x)|² under the
    stage's constraints, from ``x``, within ``box`` when given; None when the search ends at no such design. The
    restoration step of a trust-region search standing on a design outside a constraint (the minimum-norm correction
    back into the feasible set, as in the feasibility restoration of Fletcher & Leyffer's filter SQP, *Math.
    Programming* 91: 239–269, 2002): the least move, where the model's correction is best."""
    u0 = to_unit(np.atleast_2d(x), problem.bounds)[0]

    def distance(u: np.ndarray) -> tuple[float, np.ndarray]:
        d = u - u0
        return float(d @ d), 2.0 * d

    u = _slsqp(distance, u0, _feasibility(problem, inside), 100, 1e-12, box)
    found = problem.x(u[None, :])[0]
    return found if problem.feasible(found[None, :])[0] else None


def nsga2_front(
    problem: SurrogateProblem,
    objectives: Sequence[tuple[str, str]],
    *,
    seed: int = 1,
    population: int = NSGA_POPULATION,
    generations: int = NSGA_GENERATIONS,
) -> tuple[np.ndarray, np.ndarray]:
    """(objective values, designs in SI) of the feasible non-dominated set NSGA-II finds, sorted by the first."""
    n = problem.bounds.shape[0]
    n_constr = problem.constraints(np.zeros((1, n))).shape[1]

    class _Problem(Problem):  # type: ignore[misc]  # pymoo carries no types
        def __init__(self) -> None:
            super().__init__(n_var=n, n_obj=len(objectives), n_ieq_constr=n_constr, xl=-1.0, xu=1.0)

        def _evaluate(self, u: np.ndarray, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
            with np.errstate(all="ignore"):
                out["F"] = np.column_stack([problem.objective(o, u, s) for o, s in objectives])
                if n_constr:
                    out["G"] = -problem.constraints(u)

    result = pymoo_minimize(_Problem(), NSGA2(pop_size=population), ("n_gen", generations), seed=seed, verbose=False)
    if result.X is None:
        return np.empty((0, len(objectives))), np.empty((0, n))
    u = np.atleast_2d(result.X)
    x = problem.x(u)
    x = x[problem.feasible(x)]
    values = np.column_stack([problem.surrogates[o].predict(x) for o, _ in objectives])
    signed = np.column_stack([values[:, k] * (-1.0 if s == "max" else 1.0) for k, (_, s) in enumerate(objectives)])
    keep = non_dominated(signed)  # the feasible points' own front (pymoo's set is judged with its tolerances)
    order = np.argsort(values[keep, 0])
    return values[keep][order], x[keep][order]


def non_dominated(f: np.ndarray, tolerance: float = 1e-6) -> np.ndarray:
    """Indices of the rows of ``f`` (n, k; every column minimised) that no other row dominates: no worse in every
    objective and better in one, by more than ``tolerance`` × the column's spread (two designs the surrogates tell
    apart by less are one point of the front: an NSGA-II population keeps such near-twins at a constraint's edge
    with a worse second objective); of rows equal within it the first is kept."""
    f = np.asarray(f, dtype=float)
    tol = tolerance * np.maximum(np.ptp(f, axis=0), 1e-300) if len(f) else np.zeros(f.shape[1:])
    keep = []
    for i in range(len(f)):
        no_worse = np.all(f <= f[i] + tol, axis=1)
        better = np.any(f < f[i] - tol, axis=1)
        twin_before = np.any(np.all(np.abs(f[:i] - f[i]) <= tol, axis=1))
        if not np.any(no_worse & better) and not twin_before:
            keep.append(i)
    return np.array(keep, dtype=int)


def front_sample(f: np.ndarray, k: int) -> np.ndarray:
    """Indices of up to ``k`` front points spread along the first objective (its ends included)."""
    if len(f) <= k:
        return np.arange(len(f))
    return np.unique(np.round(np.linspace(0, len(f) - 1, k)).astype(int))


def constraint_scales(study: Study, surrogates: dict[str, Surrogate]) -> dict[str, float]:
    """Each constraint response's spread over its training cases (the constraints' common scale)."""
    out = {}
    for c in study.constraints:
        y = surrogates[c.response].plot_data.get("train", (np.empty(0),))[0]
        out[c.response] = float(np.std(y)) if len(y) > 1 and np.std(y) > 0 else 1.0
    return out


#: the method of an optimum that is the design of least violation of a stage no design meets on the surrogates
LEAST_VIOLATION = "least violation: no design meets every constraint of the stage on the surrogates"


#: the method of an optimum that is the least-violation search's design, feasible where no sample was
FOUND_BY_LEAST_VIOLATION = "least-violation search: a design no Monte Carlo sample found, feasible on the surrogates"


def least_violation(problem: SurrogateProblem, starts: np.ndarray, box: Box | None = None) -> np.ndarray | None:
    """The design (SI) of least total violation of the stage's constraints, Σ min(g, 0)² over the scaled constraint
    values g of :meth:`SurrogateProblem.constraints` (the validity margin held as a constraint, not traded): SLSQP
    from each start (within ``box`` when given), the best kept; None when no start ends at a possible design."""
    n = problem.bounds.shape[0]
    n_limits = len(problem.limits)
    steps = _difference_points(n)

    def total(u: np.ndarray) -> tuple[float, np.ndarray]:
        g = problem.constraints(u[None, :] + steps)[:, :n_limits]
        v = np.sum(np.minimum(g, 0.0) ** 2, axis=1)
        return float(v[0]), (v[1:] - v[0]) / FD_STEP

    cons = []
    if problem.valid_margin is not None:
        margin = problem.valid_margin
        cons = [{"type": "ineq", "fun": lambda u: margin(problem.x(u[None, :]))}]
    best_u, best_v = None, np.inf
    for start in np.atleast_2d(starts):
        u = _slsqp(total, to_unit(start[None, :], problem.bounds)[0], cons, 200, 1e-14, box)
        v = total(u)[0]
        possible = problem.valid_margin is None or problem.valid_margin(problem.x(u[None, :]))[0] >= 0
        if possible and np.isfinite(v) and v < best_v:
            best_u, best_v = u, v
    return None if best_u is None else problem.x(best_u[None, :])[0]


def _least_violation_starts(problem: SurrogateProblem, mc: MonteCarloResult, rng: np.random.Generator) -> np.ndarray:
    """The Monte Carlo cloud's samples of least total violation, then random points."""
    random = from_unit(rng.uniform(-1, 1, (STARTS // 2, problem.bounds.shape[0])), problem.bounds)
    cloud = mc.cloud_x
    if not len(cloud):
        return random
    g = problem.constraints(to_unit(cloud, problem.bounds))[:, : len(problem.limits)]
    order = np.argsort(np.sum(np.minimum(g, 0.0) ** 2, axis=1))[:STARTS]
    return np.vstack([cloud[order], random])


def optimise(
    study: Study,
    surrogates: dict[str, Surrogate],
    mc: MonteCarloResult,
    valid_margin: ValidMargin | None = None,
    *,
    seed: int = 3,
) -> list[Optimum]:
    """The optimum of every objective in every stage: SLSQP started from the stage's best Monte Carlo samples
    (the stage's best sample itself kept when no start improves on it). A stage no sample meets is searched for its
    design of least violation (:func:`least_violation`): where that design meets every constraint (a region the
    samples missed) each objective is optimised from it, otherwise it is reported once per objective as the
    stage's optimum with the method :data:`LEAST_VIOLATION` — the constraints it violates are those in conflict."""
    rng = np.random.default_rng(seed)
    scales = constraint_scales(study, surrogates)
    out = []
    nearest: dict[str, np.ndarray | None] = {}
    for k, objective in enumerate(study.objectives):
        sign = -1.0 if objective.sense == "max" else 1.0
        for si, stage in enumerate(STAGES):
            sampled = next((o for o in mc.optima if o.objective == objective.response and o.stage == stage), None)
            problem = SurrogateProblem(study, surrogates, stage, valid_margin, scales)
            if sampled is None:
                if stage == "unconstrained" or not problem.limits:
                    continue
                if stage not in nearest:
                    nearest[stage] = least_violation(problem, _least_violation_starts(problem, mc, rng))
                x = nearest[stage]
                if x is None:
                    continue
                value = float(surrogates[objective.response].predict(x[None, :])[0])
                if problem.feasible(x[None, :])[0]:
                    best = local_optimum(problem, objective.response, objective.sense, x[None, :], fallback=x)
                    if best is None or best.method != "SLSQP on the surrogates":  # no start improved on it
                        best = Optimum(objective.response, stage, value, x, FOUND_BY_LEAST_VIOLATION)
                    out.append(best)
                else:
                    out.append(Optimum(objective.response, stage, value, x, LEAST_VIOLATION))
                continue
            in_stage = mc.cloud_stage >= si
            order = np.argsort(sign * mc.cloud_f[in_stage, k])[: STARTS // 2]
            starts = np.vstack(
                [
                    sampled.x[None, :],
                    mc.cloud_x[in_stage][order],
                    from_unit(rng.uniform(-1, 1, (STARTS // 2, len(study.variables))), study.bounds),
                ]
            )
            best = local_optimum(problem, objective.response, objective.sense, starts, fallback=sampled.x)
            out.append(best or sampled)
    return out


def pareto_fronts(
    study: Study, surrogates: dict[str, Surrogate], valid_margin: ValidMargin | None = None, *, seed: int = 1
) -> list[dict[str, Any]]:
    """The constrained front of every pair of objectives by NSGA-II: objectives, values, designs."""
    problem = SurrogateProblem(study, surrogates, "constrained", valid_margin, constraint_scales(study, surrogates))
    objectives = list(study.objectives)
    fronts = []
    for i in range(len(objectives)):
        for j in range(i + 1, len(objectives)):
            pair = [(objectives[i].response, objectives[i].sense), (objectives[j].response, objectives[j].sense)]
            f, x = nsga2_front(problem, pair, seed=seed)
            fronts.append({"objectives": [o for o, _ in pair], "f": f, "x": x})
    return fronts


def front_points(fronts: list[dict[str, Any]], k: int) -> list[Optimum]:
    """Up to ``k`` points of each front, spread along it, as designs to re-evaluate with the true model."""
    out = []
    for front in fronts:
        name = " × ".join(front["objectives"])
        for i in front_sample(front["f"], k):
            out.append(Optimum(name, "constrained", float(front["f"][i, 0]), front["x"][i], "NSGA-II front point"))
    return out

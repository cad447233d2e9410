"""Monte Carlo feasibility on the surrogates: uniform samples over the design box, evaluated chunk by chunk.

For N independent uniform samples the probability of success p of a constraint is estimated by the fraction
k/N of samples that satisfy it, with its 95 % Wilson score interval (:mod:`.intervals`; never of zero width at
k = 0 or N, as the binomial standard error √(p(1−p)/N) would be). Nothing of size N is kept: per chunk the samples are
drawn, every surrogate evaluated, counts and fixed-bin histograms (for the CDFs) updated, the Pareto fronts
and the per-stage optima merged, and the first ``cloud`` samples stored for plotting.

Stages (the seed study's filtering): *unconstrained* — every sample; *constrained* — every declared
constraint satisfied, level constraints with the declared relaxation (``analysis.level_relaxation``);
*preferred* — constrained, and every level constraint at MIL-F-8785C Level 1.

Declared model uncertainty (``analysis.uncertainty``): the outputs of the matching surrogates are multiplied
per sample by (1 + δ), δ ~ U(−p, p) or N(0, p²); the probabilities of compliance are recomputed, together
with an adverse bound where every such output is moved by p (uniform) or 2p (normal) in its unfavourable
direction.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from certkit.study.analysis.intervals import interval_se, wilson
from certkit.study.analysis.pareto import FrontAccumulator, objective_subsets
from certkit.study.analysis.surrogates import Surrogate
from certkit.study.spec import Constraint, Study

STAGES = ("unconstrained", "constrained", "preferred")
HIST_BINS = 2000


def binomial_se(p: float, n: int) -> float:
    """The standard error of a fraction p of n trials, read from its Wilson interval (positive at p = 0 or 1)."""
    return interval_se(round(p * n), n) if n else float("nan")


@dataclass
class Histogram:
    """Counts of a response over fixed bins, with the samples below and above them."""

    edges: np.ndarray
    counts: np.ndarray
    below: int = 0
    above: int = 0

    @staticmethod
    def around(values: np.ndarray, marks: list[float]) -> "Histogram":
        finite = values[np.isfinite(values)]
        lo = min([float(finite.min()) if finite.size else 0.0] + marks)
        hi = max([float(finite.max()) if finite.size else 1.0] + marks)
        pad = 0.05 * (hi - lo) if hi > lo else 1.0
        return Histogram(np.linspace(lo - pad, hi + pad, HIST_BINS + 1), np.zeros(HIST_BINS, dtype=np.int64))

    def add(self, values: np.ndarray) -> None:
        values = values[np.isfinite(values)]
        self.below += int(np.sum(values < self.edges[0]))
        self.above += int(np.sum(values > self.edges[-1]))
        self.counts += np.histogram(values, self.edges)[0]

    def cdf(self) -> tuple[np.ndarray, np.ndarray]:
        """(upper bin edges, fraction of samples at or below them)."""
        total = self.counts.sum() + self.below + self.above
        return self.edges[1:], (self.below + np.cumsum(self.counts)) / max(total, 1)


@dataclass
class ConstraintOutcome:
    constraint: Constraint
    successes: int
    n: int
    relaxed_max: float | None
    relaxed_successes: int | None
    sole_violations: int
    histogram: Histogram
    flagged: bool
    uncertain_successes: int | None = None
    adverse_successes: int | None = None
    least_violation: float = float("nan")  # over the samples, on the surrogate (0 where some sample satisfies it)
    best_value: float = float("nan")  # the sample value of least violation

    @property
    def p(self) -> float:
        return self.successes / self.n

    @property
    def se(self) -> float:
        return interval_se(self.successes, self.n)

    @property
    def interval(self) -> tuple[float, float]:
        """95 % Wilson interval of the probability of success."""
        return wilson(self.successes, self.n)

    @property
    def interval_relaxed(self) -> tuple[float, float] | None:
        return None if self.relaxed_successes is None else wilson(self.relaxed_successes, self.n)

    @property
    def p_relaxed(self) -> float | None:
        return None if self.relaxed_successes is None else self.relaxed_successes / self.n

    @property
    def p_uncertain(self) -> float | None:
        return None if self.uncertain_successes is None else self.uncertain_successes / self.n

    @property
    def p_adverse(self) -> float | None:
        return None if self.adverse_successes is None else self.adverse_successes / self.n


@dataclass
class Optimum:
    """An optimum of ``objective`` in ``stage`` (or a front point: ``objective`` then names the front)."""

    objective: str
    stage: str
    value: float
    x: np.ndarray
    method: str = "best Monte Carlo sample"


@dataclass
class MonteCarloResult:
    n: int
    chunk: int
    seed: int
    seconds: float
    constraints: list[ConstraintOutcome]
    stage_counts: dict[str, int]
    uncertain_joint: int | None
    adverse_joint: int | None
    objectives: list[str]
    fronts: dict[tuple[str, tuple[int, ...]], FrontAccumulator]
    optima: list[Optimum]
    cloud_x: np.ndarray
    cloud_f: np.ndarray
    cloud_stage: np.ndarray
    flagged_responses: list[str] = field(default_factory=list)
    n_drawn: int = 0  # samples drawn; n of them were possible designs (the others masked)

    @property
    def masked(self) -> int:
        return max(self.n_drawn - self.n, 0)

    def stage_p(self, stage: str) -> tuple[float, float]:
        """(fraction of samples in ``stage``, its standard error from the Wilson interval)."""
        return self.stage_counts[stage] / self.n, interval_se(self.stage_counts[stage], self.n)

    def stage_interval(self, stage: str) -> tuple[float, float]:
        return wilson(self.stage_counts[stage], self.n)

    def ranked(self) -> list[ConstraintOutcome]:
        """Constraints by activity: the least probability of success first (show-stoppers at the top), ties
        broken by how many samples fail that constraint alone."""
        return sorted(self.constraints, key=lambda c: (c.p, -c.sole_violations))


def violation(constraint: Constraint, values: np.ndarray, max_override: float | None = None) -> np.ndarray:
    """How far each value lies outside the constraint's limits (0 inside; a level L counts up to L + ½);
    NaN where the value is not finite."""
    upper = constraint.max if max_override is None else max_override
    half = 0.5 if constraint.is_level else 0.0
    out = np.zeros(len(values))
    if constraint.min is not None:
        out = np.maximum(out, (constraint.min - half) - values)
    if upper is not None:
        out = np.maximum(out, values - (upper + half))
    result: np.ndarray = np.where(np.isfinite(values), out, np.nan)
    return result


def _adverse(values: np.ndarray, constraint: Constraint, fraction: float) -> np.ndarray:
    """Values moved by ``fraction`` of their magnitude towards the infeasible side of ``constraint``."""
    shift: np.ndarray = np.abs(values) * fraction
    if constraint.min is None or constraint.max is None:
        one_sided: np.ndarray = values - shift if constraint.max is None else values + shift
        return one_sided
    mid = 0.5 * (constraint.min + constraint.max)
    moved: np.ndarray = np.where(values >= mid, values + shift, values - shift)
    return moved


def run_monte_carlo(
    study: Study,
    surrogates: dict[str, Surrogate],
    *,
    n: int = 1_000_000,
    chunk: int = 100_000,
    seed: int = 20240615,
    cloud: int = 20_000,
    valid: Callable[[np.ndarray], np.ndarray] | None = None,
) -> MonteCarloResult:
    """Sample ``n`` uniform designs over the variables' bounds and evaluate every constraint and objective.
    ``valid``: a function of the samples (rows, SI) → mask of possible designs; the others are masked before any
    count, front or optimum (probabilities are then among possible designs)."""
    t0 = time.perf_counter()
    bounds = study.bounds
    lo, width = bounds[:, 0], bounds[:, 1] - bounds[:, 0]
    rng = np.random.default_rng(seed)
    unc_rng = np.random.default_rng([seed, 1])
    opts = study.analysis
    constraints = list(study.constraints)
    objectives = [o.response for o in study.objectives]
    maximise = tuple(o.sense == "max" for o in study.objectives)
    sign = np.array([-1.0 if m else 1.0 for m in maximise])
    relaxed = [opts.relaxed_max(c) for c in constraints]
    levels = [i for i, c in enumerate(constraints) if c.is_level]
    uncertainty = {r: opts.uncertainty_for(r) for r in {c.response for c in constraints}}
    uncertainty = {r: u for r, u in uncertainty.items() if u is not None}
    needed = list(dict.fromkeys(objectives + [c.response for c in constraints]))
    missing = [r for r in needed if r not in surrogates]
    if missing:
        raise ValueError(f"no surrogate for {', '.join(missing)}")

    succ = np.zeros(len(constraints), dtype=np.int64)
    succ_relaxed = np.zeros(len(constraints), dtype=np.int64)
    sole = np.zeros(len(constraints), dtype=np.int64)
    succ_unc = np.zeros(len(constraints), dtype=np.int64)
    succ_adv = np.zeros(len(constraints), dtype=np.int64)
    stage_counts = dict.fromkeys(STAGES, 0)
    joint_unc = joint_adv = 0
    hists: list[Histogram | None] = [None] * len(constraints)
    least = np.full(len(constraints), np.inf)
    least_value = np.full(len(constraints), np.nan)
    subsets = objective_subsets(len(objectives)) if len(objectives) >= 2 else []
    fronts = {
        (stage, cols): FrontAccumulator(len(lo), cols, tuple(maximise[c] for c in cols))
        for stage in STAGES
        for cols in subsets
    }
    best: dict[tuple[int, str], tuple[float, np.ndarray | None]] = {
        (o, s): (np.inf, None) for o in range(len(objectives)) for s in STAGES
    }
    cloud_x, cloud_f, cloud_stage = [], [], []
    kept = 0
    done = 0
    n_valid = 0
    while done < n:
        m = min(chunk, n - done)
        done += m
        x = lo + width * rng.random((m, len(lo)))
        if valid is not None:
            x = x[valid(x)]
            m = len(x)
            if not m:
                continue
        n_valid += m
        values = {r: surrogates[r].predict(x) for r in needed}
        ok_relaxed = np.ones((len(constraints), m), dtype=bool)
        level1 = np.ones(m, dtype=bool)
        ok_unc = np.ones(m, dtype=bool)  # counted only with uncertainty entries
        ok_adv = np.ones(m, dtype=bool)
        for i, c in enumerate(constraints):
            v = values[c.response]
            hist = hists[i]
            if hist is None:
                hist = hists[i] = Histogram.around(v, [t for t in (c.min, c.max) if t is not None])
            hist.add(v)
            ok = c.feasible(v)
            succ[i] += int(ok.sum())
            ok_r = c.feasible(v, relaxed[i]) if relaxed[i] is not None else ok
            succ_relaxed[i] += int(ok_r.sum())
            miss = violation(c, v, relaxed[i])
            j = int(np.nanargmin(miss)) if np.isfinite(miss).any() else -1
            if j >= 0 and miss[j] < least[i]:
                least[i], least_value[i] = miss[j], v[j]
            ok_relaxed[i] = ok_r
            if i in levels:
                level1 &= c.feasible(v, 1.0)
            u = uncertainty.get(c.response)
            if u is not None or uncertainty:
                if u is not None:
                    p = u.percent / 100.0
                    delta = unc_rng.uniform(-p, p, m) if u.distribution == "uniform" else unc_rng.normal(0.0, p, m)
                    v_unc = v * (1.0 + delta)
                    v_adv = _adverse(v, c, p if u.distribution == "uniform" else 2.0 * p)
                else:
                    v_unc = v_adv = v
                ok_u = c.feasible(v_unc, relaxed[i])
                ok_a = c.feasible(v_adv, relaxed[i])
                succ_unc[i] += int(ok_u.sum())
                succ_adv[i] += int(ok_a.sum())
                ok_unc &= ok_u
                ok_adv &= ok_a
        constrained = np.asarray(ok_relaxed.all(axis=0)) if constraints else np.ones(m, dtype=bool)
        if constraints:
            fails = ~ok_relaxed
            only = fails.sum(axis=0) == 1
            sole += (fails & only).sum(axis=1)
        preferred = constrained & level1
        if uncertainty:
            joint_unc += int(ok_unc.sum())
            joint_adv += int(ok_adv.sum())
        masks = {"unconstrained": np.ones(m, dtype=bool), "constrained": constrained, "preferred": preferred}
        f = np.column_stack([values[o] for o in objectives]) if objectives else np.empty((m, 0))
        for stage, mask in masks.items():
            stage_counts[stage] += int(mask.sum())
            if not mask.any():
                continue
            for cols in subsets:
                fronts[(stage, cols)].add(f[mask], x[mask])
            for o in range(len(objectives)):
                signed = sign[o] * f[mask, o]
                j = int(np.argmin(signed))
                if signed[j] < best[(o, stage)][0]:
                    best[(o, stage)] = (float(signed[j]), x[mask][j].copy())
        if kept < cloud:
            take = min(cloud - kept, m)
            cloud_x.append(x[:take])
            cloud_f.append(f[:take])
            cloud_stage.append(np.where(preferred[:take], 2, np.where(constrained[:take], 1, 0)))
            kept += take
    if not n_valid:
        raise ValueError(f"every one of the {n} samples was classed as an impossible design")
    histograms = [h for h in hists if h is not None]  # every constraint has one once a sample was possible
    outcomes = [
        ConstraintOutcome(
            c,
            int(succ[i]),
            n_valid,
            relaxed[i],
            int(succ_relaxed[i]) if relaxed[i] is not None else None,
            int(sole[i]),
            histograms[i],
            surrogates[c.response].flagged,
            int(succ_unc[i]) if uncertainty else None,
            int(succ_adv[i]) if uncertainty else None,
            float(least[i]),
            float(least_value[i]),
        )
        for i, c in enumerate(constraints)
    ]
    optima = [Optimum(objectives[o], s, float(sign[o] * v), xb) for (o, s), (v, xb) in best.items() if xb is not None]
    flagged = [r for r in needed if surrogates[r].flagged]
    return MonteCarloResult(
        n_valid,
        chunk,
        seed,
        time.perf_counter() - t0,
        outcomes,
        stage_counts,
        joint_unc if uncertainty else None,
        joint_adv if uncertainty else None,
        objectives,
        fronts,
        optima,
        np.concatenate(cloud_x),
        np.concatenate(cloud_f),
        np.concatenate(cloud_stage),
        flagged,
        n_drawn=n,
    )

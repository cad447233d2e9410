"""Rules of one design over several processes (``certkit evaluate`` on a multi-core machine).

The worker processes are forked from the evaluating process, so each starts from its Context (the aircraft, the
lattice and the models already built) and evaluates its share of the rules, the heaviest first (longest-processing-
time order over :attr:`Rule.cost`). The results come back in rule order and are the same as in one process: every
memoised model is a deterministic function of its inputs. Only the parts a design needs of a loads rule's run are
sent back (its load envelopes and the pitch-manoeuvre histories the actuator sizing reads). A study evaluates one
design per core and does not use this.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import TYPE_CHECKING, Any

from certkit.engine.scheduler import evaluate_rule
from certkit.engine.worker_processes import die_with_parent, stop_pool

if TYPE_CHECKING:
    from certkit.engine.context import Context
    from certkit.engine.registry import Rule
    from certkit.engine.results import Condition, RuleResult

_SHARED: dict[str, Any] = {}


def _slim(result: RuleResult) -> RuleResult:
    """What a design keeps of a loads rule's result: its findings, load envelopes and the run's records
    (:func:`certkit.design.tail_group.design_hinge_moment`)."""
    if result.run is not None:
        result.run = result.run.records_only()
    result.evidence = []
    return result


def _work(ids: tuple[str, ...]) -> list[RuleResult]:
    ctx, rules, kw, select = _SHARED["ctx"], _SHARED["rules"], _SHARED["kw"], _SHARED["select"]
    return [_slim(evaluate_rule(rules[i], ctx, only=select.get(i), **kw)) for i in ids]


def shares(rules: Sequence[type[Rule]], jobs: int) -> list[tuple[type[Rule], ...]]:
    """The rules in ``jobs`` groups of about equal summed cost (heaviest first into the lightest group)."""
    groups: list[list[type[Rule]]] = [[] for _ in range(jobs)]
    load = [0.0] * jobs
    for r in sorted(rules, key=lambda r: -r.cost):
        k = load.index(min(load))
        groups[k].append(r)
        load[k] += r.cost
    return [tuple(g) for g in groups if g]


def evaluate_rules(
    rules: Sequence[type[Rule]],
    ctx: Context,
    jobs: int = 1,
    select: Mapping[str, list[Condition] | None] | None = None,
    **kw: Any,
) -> list[RuleResult]:
    """:func:`certkit.engine.scheduler.evaluate_rule` of each rule on ``ctx`` (keywords passed on), in ``jobs`` forked
    processes when more than one is asked for and the platform forks; in rule order. ``select`` (rule id →
    conditions) restricts those rules to the same points (``only``); a rule it maps to no condition is skipped."""
    select = dict(select or {})
    rules = [r for r in rules if (chosen := select.get(r.id)) is None or len(chosen) > 0]
    if jobs <= 1 or len(rules) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [evaluate_rule(r, ctx, only=select.get(r.id), **kw) for r in rules]
    groups = shares(rules, min(jobs, len(rules)))
    _SHARED.update(ctx=ctx, rules={r.id: r for r in rules}, kw=kw, select=select)
    pool = ProcessPoolExecutor(
        len(groups),
        mp_context=multiprocessing.get_context("fork"),
        initializer=die_with_parent,
        initargs=(os.getpid(),),
    )
    try:
        done = [res for part in pool.map(_work, [tuple(r.id for r in g) for g in groups]) for res in part]
    except BaseException:  # Ctrl-C or a failure: the workers end now (they also end with this process)
        stop_pool(pool)
        raise
    finally:
        _SHARED.clear()
    pool.shutdown()
    by_id = {res.id: res for res in done}
    return [by_id[r.id] for r in rules]

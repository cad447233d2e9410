"""Runs rules over their conditions; isolates failures; deterministic with any number of jobs.

For each rule: check the inputs it needs (missing → ``not_evaluated`` before any computation),
apply the aircraft file's criteria overrides, expand the condition space, evaluate the whole batch,
and if the batch raises, evaluate condition by condition so that one bad condition is recorded
as ``not_evaluated`` with its reason while the others still run. ``jobs > 1`` spreads rules over
processes; results are put back in rule order, so they equal those of ``jobs = 1``.
"""

from __future__ import annotations

import datetime as _dt
import gc
import inspect
import math
import os
import re
import time
import traceback
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from itertools import repeat
from typing import TYPE_CHECKING, Any

from certkit import __version__
from certkit.aircraft import LoadedAircraft
from certkit.engine.context import Context
from certkit.engine.registry import Criteria, DiscoveryOptions, Loads, PluginError, Rule, discover, exit_called
from certkit.engine.results import Condition, Finding, RuleResult, RunResult, SimulationRun
from certkit.engine.worker_processes import die_with_parent, stop_pool
from certkit.errors import InputError, Problem, UserError
from certkit.units import UnitError, to_unit

if TYPE_CHECKING:
    from certkit.models.aero.lattice_store import LatticeStore

#: what runs on each result in the process that evaluated it (the report's drawing of the evidence)
Finish = Callable[[RuleResult], object]


def criteria_for(rule: type[Rule], ctx: Context) -> tuple[Criteria, dict[str, Any]]:
    """The rule's criteria with the aircraft file's overrides (checked by :func:`override_problems`)."""
    values = Criteria({name: c.value for name, c in rule.criteria.items()})
    override = ctx.aircraft.criteria.get(rule.id)
    applied: dict[str, Any] = {}
    if override is not None:
        for name, given in override.values.items():
            value, problem = _override_value(rule, name, given)
            if problem:
                raise UserError(f"criteria.{rule.id}.values.{name}: {problem}")
            default = rule.criteria[name].value
            applied[name] = {
                "default": default,
                "value": value,
                "unit": rule.criteria[name].unit,
                "justification": override.justification,
            }
            values[name] = value
    return values, applied


def criteria_metadata(rule: type[Rule], values: Criteria, overrides: dict[str, Any]) -> dict[str, Any]:
    """The criteria in force as results.json and the report state them: value, unit (``1`` without one), source,
    basis (:attr:`Criterion.basis`; ``override`` when the aircraft file set the value, with the rule's default, its
    basis and the file's justification beside it), meaning, and whether the aircraft file overrode it."""
    out = {}
    for name, c in rule.criteria.items():
        entry = {
            "value": values[name],
            "unit": c.unit or "1",
            "source": c.source,
            "basis": c.basis,
            "description": c.description,
            "overridden": name in overrides,
        }
        if name in overrides:
            entry.update(
                basis="override", default=c.value, default_basis=c.basis, justification=overrides[name]["justification"]
            )
        out[name] = entry
    return out


def check_in_force(check: str, overrides: dict[str, Any], name_the_rest: bool = False) -> str:
    """A check text as the criteria in force make it: a default value an override replaced, written as a number in
    the text ("VC ≥ VB + 1.32 U_ref"), becomes the value in force ("VC ≥ VB + 1.4 U_ref"). Paragraph labels such
    as "(2)" are never numbers here. With ``name_the_rest`` the overrides the text does not show are named after it
    ("… [override: ultimate_factor 1.65]"), so that a verdict computed with an override never reads as the
    regulation's."""
    hidden = []
    for name, o in overrides.items():
        default, value = o["default"], o["value"]
        if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (default, value)):
            hidden.append(f"{name} {value}")
            continue
        pattern = rf"(?<![\d.(]){re.escape(f'{default:g}')}(?![\d)])"
        if re.search(pattern, check):
            check = re.sub(pattern, f"{value:g}", check)
        else:
            hidden.append(f"{name} {value:g}{' ' + o['unit'] if o.get('unit') not in (None, '', '1') else ''}")
    if name_the_rest and hidden:
        check += f" [override: {', '.join(hidden)}]"
    return check


def _show_overrides(findings: list[Finding], overrides: dict[str, Any]) -> None:
    """Check texts formed from the criteria in force; the text with the defaults kept as ``check_default`` (what
    ``certkit diff`` pairs findings of two runs by)."""
    for f in findings:
        shown = check_in_force(f.check, overrides, name_the_rest=f.margin is not None)
        if shown != f.check:
            f.details = {**f.details, "check_default": f.check}
            f.check = shown


def _override_value(rule: type[Rule], name: str, given: object) -> tuple[object, str | None]:
    """An override's value in the criterion's unit (a number as given; a string with a unit converted), or why not."""
    if name not in rule.criteria:
        return given, f"rule {rule.id} has no criterion {name!r} (known: {', '.join(rule.criteria) or 'none'})"
    criterion = rule.criteria[name]
    default = criterion.value
    if isinstance(default, bool) or not isinstance(default, (int, float)):
        if type(given) is not type(default):
            return given, f"expected a {type(default).__name__} like {default!r}"
        return given, None
    if isinstance(given, str):
        try:
            return to_unit(given, criterion.unit), None
        except UnitError as exc:
            return given, f"{exc} (the criterion is in {criterion.unit or 'no unit'}, e.g. {default!r})"
    if isinstance(given, bool) or not isinstance(given, (int, float)):
        return given, f"expected a number in {criterion.unit or 'no unit'} like {default!r}"
    if not math.isfinite(given):
        return given, "must be a finite number"
    return given, None


def override_problems(loaded: LoadedAircraft, rules: list[type[Rule]]) -> list[Problem]:
    """Every criteria override of the aircraft file that names no rule of ``rules`` or no criterion of its rule, or
    whose value is not of the criterion's kind and unit: located problems, to be raised before any rule runs."""
    by_id = {r.id: r for r in rules}
    source = loaded.source
    found = []
    for rule_id, override in loaded.model.criteria.items():
        loc = ("criteria", rule_id)
        if rule_id not in by_id:
            close = [r for r in by_id if r.split("(")[0] == rule_id.split("(")[0]] or sorted(by_id)
            found.append(
                Problem(
                    ".".join(loc),
                    f"no rule {rule_id} (known: {', '.join(close)})",
                    rule_id,
                    source.line_of(loc),
                    source.path,
                )
            )
            continue
        for name, given in override.values.items():
            _, problem = _override_value(by_id[rule_id], name, given)
            if problem:
                at = loc + ("values", name)
                found.append(Problem(".".join(at), problem, given, source.line_of(at), source.path))
    return found


def check_overrides(loaded: LoadedAircraft, rules: list[type[Rule]]) -> None:
    """:func:`override_problems` as one :class:`InputError` (before a check starts)."""
    found = override_problems(loaded, rules)
    if found:
        raise InputError(loaded.path, found)


#: sections every rule's conditions and models build on (the CG-envelope corners, the altitude range, the engines,
#: the loading solver's masses): optional in the file (a derivative-table airplane flown by ``trim``/``modes`` needs
#: none of them), so a rule without them is ``not_evaluated`` naming them, never a crash
RULE_SECTIONS = ("cg_envelope", "envelope", "propulsion", "mass.MLW", "mass.MZFW", "mass.OEW")


def _describe_exception(exc: BaseException) -> str:
    return f"{exc.__class__.__name__}: {exc}"


def evaluate_rule(
    rule: type[Rule],
    ctx: Context,
    *,
    evidence: bool = True,
    keep_loads: bool = False,
    only: list[Condition] | None = None,
    wanted: frozenset[Loads] | None = None,
) -> RuleResult:
    """Evaluate one rule on the context's aircraft; ``evidence=False`` skips the plots and tables (a design
    evaluation reads only the findings); ``keep_loads`` keeps the rule's load envelopes on the result. ``only``
    (conditions, e.g. of another airplane) restricts the evaluation to the scheduled conditions that are the same
    points (:meth:`Condition.same_point`) — a partial result, for a design loop's start, never a verdict; so does
    ``wanted``, the loads the caller reads (:attr:`Rule.wanted`: a rule may leave the others out). After the
    rule's own findings come one ``not_evaluated`` finding per sub-paragraph it does not evaluate
    (:attr:`Rule.unevaluated`)."""
    try:
        result = _evaluate_own(rule, ctx, evidence, keep_loads, only, wanted)
    except SystemExit as exc:  # in a worker the pool would carry it to the parent, which would end with its code
        raise PluginError(f"rule {rule.id} ({rule.origin}): {exit_called(exc)}") from None
    result.findings += [Finding.outside_scope(para, why) for para, why in rule.unevaluated]
    return result


def _evaluate_own(
    rule: type[Rule],
    ctx: Context,
    evidence: bool,
    keep_loads: bool,
    only: list[Condition] | None = None,
    wanted: frozenset[Loads] | None = None,
) -> RuleResult:
    instance = rule()
    instance.wanted = wanted
    criteria, overrides = criteria_for(rule, ctx)
    result = RuleResult(
        rule.id,
        rule.symbol,
        rule.title,
        [],
        overrides=overrides,
        implementation=rule.implementation,
        limitations=" ".join(inspect.cleandoc(rule.limitations).split()),
        unevaluated=[list(u) for u in rule.unevaluated],  # type: ignore[misc]  # lists in results.json
        amendment=rule.amendment,
        references=list(rule.references),
        criteria=criteria_metadata(rule, criteria, overrides),
    )
    missing = ctx.missing(tuple(dict.fromkeys(RULE_SECTIONS + tuple(rule.requires))))
    if missing:
        result.findings.append(
            Finding.not_evaluated(
                Condition(),
                "inputs",
                "needs " + ", ".join(missing),
                hint=f"declare {', '.join(missing)} in the aircraft file",
            )
        )
        return result
    try:
        conditions = rule.conditions.expand(ctx.aircraft)
    except Exception as exc:  # a condition space that cannot be built is reported, not raised
        result.findings.append(Finding.not_evaluated(Condition(), "conditions", _describe_exception(exc)))
        return result
    if only is not None:
        by_place: dict[tuple[str | None, str | None], list[Condition]] = {}
        for k in only:  # same_point needs the same loading and configuration: only those are compared
            by_place.setdefault((k.loading, k.configuration), []).append(k)
        conditions = [
            c for c in conditions if any(k.same_point(c) for k in by_place.get((c.loading, c.configuration), ()))
        ]
        result.notes.append(f"partial evaluation: {len(conditions)} selected conditions")
    if wanted is not None:
        result.notes.append(
            "partial evaluation: the " + ", ".join(sorted(f"{w.surface} {w.kind}" for w in wanted)) + " loads wanted"
        )
    if not conditions:
        result.findings.append(
            Finding.not_evaluated(
                Condition(), "conditions", "no condition applies (configurations or speeds not declared)"
            )
        )
        return result
    try:
        findings = instance.evaluate(ctx, conditions, criteria)
    except UserError:
        raise
    except Exception:
        findings = []
        for cond in conditions:
            try:
                findings += instance.evaluate(ctx, [cond], criteria)
            except UserError:
                raise
            except Exception as exc:
                findings.append(
                    Finding.not_evaluated(
                        cond, "computation", _describe_exception(exc), traceback=traceback.format_exc(limit=3)
                    )
                )
    for cond in _uncovered(conditions, findings):
        findings.append(Finding.not_evaluated(cond, "computation", "the rule returned no finding for this condition"))
    if overrides:
        _show_overrides(findings, overrides)
    result.findings = findings
    if keep_loads:
        run = getattr(instance, "run", None)
        if isinstance(run, SimulationRun):
            result.run, result.load_envelopes = run, run.envelopes()
    if not evidence:
        return result
    try:
        result.evidence = instance.evidence(ctx, findings, criteria)
    except Exception as exc:
        result.notes.append(f"evidence could not be drawn: {_describe_exception(exc)}")
    return result


def _uncovered(conditions: list[Condition], findings: list[Finding]) -> list[Condition]:
    """The scheduled conditions no finding names, itself or refined (a finding's condition with more fields set).
    A refinement keeps the scheduled condition's loading, configuration, altitude and extra items, so the findings'
    conditions are indexed on those (per set of extra names the schedule uses) and each scheduled condition is
    compared with its own bucket only (a design's loads rules schedule thousands of conditions). A condition names
    itself too (:meth:`Condition.refines` holds for an equal one), so the buckets alone decide; the findings'
    conditions enter them once per object (the findings of one condition share it)."""
    covered = list({id(f.condition): f.condition for f in findings}.values())
    broad: dict[tuple[object, ...], list[Condition]] = {}
    for c in covered:
        broad.setdefault((c.loading, c.configuration), []).append(c)
    index: dict[tuple[str, ...], dict[tuple[object, ...], list[Condition]]] = {}
    extras: dict[int, dict[str, object]] = {}  # each finding condition's extra items (by object), read once
    by_names: dict[frozenset[str], list[Condition]] = {}  # the findings' conditions by the names of their extra items
    everywhere: set[Condition] | None = None
    out = []
    for cond in conditions:
        candidates: Iterable[Condition]
        if cond.loading is None or cond.configuration is None:
            everywhere = set(covered) if everywhere is None else everywhere
            if cond in everywhere:
                continue
            candidates = covered
        elif cond.altitude is None:
            candidates = broad.get((cond.loading, cond.configuration), [])
        else:
            names = tuple(k for k, _ in cond.extra)
            table = index.get(names)
            if table is None:
                if not extras:
                    extras = {id(c): dict(c.extra) for c in covered}
                    for c in covered:
                        by_names.setdefault(frozenset(extras[id(c)]), []).append(c)
                need = frozenset(names)  # a refinement carries every extra item of the scheduled condition
                table = index[names] = _refinement_index(
                    [c for have, group in by_names.items() if need <= have for c in group], extras, names
                )
            candidates = table.get(_place(cond, names, dict(cond.extra)), [])
        if not any(c.refines(cond) for c in candidates):
            out.append(cond)
    return out


def _place(c: Condition, names: tuple[str, ...], extra: dict[str, object]) -> tuple[object, ...]:
    return (c.loading, c.configuration, c.altitude, *map(extra.get, names, repeat(_ABSENT, len(names))))


_ABSENT = object()  # an extra item a finding's condition does not carry (never equal to a scheduled value)


def _refinement_index(
    covered: list[Condition], extras: Mapping[int, dict[str, object]], names: tuple[str, ...]
) -> dict[tuple[object, ...], list[Condition]]:
    """The findings' conditions (``extras``: each one's extra items, by object) keyed on what a refinement of a
    scheduled condition with extra items ``names`` keeps: loading, configuration, altitude and those items' values."""
    table: dict[tuple[object, ...], list[Condition]] = {}
    for c in covered:
        table.setdefault(_place(c, names, extras[id(c)]), []).append(c)
    return table


def _timed(rule: type[Rule], ctx: Context, finish: Finish | None = None) -> RuleResult:
    """:func:`evaluate_rule` then ``finish`` (the report's drawing), with the wall time of both in ``seconds``."""
    start = time.perf_counter()
    result = evaluate_rule(rule, ctx)
    if finish is not None:
        finish(result)
    result.seconds = time.perf_counter() - start
    return result


def _evaluate_many(
    ctx: Context, rules: list[type[Rule]], finish: Finish | None = None, progress: Any = None
) -> tuple[list[RuleResult], dict[str, Any]]:
    results = []
    for r in rules:
        if progress:
            progress.started([r.id])
        results.append(_timed(r, ctx, finish))
        if progress:
            progress.finished([results[-1]])
    return results, ctx.provenance()


def _merge_provenance(parts: list[dict[str, Any]]) -> dict[str, Any]:
    """One provenance from several workers' (same inputs give the same entries; keep one of each)."""
    merged = {
        "aerodynamics": {},
        "loadings": [],
        "components": parts[0]["components"] if parts else [],
        "component_notes": parts[0]["component_notes"] if parts else [],
    }
    seen: dict[Any, Any] = {}
    for p in parts:
        merged["aerodynamics"].update(p["aerodynamics"])
        for row in p["loadings"]:
            key = (round(row["mass_kg"], 3), round(row["x_cg_m"], 6))
            if key not in seen:
                seen[key] = dict(row)
                merged["loadings"].append(seen[key])
            else:  # the same loading named differently by different workers' rules: keep every name
                names = set(seen[key]["name"].split(" / ")) | set(row["name"].split(" / "))
                seen[key]["name"] = " / ".join(sorted(names))
    merged["aerodynamics"] = dict(sorted(merged["aerodynamics"].items()))
    merged["loadings"].sort(key=lambda r: (r["mass_kg"], r["x_cg_m"]))
    return merged


_WORKER: dict[str, Any] = {}


def _worker_init(
    loaded: LoadedAircraft,
    options: DiscoveryOptions,
    parent_pid: int,
    finish: Finish | None = None,
    lattice_store: LatticeStore | None = None,
    findings: bool = True,
) -> None:
    """A worker's Context on the aircraft the parent loaded (inherited when processes fork, pickled otherwise); the
    worker ends with its parent (:func:`certkit.engine.worker_processes.die_with_parent`)."""
    die_with_parent(parent_pid)
    _WORKER["ctx"] = Context(loaded, lattice_store)
    _WORKER["rules"] = {r.id: r for r in discover(options)}
    _WORKER["finish"] = finish
    _WORKER["findings"] = findings


def _worker_run(rule_ids: tuple[str, ...]) -> list[tuple[RuleResult, dict[str, Any]]]:
    """Rules in a worker process, one after the other on the worker's own Context (its models are reused by the
    next rules the worker takes), each encoded for ``results.json`` here, while other rules still run. What a rule
    leaves (its result, the Context's models) lives as long as the worker: it is frozen out of the cyclic garbage
    collector's scans (``gc.freeze``) before the encoding, which would otherwise rescan it at every full collection
    (about 5 % of a check's CPU)."""
    ctx = _WORKER["ctx"]
    out = []
    for rid in rule_ids:
        result = _timed(_WORKER["rules"][rid], ctx, _WORKER["finish"])
        gc.freeze()
        result.encoded = result.to_json()
        result.findings_travel = _WORKER["findings"]
        out.append((result, ctx.provenance()))
    return out


def _worker_alongside(work: Callable[[Context], Any]) -> Any:
    """Work alongside the rules (:func:`run`'s ``alongside``) on the worker's Context: it reuses the models the
    worker's rules built (the vortex lattice...) and leaves its own to them."""
    return work(_WORKER["ctx"])


def work_units(rules: list[type[Rule]]) -> list[tuple[type[Rule], ...]]:
    """The rules grouped for the worker processes: rules sharing a :attr:`Rule.run_with` key form one unit (in
    registry order), every other rule its own; the heaviest units (summed :attr:`Rule.cost`) first."""
    units: dict[object, list[type[Rule]]] = {}
    for r in rules:
        units.setdefault(r.run_with or ("", r.id), []).append(r)
    return sorted((tuple(u) for u in units.values()), key=lambda u: -sum(r.cost for r in u))  # stable on ties


def _queue(
    units: list[tuple[type[Rule], ...]], alongside: dict[str, Callable[[Context], Any]], cost: dict[str, float]
) -> list[tuple[str, Any]]:
    """The order the work is handed out in: the units (heaviest first, :func:`work_units`), each piece of work
    alongside after the units at least as heavy as its ``cost`` (after all of them without one)."""
    keyed: list[tuple[tuple[float, int, int], tuple[str, Any]]]
    keyed = [((-float(sum(r.cost for r in u)), 0, i), ("unit", u)) for i, u in enumerate(units)]
    keyed += [((-cost.get(name, -math.inf), 1, j), ("work", name)) for j, name in enumerate(alongside)]
    return [item for _, item in sorted(keyed, key=lambda k: k[0])]


def _collect(
    futures: list[Future[list[tuple[RuleResult, dict[str, Any]]]]],
    units: list[tuple[type[Rule], ...]],
    workers: int,
    progress: Any,
) -> list[tuple[RuleResult, dict[str, Any]]]:
    """Every unit's (result, provenance) pairs, in unit order, telling ``progress`` as units end (the first
    ``workers`` units were told started when submitted)."""
    if progress:
        next_unit = workers
        for done in as_completed(futures):
            progress.finished([res for res, _ in done.result()])
            if next_unit < len(units):
                progress.started([r.id for r in units[next_unit]])
                next_unit += 1
    return [part for f in futures for part in f.result()]


def run(
    loaded: LoadedAircraft,
    rules: list[type[Rule]],
    *,
    jobs: int = 1,
    options: DiscoveryOptions = DiscoveryOptions(),
    now: _dt.datetime | None = None,
    finish: Finish | None = None,
    alongside: dict[str, Callable[[Context], Any]] | None = None,
    alongside_cost: dict[str, float] | None = None,
    progress: Any = None,
    lattice_store: LatticeStore | None = None,
    findings: bool = True,
) -> RunResult:
    """Evaluate ``rules`` on ``loaded`` in ``jobs`` processes: each process takes the next unit of work
    (:func:`work_units`) when it is free, the heaviest first. ``finish`` (a picklable function of a
    :class:`RuleResult`, e.g. the report's drawing of the evidence) is applied to each result in the process that
    evaluated it, so that work runs in parallel too. ``alongside`` (name → picklable function of the evaluating
    process's :class:`Context`, e.g. the report's missions, which reuse its aerodynamic models) runs in the first
    worker free once the units heavier than its ``alongside_cost`` (on the scale of :attr:`Rule.cost`; without one,
    once every unit) are handed out (in this process with one job); each result goes to ``models[name]``.
    ``progress`` (optional) is told ``started(rule_ids)`` and ``finished(results)`` as units start and end (with
    several processes a unit counts as started when a process becomes free for it: the processes take the units in
    order). ``lattice_store``: the vortex-lattice solutions kept between runs (:class:`Context`). ``findings`` False:
    the worker processes send each result without its findings (:attr:`RuleResult.findings_travel`), for a caller that
    reads only their summary, the encoded text and the report's sections (a check written as text: ~13 MB fewer to
    pickle at the end of the longest unit)."""
    if jobs < 1:
        raise UserError(f"--jobs must be at least 1 (got {jobs})")
    if jobs == 1 or len(rules) <= 1:
        ctx = Context(loaded, lattice_store)
        results, provenance = _evaluate_many(ctx, rules, finish, progress)
        provenance = _merge_provenance([provenance])
        extra = {name: fn(ctx) for name, fn in (alongside or {}).items()}
    else:
        units = work_units(rules)
        workers = min(jobs, len(units))
        pool = ProcessPoolExecutor(
            max_workers=workers,
            initializer=_worker_init,
            initargs=(loaded, options, os.getpid(), finish, lattice_store, findings),
        )
        try:
            futures, extras = [], {}
            # in order of cost, the heaviest first (longest-processing-time order: the light units fill the end),
            # the work alongside among them by its own; the first process free takes the next
            for kind, item in _queue(units, alongside or {}, alongside_cost or {}):
                if kind == "unit":
                    futures.append(pool.submit(_worker_run, tuple(r.id for r in item)))
                else:
                    extras[item] = pool.submit(_worker_alongside, (alongside or {})[item])
            if progress:
                for unit in units[:workers]:
                    progress.started([r.id for r in unit])
            parts = _collect(futures, units, workers, progress)
            extra = {name: future.result() for name, future in extras.items()}
        except BaseException:  # Ctrl-C or a failure: the workers end now, not after their current rules
            stop_pool(pool)
            raise
        pool.shutdown()
        by_id = {res.id: res for res, _ in parts}
        results = [by_id[r.id] for r in rules]
        provenance = _merge_provenance([p for _, p in parts])
    created = (now or _dt.datetime.now(_dt.timezone.utc)).isoformat(timespec="seconds")
    return RunResult(__version__, loaded.name, loaded.sha256, loaded.path, created, results, provenance | extra)
